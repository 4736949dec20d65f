#pragma once
// What happened in one step (docs/scenes.md, "Numerical health"): a set of StepFlag, typed so that
// it cannot be mixed up with a count or an id.

#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <utility>

namespace felt {

enum class StepFlag : std::uint8_t {
  kRescued,        ///< a body's step failed and was redone with substeps
  kUnrecoverable,  ///< a body could not be rescued; it was rolled back and stopped
  /// a body's step reached its budget (HealthSettings::step_budget) or an integrator's cap and
  /// went on with what it could afford
  kOverBudget,
};

class StepFlags {
 public:
  constexpr StepFlags() = default;
  constexpr StepFlags(std::initializer_list<StepFlag> flags) {
    for (StepFlag flag : flags) set(flag);
  }

  constexpr void set(StepFlag flag) { bits_ |= bit(flag); }
  constexpr bool has(StepFlag flag) const { return (bits_ & bit(flag)) != 0; }
  /// Any of `flags` is set.
  constexpr bool any_of(StepFlags flags) const { return (bits_ & flags.bits_) != 0; }
  /// Nothing happened: the step went as planned.
  constexpr bool ok() const { return bits_ == 0; }

  constexpr StepFlags& operator|=(StepFlags other) {
    bits_ |= other.bits_;
    return *this;
  }
  friend constexpr bool operator==(StepFlags, StepFlags) = default;

  /// "ok", or the flags set joined by '+' ("rescued+over_budget"), for test failures and logs.
  friend std::ostream& operator<<(std::ostream& out, StepFlags flags) {
    if (flags.ok()) return out << "ok";
    const char* sep = "";
    const std::pair<StepFlag, const char*> names[] = {{StepFlag::kRescued, "rescued"},
                                                      {StepFlag::kUnrecoverable, "unrecoverable"},
                                                      {StepFlag::kOverBudget, "over_budget"}};
    for (const auto& [flag, name] : names) {
      if (flags.has(flag)) out << std::exchange(sep, "+") << name;
    }
    return out;
  }

 private:
  static constexpr std::uint8_t bit(StepFlag flag) {
    return static_cast<std::uint8_t>(1u << static_cast<unsigned>(flag));
  }
  std::uint8_t bits_ = 0;
};

}  // namespace felt
