#include "core/mesh/validate_mesh.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

bool mentions(const MeshReport& r, const std::string& word) {
  for (const auto* list : {&r.problems, &r.sphere_problems, &r.warnings})
    for (const auto& p : *list)
      if (p.find(word) != std::string::npos) return true;
  return false;
}

TEST(ValidateMesh, FourSharedGenusZeroMeshesTakeTheSphereAsTheyAre) {
  MESHMARK_NEEDS_SHARED();
  for (const char* name : {"bunny.obj", "mannequin.off", "spot.obj", "armadillo.obj"}) {
    const MeshReport r = validate_mesh(test::load_shared(name));
    EXPECT_TRUE(r.closed_genus_zero) << name << ": " << (r.sphere_problems.empty() ? "" : r.sphere_problems.front());
    EXPECT_TRUE(r.valid) << name;
    EXPECT_EQ(r.basis, MeshBasis::sphere) << name;
    EXPECT_EQ(r.genus, 0) << name;
    EXPECT_EQ(r.orientation, Orientation::outward) << name;
    EXPECT_EQ(r.components, 1u) << name;
  }
}

TEST(ValidateMesh, KittenIsNoSphereForGenusOneAndTakesBumps) {
  MESHMARK_NEEDS_SHARED();
  const MeshReport r = validate_mesh(test::load_shared("kitten.off"));
  EXPECT_FALSE(r.closed_genus_zero);
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.basis, MeshBasis::bumps);
  EXPECT_NE(r.basis_reason.find("genus 1"), std::string::npos) << r.basis_reason;
  EXPECT_EQ(r.genus, 1);
  EXPECT_EQ(r.euler_characteristic, 0);
  EXPECT_TRUE(mentions(r, "genus 1"));
}

TEST(ValidateMesh, BunnyWithHolesIsNoSphereForFiveBoundaryLoopsAndHasThemClosedVirtually) {
  MESHMARK_NEEDS_SHARED();
  const MeshReport r = validate_mesh(test::load_shared("bunny_holes.off"));
  EXPECT_FALSE(r.closed_genus_zero);
  EXPECT_EQ(r.basis, MeshBasis::sphere_filled);
  EXPECT_EQ(r.boundary_loops, 5u);
  EXPECT_EQ(r.boundary_edges, 223u);
  EXPECT_TRUE(mentions(r, "5 boundary loops"));
}

TEST(ValidateMesh, CowIsNoSphereForItsPinchVertexWhichIsNamed) {
  MESHMARK_NEEDS_SHARED();
  const MeshReport r = validate_mesh(test::load_shared("cow_nonmanifold.obj"));
  EXPECT_FALSE(r.closed_genus_zero);
  EXPECT_EQ(r.basis, MeshBasis::bumps);
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_EQ(r.nonmanifold_edges, 0u);
  EXPECT_EQ(r.nonmanifold_vertices, 1u);
  ASSERT_EQ(r.nonmanifold_vertex_examples.size(), 1u);
  EXPECT_EQ(r.nonmanifold_vertex_examples[0], 253);  // 254 in the file's 1-based numbering
  EXPECT_EQ(r.euler_characteristic, 1);
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_TRUE(mentions(r, "vertex 253 at (-3.507689, 1.700214, 0)"));
}

TEST(ValidateMesh, InwardMeshIsASphereAndReportedInward) {
  Mesh mesh = test::cube();
  mesh.F.col(1).swap(mesh.F.col(2));
  const MeshReport r = validate_mesh(mesh);
  EXPECT_TRUE(r.closed_genus_zero);
  EXPECT_EQ(r.orientation, Orientation::inward);
  EXPECT_FALSE(r.warnings.empty());
}

TEST(ValidateMesh, OneFlippedFaceIsInconsistent) {
  Mesh mesh = test::cube();
  std::swap(mesh.F(3, 1), mesh.F(3, 2));
  const MeshReport r = validate_mesh(mesh);
  EXPECT_EQ(r.orientation, Orientation::inconsistent);
  EXPECT_FALSE(r.closed_genus_zero);
}

TEST(ValidateMesh, TorusHasGenusOne) {
  const MeshReport r = validate_mesh(test::torus(24, 12));
  EXPECT_EQ(r.genus, 1);
  EXPECT_FALSE(r.closed_genus_zero);
}

TEST(ValidateMesh, TwoCubesAreTwoComponents) {
  const MeshReport r = validate_mesh(test::side_by_side(test::cube(), test::cube()));
  EXPECT_EQ(r.components, 2u);
  EXPECT_EQ(r.genus, 0);  // total genus of two spheres
  EXPECT_FALSE(r.closed_genus_zero);
}

TEST(ValidateMesh, MissingFaceLeavesOneBoundaryLoop) {
  Mesh mesh = test::cube();
  mesh.F.conservativeResize(11, 3);
  const MeshReport r = validate_mesh(mesh);
  EXPECT_EQ(r.boundary_edges, 3u);
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_FALSE(r.closed_genus_zero);
}

