// Files made to hurt a reader: counts the data cannot hold, lengths that are not numbers, huge
// polygons, corners that would collide in a hash table. Each is refused or read in time linear
// (or n log n) in its size, and a time limit stops any reader.

#include <gtest/gtest.h>

#include "tests/io/read_error.hpp"

#include <atomic>
#include <cmath>

#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"

namespace meshmark {
namespace {

using test::read_error;

const std::string kTetraPlyBody = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

TEST(HostileInput, PlyElementWithoutPropertiesAndAHugeCountIsSkippedNotLoopedOver) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element nothing 18446744073709551615\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n" +
      kTetraPlyBody;
  const auto r = read_mesh_from_memory(ply, MeshFormat::ply);
  EXPECT_EQ(r.mesh.V.rows(), 4);
  EXPECT_EQ(r.mesh.F.rows(), 4);
}

// A vertex element with 'z' twice and no 'x' counted three axes, and its writer then put the
// missing axis's values at byte 0 (fuzz finding): each axis once, each name once, one vertex element.
TEST(HostileInput, PlyHeadersWithRepeatedNamesAreRefused) {
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string twice_z =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float z\nproperty float y\nproperty float z\n" + faces +
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_NE(read_error(twice_z, MeshFormat::ply).find("two properties named 'z'"), std::string::npos)
      << read_error(twice_z, MeshFormat::ply);
  const std::string two_vertex_elements =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n" +
      faces + "0 0 0\n1 0 0\n0 1 0\n5 5 5\n3 0 1 2\n";
  EXPECT_NE(read_error(two_vertex_elements, MeshFormat::ply).find("two elements named 'vertex'"), std::string::npos);
}

TEST(HostileInput, PlyCountBeyondWhatTheBodyHoldsIsRefusedFromTheHeader) {
  const std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement junk 1000000000000\nproperty double w\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n" +
      std::string(64, '\0');
  EXPECT_NE(read_error(ply, MeshFormat::ply).find("more than the"), std::string::npos)
      << read_error(ply, MeshFormat::ply);
}

TEST(HostileInput, PlyListLengthThatIsNotANumberIsRefused) {
  for (const char* length : {"nan", "-nan", "inf", "2.5", "-1"}) {
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list float int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n0 0 1\n" +
        std::string(length) + " 0 1 2\n";
    EXPECT_NE(read_error(ply, MeshFormat::ply).find("list length"), std::string::npos) << length;
  }
}

TEST(HostileInput, FilesWithoutVerticesOrFacesAreRefusedInEveryFormat) {
  const std::string empty_ply =
      "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
      "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_NE(read_error(empty_ply, MeshFormat::ply).find("no vertices"), std::string::npos);
  const std::string points =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_NE(read_error(points, MeshFormat::ply).find("no faces"), std::string::npos);
  EXPECT_NE(read_error("OFF\n0 0 0\n", MeshFormat::off), "");
  EXPECT_NE(read_error("# nothing\n", MeshFormat::obj), "");
  EXPECT_NE(read_error("solid x\nendsolid x\n", MeshFormat::stl), "");
}

TEST(HostileInput, APolygonWithHundredsOfThousandsOfCornersIsCheckedInNLogN) {
  const int n = 400'000;
  std::string obj;
  obj.reserve(static_cast<std::size_t>(n) * 24);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    obj += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
  }
  obj += "f";
  for (int i = 1; i <= n; ++i) obj += " " + std::to_string(i);
  obj += "\n";
  const auto r = read_mesh_from_memory(obj, MeshFormat::obj);  // was 37 s: every pair compared
  EXPECT_EQ(r.mesh.F.rows(), n - 2);
  EXPECT_EQ(r.polygons_triangulated, 1u);
  obj += "f 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 3\n";
  EXPECT_NE(read_error(obj, MeshFormat::obj).find("repeats vertex 2"), std::string::npos);
}

