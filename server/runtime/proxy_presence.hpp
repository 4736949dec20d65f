#pragma once
// Where every haptic proxy of a scene is and what it feels, so that everyone in the scene can
// see the others (frames carry it). Written by each proxy's update on its network thread, read
// when a frame is planned; one short lock each.

#include <chrono>
#include <cstdint>
#include <mutex>
#include <vector>

#include "core/math/types.hpp"
#include "runtime/proxy_key.hpp"

namespace felt {

struct ProxyPresenceEntry {
  ProxyKey key;
  Vec3 position = Vec3::Zero();  ///< the god-object's centre
  Real radius = 0;
  bool in_contact = false;
  Vec3 force = Vec3::Zero();  ///< what its device renders
  Vec3 contact_point = Vec3::Zero();
  bool grabbing = false;
  std::chrono::steady_clock::time_point updated;
};

class ProxyPresence {
 public:
  void update(const ProxyPresenceEntry& entry);
  void forget(ProxyKey key);
  /// The proxies updated since `since`.
  std::vector<ProxyPresenceEntry> since(std::chrono::steady_clock::time_point since) const;

 private:
  mutable std::mutex mutex_;
  std::vector<ProxyPresenceEntry> entries_;  ///< a few per client: a vector beats a map
};

}  // namespace felt
