#pragma once
// Forces that haptic proxies exert back on the bodies they touch. Proxies report at their own
// rate from any thread; the physics thread applies, once per step, each proxy's mean force
// over the updates since the previous step (docs/architecture.md, "Reactions: averaged per step"),
// free updates counting as zero, scaled as its latest contact spring says against the surface
// as the step finds it (ContactSpring). A proxy slower than the physics keeps pushing with its
// last mean until its next update (a zero-order hold of the spring, not of the force), so a
// 30 Hz device dents the cloth as a 1 kHz one does, and a surface that gives way or comes back
// between updates feels the spring it would, not a force rendered for where it was.
//
// A contact is seen only at an update, so a surface moving into a slow device's proxy is pressed
// in before the spring pushes back, and the held spring then returns energy it never took in:
// the cloth bounces off a still device, higher each time. Each contact therefore runs a
// time-domain passivity observer (Hannaford and Ryu, IEEE Trans. Robotics and Automation 18(1),
// 2002): the work the device did into the contact (each push times the device's motion to its
// next update) minus the work the body took out of it (each step's force times the touched
// point's motion over the step). While that is negative, the controller withholds a held push
// (no update since the last step) from a body that gives way under it (the last step's motion,
// taken to go on): then the spring only takes energy back, while pressed in. A push with a fresh
// update, and a contact at rest, get the whole spring, as the device feels it.

#include <cstdint>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/world/world.hpp"
#include "runtime/proxy_key.hpp"

namespace felt {

/// A grabbed vertex tied to the device by a damped spring.
struct GrabSpring {
  BodyId body_id = 0;
  std::uint32_t vertex = 0;
  Vec3 target = Vec3::Zero();  ///< the device
  Real stiffness = 0;          ///< N/m
  Real damping = 0;            ///< N·s/m
};

/// The contact spring a push was rendered from: the god-object's spring of `stiffness` from the
/// device at `device`, stretched by `stretch` along `normal` (out of the surface, toward the
/// proxy) while the touched point was at `contact`. A step applies the push scaled by the stretch
/// the surface's motion since then leaves it, s = stretch + (contact now − contact)·normal, over
/// `stretch`, at most `max_force` in all: the spring against the surface as the step finds it,
/// not a force rendered for where the surface was (one step behind, and held for as long as a
/// slow device sends nothing). The step applies it explicitly, so the motion counts with at most
/// the stiffness 1 / (w h²) the touched point takes at step h (w: its inverse mass, the corners'
/// Σ bᵢ² wᵢ): symplectic Euler keeps a spring only while ω h < 2, and a 1 g point at a 10 ms
/// step takes 10 N/m, not the proxy's 400.
struct ContactSpring {
  Real stiffness = 0;  ///< N/m
  Vec3 device = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  Real stretch = 0;  ///< m, > 0
  Vec3 contact = Vec3::Zero();
  Real max_force = 0;  ///< N
};

/// What one proxy update leaves on the bodies.
struct ProxySample {
  /// a push of `force` onto the triangle with particles `corners` of body `body_id`, at the
  /// point with barycentric coordinates `barycentric`
  struct Push {
    BodyId body_id = 0;
    Triangle corners{};
    Vec3 barycentric = Vec3::Zero();
    Vec3 force = Vec3::Zero();
    std::optional<ContactSpring> spring;  ///< null: the force as it is (a grab's)
  };
  std::optional<Push> push;  ///< null: the update touched nothing (it counts as zero)
  /// where the proxy's sphere is now (null: it takes no room, e.g. while grabbing): for the
  /// next step, bodies collide with it as with a scene collider
  std::optional<Collider> sphere;
  /// what the proxy holds now (null: nothing). A grabbed cloth particle gets the spring as an
  /// anchor inside the cloth's force model for the next step, integrated with the cloth's own
  /// forces (stable for a light particle at any step), instead of the push held over the
  /// step; a grabbed solid vertex gets the push.
  std::optional<GrabSpring> grab;
};

class ReactionAccumulator {
 public:
  /// Records an update of proxy `proxy_key` (one lock: this is on the haptic path).
  void record(ProxyKey proxy_key, const ProxySample& sample);

  /// Drops a closed proxy after the next step has applied what it pushed last.
  void forget(ProxyKey proxy_key);

  /// Applies each proxy's mean force since the last step (or, without new updates, the mean it
  /// applied last) as external forces on the bodies, and its sphere as a collider for the
  /// step. Called by the physics thread only.
  void apply_and_clear(World& world);

 private:
  struct ParticleForce {
    BodyId body_id;
    std::uint32_t particle;
    Vec3 force;
  };
  /// A proxy's contact as its body felt it: the passivity observer's state.
  struct ContactEnergy {
    bool touching = false;        ///< a contact spring pushed at the last step
    ProxySample::Push push;       ///< that step's push: where it touched
    Vec3 contact = Vec3::Zero();  ///< the touched point then
    Vec3 force = Vec3::Zero();    ///< all the body got then
    Real energy = 0;       ///< J: the device's work into the contact minus the body's out of it
    Real device_work = 0;  ///< J: the device's since the last step
  };
  struct ProxyReaction;
  /// Applies `reaction`'s forces for this step, through its contact spring and, when they are
  /// `held` (no update since the last step), the passivity controller.
  static void apply_contact(World& world, ProxyReaction& reaction, bool held);
  /// The factor on `reaction`'s forces its contact spring gives against `world` now, the
  /// observer and the controller run (ContactSpring); its held push has a spring in the world.
  static Real spring_scale(const World& world, ProxyReaction& reaction, bool held);

  struct ProxyReaction {
    std::vector<ParticleForce> forces;  ///< summed per particle since the last step
    std::uint32_t samples = 0;
    std::vector<ParticleForce> held;             ///< the mean applied at the last step
    std::optional<ProxySample::Push> latest;     ///< the latest update's push (null: none)
    std::optional<ProxySample::Push> held_push;  ///< the latest push when `held` was made
    ContactEnergy contact;
    std::optional<Collider> sphere;
    std::optional<GrabSpring> grab;
    bool closed = false;
  };
  // bounds the memory a proxy can pin between two steps
  static constexpr std::size_t kMaxParticlesPerProxy = 96;

  std::mutex mutex_;
  std::unordered_map<ProxyKey, ProxyReaction> reactions_;
  std::vector<Collider> spheres_;  ///< scratch for apply_and_clear
  /// (body, particle) of the anchors the last apply_and_clear set, removed by the next
  std::vector<std::pair<BodyId, std::uint32_t>> anchored_;
};

}  // namespace felt
