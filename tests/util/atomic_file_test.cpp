#include "core/util/atomic_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

namespace meshmark {
namespace {

std::filesystem::path scratch() {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("meshmark-atomic-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::remove_all(dir);
  return dir;
}

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(AtomicFile, ReplacesTheWholeFileAndLeavesNoTemporary) {
  const auto dir = scratch();
  create_directories_durably(dir / "a" / "b");
  ASSERT_TRUE(std::filesystem::is_directory(dir / "a" / "b"));
  const auto file = dir / "a" / "b" / "blob";
  write_file_atomically(file, "first version, longer");
  write_file_atomically(file, "second");
  EXPECT_EQ(read(file), "second");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir / "a" / "b"), std::filesystem::directory_iterator()),
            1);
  std::filesystem::remove_all(dir);
}

TEST(AtomicFile, AnUnwritableDirectoryIsAnErrorNamingThePath) {
  try {
    write_file_atomically("/proc/meshmark-no/such", "x");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/meshmark-no"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace meshmark
