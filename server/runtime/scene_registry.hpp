#pragma once
// The live scenes of a server, named by ids that carry a generation so that the id of a
// removed scene is never mistaken for a later one (Box2D's b2BodyId).

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "runtime/scene_runner.hpp"

namespace felt {

/// index in the low 32 bits, generation in the high 32; 0 is never a valid id.
using SceneId = std::uint64_t;

class SceneRegistry {
 public:
  /// Takes ownership of a runner and returns its id.
  SceneId add(std::shared_ptr<SceneRunner> runner);
  /// The runner with that id, or nullptr for an unknown or stale id.
  std::shared_ptr<SceneRunner> find(SceneId id) const;
  /// Removes and stops a scene; false for an unknown id.
  bool remove(SceneId id);
  /// Removes and stops the scene if nobody but the registry holds it any more (the last session
  /// left). Sessions only obtain runners through find() or by creating them.
  void remove_if_unused(SceneId id);
  /// Stops every scene's physics thread (shutdown).
  void stop_all();
  std::size_t size() const;

 private:
  struct Slot {
    std::uint32_t generation = 0;
    std::shared_ptr<SceneRunner> runner;
  };
  mutable std::mutex mutex_;
  std::vector<Slot> slots_;
};

}  // namespace felt