TEST(ValidateMesh, ThreeFacesOnAnEdgeAreNonManifold) {
  Mesh mesh = test::cube();
  mesh.V.conservativeResize(9, 3);
  mesh.V.row(8) << 0.5, 0.5, -1;
  mesh.F.conservativeResize(13, 3);
  mesh.F.row(12) << 0, 1, 8;  // a fin on the bottom edge 0-1
  const MeshReport r = validate_mesh(mesh);
  EXPECT_GE(r.nonmanifold_edges, 1u);
  EXPECT_FALSE(r.closed_genus_zero);
}

TEST(ValidateMesh, DegenerateFaceIsNoSphere) {
  Mesh mesh = test::cube();
  mesh.V.row(3) = 0.5 * (mesh.V.row(1) + mesh.V.row(2));  // face 1,2,3 collapses to a segment
  const MeshReport r = validate_mesh(mesh);
  EXPECT_GE(r.zero_area_faces, 1u);
  EXPECT_TRUE(mentions(r, "zero-area"));
}

TEST(ValidateMesh, IsolatedVertexIsNoSphere) {
  Mesh mesh = test::cube();
  mesh.V.conservativeResize(9, 3);
  mesh.V.row(8) << 5, 5, 5;
  const MeshReport r = validate_mesh(mesh);
  EXPECT_EQ(r.isolated_vertices, 1u);
  EXPECT_FALSE(r.closed_genus_zero);
}

TEST(ValidateMesh, DuplicateVertexPositionsAreCountedAsAWarning) {
  Mesh mesh = test::cube();
  mesh.V.conservativeResize(9, 3);
  mesh.V.row(8) = mesh.V.row(0);
  mesh.F(0, 0) = 8;  // the copy takes over one corner: now a boundary appears, but it is a count we check
  const MeshReport r = validate_mesh(mesh);
  EXPECT_EQ(r.duplicate_vertices, 1u);
}

// The same reports on shapes made here, each with one feature.
TEST(ValidateMesh, EachProceduralShapeTakesTheBasisItsTopologyCalls) {
  for (const char* shape : {"creature", "creature_large"}) {
    const MeshReport r = validate_mesh(test::procedural_mesh(shape));
    EXPECT_TRUE(r.closed_genus_zero) << shape;
    EXPECT_EQ(r.basis, MeshBasis::sphere) << shape;
    EXPECT_EQ(r.orientation, Orientation::outward) << shape;
  }
  const MeshReport torus = validate_mesh(test::procedural_mesh("torus"));
  EXPECT_EQ(torus.genus, 1);
  EXPECT_EQ(torus.basis, MeshBasis::bumps);
  EXPECT_TRUE(mentions(torus, "genus 1"));
  const MeshReport holes = validate_mesh(test::procedural_mesh("creature_holes"));
  EXPECT_EQ(holes.basis, MeshBasis::sphere_filled);
  EXPECT_EQ(holes.boundary_loops, 3u);
  EXPECT_TRUE(mentions(holes, "3 boundary loops"));
  const MeshReport parts = validate_mesh(test::procedural_mesh("parts"));
  EXPECT_EQ(parts.basis, MeshBasis::bumps);
  EXPECT_NE(parts.basis_reason.find("2 components"), std::string::npos) << parts.basis_reason;
  const MeshReport pinched = validate_mesh(test::procedural_mesh("pinched"));
  EXPECT_EQ(pinched.basis, MeshBasis::bumps);
  EXPECT_EQ(pinched.nonmanifold_vertices, 1u);
  EXPECT_EQ(pinched.components, 1u);
}

TEST(ValidateMesh, AMeshTooSmallToCarryAPayloadIsRefusedOnEveryBasis) {
  const MeshReport r = validate_mesh(test::cube());
  EXPECT_TRUE(r.closed_genus_zero);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.basis, MeshBasis::none);
  EXPECT_TRUE(mentions(r, "at least 100"));
}

// A ball: its turned copies may not register, and the report says so before any work; a shape
// with distinct axes gets no such warning.
TEST(ValidateMesh, AShapeAboutAsWideEveryWayIsWarnedAbout) {
  EXPECT_TRUE(mentions(validate_mesh(test::icosphere(3)), "about as wide every way"));
  Mesh stretched = test::icosphere(3);
  stretched.V.col(0) *= 1.5;
  stretched.V.col(1) *= 1.2;
  EXPECT_FALSE(mentions(validate_mesh(stretched), "about as wide every way"));
}

