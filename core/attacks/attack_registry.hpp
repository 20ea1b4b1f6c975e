#pragma once
// Every attack by name, with its parameters and defaults: one table that the command line, the
// evaluation and attack chains all read. A chain is written as steps separated by '|', each a
// kind followed by key=value parameters:
//
//     simplify keep=0.5 | noise amplitude=0.1 relative-to=centroid | similarity

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct AttackParameter {
  std::string name;
  std::string default_value;  ///< empty: none (the attack decides, e.g. a random similarity)
  std::string help;
};

using AttackParameters = std::map<std::string, std::string>;

struct AttackKind {
  std::string name;
  std::string summary;
  std::vector<AttackParameter> parameters;
  std::function<Mesh(const Mesh&, const AttackParameters&, std::uint64_t seed)> apply;
};

/// All attack kinds, in a fixed order.
const std::vector<AttackKind>& attack_kinds();
/// The kind called `name`; throws std::invalid_argument listing the known kinds.
const AttackKind& attack_kind(const std::string& name);

struct AttackStep {
  std::string kind;
  AttackParameters parameters;  ///< only those given; defaults are filled in when applied
};
using AttackChain = std::vector<AttackStep>;

/// Parses "kind key=value ... | kind ...". Throws std::invalid_argument for an unknown kind or
/// parameter, naming it.
AttackChain parse_attack_chain(const std::string& text);
std::string to_string(const AttackChain& chain);

/// Applies one step (missing parameters take their defaults). Throws std::invalid_argument for a
/// bad parameter value.
Mesh apply_attack(const Mesh& mesh, const AttackStep& step, std::uint64_t seed);
/// Applies the steps in order; step i draws its randomness from seed and i.
Mesh apply_attack_chain(const Mesh& mesh, const AttackChain& chain, std::uint64_t seed);

}  // namespace meshmark
