#include "runtime/clock.hpp"

namespace felt {

Clock& wall_clock() {
  static WallClock clock;
  return clock;
}

}  // namespace felt
