#pragma once
// Which configurations the peer benchmark runs: every Felt cloth integrator and Bullet's soft
// body, on the 40 × 40 and 100 × 100 cloths.

#include <cstdint>
#include <string>
#include <vector>

#include "bullet_cloth.hpp"
#include "felt_cloth.hpp"

namespace felt::peers {

struct PeerConfig {
  std::uint32_t n;  ///< particles per side
  bool bullet;      ///< Bullet's soft body, else Felt
  FeltConfig felt;
  BulletConfig bullet_config;

  std::string engine() const { return bullet ? "bullet" : "felt"; }
  /// "symplectic_euler k=250 h=0.42ms", "xpbd k=1000 h=4.17ms×16", "bullet h=4.17ms it=8"
  std::string label() const;
};

/// Felt's and Bullet's configurations on the n × n cloth, interleaved so that the engines
/// alternate. Below 40 × 40 (a smoke test) without the slow explicit integrators.
std::vector<PeerConfig> peer_configs(std::uint32_t n);

}  // namespace felt::peers
