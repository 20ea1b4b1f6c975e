#include "core/io/mesh_document.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <stdexcept>

#include "core/io/mesh_io_error.hpp"
#include "core/io/document_surface.hpp"
#include "tests/io/document_helpers.hpp"
#include "tests/io/structural_diff.hpp"
#include "tests/procedural_assets.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// The twelve shared assets and those made here, by their main file, and how closely a moved position comes back
// (a fraction of the bounding-box diagonal): the precision the file stores positions with.
struct Asset {
  const char* path;  ///< under the shared assets, or "procedural/<kind>" (tests/procedural_assets.hpp)
  double tolerance;
};
const Asset kAssets[] = {
    {"procedural/gltf", 1e-6},
    {"procedural/glb", 1e-6},
    {"procedural/obj", 1e-6},  // nine digits
    {"procedural/ply", 1e-6},
    {"procedural/stl", 1e-6},
    {"procedural/3mf", 1e-6},
    {"Duck/glTF-Binary/Duck.glb", 1e-6},
    {"BoxTextured/glTF-Binary/BoxTextured.glb", 1e-6},
    {"Avocado/glTF/Avocado.gltf", 1e-6},
    {"Avocado-Quantized/glTF-Quantized/Avocado.gltf", 5e-5},  // u16 steps of 3.8e-6 on a diagonal of 0.08
    {"WaterBottle-Draco/glTF-Draco/WaterBottle.gltf", 1e-3},  // Draco, 11 bits
    {"CesiumMilkTruck/glTF-Binary/CesiumMilkTruck.glb", 1e-6},
    {"MorphPrimitivesTest/glTF-Binary/MorphPrimitivesTest.glb", 1e-6},
    {"spot-cow-obj/cow.obj", 1e-5},  // six decimals
    {"sword-obj/UV.obj", 1e-5},
    {"frag115-ply/frag_115.ply", 1e-6},
    {"idler_riser-stl/idler_riser.STL", 1e-6},
    {"sphere_logo-3mf/sphere_logo.3mf", 1e-5},
};

std::string asset_name(const ::testing::TestParamInfo<Asset>& info) {
  std::string name = info.param.path;
  name = name.rfind("procedural/", 0) == 0 ? "procedural_" + name.substr(11) : name.substr(0, name.find('/'));
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

bool is_draco(const MeshDocument& doc) {
  for (const DocumentPart& p : doc.parts())
    for (const std::string& a : p.attributes)
      if (a.rfind("KHR_draco_mesh_compression", 0) == 0) return true;
  return false;
}

class AssetDocument : public ::testing::TestWithParam<Asset> {
 protected:
  void SetUp() override { MESHMARK_NEEDS_SHARED_FOR(GetParam().path); }
};

TEST_P(AssetDocument, UnchangedPositionsWriteTheInputBackByteForByte) {
  const auto path = test::named_asset(GetParam().path);
  const auto doc = read_document_file(path);
  const DocumentFiles files = doc->write(doc->slot_positions(), {});
  EXPECT_EQ(files.size(), 1u);
  EXPECT_TRUE(files.at("") == read_file_bytes(path, 1u << 30));
}

TEST_P(AssetDocument, MovedPositionsComeBackAtTheFilesPrecision) {
  const auto path = test::named_asset(GetParam().path);
  const auto doc = read_document_file(path);
  const Vertices P = test::moved(doc->slot_positions(), 2e-3);
  const auto back = test::read_written(doc->write(P, {}), path);
  ASSERT_EQ(back->slot_positions().rows(), P.rows());
  double error = 0;
  if (!is_draco(*doc)) {
    error = (back->slot_positions() - P).rowwise().norm().maxCoeff();
  } else {  // Draco numbers its points anew when it encodes: compare as point sets
    const Vertices& Q = back->slot_positions();
    for (Eigen::Index i = 0; i < Q.rows(); ++i)
      error = std::max(error, (P.rowwise() - Q.row(i)).rowwise().norm().minCoeff());
  }
  EXPECT_LT(error, GetParam().tolerance * test::diagonal(P)) << "of a diagonal " << test::diagonal(P);
}

TEST_P(AssetDocument, MovedPositionsKeepTrianglesAndParts) {
  const auto path = test::named_asset(GetParam().path);
  const auto doc = read_document_file(path);
  const auto back = test::read_written(doc->write(test::moved(doc->slot_positions(), 2e-3), {}), path);
  if (is_draco(*doc)) EXPECT_EQ(back->slot_triangles().rows(), doc->slot_triangles().rows());
  else EXPECT_TRUE(back->slot_triangles() == doc->slot_triangles());
  const std::vector<DocumentPart> before = doc->parts(), after = back->parts();
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i) {
    const DocumentPart &a = before[i], &b = after[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.stored_vertices, b.stored_vertices) << a.name;
    EXPECT_EQ(a.triangles, b.triangles) << a.name;
    EXPECT_EQ(a.instances, b.instances) << a.name;
    EXPECT_EQ(a.attributes, b.attributes) << a.name;
  }
}

