#include "core/io/read_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "core/io/write_mesh.hpp"
#include "tests/io/read_error.hpp"
#include "tests/procedural_assets.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

using test::read_error;

TEST(ReadMesh, SharedMeshesHaveTheirDocumentedCounts) {
  MESHMARK_NEEDS_SHARED();
  const std::pair<const char*, std::array<int, 2>> expected[] = {
      {"bunny.obj", {34817, 69630}},        {"mannequin.off", {11703, 23402}}, {"spot.obj", {2930, 5856}},
      {"armadillo.obj", {43243, 86482}},    {"kitten.off", {2500, 5000}},      {"bunny_holes.off", {34834, 69451}},
      {"cow_nonmanifold.obj", {2903, 5804}}};
  for (const auto& [name, counts] : expected) {
    const Mesh& mesh = test::load_shared(name);
    EXPECT_EQ(mesh.V.rows(), counts[0]) << name;
    EXPECT_EQ(mesh.F.rows(), counts[1]) << name;
  }
}

TEST(ReadMesh, ObjWithTextureCornersUsesPositionIndices) {
  const Mesh obj = read_mesh(test::procedural_asset("obj")).mesh;  // faces "f v/vt/vn"
  EXPECT_EQ(obj.F.minCoeff(), 0);
  EXPECT_EQ(obj.F.maxCoeff(), obj.V.rows() - 1);
}

