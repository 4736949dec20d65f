#pragma once
// Frames encoded once per (snapshot, encoding): what a frame costs to encode is its bodies
// (positions, normals, strain, triangles), and every subscriber that takes the same snapshot in
// the same encoding gets the same bytes for them. The server's frame encoder keeps each body's
// bytes while the snapshot lives, and every frame of that snapshot copies them in. Only what
// differs per client is encoded per client (FrameStream::encode): the frame's header (sequence,
// skipped frames, delta base), the proxies as the client sees them, and bodies sent as deltas
// against the client's acknowledged frame. Sessions tick on a common grid of their period
// (SessionFrames), so subscribers at one rate take the same snapshot.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "net/frame_stream.hpp"
#include "runtime/snapshot.hpp"

namespace felt::net {

/// How one body of a frame is encoded, when it is not a delta.
struct BodyEncoding {
  bool quantized = false;
  bool normals = false;
  bool scalars = false;
  bool triangles = false;
  bool operator==(const BodyEncoding&) const = default;
};

/// One body of a frame, encoded: its bytes as a Frame.bodies entry (field tag, length,
/// BodyFrame), and for 16-bit values what a later delta needs of it.
struct EncodedBody {
  std::string bytes;
  FrameStream::BodyRecord record;
};

class SharedFrameBodies {
 public:
  /// Body `index` of `snapshot` in `encoding`: made by `encode` on the first call, the same
  /// bytes for every later call while the snapshot lives. Any thread.
  std::shared_ptr<const EncodedBody> get(const std::shared_ptr<const SceneSnapshot>& snapshot,
                                         std::size_t index, const BodyEncoding& encoding,
                                         const std::function<EncodedBody()>& encode);
  /// Bodies encoded so far, and bodies handed out without encoding them again.
  std::uint64_t encoded() const;
  std::uint64_t shared() const;

 private:
  struct Entry {
    std::weak_ptr<const SceneSnapshot> snapshot;
    std::size_t index = 0;
    BodyEncoding encoding;
    std::shared_ptr<const EncodedBody> body;
  };
  mutable std::mutex mutex_;
  std::vector<Entry> entries_;  ///< of the snapshots still alive (a few: a frame period's worth)
  std::uint64_t encoded_ = 0;
  std::uint64_t shared_ = 0;
};

}  // namespace felt::net
