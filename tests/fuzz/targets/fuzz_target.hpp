#pragma once
// What every coverage-guided fuzz target shares. A target is one function,
// LLVMFuzzerTestOneInput, that takes any bytes and aborts (a crash the fuzzer keeps) when an
// invariant it checks does not hold; the sanitizers catch the rest. The same file builds into
// a libFuzzer binary (-DFELT_FUZZ=ON, scripts/fuzz) and into a test of the suite that replays
// the target's committed seed corpus and every input that once crashed it
// (replay_committed_inputs.cpp).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <source_location>
#include <span>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace felt::fuzz {

/// Aborts with `what` and where unless `condition` holds.
inline void check(bool condition, std::string_view what,
                  std::source_location where = std::source_location::current()) {
  if (condition) return;
  std::fprintf(stderr, "%s:%u: fuzz check failed: %.*s\n", where.file_name(), where.line(),
               static_cast<int>(what.size()), what.data());
  std::abort();
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace felt::fuzz
