#pragma once
// The substeps a body takes after a rescue (issue 27): a body that needed k substeps keeps them,
// so that it does not fail, roll back and redo every step; after a calm while it tries k/2, and
// each time such a halving had to be undone it waits twice as long before the next.

#include <algorithm>
#include <cstdint>

#include "core/step/substep_rescue.hpp"

namespace felt {

class StickySubsteps {
 public:
  /// The substeps to start this step with: k, or k/2 once `relax_steps` calm steps have passed
  /// (2, 4, ... times as many after halvings that were undone).
  int start(std::int64_t relax_steps) {
    const std::int64_t wait = std::max<std::int64_t>(1, relax_steps) << backoff_;
    if (calm_ >= wait) halved_ = false;  // the last halving held
    if (substeps_ > 1 && calm_ >= wait) {
      substeps_ /= 2;
      halved_ = true;
      calm_ = 0;
    }
    return substeps_;
  }

  /// What the step that started with start() came to.
  void record(const RescueOutcome& outcome) {
    ++calm_;
    if (!outcome.rescued) return;
    ++rescued_steps_;
    substeps_ = outcome.substeps;
    // the halving was too much: wait twice as long before trying it again
    if (halved_) backoff_ = std::min(backoff_ + 1, kLongestBackoff);
    halved_ = false;
    calm_ = 0;
  }

  int substeps() const { return substeps_; }
  std::uint64_t rescued_steps() const { return rescued_steps_; }

 private:
  static constexpr int kLongestBackoff = 20;

  int substeps_ = 1;
  std::int64_t calm_ = 0;  ///< steps since the substeps last changed
  int backoff_ = 0;        ///< halvings undone so far, up to kLongestBackoff
  bool halved_ = false;    ///< the last change was a halving
  std::uint64_t rescued_steps_ = 0;
};

}  // namespace felt
