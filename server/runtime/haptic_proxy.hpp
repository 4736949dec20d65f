#pragma once
// One haptic device's proxy in a scene: the god-object that renders contact, and grabbing
// (thesis 1 "picking"): while the grab button is held after touching a body, the touched
// triangle's nearest vertex is tied to the device by a spring; the device feels that spring,
// which carries the vertex's share of the body's weight, and the body feels the opposite
// force. Owned and updated by one thread at a time (a session's strand or the servo thread).

#include <cstdint>
#include <optional>

#include "core/haptics/god_object.hpp"
#include "core/haptics/local_model.hpp"
#include "core/haptics/surface_stiffness_estimate.hpp"
#include "runtime/haptic_frame.hpp"
#include "runtime/local_model_feed.hpp"
#include "runtime/proxy_key.hpp"
#include "runtime/reaction_accumulator.hpp"

namespace felt {

/// ProxyUpdate.buttons: bit 0 grabs.
constexpr std::uint32_t kGrabButton = 1u;

/// What a client's local renderer felt at its device's position (a local-model proxy): the
/// body takes the reaction of this contact instead of the server's own.
struct LocalContact {
  bool in_contact = false;
  std::uint32_t body_id = 0;
  std::int32_t triangle = -1;
  Vec3 barycentric = Vec3::Zero();
  Vec3 proxy = Vec3::Zero();  ///< the client's god-object centre
  Real stiffness = 0;         ///< N/m the client rendered with
};

/// A local model cut for a proxy, and when its positions are the surface rendered.
struct LocalModelCut {
  LocalModel model;
  std::uint64_t step = 0;
  SteadyClock::time_point rendered_at;
};

struct ProxyOutput {
  HapticContact contact;  ///< force = what the device renders (the grab spring while grabbing)
  bool grabbing = false;
  std::uint32_t grabbed_body = 0;  ///< while grabbing: the body and surface vertex held
  std::uint32_t grabbed_vertex = 0;
  std::optional<LocalModelCut> local_model;  ///< a local-model proxy's next model, when due
  /// A local-model proxy's update: the force on the device whose opposite the body takes (zero:
  /// none), and how stiff the touched body's surface has been under the contact's pushes
  /// (SurfaceStiffnessEstimate; 0: unknown).
  Vec3 local_push = Vec3::Zero();
  std::uint32_t pushed_body = 0;
  Real pushed_body_stiffness = 0;
};

class HapticProxy {
 public:
  /// `key` names the proxy to the scene's reaction accumulator.
  HapticProxy(ProxyKey key, const ProxySettings& settings) : key_(key), settings_(settings) {}

  ProxyKey key() const { return key_; }
  const ProxySettings& settings() const { return settings_; }
  /// Makes this a local-model proxy: its client renders forces against models of the surface.
  void enable_local_model(const LocalModelRequest& request) { local_model_.emplace(request); }
  /// The feed of a local-model proxy, or null.
  LocalModelFeed* local_model() { return local_model_ ? &*local_model_ : nullptr; }
  bool has_local_model() const { return local_model_.has_value(); }

  /// One update with the device at `device` and its `buttons`, against `surface` as rendered
  /// now, `dt` seconds after the previous update (0: unknown); the reaction on the touched body
  /// goes to `reactions`. A device position that is not finite or beyond ±1e6 m is no reading
  /// (GodObject::update): no force either way, a grab is kept for the next. With `local` (what
  /// a local renderer felt, not grabbing) the body takes that contact's reaction,
  /// stiffness · (proxy − device) clamped to max_force, at its triangle if the surface has it.
  ProxyOutput update(const HapticSurface& surface, Real dt, const Vec3& device,
                     std::uint32_t buttons, ReactionAccumulator& reactions,
                     const LocalContact* local = nullptr);

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
  /// The spring of a push onto `corners` of `body` at `barycentric`, from the proxy at `proxy`
  /// held by the device at `device`, shaded along `normal` (zero: along the spring); null when
  /// it is not stretched (ContactSpring).
  std::optional<ContactSpring> contact_spring(const HapticSurface& surface, const HapticBody& body,
                                              const Triangle& corners, const Vec3& barycentric,
                                              const Vec3& proxy, const Vec3& device,
                                              const Vec3& normal) const;
  /// The room the finger takes around a proxy centred at `centre` (see update), if any.
  std::optional<Collider> finger(const Vec3& centre) const;
  /// What the body feels of a local renderer's contact.
  ProxySample local_sample(const HapticSurface& surface, const Vec3& device,
                           const LocalContact& local) const;
  /// Adds a local contact pushing with `push` (on the device) to the estimate of how stiff the
  /// touched surface is; a contact that ends or moves to another body starts a new estimate.
  void estimate_stiffness(const HapticSurface& surface, const LocalContact& local, const Vec3& push,
                          ProxyOutput& out);

  ProxyKey key_;
  ProxySettings settings_;
  std::optional<GodObject> god_;
  std::optional<Grab> grab_;
  std::optional<LocalModelFeed> local_model_;
  SurfaceStiffnessEstimate stiffness_estimate_;
  std::optional<std::uint32_t> estimated_body_;  ///< whose surface stiffness_estimate_ is of
  SteadyClock::time_point last_update_{};
};

}  // namespace felt
