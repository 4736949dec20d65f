#pragma once
// Forces that haptic proxies exert back on the bodies they touch. Proxies report at their own
// rate from any thread; the physics thread applies, once per step, each proxy's mean force
// over the updates since the previous step (DESIGN: reaction averaged over each physics step),
// free updates counting as zero. A proxy slower than the physics keeps pushing with its last
// mean until its next update (a zero-order hold), so a 30 Hz device dents the cloth as a
// 1 kHz one does.

#include <cstdint>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/world/world.hpp"

namespace felt {

/// A grabbed vertex tied to the device by a damped spring.
struct GrabSpring {
  std::uint32_t body_id = 0;
  std::uint32_t vertex = 0;
  Vec3 target = Vec3::Zero();  ///< the device
  Real stiffness = 0;          ///< N/m
  Real damping = 0;            ///< N·s/m
};

/// What one proxy update leaves on the bodies.
struct ProxySample {
  /// a push of `force` onto the triangle with particles `corners` of body `body_id`, at the
  /// point with barycentric coordinates `barycentric`
  struct Push {
    std::uint32_t body_id = 0;
    Triangle corners{};
    Vec3 barycentric = Vec3::Zero();
    Vec3 force = Vec3::Zero();
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
  void record(std::uint64_t proxy_key, const ProxySample& sample);

  /// Drops a closed proxy after the next step has applied what it pushed last.
  void forget(std::uint64_t proxy_key);

  /// Applies each proxy's mean force since the last step (or, without new updates, the mean it
  /// applied last) as external forces on the bodies, and its sphere as a collider for the
  /// step. Called by the physics thread only.
  void apply_and_clear(World& world);

 private:
  struct ParticleForce {
    std::uint32_t body_id;
    std::uint32_t particle;
    Vec3 force;
  };
  struct ProxyReaction {
    std::vector<ParticleForce> forces;  ///< summed per particle since the last step
    std::uint32_t samples = 0;
    std::vector<ParticleForce> held;  ///< the mean applied at the last step
    std::optional<Collider> sphere;
    std::optional<GrabSpring> grab;
    bool closed = false;
  };
  // bounds the memory a proxy can pin between two steps
  static constexpr std::size_t kMaxParticlesPerProxy = 96;

  std::mutex mutex_;
  std::unordered_map<std::uint64_t, ProxyReaction> reactions_;
  std::vector<Collider> spheres_;  ///< scratch for apply_and_clear
  /// (body, particle) of the anchors the last apply_and_clear set, removed by the next
  std::vector<std::pair<std::uint32_t, std::uint32_t>> anchored_;
};

}  // namespace felt
