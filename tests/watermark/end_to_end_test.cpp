// The watermark's contract on the four shared meshes and the four hard genus-0 meshes of the
// corpus, with the default scheme and strength.
// Each mesh runs as one ctest entry (see tests/CMakeLists.txt) so that its model is prepared
// once and shared by the tests below.

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <mutex>

#include "core/attacks/reorder.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "core/metrics/compare_meshes.hpp"
#include "core/watermark/watermark.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

const std::string kKey = "studio secret 42";
const Bits& payload() {
  static const Bits p = bits_from_hex("c0ffee15deadbeef");
  return p;
}

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
  DetectOptions options;
  options.expected = payload();
  return detect_watermark(m.model, suspect, key, options, m.target.get());
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
  return name.substr(0, name.find('.'));
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, EndToEnd,
                         ::testing::Values("bunny.obj", "mannequin.off", "spot.obj", "armadillo.obj"), mesh_name);

// The genus-0 shapes the conformal flow could not map (limbs, claws, a blade, a hand).
INSTANTIATE_TEST_SUITE_P(HardGenusZero, EndToEnd,
                         ::testing::Values("corpus/human_man.obj", "corpus/scorpion_lowres.obj", "corpus/sword.obj",
                                           "corpus/arm.obj"),
                         mesh_name);

}  // namespace
}  // namespace meshmark
