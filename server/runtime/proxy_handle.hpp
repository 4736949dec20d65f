#pragma once
// A haptic proxy as a client's connection holds it: the scene owns what proxies share (the
// haptic frames, the reactions on its bodies, who is touching where), the handle one proxy's
// god-object. Updates render through the scene, and the handle closes the proxy when it goes,
// so the scene forgets its pending reaction and its presence (no close to forget).

#include <cstdint>
#include <utility>

#include "runtime/haptic_proxy.hpp"

namespace felt {

class SceneRunner;

class ProxyHandle {
 public:
  /// Made by SceneRunner::open_proxy; must not outlive `scene`.
  ProxyHandle(SceneRunner& scene, HapticProxy proxy) : scene_(&scene), proxy_(std::move(proxy)) {}
  ProxyHandle(ProxyHandle&& other) noexcept
      : scene_(std::exchange(other.scene_, nullptr)), proxy_(std::move(other.proxy_)) {}
  ProxyHandle(const ProxyHandle&) = delete;
  ProxyHandle& operator=(const ProxyHandle&) = delete;
  ProxyHandle& operator=(ProxyHandle&&) = delete;
  ~ProxyHandle();

  /// One update with the device at `device` and its `buttons`, against the scene's surfaces as
  /// rendered now; `local` is what the client's local renderer felt (SceneRunner::render).
  ProxyOutput update(const Vec3& device, std::uint32_t buttons,
                     const LocalContact* local = nullptr);

  const ProxySettings& settings() const { return proxy_.settings(); }
  /// Makes this a local-model proxy: its client renders forces against models of the surface.
  void enable_local_model(const LocalModelRequest& request) { proxy_.enable_local_model(request); }
  bool has_local_model() const { return proxy_.has_local_model(); }
  /// When the last update was.
  SteadyClock::time_point last_update() const { return proxy_.last_update(); }
  /// Lets go of the surface kept from the last update when that is more than `idle` ago.
  void forget_surface_if_idle(SteadyClock::time_point now, SteadyClock::duration idle) {
    proxy_.forget_surface_if_idle(now, idle);
  }

 private:
  SceneRunner* scene_;  ///< null once moved from
  HapticProxy proxy_;
};

}  // namespace felt
