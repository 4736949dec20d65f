#pragma once
// One session's frame subscription: which bodies, how they are encoded (float32, or 16-bit
// quantized and optionally as deltas against the last frame the client acknowledged), and
// which triangles the client already has. Snapshot -> felt.v1.Frame; no sockets. A frame is
// planned on the session's thread and encoded on any (the server's frame encoder), so that
// encoding never holds up the haptic updates that thread answers; its bodies are encoded once
// per snapshot and encoding for every subscriber (shared_frame_bodies.hpp).

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "felt/v1/frames.pb.h"
#include "runtime/proxy_presence.hpp"
#include "runtime/scene_registry.hpp"
#include "runtime/snapshot.hpp"
#include "wire/vector_quantizer.hpp"

namespace felt::net {

class SharedFrameBodies;

struct FrameOptions {
  double rate_hz = 60;
  bool normals = false;
  std::vector<BodyId> bodies;  ///< only these, sorted (empty: all)
  bool quantized = false;
  bool deltas = false;   ///< quantized only
  bool scalars = false;  ///< a number per vertex: a cloth's strain
  /// frames written and not yet acknowledged, at most (0: no limit)
  std::uint32_t max_unacknowledged = 0;
};

/// A proxy as a frame shows it to one subscriber.
struct ProxyView {
  std::string client_name;
  bool own = false;          ///< the subscriber's
  ProxyPresenceEntry state;  ///< its key names its client and its number there
};

class FrameStream {
 public:
  /// What a client's delta history may cost, bytes: the frames kept as bases and the
  /// acknowledged base (the frame being built comes on top).
  static constexpr std::size_t kMaxHistoryBytes = std::size_t{64} << 20;

  explicit FrameStream(std::size_t max_history_bytes = kMaxHistoryBytes)
      : max_history_bytes_(max_history_bytes) {}

  bool active() const { return active_; }
  const FrameOptions& options() const { return options_; }

  /// Starts (or replaces) the subscription: the next frame is a key frame with triangles.
  void start(const FrameOptions& options);
  void stop();
  /// The session is in another scene now: triangles again, no delta bases.
  void restart();

  /// Whether `snapshot` is newer than the last frame built.
  bool has_new(const SceneSnapshot& snapshot) const { return snapshot.version != last_version_; }

  struct BodyRecord {
    BodyId body_id = 0;
    wire::QuantizationBounds bounds;
    std::vector<std::uint16_t> positions;
    std::vector<std::uint16_t> normals;
  };
  /// What a later delta needs of a frame: its quantized values.
  struct FrameRecord {
    std::uint64_t sequence = 0;
    std::vector<BodyRecord> bodies;
    const BodyRecord* find(BodyId id) const;
    std::size_t bytes() const;
  };
  /// The next frame, decided on the session's thread: everything its encoding reads, so that
  /// it can be encoded on another thread while the stream goes on.
  struct Plan {
    std::shared_ptr<const SceneSnapshot> snapshot;
    SceneId scene = 0;
    std::uint64_t skipped = 0;
    std::uint64_t sequence = 0;
    FrameOptions options;
    std::shared_ptr<const FrameRecord> base;  ///< the deltas' base; null: values
    std::vector<BodyId> with_triangles;       ///< the bodies whose triangles this frame carries
    std::vector<ProxyView> proxies;           ///< the scene's proxies now
  };
  /// Plans the next frame from `snapshot`; `skipped` frames were dropped before it. The frame
  /// counts as built from here on (has_new, dropped).
  Plan plan(std::shared_ptr<const SceneSnapshot> snapshot, SceneId scene, std::uint64_t skipped);
  /// Encodes `plan` as a length-delimited ServerMessage holding its Frame, appended to `out`,
  /// and what later deltas need of it as `record`. Bodies that are not deltas come from
  /// `shared`, encoded there once per snapshot and encoding. Touches no stream: any thread.
  static void encode(const Plan& plan, SharedFrameBodies& shared, std::string& out,
                     FrameRecord& record);
  /// Puts `proxies` into `frame`.
  static void put_proxies(const std::vector<ProxyView>& proxies, felt::v1::Frame& frame);
  /// The frame planned last was encoded as `record`.
  void encoded(FrameRecord record) { building_ = std::move(record); }
  /// plan, encode and encoded in a row, the frame parsed back from its bytes.
  void build(std::shared_ptr<const SceneSnapshot> snapshot, SceneId scene, std::uint64_t skipped,
             felt::v1::Frame& frame);
  /// The frame last built was replaced before it was sent: the triangles it carried must go
  /// again, and it cannot be a delta base.
  void dropped();
  /// The frame last built was handed to the socket.
  void written();
  /// The client has frame `sequence`, and every frame before it; later deltas may use it as
  /// their base. False when no frame with that sequence was built.
  bool acknowledge(std::uint64_t sequence);
  /// The subscription's window of unacknowledged frames is full: no frame may be built.
  bool window_full() const {
    return options_.max_unacknowledged != 0 &&
           unacknowledged_.size() >= options_.max_unacknowledged;
  }
  /// The largest window a subscription may ask for: the stream keeps the sequence of each
  /// frame in it.
  static constexpr std::uint32_t kMaxWindow = 64;

  /// Frames written and kept as possible delta bases, at most; fewer when they would cost more
  /// than the history's budget (a scene of millions of vertices), and none when one frame
  /// would: every frame is then a key frame.
  static constexpr std::size_t kKeptFrames = 8;
  /// The bytes the delta history holds now (within the budget).
  std::size_t history_bytes() const;
  /// A delta's base is at most this many frames older than the delta; older, and the frame is a
  /// key frame until an acknowledgement brings a newer base (a client keeps its last 16).
  static constexpr std::uint64_t kMaxBaseAge = 12;

 private:
  std::size_t max_history_bytes_;
  bool active_ = false;
  FrameOptions options_;
  std::uint64_t next_sequence_ = 1;
  std::uint64_t last_version_ = ~std::uint64_t{0};
  /// the bodies (and which of their surfaces: a reset brings new ones under old ids) whose
  /// triangles the client has
  struct Topology {
    BodyId body_id = 0;
    /// held, so that a freed surface's address cannot come back as a new surface's
    std::shared_ptr<const std::vector<Triangle>> surface;
    bool operator==(const Topology&) const = default;
  };
  std::vector<Topology> topology_sent_;
  std::vector<Topology> building_topology_;  ///< those the last frame carries
  FrameRecord building_;                     ///< the last frame built
  /// shared with the plans that use them as bases, which may be encoding on another thread
  std::deque<std::shared_ptr<const FrameRecord>> written_;
  std::shared_ptr<const FrameRecord> base_;  ///< the latest acknowledged frame still kept
  /// the frames written and not acknowledged, oldest first; kept only under a window
  std::deque<std::uint64_t> unacknowledged_;
};

}  // namespace felt::net
