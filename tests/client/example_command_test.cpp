// `meshmark example` writes the shapes the walkthroughs use when a user has no mesh of their own.

#include <gtest/gtest.h>

#include "core/io/read_mesh.hpp"
#include "core/mesh/example_shapes.hpp"
#include "core/mesh/validate_mesh.hpp"
#include "tests/client/cli_runner.hpp"
#include "tests/procedural_meshes.hpp"

namespace meshmark::test {
namespace {

TEST(ExampleCommand, WritesTheNamedShapeExactlyAndItCanBeWatermarked) {
  const auto out = process_temp_folder("meshmark-example") / "creature.ply";
  const CliRun run = run_cli("example creature " + out.string());
  ASSERT_EQ(run.exit_status, 0) << run.out;
  const Mesh written = read_mesh(out).mesh;
  EXPECT_TRUE(written.V == example_shape("creature").V);  // the PLY writer keeps every double
  EXPECT_TRUE(written.F == example_shape("creature").F);
  EXPECT_TRUE(validate_mesh(written).valid);
}

TEST(ExampleCommand, AnUnknownShapeIsRefusedNamingTheKnownOnes) {
  const CliRun run = run_cli("example teapot " + (process_temp_folder("meshmark-example") / "t.obj").string(), true);
  EXPECT_EQ(run.exit_status, 2);
  EXPECT_NE(run.out.find("no example shape named 'teapot'"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(example_shape_names()), std::string::npos) << run.out;
}

}  // namespace
}  // namespace meshmark::test
