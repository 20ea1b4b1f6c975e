#include "core/util/atomic_file.hpp"

#include "tests/procedural_meshes.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

namespace meshmark {
namespace {

// A folder of this test's own: ctest runs tests of one program as processes side by side, and a
// name from gtest's time-based seed was shared by two started in the same millisecond.
std::filesystem::path scratch() {
  const auto dir =
      test::process_temp_folder("meshmark-atomic") / ::testing::UnitTest::GetInstance()->current_test_info()->name();
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

// Files of a megabyte and more go past the page cache in aligned blocks, the last one padded and
// cut: every length reads back to the byte, over the smaller version it replaces too.
TEST(AtomicFile, LargeFilesAreWrittenToTheByteWhateverTheirLength) {
  const auto dir = scratch();
  create_directories_durably(dir);
  const auto file = dir / "large";
  for (const std::size_t size :
       {std::size_t{1} << 20, (std::size_t{1} << 20) + 1, (std::size_t{3} << 20) + 4095, std::size_t{5000000}}) {
    std::string bytes(size, '\0');
    for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<char>('a' + (i * 7919) % 26);
    write_file_atomically(file, bytes);
    EXPECT_EQ(std::filesystem::file_size(file), size);
    EXPECT_TRUE(read(file) == bytes) << size;
  }
  write_file_atomically(file, "small again");
  EXPECT_EQ(read(file), "small again");
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
