// meshmark: the command-line tool. Local work on mesh files, and calls to a meshmarkd daemon.

#include <cstdio>
#include <exception>

#include "client/commands/commands.hpp"
#include "core/util/huge_pages.hpp"

int main(int argc, char** argv) {
  meshmark::restart_with_huge_pages(argv);  // first: nothing done yet is lost to the restart
  CLI::App app{"meshmark: robust watermarks in the geometry of 3D meshes"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "meshmark 0.1.0");
  meshmark::cli::Action action;
  meshmark::cli::register_info(app, action);
  meshmark::cli::register_sphere(app, action);
  meshmark::cli::register_embed(app, action);
  meshmark::cli::register_detect(app, action);
  meshmark::cli::register_trace(app, action);
  meshmark::cli::register_attack(app, action);
  meshmark::cli::register_compare(app, action);
  meshmark::cli::register_eval(app, action);
  meshmark::cli::register_bench(app, action);
  meshmark::cli::register_remote(app, action);
  meshmark::cli::register_example(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);
    return status == 0 ? 0 : meshmark::cli::kExitError;
  }
  try {
    return action();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meshmark: error: %s\n", e.what());
    return meshmark::cli::kExitError;
  }
}
