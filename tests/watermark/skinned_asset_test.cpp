// A skinned, morphing, animated glTF (made here: the creature bound to two joints, one morph
// target, a rotation animation) marked as `meshmark embed` marks it: only the base positions and
// what follows them move; joints, weights, inverse bind matrices, morph deltas and animations
// keep their bytes, so two recipients' copies differ in nothing else; the copy reads in bind pose.

#include <gtest/gtest.h>

#include <fstream>

#include "core/io/document_surface.hpp"
#include "core/mesh/weld_positions.hpp"
#include "core/watermark/watermark.hpp"
#include "tests/io/structural_diff.hpp"
#include "tests/procedural_assets.hpp"
#include "tests/test_data.hpp"
#include "tests/watermark/end_to_end_secrets.hpp"

namespace meshmark {
namespace {

TEST(SkinnedAsset, OnlyBasePositionsMoveAndTheCopyReadsInBindPose) {
  const auto original = test::procedural_asset("skinned-glb");
  const auto marked_folder = test::process_temp_folder("skinned-marked");
  const auto document = read_document_file(original);
  const WeldedSurface surface = document_surface(*document);
  const PreparedModel model = prepare_model(surface.mesh);
  const EmbedResult embedded = embed_watermark(model, test::kEndToEndKey, test::end_to_end_payload());
  const MovedSlots moved = move_slots(*document, surface, embedded.mesh.V);
  const auto marked = marked_folder / "skinned.glb";
  for (const auto& [file, bytes] : document->write(moved.positions, moved.rotations))
    std::ofstream(file.empty() ? marked : marked_folder / file, std::ios::binary) << bytes;

  EXPECT_EQ(test::difference_outside_positions(original, marked), "");
  const Mesh scene = read_document_file(marked)->scene();  // base positions: the bind pose
  const RegistrationTarget target(model.outward_mesh());
  const DetectResult r = test::detect_end_to_end(model, target, weld_positions(scene.V, scene.F).mesh);
  EXPECT_TRUE(r.detected) << "p " << r.p_value;
  ASSERT_TRUE(r.ber.has_value());
  EXPECT_EQ(*r.ber, 0.0);
}

}  // namespace
}  // namespace meshmark
