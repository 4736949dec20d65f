#pragma once
// A scene's rescued, unrecoverable and over-budget steps (core/world/world.hpp), counted as the
// physics thread takes them and told to the scene's members as events: coalesced, at most one of
// each kind per half second, so that an exploding scene does not send an event every step.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/world/world.hpp"
#include "runtime/clock.hpp"
#include "runtime/scene_members.hpp"

namespace felt {

class HealthEvents {
 public:
  static constexpr std::chrono::milliseconds kInterval{500};

  explicit HealthEvents(SceneMembers& members) : members_(members) {}

  /// Counts the step `report` describes.
  void count(const StepReport& report);
  /// Tells the members of the steps not told yet, each kind unless its last event was less
  /// than kInterval before `now` (`at_once`: regardless). `stamp` carries the scene's step,
  /// time and time scale.
  void report(Clock::time_point now, bool at_once, const SceneEvent& stamp);

  std::uint64_t rescued() const { return rescued_.total; }
  std::uint64_t unrecoverable() const { return unrecoverable_.total; }
  std::uint64_t over_budget() const { return over_budget_.total; }

 private:
  /// Steps of one kind of trouble: how many since the start, how many of them events have
  /// told, and the bodies of the last one.
  struct Troubled {
    std::uint64_t total = 0;
    std::uint64_t reported = 0;
    /// unrecoverable: the bodies of the last step; rescued and over budget: every body since
    /// the last event
    std::vector<BodyId> bodies;
    std::optional<Clock::time_point> last_event;
  };

  SceneMembers& members_;
  Troubled unrecoverable_, rescued_, over_budget_;
};

}  // namespace felt
