// meshmark example SHAPE OUT: writes a shape made by code (core/mesh/example_shapes.hpp), for
// trying meshmark without a mesh of one's own: the walkthroughs and the Docker test use it.

#include <cstdio>

#include "client/commands/commands.hpp"
#include "core/io/write_mesh.hpp"
#include "core/mesh/example_shapes.hpp"

namespace meshmark::cli {

void register_example(CLI::App& app, Action& action) {
  auto* cmd =
      app.add_subcommand("example", "Write an example shape to try meshmark on (" + example_shape_names() + ")");
  auto shape = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  cmd->add_option("shape", *shape, "Which shape: " + example_shape_names())->required();
  cmd->add_option("out", *out, "Output mesh file (.obj, .off, .ply, .stl)")->required();
  cmd->callback([&action, shape, out] {
    action = [shape, out] {
      const Mesh mesh = example_shape(*shape);
      write_mesh(*out, mesh, {.lossless_text = true});  // the shape exactly as the tests make it
      std::printf("%s: the example shape '%s', %lld vertices, %lld faces\n", out->c_str(), shape->c_str(),
                  static_cast<long long>(mesh.V.rows()), static_cast<long long>(mesh.F.rows()));
      return kExitOk;
    };
  });
}

}  // namespace meshmark::cli
