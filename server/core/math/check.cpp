#include "core/math/check.hpp"

#include <cstdio>
#include <cstdlib>
#include <utility>

namespace felt {
namespace {

CheckHandler& handler() {
  static CheckHandler installed;
  return installed;
}

}  // namespace

CheckHandler set_check_handler(CheckHandler next) {
  return std::exchange(handler(), std::move(next));
}

void check_failed(const char* expression, const std::source_location& where) {
  if (handler()) handler()(expression, where);
  // a handler that returns does not make the broken invariant hold
  std::fprintf(stderr, "%s:%u: check failed: %s\n", where.file_name(), where.line(), expression);
  std::abort();
}

}  // namespace felt
