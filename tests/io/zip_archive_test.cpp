#include "core/io/zip_archive.hpp"

#include <gtest/gtest.h>

#include "core/io/mesh_document.hpp"
#include "core/io/mesh_io_error.hpp"
#include "core/io/packaged_document.hpp"
#include "tests/procedural_assets.hpp"

namespace meshmark {
namespace {

// A 3MF package of five deflated entries, as a zip tool writes them.
const std::string kModel = "<?xml version=\"1.0\"?>\n<model>" + std::string(200'000, ' ') + "</model>\n";
std::string package() { return test::threemf_package(kModel); }

TEST(ZipArchive, ListsTheEntriesOfA3mfPackage) {
  const ZipArchive zip(package(), 1u << 30, "p");
  ASSERT_EQ(zip.entries().size(), 5u);
  EXPECT_NE(zip.find("3D/3dmodel.model"), nullptr);
  EXPECT_NE(zip.find("3d/3DMODEL.model"), nullptr);  // OPC names compare without case
  EXPECT_EQ(zip.find("3D/other.model"), nullptr);
}

TEST(ZipArchive, ExtractedEntriesMatchTheirCrc) {
  const ZipArchive zip(package(), 1u << 30, "p");
  const std::string model = zip.extract(*zip.find("3D/3dmodel.model"));
  EXPECT_EQ(model, kModel);
}

// A small archive whose one entry is extracted again and again (a glTF whose buffers all name one
// file): every extraction counts against one budget, a multiple of the archive's size.
TEST(ZipArchive, ExtractionsTogetherStayWithinTheInflateBudget) {
  const std::string bytes = package();
  ASSERT_LT(bytes.size() * kMaxInflateRatio, kMinInflateBudget);  // the floor is the budget here
  const ZipArchive zip(bytes, 1u << 30, "p");
  const ZipEntry& model = *zip.find("3D/3dmodel.model");
  std::size_t inflated = 0;
  try {
    for (int k = 0; k < 1000; ++k) inflated += zip.extract(model).size();
    FAIL() << "extracted a thousand times";
  } catch (const MeshLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("more than " + std::to_string(kMinInflateBudget) + " bytes together"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LE(inflated, kMinInflateBudget);
  EXPECT_GT(inflated + model.size, kMinInflateBudget);
}

TEST(ZipArchive, NoNewContentsGivesTheSameBytes) {
  const std::string bytes = package();
  EXPECT_TRUE(ZipArchive(bytes, 1u << 30, "p").with_contents({}) == bytes);
}

TEST(ZipArchive, ReplacedEntryReadsBackAndTheOthersKeepTheirBytes) {
  const std::string bytes = package();
  const ZipArchive zip(bytes, 1u << 30, "p");
  const std::string texture = "3D/Textures/texture.png";
  const std::string written = zip.with_contents({{"3D/3dmodel.model", "<model>new</model>"}});
  const ZipArchive back(written, 1u << 30, "p");
  ASSERT_EQ(back.entries().size(), zip.entries().size());
  EXPECT_EQ(back.extract(*back.find("3D/3dmodel.model")), "<model>new</model>");
  const ZipEntry &a = *zip.find(texture), &b = *back.find(texture);
  EXPECT_EQ(written.substr(b.data, b.compressed_size), bytes.substr(a.data, a.compressed_size));
  EXPECT_EQ(back.extract(b), zip.extract(a));
}

TEST(ZipArchive, CorruptDataFailsItsCrc) {
  std::string bytes = package();
  const ZipArchive zip(bytes, 1u << 30, "p");
  const ZipEntry& rels = *zip.find("_rels/.rels");
  bytes[rels.data + 10] ^= 0x55;
  const ZipArchive damaged(bytes, 1u << 30, "p");
  EXPECT_THROW(damaged.extract(*damaged.find("_rels/.rels")), MeshIoError);
}

TEST(ZipArchive, EntryAboveTheLimitIsALimitErrorBeforeInflating) {
  const ZipArchive zip(package(), 100'000, "p");
  EXPECT_THROW(zip.extract(*zip.find("3D/3dmodel.model")), MeshLimitError);
}

TEST(ZipArchive, WhatIsNotZipIsRefusedWithAReason) {
  try {
    ZipArchive(std::string(100, 'x'), 1u << 30, "p");
    FAIL();
  } catch (const MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("not a ZIP archive"), std::string::npos);
  }
  std::string truncated = package();
  truncated.resize(truncated.size() / 2);
  EXPECT_THROW(ZipArchive(truncated, 1u << 30, "p"), MeshIoError);
}

// What write_zip packs, the reader gives back: each entry, in order, byte for byte.
TEST(WriteZip, EveryFileReadsBackInItsOrder) {
  std::string binary(70'000, '\0');
  for (std::size_t i = 0; i < binary.size(); ++i) binary[i] = static_cast<char>(i * 7 % 256);
  const std::vector<std::pair<std::string, std::string>> files = {
      {"chair.gltf", "{\"asset\":{}}"}, {"chair.bin", binary}, {"textures/wood grain.png", ""}};
  const ZipArchive zip(write_zip(files), 1u << 30, "written");
  ASSERT_EQ(zip.entries().size(), files.size());
  for (std::size_t k = 0; k < files.size(); ++k) {
    EXPECT_EQ(zip.entries()[k].name, files[k].first);
    EXPECT_EQ(zip.extract(zip.entries()[k]), files[k].second) << files[k].first;
  }
  EXPECT_TRUE(looks_zipped(zip.bytes()));
}

TEST(WriteZip, NamesThatCouldEscapeOrRepeatAreRefused) {
  for (const std::string& name : {std::string(), std::string("/etc/passwd"), std::string("../x"), std::string("a\\b")})
    EXPECT_THROW(write_zip({{name, "x"}}), MeshIoError) << name;
  EXPECT_THROW(write_zip({{"a.obj", "x"}, {"a.obj", "y"}}), MeshIoError);
}

}  // namespace
}  // namespace meshmark
