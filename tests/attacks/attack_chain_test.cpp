// The attack-chain language: "kind key=value ... | kind ...".

#include <gtest/gtest.h>

#include "core/attacks/attack_registry.hpp"

namespace meshmark {
namespace {

TEST(AttackChain, ParsesKindsAndParametersInOrder) {
  const AttackChain chain = parse_attack_chain("noise amplitude=0.003 | simplify keep=0.5|reorder");
  ASSERT_EQ(chain.size(), 3u);
  EXPECT_EQ(chain[0].kind, "noise");
  EXPECT_EQ(chain[0].parameters.at("amplitude"), "0.003");
  EXPECT_EQ(chain[1].kind, "simplify");
  EXPECT_EQ(chain[1].parameters.at("keep"), "0.5");
  EXPECT_EQ(chain[2].kind, "reorder");
  EXPECT_TRUE(chain[2].parameters.empty());
}

TEST(AttackChain, PrintsWhatItParses) {
  const AttackChain chain = parse_attack_chain("noise amplitude=0.003 | simplify keep=0.5");
  EXPECT_EQ(to_string(parse_attack_chain(to_string(chain))), to_string(chain));
}

TEST(AttackChain, AnUnknownKindIsRefusedByName) {
  try {
    parse_attack_chain("noise | melt");
    FAIL() << "an unknown attack was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("melt"), std::string::npos) << e.what();
  }
}

TEST(AttackChain, AnUnknownParameterIsRefusedByName) {
  try {
    parse_attack_chain("simplify ratio=0.5");
    FAIL() << "an unknown parameter was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ratio"), std::string::npos) << e.what();
  }
}

TEST(AttackChain, AnEmptyStepIsRefused) { EXPECT_THROW(parse_attack_chain("noise || reorder"), std::invalid_argument); }

}  // namespace
}  // namespace meshmark
