// meshmark attack KIND IN OUT [options]: reproducible attacks on a mesh file.

#include <cstdio>

#include "client/commands/commands.hpp"
#include "core/attacks/subdivide.hpp"
#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"

namespace meshmark::cli {

namespace {

struct AttackFiles {
  std::string in, out;
};

void add_files(CLI::App* cmd, AttackFiles& files) {
  cmd->add_option("in", files.in, "Input mesh")->required();
  cmd->add_option("out", files.out, "Output mesh (format from the extension)")->required();
}

int run(const AttackFiles& files, const std::function<Mesh(const Mesh&)>& attack) {
  const Mesh in = read_mesh(files.in).mesh;
  const Mesh out = attack(in);
  write_mesh(files.out, out);
  std::printf("%s: %lld vertices, %lld faces -> %s: %lld vertices, %lld faces\n", files.in.c_str(),
              static_cast<long long>(in.V.rows()), static_cast<long long>(in.F.rows()), files.out.c_str(),
              static_cast<long long>(out.V.rows()), static_cast<long long>(out.F.rows()));
  return kExitOk;
}

void register_subdivide(CLI::App* attack, Action& action) {
  auto* cmd = attack->add_subcommand("subdivide", "Subdivide every face (midpoint, Loop or sqrt3)");
  struct Args {
    AttackFiles files;
    std::string scheme = "loop";
    int steps = 1;
  };
  auto args = std::make_shared<Args>();
  add_files(cmd, args->files);
  cmd->add_option("--scheme", args->scheme, "midpoint, loop or sqrt3")->capture_default_str();
  cmd->add_option("--steps", args->steps, "Number of subdivision steps")->capture_default_str()->check(CLI::Range(0, 6));
  cmd->callback([&action, args] {
    action = [args] {
      const SubdivisionScheme scheme = parse_subdivision_scheme(args->scheme);
      return run(args->files, [&](const Mesh& m) { return subdivide(m, scheme, args->steps); });
    };
  });
}

}  // namespace

void register_attack(CLI::App& app, Action& action) {
  auto* attack = app.add_subcommand("attack", "Apply a reproducible attack to a mesh file");
  attack->require_subcommand(1);
  register_subdivide(attack, action);
}

}  // namespace meshmark::cli
