// The attack-chain parser on arbitrary text: refused with std::invalid_argument, or a chain that
// prints and parses back to itself and applies to a small mesh without crashing.

#include <string>

#include "core/attacks/attack_registry.hpp"
#include "tests/fuzz/fuzz_target.hpp"

namespace {

meshmark::Mesh octahedron() {
  meshmark::Mesh m;
  m.V.resize(6, 3);
  m.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return m;
}

// Chains that are valid but legitimately heavy (subdivide steps=11 makes 33M faces, a fine
// resampling grid holds millions of points) are parsed, not applied: the fuzzer looks for
// crashes, not for work it asked for.
bool light(const meshmark::AttackChain& chain) {
  for (const auto& step : chain)
    for (const auto& [key, value] : step.parameters) {
      double v = 0;
      try {
        v = std::stod(value);
      } catch (const std::exception&) {
        continue;  // the attack itself refuses it
      }
      if ((key == "steps" && v > 3) || (key == "iterations" && v > 50) || (key == "edge" && v != 0 && v < 0.05) ||
          (key == "spacing" && v < 2))
        return false;
    }
  return chain.size() <= 8;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  meshmark::AttackChain chain;
  try {
    chain = meshmark::parse_attack_chain(std::string(as_text(data, size)));
  } catch (const std::invalid_argument&) {
    return 0;
  }
  if (meshmark::to_string(meshmark::parse_attack_chain(meshmark::to_string(chain))) != meshmark::to_string(chain))
    __builtin_trap();
  static const meshmark::Mesh mesh = octahedron();
  if (!light(chain)) return 0;
  try {
    (void)meshmark::apply_attack_chain(mesh, chain, 1);
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
