#pragma once
// How many times longer than in a plain optimized build a test may wait on the wall clock.
// A sanitizer slows everything down, the physics threads and a feltd built the same way
// included (AddressSanitizer about 2-4 times, ThreadSanitizer 5-15 times), so a test that waits
// for something to happen in time scales its deadline with scaled(); what it then checks does
// not change. FELT_TEST_TIME_SCALE sets the factor by hand (a loaded machine, valgrind).

#include <chrono>
#include <cstdlib>

// GCC defines __SANITIZE_*__; clang (the fuzz build's) tells through __has_feature.
#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define FELT_UNDER_THREAD_SANITIZER 1
#endif
#if __has_feature(address_sanitizer)
#define FELT_UNDER_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_THREAD__)
#define FELT_UNDER_THREAD_SANITIZER 1
#endif
#if defined(__SANITIZE_ADDRESS__)
#define FELT_UNDER_ADDRESS_SANITIZER 1
#endif

namespace felt::test {

inline double time_scale() {
  if (const char* value = std::getenv("FELT_TEST_TIME_SCALE")) {
    const double factor = std::strtod(value, nullptr);
    if (factor >= 1) return factor;
  }
#if defined(FELT_UNDER_THREAD_SANITIZER)
  return 10;
#elif defined(FELT_UNDER_ADDRESS_SANITIZER)
  return 4;
#else
  return 1;
#endif
}

/// `timeout` times time_scale().
template <class Rep, class Period>
std::chrono::milliseconds scaled(std::chrono::duration<Rep, Period> timeout) {
  return std::chrono::milliseconds(static_cast<std::chrono::milliseconds::rep>(
      std::chrono::duration<double, std::milli>(timeout).count() * time_scale()));
}

}  // namespace felt::test
