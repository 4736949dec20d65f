#pragma once
// One haptic device's proxy in a scene: the god-object that renders contact, and grabbing
// (thesis 1 "picking"): while the grab button is held after touching a body, the touched
// triangle's nearest vertex is tied to the device by a spring; the device feels that spring,
// which carries the vertex's share of the body's weight, and the body feels the opposite
// force. Owned and updated by one thread at a time (a session's strand or the servo thread).

#include <cstdint>
#include <optional>

#include "core/haptics/god_object.hpp"
#include "runtime/haptic_frame.hpp"
#include "runtime/reaction_accumulator.hpp"

namespace felt {

/// ProxyUpdate.buttons: bit 0 grabs.
constexpr std::uint32_t kGrabButton = 1u;

struct ProxyOutput {
  HapticContact contact;  ///< force = what the device renders (the grab spring while grabbing)
  bool grabbing = false;
  std::uint32_t grabbed_body = 0;  ///< while grabbing: the body and surface vertex held
  std::uint32_t grabbed_vertex = 0;
};

class HapticProxy {
 public:
  /// `key` names the proxy to the scene's reaction accumulator.
  HapticProxy(std::uint64_t key, const ProxySettings& settings) : key_(key), settings_(settings) {}

  std::uint64_t key() const { return key_; }
  const ProxySettings& settings() const { return settings_; }

  /// One update with the device at `device` and its `buttons`, against `surface` as rendered
  /// now, `dt` seconds after the previous update (0: unknown); the reaction on the touched body
  /// goes to `reactions`. A device position that is not finite or beyond ±1e6 m is no reading
  /// (GodObject::update): no force either way, a grab is kept for the next.
  ProxyOutput update(const HapticSurface& surface, Real dt, const Vec3& device,
                     std::uint32_t buttons, ReactionAccumulator& reactions);

  /// Seconds since the previous call (0 the first time): the `dt` of a live update.
  Real seconds_since_last(SteadyClock::time_point now);
  /// When the last live update was (what seconds_since_last was given).
  SteadyClock::time_point last_update() const { return last_update_; }
  /// When the last live update is more than `idle` before `now`, lets go of the surface the
  /// god-object kept from it (see GodObject::forget_previous_surface).
  void forget_surface_if_idle(SteadyClock::time_point now, SteadyClock::duration idle);

 private:
  struct Grab {
    std::uint32_t body = 0;
    std::uint32_t vertex = 0;
  };

  /// Where a new god-object starts: at the device, or pushed out of the surface it overlaps
  /// so that a device already inside something feels it at once.
  Vec3 starting_point(const HapticSurface& surface, const Vec3& device) const;
  Vec3 grab_force(const HapticSurface& surface, const Vec3& device) const;
  /// The reply to an update that is no reading: no force, nothing pushed or pulled.
  ProxyOutput hold(ReactionAccumulator& reactions) const;

  std::uint64_t key_;
  ProxySettings settings_;
  std::optional<GodObject> god_;
  std::optional<Grab> grab_;
  SteadyClock::time_point last_update_{};
};

}  // namespace felt