// The surface moved as embed moves it (welded copies together, normals turned with it): the
// written file differs from the input only in positions, normals and what describes them.
TEST_P(AssetDocument, MovingTheSurfaceChangesNothingButPositionsAndNormals) {
  const auto path = test::named_asset(GetParam().path);
  const auto doc = read_document_file(path);
  const WeldedSurface surface = document_surface(*doc);
  const MovedSlots moved = move_slots(*doc, surface, test::moved(surface.mesh.V, 2e-3));
  const DocumentFiles files = doc->write(moved.positions, moved.rotations);
  const auto folder = std::filesystem::temp_directory_path() / ("meshmark-structure-" + asset_name({GetParam(), 0}));
  std::filesystem::create_directories(folder);
  for (const auto& [name, bytes] : files)
    if (!name.empty()) std::ofstream(folder / name, std::ios::binary) << bytes;
  EXPECT_EQ(test::difference_outside_positions(read_file_bytes(path, 1u << 30), files.at(""), doc->format(),
                                               path.parent_path(), folder),
            "");
  EXPECT_NE(files.at(""), read_file_bytes(path, 1u << 30));
  std::filesystem::remove_all(folder);
}

// A document that says it turns no stored directions (move_slots then spares computing the turns)
// writes the same bytes whatever they are.
TEST_P(AssetDocument, ADocumentThatTurnsNoDirectionsIgnoresTheirTurns) {
  const auto doc = read_document_file(test::named_asset(GetParam().path));
  if (doc->turns_directions()) GTEST_SKIP() << "it turns its directions";
  const Vertices P = test::moved(doc->slot_positions(), 2e-3);
  const NormalRotations turned(static_cast<std::size_t>(P.rows()),
                               Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized())));
  EXPECT_TRUE(doc->write(P, turned) == doc->write(P, {}));
}

// A reader that welded already (STL's) spares document_surface welding again: the surface is
// what welding the scene gives, vertex for vertex and face for face.
TEST_P(AssetDocument, TheSurfaceIsTheWeldOfTheSceneWhetherOrNotTheReaderWelded) {
  const auto doc = read_document_file(test::named_asset(GetParam().path));
  const Mesh scene = doc->scene();
  const WeldedSurface welded = weld_positions(scene.V, scene.F), surface = document_surface(*doc);
  EXPECT_TRUE(surface.mesh.V == welded.mesh.V);
  EXPECT_TRUE(surface.mesh.F == welded.mesh.F);
  EXPECT_EQ(surface.vertex_of, welded.vertex_of);
  EXPECT_EQ(surface.face_of, welded.face_of);
  EXPECT_EQ(surface.welded_copies + surface.collapsed_triangles + surface.duplicate_triangles,
            welded.welded_copies + welded.collapsed_triangles + welded.duplicate_triangles);
  if (doc->format() == MeshFormat::stl) {
    EXPECT_TRUE(doc->scene_welded());
  }
}

// A document read only to be read (a copy read back, a suspect) holds the same scene; one that
// then keeps nothing for writing refuses to write rather than write something else.
TEST_P(AssetDocument, ADocumentReadOnlyToBeReadHoldsTheSameScene) {
  const auto path = test::named_asset(GetParam().path);
  DocumentReadOptions read_only;
  read_only.for_writing = false;
  const auto full = read_document_file(path), reading = read_document_file(path, read_only);
  const Mesh a = full->scene(), b = reading->scene();
  EXPECT_TRUE(a.V == b.V);
  EXPECT_TRUE(a.F == b.F);
  if (reading->format() == MeshFormat::ply || reading->format() == MeshFormat::obj) {
    EXPECT_THROW(reading->write(reading->slot_positions(), {}), std::logic_error);
  }
}

TEST_P(AssetDocument, TheSceneHoldsEveryInstance) {
  const auto doc = read_document_file(test::named_asset(GetParam().path));
  std::size_t triangles = 0;
  for (const DocumentPart& p : doc->parts()) triangles += p.triangles * p.instances;
  EXPECT_EQ(static_cast<std::size_t>(doc->scene().F.rows()), triangles);
}

INSTANTIATE_TEST_SUITE_P(Shared, AssetDocument, ::testing::ValuesIn(kAssets), asset_name);

}  // namespace
}  // namespace meshmark

namespace meshmark {
namespace {

// An OBJ naming its material libraries: each once however often it is named, and no more than
// kMaxCompanions in all (a line of a million names must not cost a million list searches).
// A facet whose corners weld together leaves the STL reader's vertices on no kept triangle: the
// scene is then not taken as welded, and the surface leaves them out as welding does.
TEST(StlDocument, AFacetCollapsedByWeldingLeavesTheSurfaceToTheWelder) {
  const std::string stl =
      "solid t\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
      "facet normal 0 0 1\nouter loop\nvertex 5 5 5\nvertex 5 5 5\nvertex 6 6 6\nendloop\nendfacet\n"
      "endsolid t\n";
  const auto doc = read_document(stl, MeshFormat::stl);
  EXPECT_FALSE(doc->scene_welded());
  const WeldedSurface surface = document_surface(*doc);
  EXPECT_EQ(surface.mesh.V.rows(), 3);
  EXPECT_EQ(surface.mesh.F.rows(), 1);
}

TEST(ObjDocument, MaterialLibrariesAreListedOnceAndWithinTheirLimit) {
  const std::string tetrahedron = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::string names;
  for (std::size_t k = 0; k < kMaxCompanions; ++k) names += " lib" + std::to_string(k) + ".mtl";
  const auto listed = read_document("mtllib" + names + names + "\n" + tetrahedron, MeshFormat::obj, {}, "a.obj");
  EXPECT_EQ(listed->companions().size(), kMaxCompanions);
  try {
    read_document("mtllib" + names + " one-more.mtl\n" + tetrahedron, MeshFormat::obj, {}, "b.obj");
    FAIL() << "read";
  } catch (const MeshLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("more than " + std::to_string(kMaxCompanions) + " companion files"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace meshmark
