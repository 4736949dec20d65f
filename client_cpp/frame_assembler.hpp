#pragma once
// Streamed frames back into vertex buffers: float32 or 16-bit quantized, key frames or deltas
// against an acknowledged frame, with each body's triangles remembered from the frame that
// carried them (the server sends them once per subscription).

#include <cstdint>
#include <deque>
#include <expected>
#include <map>
#include <string>
#include <vector>

#include "felt/v1/frames.pb.h"

namespace felt::client {

struct DecodedBody {
  std::uint32_t body_id = 0;
  std::string name;
  std::vector<float> positions;  ///< x, y, z per vertex
  std::vector<float> normals;    ///< empty unless subscribed with normals
  std::vector<float> scalars;    ///< one per vertex when subscribed with scalars (strain)
  const std::vector<std::uint32_t>* triangles = nullptr;  ///< three per triangle; null: unknown
};

struct DecodedFrame {
  std::uint64_t scene_id = 0;
  std::uint64_t step = 0;
  double sim_time = 0;
  std::uint64_t sequence = 0;
  std::uint64_t skipped = 0;
  std::vector<DecodedBody> bodies;
  std::vector<felt::v1::ProxyPresence> proxies;  ///< every proxy in the scene, own ones marked
};

class FrameAssembler {
 public:
  /// Decodes `frame`. A delta frame needs its base frame decoded before (and still kept: the
  /// latest kKeptFrames are); an error says what is missing or malformed.
  std::expected<DecodedFrame, std::string> assemble(const felt::v1::Frame& frame);

  /// Forgets triangles and bases (after subscribing again or joining another scene).
  void clear();

  static constexpr std::size_t kKeptFrames = 16;

 private:
  struct QuantizedBody {
    std::vector<std::uint16_t> positions, normals;
  };
  struct Kept {
    std::uint64_t sequence = 0;
    std::map<std::uint32_t, QuantizedBody> bodies;
  };

  std::map<std::uint32_t, std::vector<std::uint32_t>> triangles_;
  std::deque<Kept> kept_;
};

}  // namespace felt::client
