// meshmark attack KIND IN OUT [--seed N] [--PARAM VALUE ...]   and   meshmark attack chain IN OUT --steps "..."
// The subcommands come from the attack registry in core. IN or OUT may be '-' (standard input or
// output) with --format, so attacks also chain through a pipe.

#include <cstdio>
#include <iostream>
#include <iterator>

#include "client/commands/commands.hpp"
#include "core/attacks/attack_registry.hpp"
#include "core/io/read_mesh.hpp"
#include "core/io/write_mesh.hpp"

namespace meshmark::cli {

namespace {

struct AttackArgs {
  std::string in, out, format = "ply";
  std::uint64_t seed = 1;
};

void add_common(CLI::App* cmd, AttackArgs& args) {
  cmd->add_option("in", args.in, "Input mesh, or - for standard input")->required();
  cmd->add_option("out", args.out, "Output mesh (format from the extension), or - for standard output")->required();
  cmd->add_option("--seed", args.seed, "Seed of the attack's randomness")->capture_default_str();
  cmd->add_option("--format", args.format, "Format of - (obj, off, ply, stl)")->capture_default_str();
}

Mesh read_input(const AttackArgs& args) {
  if (args.in != "-") return read_mesh(args.in).mesh;
  const auto format = parse_mesh_format(args.format);
  if (!format) throw std::invalid_argument("unknown --format '" + args.format + "'");
  const std::string bytes{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
  return read_mesh_from_memory(bytes, *format, {}, "standard input").mesh;
}

int write_output(const AttackArgs& args, const Mesh& in, const Mesh& out, const std::string& what) {
  if (args.out == "-") {
    const auto format = parse_mesh_format(args.format);
    if (!format) throw std::invalid_argument("unknown --format '" + args.format + "'");
    std::cout << write_mesh_to_memory(out, *format, {.binary = *format == MeshFormat::ply});
  } else {
    write_mesh(args.out, out);
  }
  std::fprintf(stderr, "%s: %lld vertices, %lld faces -> %lld vertices, %lld faces\n", what.c_str(),
               static_cast<long long>(in.V.rows()), static_cast<long long>(in.F.rows()),
               static_cast<long long>(out.V.rows()), static_cast<long long>(out.F.rows()));
  return kExitOk;
}

void register_kind(CLI::App* attack, const AttackKind& kind, Action& action) {
  auto* cmd = attack->add_subcommand(kind.name, kind.summary);
  auto args = std::make_shared<AttackArgs>();
  auto values = std::make_shared<AttackParameters>();
  add_common(cmd, *args);
  for (const AttackParameter& p : kind.parameters) {
    auto* option = cmd->add_option("--" + p.name, (*values)[p.name], p.help);
    if (!p.default_value.empty()) option->default_str(p.default_value);
  }
  cmd->callback([&action, &kind, args, values] {
    action = [&kind, args, values] {
      AttackStep step{kind.name, {}};
      for (const auto& [k, v] : *values)
        if (!v.empty()) step.parameters[k] = v;
      const Mesh in = read_input(*args);
      return write_output(*args, in, apply_attack(in, step, args->seed), to_string(AttackChain{step}));
    };
  });
}

}  // namespace

void register_attack(CLI::App& app, Action& action) {
  auto* attack = app.add_subcommand("attack", "Apply a reproducible attack to a mesh");
  attack->require_subcommand(1);
  for (const AttackKind& kind : attack_kinds()) register_kind(attack, kind, action);

  auto* chain = attack->add_subcommand("chain", "Apply several attacks in a row");
  auto args = std::make_shared<AttackArgs>();
  auto steps = std::make_shared<std::string>();
  add_common(chain, *args);
  chain
      ->add_option("--steps", *steps,
                   "e.g. \"simplify keep=0.5 | noise amplitude=0.1 relative-to=centroid | similarity\"")
      ->required();
  chain->callback([&action, args, steps] {
    action = [args, steps] {
      const AttackChain parsed = parse_attack_chain(*steps);
      const Mesh in = read_input(*args);
      return write_output(*args, in, apply_attack_chain(in, parsed, args->seed), to_string(parsed));
    };
  });
}

}  // namespace meshmark::cli
