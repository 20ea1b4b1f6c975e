#include <gtest/gtest.h>

#include "core/io/mesh_document.hpp"
#include "core/io/mesh_io_error.hpp"
#include "core/io/zip_archive.hpp"
#include "tests/procedural_assets.hpp"

namespace meshmark {
namespace {

// A package (texture, relationships and content types) around a model small enough to check by hand.
std::string package_with(const std::string& model) { return test::threemf_package(model); }

std::string model_of(const std::string& package) {
  const ZipArchive zip(package, 1u << 30, "p");
  return zip.extract(*zip.find("3D/3dmodel.model"));
}

constexpr const char* kHeader =
    R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
)";
constexpr const char* kTetrahedron = R"(
  <object id="1" type="model" name="tet"><mesh><vertices>
    <vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/><vertex x="0" y="0" z="1"/>
  </vertices><triangles>
    <triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="1" v3="3"/><triangle v1="0" v2="3" v3="2"/><triangle v1="1" v2="2" v3="3"/>
  </triangles></mesh></object>)";

// A tetrahedron placed twice: scaled by 2 and raised by 5, and through a component moved by 10 in x.
std::string two_placements() {
  return std::string(kHeader) + " <resources>" + kTetrahedron + R"(
  <object id="2"><components><component objectid="1" transform="1 0 0 0 1 0 0 0 1 10 0 0"/></components></object>
 </resources>
 <build><item objectid="1" transform="2 0 0 0 2 0 0 0 2 0 0 5"/><item objectid="2"/></build>
</model>)";
}

std::unique_ptr<MeshDocument> read_3mf(const std::string& package) {
  return read_document(package, MeshFormat::threemf, {}, "test.3mf");
}

TEST(ThreeMfDocument, SlotsAreTheFirstPlacementInWorldSpace) {
  const auto doc = read_3mf(package_with(two_placements()));
  ASSERT_EQ(doc->slot_positions().rows(), 4);
  EXPECT_EQ(doc->slot_positions().row(1), Eigen::RowVector3d(2, 0, 5));
  EXPECT_EQ(doc->slot_positions().row(3), Eigen::RowVector3d(0, 0, 7));
  EXPECT_EQ(doc->slot_triangles().rows(), 4);
}

TEST(ThreeMfDocument, TheSceneHoldsEveryPlacement) {
  const auto doc = read_3mf(package_with(two_placements()));
  const Mesh scene = doc->scene();
  ASSERT_EQ(scene.V.rows(), 8);
  EXPECT_EQ(scene.V.row(5), Eigen::RowVector3d(11, 0, 0));
  ASSERT_EQ(doc->parts().size(), 1u);
  EXPECT_EQ(doc->parts()[0].instances, 2u);
  EXPECT_EQ(doc->parts()[0].name, "object 1 'tet'");
}

TEST(ThreeMfDocument, MovedVertexIsWrittenInObjectSpaceAndNothingElseChanges) {
  const std::string model = two_placements();
  const auto doc = read_3mf(package_with(model));
  Vertices P = doc->slot_positions();
  P.row(1) << 3, 0, 5;  // object space (1.5, 0, 0)
  const std::string written = doc->write(P, {}).at("");
  std::string expected = model;
  expected.replace(expected.find(R"(<vertex x="1")") + 11, 1, "1.5");
  EXPECT_EQ(model_of(written), expected);
  EXPECT_EQ(read_3mf(written)->slot_positions().row(1), Eigen::RowVector3d(3, 0, 5));
}

TEST(ThreeMfDocument, EveryOtherPartOfThePackageKeepsItsBytes) {
  const std::string bytes = read_file_bytes(test::procedural_asset("3mf"), 1u << 30);
  const auto doc = read_3mf(bytes);
  Vertices P = doc->slot_positions();
  P.row(0).array() += 0.5;
  const std::string written = doc->write(P, {}).at("");
  const ZipArchive before(bytes, 1u << 30, "a"), after(written, 1u << 30, "b");
  for (const ZipEntry& e : before.entries()) {
    const ZipEntry* w = after.find(e.name);
    ASSERT_NE(w, nullptr) << e.name;
    if (e.name == "3D/3dmodel.model") continue;
    EXPECT_EQ(written.substr(w->data, w->compressed_size), bytes.substr(e.data, e.compressed_size)) << e.name;
  }
}

// The message a model part makes reading fail with.
std::string error_of(const std::string& model) {
  try {
    read_3mf(package_with(model));
  } catch (const MeshIoError& e) {
    return e.what();
  }
  return "";
}

TEST(ThreeMfDocument, BrokenModelsAreRefusedWithAReason) {
  const std::string resources = std::string(kHeader) + " <resources>" + kTetrahedron;
  EXPECT_NE(error_of(resources + "</resources><build><item objectid=\"9\"/></build></model>").find("not defined"),
            std::string::npos);
  EXPECT_NE(error_of(resources + "</resources><build></build></model>").find("no item"), std::string::npos);
  EXPECT_NE(error_of(resources + R"(<object id="3"><components><component objectid="3"/></components></object>
    </resources><build><item objectid="3"/></build></model>)")
                .find("deeper than 32"),
            std::string::npos);
  EXPECT_NE(error_of("<!DOCTYPE model [<!ENTITY a \"b\">]>" + resources + "</resources></model>").find("DOCTYPE"),
            std::string::npos);
  EXPECT_NE(
      error_of(std::string(kHeader) + R"(<resources><object id="1"><mesh><vertices><vertex x="0" y="nan" z="0"/>)")
          .find("not a finite number"),
      std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + R"(<resources><object id="1"><mesh><vertices><vertex x="0" y="0" z="0"/>
    </vertices><triangles><triangle v1="0" v2="1" v3="2"/></triangles></mesh></object></resources>
    <build><item objectid="1"/></build></model>)")
                .find("refers to vertex"),
            std::string::npos);
  // 2^63 and 2^64 − 1: an index that wrapped negative once passed the range check.
  for (const char* huge : {"9223372036854775808", "18446744073709551615"})
    EXPECT_NE(
        error_of(std::string(kHeader) + R"(<resources><object id="1"><mesh><vertices><vertex x="0" y="0" z="0"/>
    <vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/></vertices><triangles><triangle v1="0" v2="1" v3=")" +
                 huge + R"("/></triangles></mesh></object></resources><build><item objectid="1"/></build></model>)")
            .find("refers to vertex"),
        std::string::npos)
        << huge;
  EXPECT_NE(error_of("<model xmlns=\"urn:other\"></model>").find("core namespace"), std::string::npos);
}

// Components that each place the next level twice: a kilobyte that would place the tetrahedron
// 2^30 times. Refused once its instances pass the scene's budget, before they cost much.
TEST(ThreeMfDocument, AComponentHierarchyThatRepeatsItselfIsRefusedWithinTheSceneBudget) {
  std::string model = std::string(kHeader) + " <resources>" + kTetrahedron;
  for (int level = 2; level <= 31; ++level)
    model += "<object id=\"" + std::to_string(level) + "\"><components><component objectid=\"" +
             std::to_string(level - 1) + "\"/><component objectid=\"" + std::to_string(level - 1) +
             "\" transform=\"1 0 0 0 1 0 0 0 1 1 0 0\"/></components></object>";
  model += "</resources><build><item objectid=\"31\"/></build></model>";
  const std::string error = error_of(model);
  EXPECT_NE(error.find("more than 10000 times over"), std::string::npos) << error;
}

}  // namespace
}  // namespace meshmark
