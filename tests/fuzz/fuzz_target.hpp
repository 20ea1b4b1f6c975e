#pragma once
// Each fuzz target defines LLVMFuzzerTestOneInput (libFuzzer's entry point). Built with clang's
// -fsanitize=fuzzer it is a fuzzer; linked with regression_main.cpp instead it replays a corpus
// folder, which is how ctest runs the committed cases on every build.

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}