TEST(HostileInput, StlCornersWeldByExactPositionInOrderOfFirstAppearance) {
  // Two triangles sharing an edge, the shared corners written once as -0.0 and once as 0.0.
  const std::string stl =
      "solid t\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
      "facet normal 0 0 1\nouter loop\nvertex 1 0 -0\nvertex 1 1 0\nvertex -0 1 0\nendloop\nendfacet\n"
      "endsolid t\n";
  const auto r = read_mesh_from_memory(stl, MeshFormat::stl);
  ASSERT_EQ(r.mesh.V.rows(), 4);
  EXPECT_EQ(r.mesh.V.rows(), 4);  // six corners, two welded pairs
  EXPECT_EQ(r.mesh.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(r.mesh.F.row(1), Eigen::RowVector3i(1, 3, 2));
}

TEST(HostileInput, ManyStlCornersAtFewPositionsWeldIntoOneVertexEach) {
  // 120k triangles whose corners share three positions (the welder sorts: no input makes it quadratic).
  Mesh soup;
  const int n = 120'000;
  soup.V.resize(3 * n, 3);
  soup.F.resize(n, 3);
  for (int t = 0; t < n; ++t) {
    soup.V.row(3 * t) << 0, 0, 0;
    soup.V.row(3 * t + 1) << 1, 0, 0;
    soup.V.row(3 * t + 2) << 0, 1, 0;
    soup.F.row(t) << 3 * t, 3 * t + 1, 3 * t + 2;
  }
  const auto r = read_mesh_from_memory(write_mesh_to_memory(soup, MeshFormat::stl, {.binary = true}), MeshFormat::stl);
  EXPECT_EQ(r.mesh.V.rows(), 3);
}

TEST(HostileInput, CoordinatesBeyondTheSupportedRangeAreRefused) {
  EXPECT_NE(read_error("v 1e200 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n", MeshFormat::obj).find("1e30"), std::string::npos);
}

TEST(HostileInput, ATimeLimitStopsAReader) {
  std::string obj;
  for (int i = 0; i < 20000; ++i) obj += "v 0 0 " + std::to_string(i) + "\n";
  obj += "f 1 2 3\n";
  JobControl expired;
  expired.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  ReadOptions options;
  options.control = &expired;
  EXPECT_THROW(read_mesh_from_memory(obj, MeshFormat::obj, options), TimeLimitExceeded);
  std::atomic<bool> cancel{true};
  JobControl canceled;
  canceled.cancel = &cancel;
  options.control = &canceled;
  EXPECT_THROW(read_mesh_from_memory(obj, MeshFormat::obj, options), Canceled);
}

TEST(HostileInput, LimitsAreReportedAsLimitErrors) {
  ReadOptions options;
  options.max_vertices = 2;
  EXPECT_THROW(read_mesh_from_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", MeshFormat::obj, options), MeshLimitError);
}

}  // namespace
}  // namespace meshmark

namespace meshmark {
namespace {

TEST(WriteMesh, BinaryStlRefusesCoordinatesItsFloatsCannotHold) {
  Mesh far;
  far.V.resize(3, 3);
  far.V << 1e12, 0, 0, 1e12 + 1, 0, 0, 1e12, 1, 0;  // rounding to float would move them by 1e5
  far.F.resize(1, 3);
  far.F << 0, 1, 2;
  try {
    write_mesh_to_memory(far, MeshFormat::stl, {.binary = true});
    FAIL() << "written";
  } catch (const MeshIoError& e) {
    EXPECT_NE(std::string(e.what()).find("32-bit floats"), std::string::npos) << e.what();
  }
  far.V.col(0).array() -= 1e12;
  EXPECT_NO_THROW(write_mesh_to_memory(far, MeshFormat::stl, {.binary = true}));
  Mesh huge = far;
  huge.V(0, 0) = 1e39;  // beyond float range (readers refuse it; a computed mesh might not)
  EXPECT_THROW(write_mesh_to_memory(huge, MeshFormat::stl, {.binary = true}), MeshIoError);
}

}  // namespace
}  // namespace meshmark
