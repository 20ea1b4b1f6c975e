// The smooth field registration fits after the rigid pose: it takes a bent or twisted surface
// back onto its original, is the identity until fitted, and fits nothing from too few points.

#include "core/registration/smooth_deformation.hpp"

#include <gtest/gtest.h>

#include "core/attacks/bend_twist.hpp"
#include "core/mesh/vertex_normals.hpp"
#include "core/metrics/compare_meshes.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

struct Original {
  const Mesh& mesh = test::procedural_mesh("creature");
  AabbTree tree{mesh.V, mesh.F};
  Vertices normals = face_normals(mesh.V, mesh.F);
  double diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
};

const Original& original() {
  static const Original o;
  return o;
}

TEST(SmoothDeformation, TakesABentOrTwistedSurfaceBackOntoTheOriginal) {
  for (const bool bent : {true, false}) {
    const Mesh deformed = bent ? bend(original().mesh, 30) : twist(original().mesh, 30);
    const Vertices samples = sample_surface(deformed, 4000);
    const DeformationFit fit =
        fit_smooth_deformation(samples, original().tree, original().normals, original().diagonal);
    ASSERT_FALSE(fit.deformation.identity()) << (bent ? "bend" : "twist");
    EXPECT_GT(fit.rigid_rms, 3e-3 * original().diagonal);
    EXPECT_LT(fit.deformed_rms, 0.1 * fit.rigid_rms) << (bent ? "bend" : "twist");
    // The field moves the samples themselves onto the surface, not only their distances.
    const Vertices back = fit.deformation.apply_to_rows(samples);
    double worst = 0;
    for (Eigen::Index i = 0; i < back.rows(); i += 10)
      worst = std::max(worst, std::sqrt(original().tree.closest_point(back.row(i).transpose())->distance_squared));
    EXPECT_LT(worst, 0.02 * original().diagonal);
  }
}

// A shared mesh bent by 20° and put back by a field fitted to 5,000 of its samples: the bend keeps
// the vertices, so each one's error is known. Distances in diagonals.
struct PutBack {
  Eigen::VectorXd before, after;
  double rms(const Eigen::VectorXd& d) const { return std::sqrt(d.squaredNorm() / static_cast<double>(d.size())); }
};

PutBack bent_by_20_degrees_and_put_back(const char* shared_mesh) {
  const Mesh& original = test::load_shared(shared_mesh);
  const Mesh bent = bend(original, 20);
  const double diagonal = (original.V.colwise().maxCoeff() - original.V.colwise().minCoeff()).norm();
  const AabbTree tree(original.V, original.F);
  const DeformationFit fit =
      fit_smooth_deformation(sample_surface(bent, 5000), tree, face_normals(original.V, original.F), diagonal);
  const Vertices back = fit.deformation.apply_to_rows(bent.V);
  return {(bent.V - original.V).rowwise().norm() / diagonal, (back - original.V).rowwise().norm() / diagonal};
}

// A long thin limb bent by 20°: its ends lie far from their places after the rigid pose, where a
// cubic fitted at once from those correspondences stalls; fitted coarse to fine, the field puts
// every vertex back where it was.
TEST(SmoothDeformation, PutsALongLimbsVerticesBackWhereTheyWere) {
  MESHMARK_NEEDS_SHARED();
  const PutBack arm = bent_by_20_degrees_and_put_back("corpus/arm.obj");
  EXPECT_GT(arm.rms(arm.before), 0.02);
  EXPECT_LT(arm.rms(arm.after), 0.003) << "before: " << arm.rms(arm.before);  // 0.88 % fitted at once, 0.22 % now
}

// A long body of revolution bent by 20°: its far ends are the last correspondences to come close.
// Fitted only to the closest nine tenths, as the fit's RMS counts them, the field crept toward them
// a little each step and stopped short (the screwdriver's vertices 0.19 % of the diagonal from
// their places, the farthest 1.1 %; 7 bits of 64 read wrong); fitted to all but the farthest 3 %,
// 0.02 %, the farthest 0.05 %: the mark's own size.
TEST(SmoothDeformation, BringsABentLongBodysEndsBackWithinTheMarksSize) {
  MESHMARK_NEEDS_SHARED();
  const PutBack screwdriver = bent_by_20_degrees_and_put_back("corpus/screwdriver.off");
  EXPECT_LT(screwdriver.rms(screwdriver.after), 0.0005);
  EXPECT_LT(screwdriver.after.maxCoeff(), 0.002);
}

TEST(SmoothDeformation, IsTheIdentityUntilFittedAndFitsNothingFromTooFewPoints) {
  const SmoothDeformation none;
  const Eigen::Vector3d x(0.3, -1.2, 4.0);
  EXPECT_EQ(none.apply(x), x);
  const Vertices few = sample_surface(original().mesh, 20);
  EXPECT_TRUE(
      fit_smooth_deformation(few, original().tree, original().normals, original().diagonal).deformation.identity());
}

}  // namespace
}  // namespace meshmark
