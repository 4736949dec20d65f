#include "frame_assembler.hpp"

#include <algorithm>

#include "wire/vector_quantizer.hpp"

namespace felt::client {
namespace {

namespace v1 = felt::v1;

/// The quantized values of `q` (a key frame's values, or deltas against `base`), dequantized
/// into `out`.
std::expected<void, std::string> decode(const v1::QuantizedVectors& q, std::size_t count,
                                        const std::vector<std::uint16_t>* base,
                                        std::vector<std::uint16_t>& values,
                                        std::vector<float>& out) {
  if (q.lower_size() != 3 || q.upper_size() != 3) return std::unexpected("bounds need 3 values");
  wire::QuantizationBounds bounds;
  for (int k = 0; k < 3; ++k) {
    bounds.lower[k] = q.lower(k);
    bounds.upper[k] = q.upper(k);
  }
  if (!q.deltas().empty()) {
    if (!base) return std::unexpected("a delta without its base frame");
    if (!wire::read_deltas(q.deltas(), *base, values)) return std::unexpected("malformed deltas");
  } else if (!wire::read_values(q.values(), 3 * count, values)) {
    return std::unexpected("malformed quantized values");
  }
  wire::dequantize(values, bounds, out);
  return {};
}

}  // namespace

void FrameAssembler::clear() {
  triangles_.clear();
  kept_.clear();
}

std::expected<DecodedFrame, std::string> FrameAssembler::assemble(const v1::Frame& frame) {
  const Kept* base = nullptr;
  if (frame.base_sequence() != 0) {
    const auto it = std::find_if(kept_.begin(), kept_.end(), [&](const Kept& k) {
      return k.sequence == frame.base_sequence();
    });
    if (it == kept_.end()) {
      return std::unexpected("frame " + std::to_string(frame.sequence()) +
                             " is a delta against frame " + std::to_string(frame.base_sequence()) +
                             ", which is not kept");
    }
    base = &*it;
  }
  DecodedFrame out;
  out.scene_id = frame.scene_id();
  out.step = frame.step();
  out.sim_time = frame.sim_time();
  out.sequence = frame.sequence();
  out.skipped = frame.skipped();
  out.proxies.assign(frame.proxies().begin(), frame.proxies().end());
  Kept kept;
  kept.sequence = frame.sequence();
  for (const v1::BodyFrame& body : frame.bodies()) {
    DecodedBody& decoded = out.bodies.emplace_back();
    decoded.body_id = body.body_id();
    decoded.name = body.name();
    decoded.scalars.assign(body.scalars().begin(), body.scalars().end());
    if (body.triangles_size() > 0) {
      triangles_[body.body_id()].assign(body.triangles().begin(), body.triangles().end());
    }
    if (body.has_quantized_positions()) {
      const QuantizedBody* base_body = nullptr;
      if (base) {
        const auto found = base->bodies.find(body.body_id());
        if (found != base->bodies.end()) base_body = &found->second;
      }
      QuantizedBody& q = kept.bodies[body.body_id()];
      const std::size_t count = body.vertex_count();
      if (auto ok =
              decode(body.quantized_positions(), count, base_body ? &base_body->positions : nullptr,
                     q.positions, decoded.positions);
          !ok) {
        return std::unexpected("body " + std::to_string(body.body_id()) + ": " + ok.error());
      }
      if (body.has_quantized_normals()) {
        if (auto ok = decode(body.quantized_normals(), count,
                             base_body ? &base_body->normals : nullptr, q.normals, decoded.normals);
            !ok) {
          return std::unexpected("body " + std::to_string(body.body_id()) +
                                 " normals: " + ok.error());
        }
      }
    } else {
      decoded.positions.assign(body.positions().begin(), body.positions().end());
      decoded.normals.assign(body.normals().begin(), body.normals().end());
    }
  }
  // pointers into the map stay valid while it only grows
  for (DecodedBody& body : out.bodies) {
    const auto it = triangles_.find(body.body_id);
    body.triangles = it == triangles_.end() ? nullptr : &it->second;
  }
  if (!kept.bodies.empty()) {
    kept_.push_back(std::move(kept));
    if (kept_.size() > kKeptFrames) kept_.pop_front();
  }
  return out;
}

}  // namespace felt::client