TEST(ReadMesh, ExponentWithThreeDigitsParses) {
  const auto r = read_mesh_from_memory("OFF\n3 1 0\n-3.67632e-005 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::off);
  EXPECT_DOUBLE_EQ(r.mesh.V(0, 0), -3.67632e-5);
}

TEST(ReadMesh, ObjNegativeIndicesCountBack) {
  const auto r = read_mesh_from_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n", MeshFormat::obj);
  EXPECT_EQ(r.mesh.F.row(0), Eigen::RowVector3i(0, 1, 2));
}

TEST(ReadMesh, QuadsAreFanTriangulatedAndCounted) {
  const auto r = read_mesh_from_memory("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", MeshFormat::obj);
  ASSERT_EQ(r.mesh.F.rows(), 2);
  EXPECT_EQ(r.polygons_triangulated, 1u);
  EXPECT_EQ(r.mesh.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(r.mesh.F.row(1), Eigen::RowVector3i(0, 2, 3));
}

class RoundTrip : public ::testing::TestWithParam<std::tuple<MeshFormat, bool, bool>> {};

TEST_P(RoundTrip, KeepsVertexOrderFacesAndExactCoordinatesWhenAskedToBeLossless) {
  const auto [format, binary, big_endian] = GetParam();
  Mesh mesh = test::procedural_mesh("creature_large");
  // STL has no vertex list: a mesh read from STL numbers vertices by first appearance, and it
  // is such a mesh that must come back unchanged.
  if (format == MeshFormat::stl) mesh = read_mesh_from_memory(write_mesh_to_memory(mesh, format), format).mesh;
  const std::string bytes = write_mesh_to_memory(mesh, format, {binary, big_endian, /*lossless_text=*/true});
  const Mesh back = read_mesh_from_memory(bytes, format).mesh;
  ASSERT_EQ(back.V.rows(), mesh.V.rows());
  EXPECT_TRUE(back.V == mesh.V);  // bit for bit
  EXPECT_TRUE(back.F == mesh.F);
}

// By default text keeps 1e-7 of the diagonal: every coordinate within half of that, the file
// about a third smaller than with every double's 17 digits.
TEST_P(RoundTrip, TextKeepsATenMillionthOfTheDiagonalByDefault) {
  const auto [format, binary, big_endian] = GetParam();
  if (binary || format == MeshFormat::stl) GTEST_SKIP() << "binary files store the numbers; STL renumbers";
  Mesh mesh = test::procedural_mesh("creature_large");
  mesh.V = mesh.V * 0.3 + Eigen::MatrixXd::Constant(mesh.V.rows(), 3, 7.0);  // an extent and an offset
  const double diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  const std::string rounded = write_mesh_to_memory(mesh, format);
  const Mesh back = read_mesh_from_memory(rounded, format).mesh;
  ASSERT_EQ(back.V.rows(), mesh.V.rows());
  EXPECT_TRUE(back.F == mesh.F);
  const double quantum = std::pow(10.0, std::floor(std::log10(1e-7 * diagonal)));
  EXPECT_LE((back.V - mesh.V).cwiseAbs().maxCoeff(), 0.5 * quantum * (1 + 1e-9));
  EXPECT_GT((back.V - mesh.V).cwiseAbs().maxCoeff(), 0.0);  // rounded indeed
  const std::string lossless = write_mesh_to_memory(mesh, format, {.lossless_text = true});
  EXPECT_LT(rounded.size(), lossless.size() * 3 / 4) << rounded.size() << " vs " << lossless.size();
}

INSTANTIATE_TEST_SUITE_P(
    Formats, RoundTrip,
    ::testing::Values(std::tuple{MeshFormat::obj, false, false}, std::tuple{MeshFormat::off, false, false},
                      std::tuple{MeshFormat::ply, false, false}, std::tuple{MeshFormat::ply, true, false},
                      std::tuple{MeshFormat::ply, true, true}, std::tuple{MeshFormat::stl, false, false}));

TEST(ReadMesh, BinaryStlRoundTripsFloatCoordinatesAndWeldsCorners) {
  Mesh mesh = test::icosphere(2);
  mesh.V = mesh.V.cast<float>().cast<double>();  // binary STL holds floats
  const std::string bytes = write_mesh_to_memory(mesh, MeshFormat::stl, {.binary = true});
  EXPECT_EQ(bytes.size(), 84 + 50 * static_cast<std::size_t>(mesh.F.rows()));
  const ReadResult first = read_mesh_from_memory(bytes, MeshFormat::stl);
  EXPECT_EQ(first.mesh.V.rows(), mesh.V.rows());
  // Welded corners are numbered by first appearance: corner k of face f is the same point.
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(first.mesh.V.row(first.mesh.F(f, k)) == mesh.V.row(mesh.F(f, k)));
  const std::string again = write_mesh_to_memory(first.mesh, MeshFormat::stl, {.binary = true});
  const ReadResult second = read_mesh_from_memory(again, MeshFormat::stl);
  EXPECT_TRUE(second.mesh.V == first.mesh.V);
  EXPECT_TRUE(second.mesh.F == first.mesh.F);
}

TEST(ReadMesh, ParallelReadsOfDifferentFilesAgreeWithSerialReads) {
  const std::vector<std::filesystem::path> names = {
      test::procedural_file("creature_large"), test::procedural_file("creature_large", "off"),
      test::procedural_file("creature"), test::procedural_file("torus", "off")};
  std::vector<Mesh> serial;
  for (const auto& n : names) serial.push_back(read_mesh(n).mesh);
  std::vector<Mesh> parallel(names.size() * 2);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < parallel.size(); ++i)
    threads.emplace_back([&, i] { parallel[i] = read_mesh(names[i % names.size()]).mesh; });
  for (auto& t : threads) t.join();
  for (std::size_t i = 0; i < parallel.size(); ++i) {
    EXPECT_TRUE(parallel[i].V == serial[i % names.size()].V) << names[i % names.size()];
    EXPECT_TRUE(parallel[i].F == serial[i % names.size()].F) << names[i % names.size()];
  }
}

TEST(ReadMeshErrors, TruncatedOff) {
  EXPECT_NE(read_error("OFF\n4 2 0\n0 0 0\n1 0 0\n", MeshFormat::off).find("truncated"), std::string::npos);
}

TEST(ReadMeshErrors, TruncatedBinaryPly) {
  const Mesh mesh = test::icosphere(1);
  std::string bytes = write_mesh_to_memory(mesh, MeshFormat::ply, {.binary = true});
  bytes.resize(bytes.size() - 7);
  EXPECT_NE(read_error(bytes, MeshFormat::ply).find("truncated"), std::string::npos);
}

TEST(ReadMeshErrors, GarbageIsRefusedInEveryFormat) {
  std::string garbage(4096, '\0');
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<char>((i * 7919u) % 251u);
  for (MeshFormat f : {MeshFormat::obj, MeshFormat::off, MeshFormat::ply, MeshFormat::stl})
    EXPECT_FALSE(read_error(garbage, f).empty()) << to_string(f);
}

TEST(ReadMeshErrors, EmptyInputIsRefused) {
  for (MeshFormat f : {MeshFormat::obj, MeshFormat::off, MeshFormat::ply, MeshFormat::stl})
    EXPECT_FALSE(read_error("", f).empty()) << to_string(f);
}

TEST(ReadMeshErrors, HeaderClaimingATrillionVerticesFailsFastWithoutAllocating) {
  EXPECT_NE(read_error("OFF\n1000000000000 1 0\n0 0 0\n", MeshFormat::off).find("truncated"), std::string::npos);
  const std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0000";
  EXPECT_NE(read_error(ply, MeshFormat::ply).find("claims"), std::string::npos);
}

TEST(ReadMeshErrors, NanAndInfiniteCoordinates) {
  EXPECT_NE(read_error("v 0 nan 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::obj).find("finite"), std::string::npos);
  EXPECT_NE(read_error("OFF\n3 1 0\n0 0 inf\n1 0 0\n0 1 0\n3 0 1 2\n", MeshFormat::off).find("finite"),
            std::string::npos);
  EXPECT_NE(read_error("v 0 1e999 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::obj).find("three numbers"),
            std::string::npos);
}

TEST(ReadMeshErrors, FaceIndexOutOfRange) {
  EXPECT_NE(read_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", MeshFormat::obj).find("only 3 vertices"),
            std::string::npos);
  EXPECT_NE(read_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n", MeshFormat::off).find("refers to vertex"),
            std::string::npos);
}

TEST(ReadMeshErrors, FaceWithFewerThanThreeVertices) {
  EXPECT_NE(read_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", MeshFormat::obj).find("at least 3"), std::string::npos);
  EXPECT_NE(read_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", MeshFormat::off).find("at least 3"),
            std::string::npos);
}

TEST(ReadMeshErrors, FaceRepeatingAVertex) {
  EXPECT_NE(read_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1\n", MeshFormat::obj).find("repeats"), std::string::npos);
}

TEST(ReadMeshErrors, TriangleStripsAreRefusedWithAReason) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_NE(read_error(ply, MeshFormat::ply).find("strips"), std::string::npos);
}

TEST(ReadMeshErrors, VertexLimitIsEnforced) {
  ReadOptions options;
  options.max_vertices = 2;
  EXPECT_NE(read_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::obj, options).find("limit"),
            std::string::npos);
}

TEST(ReadMeshErrors, ErrorsNameTheLine) {
  EXPECT_NE(read_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", MeshFormat::obj).find("line 4"), std::string::npos);
}

TEST(ReadMeshErrors, UnknownExtension) { EXPECT_THROW(read_mesh("model.xyz"), MeshIoError); }

}  // namespace
}  // namespace meshmark
