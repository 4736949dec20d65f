#pragma once
// What a fuzz test runs: a fixed seed and number of cases, so that CI runs the same cases every
// time; FELT_FUZZ_SEED and FELT_FUZZ_CASES run others, or more, by hand.

#include <cstdint>
#include <cstdlib>

namespace felt::test {

struct FuzzSettings {
  std::uint64_t seed = 0;
  std::uint64_t cases = 0;
};

inline FuzzSettings fuzz_settings(std::uint64_t ci_cases) {
  constexpr std::uint64_t kCiSeed = 20261206;
  const auto from_environment = [](const char* name, std::uint64_t fallback) {
    const char* value = std::getenv(name);
    return value ? std::strtoull(value, nullptr, 10) : fallback;
  };
  return {from_environment("FELT_FUZZ_SEED", kCiSeed),
          from_environment("FELT_FUZZ_CASES", ci_cases)};
}

}  // namespace felt::test
