// A validation report stored and read back is the report: every count, example and sentence.

#include "core/mesh/mesh_report_io.hpp"

#include <gtest/gtest.h>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(MeshReportIo, EveryKindOfReportComesBackEqual) {
  // Closed, with holes, pinched (non-manifold), in parts, wound inward: every field is set somewhere.
  for (const char* name : {"creature", "creature_holes", "pinched", "parts", "creature_inward"}) {
    const MeshReport report = validate_mesh(test::procedural_mesh(name));
    BinaryWriter w;
    put_mesh_report(w, report);
    BinaryReader r(w.bytes());
    EXPECT_TRUE(get_mesh_report(r) == report) << name;
    EXPECT_EQ(r.remaining(), 0u) << name;
  }
}

TEST(MeshReportIo, ATruncatedOrForeignReportIsRefused) {
  BinaryWriter w;
  put_mesh_report(w, validate_mesh(test::procedural_mesh("pinched")));
  for (const std::size_t keep : {std::size_t{0}, std::size_t{40}, w.bytes().size() - 1}) {
    BinaryReader r(std::string_view(w.bytes()).substr(0, keep));
    EXPECT_THROW(get_mesh_report(r), std::runtime_error) << keep;
  }
  std::string huge_list(8 * 13 + 8 + 1 + 4 + 1 + 8, '\0');  // counts, Euler, genus, orientation, diagonal
  huge_list += std::string(8, '\xff');                      // then a list of 2^64 − 1 examples
  BinaryReader r(huge_list);
  EXPECT_THROW(get_mesh_report(r), std::runtime_error);
}

}  // namespace
}  // namespace meshmark
