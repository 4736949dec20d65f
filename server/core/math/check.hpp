#pragma once
// Invariant checks. A failed FELT_CHECK calls the installed handler (abort by default); tests
// install one that throws so that a broken invariant fails the test instead of the process.

#include <functional>
#include <source_location>

namespace felt {

using CheckHandler = std::function<void(const char* expression, const std::source_location&)>;

/// Installs `handler` for failed checks and returns the previous one.
CheckHandler set_check_handler(CheckHandler handler);

[[noreturn]] void check_failed(const char* expression,
                               const std::source_location& where = std::source_location::current());

}  // namespace felt

#define FELT_CHECK(expr)                      \
  do {                                        \
    if (!(expr)) ::felt::check_failed(#expr); \
  } while (false)