// Many tiny parts (each below the size even a low-poly part needs to carry anything) are refused
// as a whole, however many vertices they add up to: info and embed agree.
TEST(ValidateMesh, AModelOfOnlyTinyPartsIsRefusedNamingWhy) {
  const Mesh& piece = test::procedural_mesh("creature_small");
  Mesh parts = test::cube();
  for (int k = 1; k < 40; ++k) parts = test::side_by_side(parts, test::cube(), 3.0 * k);
  ASSERT_GE(parts.V.rows(), 300);
  const MeshReport r = validate_mesh(parts);
  EXPECT_FALSE(r.valid);
  EXPECT_TRUE(mentions(r, "lie in parts of at least 16")) << r.problems.front();
  EXPECT_TRUE(validate_mesh(test::side_by_side(piece, test::cube())).valid);
}

// Parts below kMinMarkedComponentVertices carry when the larger parts alone could not: a
// low-poly model of small parts is marked as a whole; beside a large part they stay unmarked.
TEST(ValidateMesh, SmallPartsCarryOnlyWhenTheLargerPartsAloneHoldTooFew) {
  Mesh parts = test::creature(1);  // 42 vertices
  for (int k = 1; k < 4; ++k) parts = test::side_by_side(parts, test::creature(1), 3.0 * k);
  const MeshReport low_poly = validate_mesh(parts);
  EXPECT_TRUE(low_poly.valid);
  EXPECT_EQ(low_poly.marked_component_floor, kMinLowPolyComponentVertices);
  EXPECT_EQ(low_poly.small_components, 0u);
  const MeshReport beside_a_large_part =
      validate_mesh(test::side_by_side(test::procedural_mesh("creature"), test::creature(1)));
  EXPECT_EQ(beside_a_large_part.marked_component_floor, kMinMarkedComponentVertices);
  EXPECT_EQ(beside_a_large_part.small_components, 1u);
}

TEST(ValidateMesh, TwoCopiesOfASphereTakeBumpsAndNameTheComponents) {
  const Mesh& creature = test::procedural_mesh("creature");
  const MeshReport r = validate_mesh(test::side_by_side(creature, creature));
  EXPECT_EQ(r.basis, MeshBasis::bumps);
  EXPECT_NE(r.basis_reason.find("2 components"), std::string::npos) << r.basis_reason;
  EXPECT_EQ(r.small_components, 0u);
}

TEST(ValidateMesh, ComponentsTooSmallToCarryAreCountedAndWarnedAbout) {
  const MeshReport r = validate_mesh(test::side_by_side(test::procedural_mesh("creature"), test::cube()));
  EXPECT_EQ(r.small_components, 1u);
  EXPECT_EQ(r.basis, MeshBasis::bumps);
  EXPECT_FALSE(r.warnings.empty());
}

}  // namespace
}  // namespace meshmark

namespace meshmark {
namespace {

TEST(ValidateMesh, AMeshThatLostItsShapeToRoundingIsRefusedWithTheReason) {
  Mesh far = test::procedural_mesh("creature");
  far.V.col(0).array() += 1e12;  // the creature spans ~5: at 1e12, doubles keep ~4 digits of it
  const MeshReport r = validate_mesh(far);
  EXPECT_FALSE(r.valid);
  EXPECT_FALSE(r.closed_genus_zero);
  ASSERT_FALSE(r.problems.empty());
  EXPECT_NE(r.problems.back().find("digits"), std::string::npos) << r.problems.back();
  Mesh near = test::procedural_mesh("creature");
  near.V.col(0).array() += 1e6;  // still ~10 digits: fine
  EXPECT_TRUE(validate_mesh(near).valid);
}

// With a second thread the positions' checks run beside the connectivity's: the same report,
// word for word, on meshes with every kind of finding (holes, pinches, genus, zero-area faces,
// duplicates, shapes too round or too far from the origin).
TEST(ValidateMesh, TheReportIsTheSameOnOneThreadAndOnTwo) {
  Mesh degenerate = test::cube();
  degenerate.V.row(3) = 0.5 * (degenerate.V.row(1) + degenerate.V.row(2));
  Mesh far = test::procedural_mesh("creature");
  far.V.col(0).array() += 1e12;
  std::vector<Mesh> meshes{degenerate, far, icosphere(3), test::procedural_mesh("torus")};
  for (const char* name : {"cow_nonmanifold.obj", "bunny_holes.off", "kitten.off"})
    if (test::shared_present()) meshes.push_back(test::load_shared(name));
  for (const Mesh& mesh : meshes) {
    const MeshReport one = validate_mesh(mesh, {.threads = 1}), two = validate_mesh(mesh, {.threads = 2});
    EXPECT_EQ(one.problems, two.problems);
    EXPECT_EQ(one.sphere_problems, two.sphere_problems);
    EXPECT_EQ(one.warnings, two.warnings);
    EXPECT_EQ(one.zero_area_faces, two.zero_area_faces);
    EXPECT_EQ(one.zero_area_face_examples, two.zero_area_face_examples);
    EXPECT_EQ(one.duplicate_vertices, two.duplicate_vertices);
    EXPECT_EQ(one.basis, two.basis);
    EXPECT_EQ(one.valid, two.valid);
  }
}

}  // namespace
}  // namespace meshmark
