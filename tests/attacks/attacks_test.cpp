// Each attack does what it must, and the same seed gives the same result.

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/attacks/add_noise.hpp"
#include "core/attacks/attack_registry.hpp"
#include "core/mesh/validate_mesh.hpp"
#include "core/attacks/crop.hpp"
#include "core/attacks/draco_compress.hpp"
#include "core/attacks/split_vertices.hpp"
#include "core/mesh/weld_positions.hpp"
#include "core/attacks/quantize.hpp"
#include "core/attacks/remesh.hpp"
#include "core/attacks/reorder.hpp"
#include "core/attacks/round_digits.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "core/attacks/simplify.hpp"
#include "core/mesh/laplacian_smooth.hpp"
#include "core/mesh/massmatrix.hpp"
#include "core/mesh/orientation.hpp"
#include "core/mesh/validate_mesh.hpp"
#include "core/metrics/compare_meshes.hpp"
#include "core/spatial/point_index.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// A closed genus-0 shape with thin limbs, 10,242 vertices.
const Mesh& subject() { return test::procedural_mesh("creature_large"); }
double diagonal(const Mesh& m) { return (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm(); }
bool same(const Mesh& a, const Mesh& b) { return a.V == b.V && a.F == b.F; }

TEST(RoundDigits, KeepsWhatPrintingWithThatManyDigitsKeeps) {
  Mesh m = subject();
  m.V(0, 0) = 0;
  m.V(1, 1) = -123456.789;
  const Mesh r = round_digits(m, 6);
  char text[32];
  for (Eigen::Index i = 0; i < m.V.size(); ++i) {
    std::snprintf(text, sizeof text, "%.6g", m.V.data()[i]);
    const double printed = std::stod(text);
    EXPECT_NEAR(r.V.data()[i], printed, 1e-12 * std::max(1.0, std::abs(printed))) << m.V.data()[i];
  }
  EXPECT_EQ(r.V(1, 1), -123457.0);
  EXPECT_TRUE(r.F == m.F);
  EXPECT_THROW(round_digits(m, 0), std::invalid_argument);
}

TEST(Reorder, KeepsTheSurfaceAndChangesTheOrder) {
  const Mesh r = reorder(subject(), 1);
  EXPECT_EQ(r.V.rows(), subject().V.rows());
  EXPECT_FALSE(r.V == subject().V);
  EXPECT_FALSE(r.F == subject().F);
  EXPECT_LT(compare_meshes(subject(), r, {20000}).hausdorff, 1e-12);
  EXPECT_TRUE(validate_mesh(r).closed_genus_zero);
}

TEST(SplitVertices, KeepsTheShapeAndWeldsBackToTheOriginal) {
  const Mesh split = split_vertices(subject(), 0.3, 4);
  EXPECT_GT(split.V.rows(), subject().V.rows() * 3 / 2);
  EXPECT_EQ(split.F.rows(), subject().F.rows());
  EXPECT_LT(compare_meshes(subject(), split, {20000}).hausdorff, 1e-12);
  const WeldedSurface welded = weld_positions(split.V, split.F);
  EXPECT_EQ(welded.mesh.V.rows(), subject().V.rows());
  EXPECT_TRUE(validate_mesh(welded.mesh).closed_genus_zero);
}

TEST(SplitVertices, NoneAndAllAreTheExtremes) {
  EXPECT_TRUE(same(split_vertices(subject(), 0, 1), subject()));
  EXPECT_EQ(split_vertices(subject(), 1, 1).V.rows(), 3 * subject().F.rows());
  EXPECT_THROW(split_vertices(subject(), 1.5, 1), std::invalid_argument);
}

TEST(DracoCompress, RoundsPositionsToItsGridAndRenumbersThem) {
  for (const int bits : {11, 14}) {
    const Mesh d = draco_compress(subject(), bits);
    EXPECT_EQ(d.F.rows(), subject().F.rows());
    EXPECT_FALSE(d.V == subject().V);
    const double step =
        (subject().V.colwise().maxCoeff() - subject().V.colwise().minCoeff()).maxCoeff() / ((1 << bits) - 1);
    const SurfaceDistance e = compare_meshes(subject(), d, {20000});
    EXPECT_LT(e.hausdorff, step) << bits;
    EXPECT_GT(e.hausdorff, step / 100) << bits;  // it did quantize
  }
  EXPECT_THROW(draco_compress(subject(), 31), std::invalid_argument);
}

TEST(Reorder, IsDeterministicForASeed) {
  EXPECT_TRUE(same(reorder(subject(), 4), reorder(subject(), 4)));
  EXPECT_FALSE(same(reorder(subject(), 4), reorder(subject(), 5)));
}

TEST(Similarity, PreservesShapeUpToScale) {
  const Similarity T = random_similarity(subject(), 3);
  const Mesh moved = transform_mesh(subject(), T);
  const Eigen::VectorXd before = face_areas(subject().V, subject().F), after = face_areas(moved.V, moved.F);
  EXPECT_NEAR(after.sum() / before.sum(), T.scale * T.scale, 1e-9);
  EXPECT_NEAR(T.R.determinant(), 1.0, 1e-12);
  EXPECT_GE(T.scale, 0.5);
  EXPECT_LE(T.scale, 2.0);
  EXPECT_TRUE(same(transform_mesh(subject(), random_similarity(subject(), 3)), moved));
}

// The mirror image keeps the area and the enclosed volume's sign (its faces rewound: outward stays
// outward), is the shape reflected (a linear map of determinant −1), and mirrored again through
// the same plane is the shape itself.
TEST(Mirror, ReflectsTheShapeKeepingItsFacesOutward) {
  const Mesh& shape = subject();
  for (const int axis : {0, -1}) {
    const Mesh mirrored = mirror_mesh(shape, axis, 7);
    EXPECT_NEAR(face_areas(mirrored.V, mirrored.F).sum(), face_areas(shape.V, shape.F).sum(), 1e-9);
    EXPECT_NEAR(signed_volume(mirrored.V, mirrored.F), signed_volume(shape.V, shape.F), 1e-9);
    Eigen::MatrixXd affine(shape.V.rows(), 4);  // the linear map taking the shape onto its image
    affine << shape.V, Eigen::VectorXd::Ones(shape.V.rows());
    const Eigen::MatrixXd map = affine.colPivHouseholderQr().solve(Eigen::MatrixXd(mirrored.V));
    EXPECT_NEAR(map.topRows(3).determinant(), -1.0, 1e-9) << "a reflection, no rotation";
    EXPECT_LT((mirror_mesh(mirrored, axis, 7).V - shape.V).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_TRUE(mirror_mesh(mirrored, axis, 7).F == shape.F);
  }
  EXPECT_FALSE(same(mirror_mesh(shape, -1, 7), mirror_mesh(shape, -1, 8)));
}

TEST(Noise, MovesEachCoordinateWithinTheAmplitude) {
  for (auto reference : {NoiseReference::bbox_diagonal, NoiseReference::centroid_distance}) {
    const double a = 0.3 / 100 * noise_reference_length(subject(), reference);
    const Mesh noisy = add_noise(subject(), 0.3, reference, 7);
    const Eigen::ArrayXXd delta = (noisy.V - subject().V).array();
    EXPECT_LE(delta.abs().maxCoeff(), a);
    EXPECT_GT(delta.abs().maxCoeff(), 0.9 * a);
    // Uniform on [−a, a]: RMS a/√3.
    EXPECT_NEAR(std::sqrt(delta.square().mean()), a / std::sqrt(3.0), 0.02 * a);
    EXPECT_TRUE(noisy.F == subject().F);
    EXPECT_TRUE(same(noisy, add_noise(subject(), 0.3, reference, 7)));
  }
}

TEST(Smooth, ShrinksTheSurfaceAndSmoothsIt) {
  const Mesh s = laplacian_smooth(subject(), 0.03, 30);
  const double area_before = face_areas(subject().V, subject().F).sum(), area_after = face_areas(s.V, s.F).sum();
  EXPECT_LT(area_after, area_before);
  EXPECT_GT(area_after, 0.9 * area_before);
  EXPECT_TRUE(s.F == subject().F);
  EXPECT_TRUE(same(laplacian_smooth(subject(), 0.03, 0), subject()));
}

TEST(Quantize, SnapsEveryCoordinateToTheGrid) {
  const Mesh q = quantize(subject(), 8);
  const Eigen::RowVector3d lo = subject().V.colwise().minCoeff(), hi = subject().V.colwise().maxCoeff();
  for (int k = 0; k < 3; ++k) {
    std::set<double> levels;
    for (Eigen::Index v = 0; v < q.V.rows(); ++v) levels.insert(q.V(v, k));
    EXPECT_LE(levels.size(), 256u);
    const double step = (hi[k] - lo[k]) / 255;
    EXPECT_LE((q.V.col(k) - subject().V.col(k)).cwiseAbs().maxCoeff(), 0.5 * step * (1 + 1e-9));
  }
}

TEST(Simplify, HitsItsVertexCountAndKeepsTheMeshClosed) {
  for (double fraction : {0.5, 0.25, 0.1}) {
    const Mesh s = simplify(subject(), fraction);
    EXPECT_EQ(s.V.rows(), std::lround(fraction * static_cast<double>(subject().V.rows())));
    const MeshReport r = validate_mesh(s);
    EXPECT_EQ(r.boundary_edges, 0u) << fraction;
    EXPECT_EQ(r.nonmanifold_edges, 0u) << fraction;
    EXPECT_EQ(r.genus, 0) << fraction;
    // The shape stays: within a small fraction of the diagonal.
    EXPECT_LT(compare_meshes(subject(), s, {20000}).mrms_relative(), 0.005) << fraction;
  }
}

TEST(Simplify, IsDeterministic) { EXPECT_TRUE(same(simplify(subject(), 0.3), simplify(subject(), 0.3))); }

TEST(Crop, RemovesAboutTheAskedFractionOfTheArea) {
  const double total = face_areas(subject().V, subject().F).sum();
  for (double fraction : {0.1, 0.3, 0.5}) {
    const Mesh c = crop(subject(), fraction, 2);
    const double kept = face_areas(c.V, c.F).sum();
    EXPECT_NEAR(1 - kept / total, fraction, 0.01) << fraction;
    EXPECT_GT(validate_mesh(c).boundary_edges, 0u);  // it is open now
  }
  EXPECT_TRUE(same(crop(subject(), 0.3, 2), crop(subject(), 0.3, 2)));
  EXPECT_FALSE(same(crop(subject(), 0.3, 2), crop(subject(), 0.3, 3)));
}

TEST(Crop, DropsTheVerticesItOrphans) {
  const Mesh c = crop(subject(), 0.3, 2);
  EXPECT_EQ(validate_mesh(c).isolated_vertices, 0u);
}

TEST(Remesh, MovesAlmostEveryVertexAndKeepsTheSurface) {
  const Mesh r = remesh(subject());
  const PointIndex original(subject().V);
  const double d = diagonal(subject());
  Eigen::Index kept = 0;
  for (Eigen::Index v = 0; v < r.V.rows(); ++v)
    kept += std::sqrt(original.nearest(r.V.row(v).transpose()).second) <= 1e-9 * d;
  EXPECT_LT(kept, r.V.rows() / 100) << "only sharp tips and corners stay in place";
  EXPECT_LT(compare_meshes(subject(), r, {20000}).mrms_relative(), 0.002);
  const MeshReport report = validate_mesh(r);
  EXPECT_TRUE(report.closed_genus_zero) << (report.sphere_problems.empty() ? "" : report.sphere_problems.front());
  EXPECT_NEAR(static_cast<double>(r.V.rows()) / subject().V.rows(), 1.0, 0.35);
}

TEST(Remesh, IsDeterministic) { EXPECT_TRUE(same(remesh(subject()), remesh(subject()))); }

// An attacker's tools take any mesh: a face a halfedge mesh cannot hold gets its own corners.
TEST(Simplify, TakesAMeshWithAPinchVertex) {
  MESHMARK_NEEDS_SHARED();
  const Mesh& cow = test::load_shared("cow_nonmanifold.obj");
  const Mesh s = simplify(cow, 0.5);
  EXPECT_NEAR(static_cast<double>(s.V.rows()) / cow.V.rows(), 0.5, 0.05);
  EXPECT_LT(compare_meshes(cow, s, {20000}).mrms_relative(), 0.01);
}

// The cow's horns and ears are thinner than the mean edge: collapses that would cut them off are
// refused (0.22 % MRMS before the surface-distance check, 0.05 % after).
TEST(Remesh, TakesAMeshWithAPinchVertexAndKeepsItsThinTips) {
  MESHMARK_NEEDS_SHARED();
  const Mesh& cow = test::load_shared("cow_nonmanifold.obj");
  EXPECT_LT(compare_meshes(cow, remesh(cow), {20000}).mrms_relative(), 0.001);
}

// Boundary edges carry Garland and Heckbert's constraint planes: the beetle's 23 holes and cut
// non-manifold edges kept their outline (0.26 % MRMS at half the vertices before, 0.07 % after).
TEST(Simplify, KeepsTheOutlineOfHolesAndOpenEdges) {
  MESHMARK_NEEDS_SHARED();
  const Mesh& beetle = test::load_shared("corpus/beetle.obj");
  EXPECT_LT(compare_meshes(beetle, simplify(beetle, 0.5), {20000}).mrms_relative(), 0.001);
}

TEST(Simplify, KeepsTheOutlineOfProceduralHolesAndAPinch) {
  for (const char* shape : {"creature_holes", "pinched"}) {
    const Mesh& mesh = test::procedural_mesh(shape);
    const Mesh s = simplify(mesh, 0.5);
    EXPECT_NEAR(static_cast<double>(s.V.rows()) / mesh.V.rows(), 0.5, 0.05) << shape;
    EXPECT_LT(compare_meshes(mesh, s, {20000}).mrms_relative(), 0.001) << shape;
  }
}

TEST(Remesh, KeepsTheOutlineOfProceduralHolesAndAPinch) {
  for (const char* shape : {"creature_holes", "pinched"}) {
    const Mesh& mesh = test::procedural_mesh(shape);
    const Mesh r = remesh(mesh);
    EXPECT_EQ(validate_mesh(r).boundary_loops, validate_mesh(mesh).boundary_loops) << shape;
    EXPECT_LT(compare_meshes(mesh, r, {20000}).mrms_relative(), 0.001) << shape;
  }
}

TEST(Remesh, KeepsEveryHoleOutline) {
  MESHMARK_NEEDS_SHARED();
  const Mesh& bunny = test::load_shared("bunny_holes.off");
  const Mesh r = remesh(bunny);
  EXPECT_EQ(validate_mesh(r).boundary_loops, validate_mesh(bunny).boundary_loops);
  EXPECT_LT(compare_meshes(bunny, r, {20000}).mrms_relative(), 0.0003);
}

// Found by fuzzing: a tetrahedron relaxed into one point (edges of 1e-17 at coordinates of 0.2)
// made every pass split every edge without shortening it, doubling the mesh each time.
TEST(Remesh, RefusesAMeshBelowItsCoordinatesPrecision) {
  Mesh point_like;
  point_like.V.resize(4, 3);
  point_like.V << 0.2, 0.2, 0.2, 0.2, 0.2, 0.2 + 1e-17, 0.2, 0.2 + 1e-17, 0.2, 0.2 + 1e-17, 0.2, 0.2;
  point_like.F.resize(4, 3);
  point_like.F << 0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2;
  EXPECT_THROW(remesh(point_like), std::invalid_argument);
}

}  // namespace
}  // namespace meshmark

