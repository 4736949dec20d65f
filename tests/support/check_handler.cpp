// Installed before every test: a failed FELT_CHECK throws, so the test that broke an invariant
// fails with the expression and location, and the other tests still run.

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/math/check.hpp"

namespace {

class ThrowingCheckHandler : public ::testing::Environment {
 public:
  void SetUp() override {
    felt::set_check_handler([](const char* expression, const std::source_location& where) {
      throw std::logic_error(std::string(where.file_name()) + ":" + std::to_string(where.line()) +
                             ": check failed: " + expression);
    });
  }
};

const auto* const kInstalled = ::testing::AddGlobalTestEnvironment(new ThrowingCheckHandler);

}  // namespace
