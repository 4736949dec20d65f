#pragma once
// A local-model proxy's renderer (docs/protocol.md 7.5): the client side of remote haptics. It
// runs the server's own god-object (felt_haptics, the same code feltd renders with) at the
// device's rate against the latest LocalModel the server sent, moved on by its vertex
// velocities to each tick's time (ExtrapolatedSurface), with the touched surface giving under
// the device's push as the model's stiffness says (yielding_contact) and the stiffness lowered
// where the round trip would make the contact active (passive_stiffness). What it felt goes
// upstream in the next ProxyUpdate (LocalContact) for the server to push the body with.
//
// Not thread-safe: the device loop owns it; a model read on the network thread is handed over
// as a LocalModel (local_model_from) with the time it describes.

#include <optional>
#include <utility>
#include <vector>

#include "core/haptics/extrapolated_surface.hpp"
#include "core/haptics/god_object.hpp"
#include "felt/v1/haptics.pb.h"

namespace felt::client {

/// The most ticks a late tick renders (the ones it missed and its own): a loop stalled longer
/// moves on in larger steps.
inline constexpr int kMaxCatchUpTicks = 50;

struct LocalRendererOptions {
  /// N·s/m: the damping of the device and the hand holding it that the passivity rule counts
  /// on (passive_stiffness)
  double device_damping = 20;
  double servo_period = 1e-3;  ///< s: how often tick() is called (a late call catches up)
};

/// What one tick rendered.
struct LocalForce {
  felt::HapticContact contact;  ///< force: what the device renders (zero before a model came)
  double stiffness = 0;         ///< N/m, rendered with
};

class LocalRenderer {
 public:
  /// `settings`: the proxy's as ProxyOpened gave them (every field set).
  LocalRenderer(const felt::v1::ProxySettings& settings, const LocalRendererOptions& options);

  /// Renders against `model` from now on; it shows the surface at `time` (s, the steady clock
  /// of tick()), and arrived `round_trip` seconds after the update it answers was sent.
  void take(const felt::LocalModel& model, double time, double round_trip);

  /// One servo tick with the device at `device` at `time` (s).
  LocalForce tick(const felt::Vec3& device, double time);

  /// What the last tick felt, for the next ProxyUpdate.
  felt::v1::LocalContact upstream() const;

 private:
  felt::ProxySettings settings_;
  LocalRendererOptions options_;
  felt::ExtrapolatedSurface surface_;
  std::optional<felt::GodObject> god_;
  double delay_ = 0;                             ///< s: the last round trip
  double last_time_ = 0;                         ///< of the last tick
  felt::Vec3 last_device_ = felt::Vec3::Zero();  ///< at the last tick
  LocalForce last_;
  felt::Vec3 model_push_ = felt::Vec3::Zero();  ///< the latest model's push
  /// per body of the latest model: its surface's stiffness (N/m, 0: unknown)
  std::vector<std::pair<std::uint32_t, double>> surface_stiffness_;

  double surface_stiffness(std::uint32_t body_id) const;
};

/// `model` in the core's terms, or nothing when it is malformed (a bad id or a number that is
/// not finite) or describes a surface over kMaxLocalModelSurface: such a model is dropped.
std::optional<felt::LocalModel> local_model_from(const felt::v1::LocalModel& model);

/// Seconds of the steady clock at which `model` shows the surface, read `received` (s) after a
/// round trip of `round_trip` s: its age when sent, and half the round trip on the way.
double local_model_time(const felt::v1::LocalModel& model, double received, double round_trip);

}  // namespace felt::client
