// What the model cache keeps beside a model: its parsed upload, charged to the memory ceiling
// only while the model itself is kept.

#include "server/model_cache.hpp"

#include <gtest/gtest.h>

#include "core/io/write_mesh.hpp"
#include "tests/server/daemon_process.hpp"
#include "tests/test_data.hpp"

namespace meshmark::server {
namespace {

class ModelCacheUploads : public ::testing::Test {
 protected:
  static std::shared_ptr<const PreparedEntry> entry() {
    static const auto prepared = std::make_shared<const PreparedEntry>(prepare_model(test::creature(2)));
    return prepared;
  }
  static std::shared_ptr<const ParsedUpload> upload() {
    return std::make_shared<const ParsedUpload>(write_mesh_to_memory(test::creature(2), MeshFormat::obj),
                                                MeshFormat::obj, DocumentReadOptions{});
  }
  LocalBlobStore blobs{test::temp_dir("model-cache") / "blobs"};
};

TEST_F(ModelCacheUploads, AnUploadIsKeptBesideItsModelChargedToTheCeilingUntilTheModelGoes) {
  MemoryBudget memory{std::size_t{1} << 30};
  ModelCache models{blobs, 2, memory};
  models.keep("mdl_1", entry());
  const std::size_t model_bytes = memory.reserved();
  EXPECT_EQ(models.upload("mdl_1", MeshFormat::obj), nullptr);

  const auto parsed = upload();
  EXPECT_EQ(parsed->surface.mesh.V.rows(), entry()->model.mesh.V.rows());
  models.keep_upload("mdl_1", parsed, 1000);
  EXPECT_EQ(models.upload("mdl_1", MeshFormat::obj), parsed);
  EXPECT_EQ(models.upload("mdl_1", MeshFormat::ply), nullptr) << "kept for the format it was read in only";
  EXPECT_EQ(memory.reserved(), model_bytes + 1000);

  models.keep_upload("mdl_2", upload(), 1000);  // no such model kept: nothing to keep it beside
  EXPECT_EQ(models.upload("mdl_2", MeshFormat::obj), nullptr);
  EXPECT_EQ(memory.reserved(), model_bytes + 1000);

  models.evict("mdl_1");
  EXPECT_EQ(models.upload("mdl_1", MeshFormat::obj), nullptr);
  EXPECT_EQ(memory.reserved(), 0u);
}

TEST_F(ModelCacheUploads, AnUploadThatFindsNoRoomUnderTheCeilingIsNotKeptAndMakesNone) {
  MemoryBudget memory{std::size_t{1} << 30};
  ModelCache models{blobs, 2, memory};
  models.keep("mdl_1", entry());
  const auto held = memory.try_reserve(memory.available() - 500);  // a job holds all but 500 bytes
  ASSERT_TRUE(held);
  models.keep_upload("mdl_1", upload(), 1000);
  EXPECT_EQ(models.upload("mdl_1", MeshFormat::obj), nullptr);
  models.keep_upload("mdl_1", upload(), 400);  // what fits is kept, and the model stays
  EXPECT_NE(models.upload("mdl_1", MeshFormat::obj), nullptr);
}

}  // namespace
}  // namespace meshmark::server
