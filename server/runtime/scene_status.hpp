#pragma once
// A scene's clock as a request that controls it is answered with.

#include <cstdint>

namespace felt {

struct SceneStatus {
  std::uint64_t step = 0;
  double sim_time = 0;
  bool paused = false;
  double time_scale = 1;
};

}  // namespace felt