namespace meshmark {
namespace {

// Found by fuzzing: remeshing a tetrahedron collapsed it into two triangles glued at all three
// edges, and remeshing that made faces that repeat a vertex (OpenMesh then aborted).
TEST(Attacks, CollapsesNeverTurnASmallClosedMeshIntoAPillow) {
  Mesh octahedron;
  octahedron.V.resize(6, 3);
  octahedron.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  octahedron.F.resize(8, 3);
  octahedron.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  Mesh m = apply_attack_chain(octahedron, parse_attack_chain("simplify keep=0.5 | remesh iterations=3"), 1);
  for (int round = 0; round < 4; ++round) m = apply_attack_chain(m, parse_attack_chain("remesh iterations=5"), 1);
  EXPECT_GE(m.V.rows(), 4);
  const MeshReport report = validate_mesh(m);
  EXPECT_EQ(report.nonmanifold_edges, 0u);
  EXPECT_EQ(report.boundary_edges, 0u);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    EXPECT_TRUE(m.F(f, 0) != m.F(f, 1) && m.F(f, 1) != m.F(f, 2) && m.F(f, 0) != m.F(f, 2)) << "face " << f;
}

}  // namespace
}  // namespace meshmark

namespace meshmark {
namespace {

// `--keep 0.5 --remove 0.2` used to apply remove silently.
TEST(AttackRegistry, SimplificationRefusesKeepAndRemoveTogether) {
  EXPECT_THROW(apply_attack_chain(subject(), parse_attack_chain("simplify keep=0.5 remove=0.2"), 1),
               std::invalid_argument);
  EXPECT_EQ(apply_attack_chain(subject(), parse_attack_chain("simplify remove=0.2"), 1).V.rows(),
            std::lround(0.8 * static_cast<double>(subject().V.rows())));
  EXPECT_EQ(apply_attack_chain(subject(), parse_attack_chain("simplify"), 1).V.rows(),
            std::lround(0.5 * static_cast<double>(subject().V.rows())));
}

}  // namespace
}  // namespace meshmark
