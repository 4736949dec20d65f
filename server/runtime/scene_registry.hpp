#pragma once
// The live scenes of a server, named by ids that carry a generation so that the id of a
// removed scene is never mistaken for a later one (Box2D's b2BodyId), and who is in each.

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include "ids/strong_id.hpp"
#include "runtime/scene_runner.hpp"

namespace felt {

/// index in the low 32 bits, generation in the high 32; 0 is never a valid id.
using SceneId = StrongId<struct SceneIdTag, std::uint64_t>;

class SceneRegistry {
 public:
  SceneRegistry();
  ~SceneRegistry();
  SceneRegistry(const SceneRegistry&) = delete;
  SceneRegistry& operator=(const SceneRegistry&) = delete;

  /// Takes ownership of a runner and returns its id. `first`, when given, is a member from the
  /// start (the client that loaded it, until it joins for real): under the same lock, so the
  /// scene is never without its owner, whom another client could then take it from.
  SceneId add(std::shared_ptr<SceneRunner> runner,
              std::optional<SceneMembers::Member> first = std::nullopt);
  /// The runner with that id, or nullptr for an unknown or stale id.
  std::shared_ptr<SceneRunner> find(SceneId id) const;
  /// Adds `member` to scene `id` and returns it (nullptr for an unknown id), under the same
  /// lock as leave(), so a scene is never removed between being found and being joined.
  std::shared_ptr<SceneRunner> join(SceneId id, SceneMembers::Member member);
  /// Takes `client` out of scene `id`; a scene that is not persistent is removed when its last
  /// member leaves, and stopped. True when the scene was removed.
  bool leave(SceneId id, ClientId client);
  /// Removes a scene and stops it; false for an unknown id.
  bool remove(SceneId id);
  /// Stops every scene's physics thread, the removed ones' too (shutdown).
  void stop_all();
  std::size_t size() const;
  /// The live persistent (`keep`) scenes `owner` loaded.
  std::size_t kept_by(ClientId owner) const;
  /// Every live scene, in slot order.
  std::vector<std::pair<SceneId, std::shared_ptr<SceneRunner>>> list() const;

 private:
  struct Slot {
    std::uint32_t generation = 0;
    std::shared_ptr<SceneRunner> runner;
  };
  /// The slot of a live scene `id`, or null; the mutex must be held.
  Slot* slot(SceneId id);
  /// Hands a removed scene to the retiring thread: stopping waits for the scene's step (or a
  /// reset's rebuild), and whoever removes it (a network thread) must not wait.
  void retire(std::shared_ptr<SceneRunner> runner);
  void retire_loop(std::stop_token stop);

  mutable std::mutex mutex_;
  std::vector<Slot> slots_;

  std::mutex retiring_mutex_;
  std::condition_variable_any retiring_wake_;
  std::vector<std::shared_ptr<SceneRunner>> retiring_;
  std::size_t stopping_ = 0;  ///< scenes taken off retiring_ and not stopped yet
  std::jthread retirer_;
};

}  // namespace felt
