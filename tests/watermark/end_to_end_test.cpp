// The watermark's contract on the four shared meshes, the four hard genus-0 meshes of the
// corpus and every kind of mesh the sphere cannot take as it is (holes, handles, several parts,
// non-manifold spots), with the default scheme and strength.
// Each mesh runs as one ctest entry (see tests/CMakeLists.txt) so that its model is prepared
// once and shared by the tests below.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>

#include "core/attacks/add_noise.hpp"
#include "core/attacks/crop.hpp"
#include "core/attacks/quantize.hpp"
#include "core/attacks/remesh.hpp"
#include "core/attacks/reorder.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "core/attacks/simplify.hpp"
#include "core/attacks/smooth.hpp"
#include "core/metrics/compare_meshes.hpp"
#include "core/watermark/watermark.hpp"
#include "tests/test_data.hpp"
#include "tests/watermark/end_to_end_secrets.hpp"

namespace meshmark {
namespace {

const std::string& kKey = test::kEndToEndKey;
const Bits& payload() { return test::end_to_end_payload(); }

struct Marked {
  PreparedModel model;
  std::unique_ptr<RegistrationTarget> target;
  EmbedResult embedded;
};

const Marked& marked(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<Marked>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[name];
  if (!slot) {
    slot = std::make_unique<Marked>();
    slot->model = prepare_model(test::load_shared(name));
    slot->target = std::make_unique<RegistrationTarget>(slot->model.mesh);
    slot->embedded = embed_watermark(slot->model, kKey, payload());
  }
  return *slot;
}

DetectResult detect(const Marked& m, const Mesh& suspect, const std::string& key = kKey) {
  return test::detect_end_to_end(m.model, *m.target, suspect, key);
}

class EndToEnd : public ::testing::TestWithParam<std::string> {};

TEST_P(EndToEnd, OutputKeepsTheFacesAndTheVertexOrder) {
  const Marked& m = marked(GetParam());
  const Mesh& original = test::load_shared(GetParam());
  EXPECT_TRUE(m.embedded.mesh.F == original.F);
  ASSERT_EQ(m.embedded.mesh.V.rows(), original.V.rows());
  // Every vertex moved by less than a fraction of the diagonal: it is still the same vertex.
  EXPECT_LT((m.embedded.mesh.V - original.V).rowwise().norm().maxCoeff(), 0.005 * m.model.diagonal);
  EXPECT_GT((m.embedded.mesh.V - original.V).norm(), 0.0);
}

TEST_P(EndToEnd, DistortionIsWithinTheBudget) {
  const Marked& m = marked(GetParam());
  const SurfaceDistance d = compare_meshes(test::load_shared(GetParam()), m.embedded.mesh);
  EXPECT_LE(d.mrms_relative(), 0.0005);  // 0.05 % of the bounding-box diagonal
  EXPECT_GT(d.mrms_relative(), 0.0002);  // and the budget is actually used
}

TEST_P(EndToEnd, EmbeddingIsDeterministic) {
  const Marked& m = marked(GetParam());
  const EmbedResult again = embed_watermark(m.model, kKey, payload());
  EXPECT_TRUE(again.mesh.V == m.embedded.mesh.V);
}

TEST_P(EndToEnd, UnattackedCopyIsDetectedWithoutErrors) {
  const DetectResult r = detect(marked(GetParam()), marked(GetParam()).embedded.mesh);
  EXPECT_TRUE(r.detected);
  EXPECT_EQ(r.ber, 0.0);
  EXPECT_LT(r.p_value, 1e-9);
  ASSERT_TRUE(r.payload.has_value());
  EXPECT_EQ(*r.payload, payload());
}

TEST_P(EndToEnd, ReorderedCopyIsReadWithoutErrors) {
  const Marked& m = marked(GetParam());
  const DetectResult r = detect(m, reorder(m.embedded.mesh, 11));
  EXPECT_EQ(r.ber, 0.0);
  EXPECT_TRUE(r.detected);
}

TEST_P(EndToEnd, SimilarityTransformedCopyIsReadWithoutErrors) {
  const Marked& m = marked(GetParam());
  const Mesh moved = transform_mesh(m.embedded.mesh, random_similarity(m.embedded.mesh, 12));
  const DetectResult r = detect(m, moved);
  EXPECT_EQ(r.ber, 0.0);
  EXPECT_TRUE(r.detected);
}

TEST_P(EndToEnd, UnmarkedOriginalIsNotDetected) {
  const Marked& m = marked(GetParam());
  const DetectResult r = detect(m, m.model.mesh);
  EXPECT_FALSE(r.detected);
  EXPECT_GT(r.p_value, 1e-3);
}

TEST_P(EndToEnd, WrongKeyIsNotDetected) {
  const Marked& m = marked(GetParam());
  const DetectResult r = detect(m, m.embedded.mesh, "someone else's key");
  EXPECT_FALSE(r.detected);
  EXPECT_GT(r.p_value, 1e-3);
}

std::string mesh_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param.substr(info.param.rfind('/') + 1);
  name = name.substr(0, name.find('.'));
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

// The attacks of the robustness table, on the meshes that need more than the sphere.
class AnyMeshEndToEnd : public EndToEnd {};

void expect_read(const Marked& m, const Mesh& attacked, const std::string& attack) {
  const double distortion = compare_meshes(m.model.mesh, attacked, {20000}).mrms_relative();
  const DetectResult r = detect(m, attacked);
  EXPECT_EQ(r.ber, 0.0) << attack << " (the attack's own distortion: MRMS " << 100 * distortion << " %)";
  EXPECT_TRUE(r.detected) << attack << ": log10 p " << r.log10_p_value << " (MRMS " << 100 * distortion << " %)";
}

TEST_P(AnyMeshEndToEnd, TheBasisIsTheOneTheReportNames) {
  const Marked& m = marked(GetParam());
  EXPECT_EQ(m.model.basis, m.model.report.basis);
  EXPECT_NE(m.model.basis, MeshBasis::sphere);
  EXPECT_FALSE(m.model.basis_reason.empty());
}

TEST_P(AnyMeshEndToEnd, NoiseSmoothingAndQuantizationLeaveNoErrors) {
  const Marked& m = marked(GetParam());
  expect_read(m, add_noise(m.embedded.mesh, 0.3, NoiseReference::centroid_distance, 5), "noise 0.3 % of the centroid distance");
  expect_read(m, laplacian_smooth(m.embedded.mesh, 0.03, 10), "smoothing λ 0.03 × 10");
  expect_read(m, quantize(m.embedded.mesh, 9), "quantization to 9 bits");
}

TEST_P(AnyMeshEndToEnd, SimplificationCropAndRemeshingLeaveNoErrors) {
  const Marked& m = marked(GetParam());
  expect_read(m, crop(m.embedded.mesh, 0.1, 6), "crop 10 %");
  // Halving a mesh of a thousand vertices, or remeshing at the mean edge length a mesh whose
  // detail is much finer (the cow's head, the beetle's legs), moves the surface by more than three
  // times the watermark's whole budget (beetle simplified 0.27 %, remeshed 1.9 %; cow remeshed
  // 0.22 % MRMS): the copy is no longer the asset. Those are reported, not asserted
  // (docs/results.md lists them).
  for (const auto& [label, attacked] : {std::pair<std::string, Mesh>{"simplification to 50 %", simplify(m.embedded.mesh, 0.5)},
                                        std::pair<std::string, Mesh>{"remeshing", remesh(m.embedded.mesh)}}) {
    const double distortion = compare_meshes(m.model.mesh, attacked, {20000}).mrms_relative();
    if (distortion < 0.0015) expect_read(m, attacked, label);
    else std::printf("%s not checked on %s: it distorts the mesh by %.2f %% MRMS\n", label.c_str(), GetParam().c_str(), 100 * distortion);
  }
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, EndToEnd,
                         ::testing::Values("bunny.obj", "mannequin.off", "spot.obj", "armadillo.obj"), mesh_name);

// The genus-0 shapes the conformal flow could not map (limbs, claws, a blade, a hand).
INSTANTIATE_TEST_SUITE_P(HardGenusZero, EndToEnd,
                         ::testing::Values("corpus/human_man.obj", "corpus/scorpion_lowres.obj", "corpus/sword.obj",
                                           "corpus/arm.obj"),
                         mesh_name);

// What the sphere cannot take as it is: holes (closed virtually), handles, several parts,
// non-manifold edges and pinches, inconsistent winding, zero-area faces (multiscale bumps).
#define MESHMARK_ANY_MESHES                                                                                     \
  ::testing::Values("kitten.off", "bunny_holes.off", "cow_nonmanifold.obj", "corpus/fertility.off",            \
                    "corpus/rocker-arm.obj", "corpus/face.obj", "corpus/tower_holes.obj", "corpus/human_neutral.obj", \
                    "corpus/mite.obj", "corpus/beetle.obj", "corpus/ogre.obj")
INSTANTIATE_TEST_SUITE_P(AnyMesh, EndToEnd, MESHMARK_ANY_MESHES, mesh_name);
INSTANTIATE_TEST_SUITE_P(AnyMesh, AnyMeshEndToEnd, MESHMARK_ANY_MESHES, mesh_name);

}  // namespace
}  // namespace meshmark
