#include "client/commands/stored_originals.hpp"

#include <gtest/gtest.h>

#include "core/attacks/reorder.hpp"
#include "core/attacks/round_digits.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "core/io/mesh_document.hpp"
#include "core/io/write_mesh.hpp"
#include "core/mesh/mesh_digest.hpp"
#include "core/util/atomic_file.hpp"
#include "core/watermark/prepared_model_io.hpp"
#include "core/watermark/watermark.hpp"
#include "tests/procedural_meshes.hpp"

namespace meshmark::cli {
namespace {

namespace fs = std::filesystem;

// A records folder as `embed` leaves it: the creature stored on the tetrahedral grid, beside
// files that are not stored originals.
fs::path folder_storing_the_creature() {
  const fs::path folder = test::process_temp_folder("stored-originals") / "records";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const PreparedModel model = prepare_model(test::procedural_mesh("creature"));
  const fs::path stem = folder / stored_original_stem(model.digest, BaseSolid::tetrahedron);
  write_file_atomically(fs::path(stem).concat(".ply"),
                        write_mesh_to_memory(model.mesh, MeshFormat::ply, {.binary = true}));
  write_file_atomically(fs::path(stem).concat(".prepared"), serialize_prepared_model(model));
  write_file_atomically(folder / "meshmark-original-0123-tetra.ply", "ply\nend_header\n");  // a name too short
  write_file_atomically(folder / "copy.ply-0123456789abcdef.record.json", "{}");
  return folder;
}

// The master re-exported since (6 digits, renumbered, moved) is found as the stored original and
// loaded as it was prepared, so a copy marked on it reads as before; the exact file needs no
// search (its own preparation is the stored one), another base or another shape finds none.
TEST(StoredOriginals, AReExportedMasterIsFoundAsTheOriginalStoredAndPreparedBeforeIt) {
  const fs::path folder = folder_storing_the_creature();
  const std::vector<StoredOriginal> stored = stored_originals_in(folder, BaseSolid::tetrahedron);
  ASSERT_EQ(stored.size(), 1u);
  const Mesh& creature = test::procedural_mesh("creature");
  EXPECT_EQ(stored[0].vertices, creature.V.rows());
  EXPECT_EQ(stored[0].faces, creature.F.rows());
  EXPECT_TRUE(stored_originals_in(folder, BaseSolid::octahedron).empty());
  EXPECT_TRUE(stored_originals_in(folder / "absent", BaseSolid::tetrahedron).empty());

  const Mesh exported = round_digits(reorder(transform_mesh(creature, random_similarity(creature, 5)), 6), 6);
  const std::vector<FoundOriginal> found = find_stored_originals(exported, stored, nullptr);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].model.digest, mesh_digest(creature));
  EXPECT_EQ(found[0].mesh_file, stored[0].mesh_file);
  EXPECT_LT(found[0].mrms_relative, 1e-6);
  const Bits payload = bits_from_hex("0123456789abcdef");
  const Mesh copy = embed_watermark(prepare_model(creature), "k", payload).mesh;
  EXPECT_EQ(detect_watermark(found[0].model, copy, "k").payload, payload);

  EXPECT_TRUE(find_stored_originals(creature, stored, nullptr).empty());
  EXPECT_TRUE(find_stored_originals(test::procedural_mesh("torus"), stored, nullptr).empty());
}

}  // namespace
}  // namespace meshmark::cli
