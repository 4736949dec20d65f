#include "net/frame_stream.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/geometry/surface_normals.hpp"
#include "felt/v1/envelope.pb.h"
#include "net/shared_frame_bodies.hpp"
#include "net/wire_convert.hpp"
#include "runtime/vertex_scalars.hpp"
#include "wire/frame_codec.hpp"

namespace felt::net {
namespace {

// key frames bound each body with this much room around it, so that the frames after it still
// fit the same bounds (and can be deltas) while the body moves
constexpr float kBoundsMargin = 0.25f;
constexpr float kMinBoundsMargin = 0.01f;  // m
// protobuf's wire type of a message field: a field tag is (number << 3) | wire type
constexpr std::uint64_t kLengthDelimited = 2;

void to_floats(const std::vector<Vec3>& vectors, std::vector<float>& out) {
  static_assert(sizeof(Vec3) == 3 * sizeof(Real), "a vector buffer is its coordinates in a row");
  out.resize(3 * vectors.size());
  // one flat loop over the coordinates, which vectorizes
  const Real* in = vectors.empty() ? nullptr : vectors.front().data();
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(in[i]);
}

void put_floats(const std::vector<Vec3>& vectors, google::protobuf::RepeatedField<float>& out) {
  out.Reserve(static_cast<int>(3 * vectors.size()));
  for (const Vec3& v : vectors) {
    for (int k = 0; k < 3; ++k) out.AddAlreadyReserved(static_cast<float>(v[k]));
  }
}

void put_bounds(const wire::QuantizationBounds& bounds, felt::v1::QuantizedVectors& out) {
  for (int k = 0; k < 3; ++k) {
    out.add_lower(bounds.lower[k]);
    out.add_upper(bounds.upper[k]);
  }
}

/// Encodes `q` as deltas against `base` when there is one of the same size, else as values.
void put_values(const std::vector<std::uint16_t>& q, const std::vector<std::uint16_t>* base,
                felt::v1::QuantizedVectors& out) {
  if (base && base->size() == q.size()) {
    wire::append_deltas(q, *base, *out.mutable_deltas());
  } else {
    wire::append_values(q, *out.mutable_values());
  }
}

/// `body`'s positions as floats, in a buffer per encoding thread (kept: a frame then allocates
/// nothing for it).
const std::vector<float>& positions_as_floats(const BodySnapshot& body) {
  thread_local std::vector<float> floats;
  to_floats(body.positions, floats);
  return floats;
}

/// `body`'s vertex normals: the snapshot's when it carries them (haptics render in its scene),
/// else found here, on the frame encoder's thread, in a buffer per thread.
const std::vector<Vec3>& normals_of(const BodySnapshot& body) {
  if (body.normals.size() == body.positions.size()) return body.normals;
  thread_local std::vector<Vec3> found;
  compute_vertex_normals(body.positions, body.triangles(), found);
  return found;
}

/// `body` as 16-bit values: as deltas against `base` (whose bounds `positions`, the body's
/// positions as floats, fit) or, without one, as values within new bounds.
void put_quantized(const BodySnapshot& body, const std::vector<float>& positions, bool with_normals,
                   const FrameStream::BodyRecord* base, FrameStream::BodyRecord& record,
                   felt::v1::BodyFrame& out) {
  // a delta keeps its base's bounds
  record.bounds =
      base ? base->bounds : wire::bounds_around(positions, kBoundsMargin, kMinBoundsMargin);
  wire::quantize(positions, record.bounds, record.positions);
  felt::v1::QuantizedVectors& quantized = *out.mutable_quantized_positions();
  put_bounds(record.bounds, quantized);
  put_values(record.positions, base ? &base->positions : nullptr, quantized);
  if (with_normals) {
    thread_local std::vector<float> normals_floats;
    to_floats(normals_of(body), normals_floats);
    const wire::QuantizationBounds unit{{-1, -1, -1}, {1, 1, 1}};
    wire::quantize(normals_floats, unit, record.normals);
    felt::v1::QuantizedVectors& normals = *out.mutable_quantized_normals();
    put_bounds(unit, normals);
    put_values(record.normals, base ? &base->normals : nullptr, normals);
  }
}

/// `body` in `options`' encoding, with its triangles when `triangles`, as the one body of
/// `frame`; its 16-bit values go to `record`, as deltas against `base` when given (whose bounds
/// `positions` fit).
void put_body(const BodySnapshot& body, const std::vector<float>* positions,
              const FrameOptions& options, bool triangles, const FrameStream::BodyRecord* base,
              FrameStream::BodyRecord& record, felt::v1::Frame& frame) {
  felt::v1::BodyFrame& out = *frame.add_bodies();
  out.set_body_id(body.body_id.value());
  out.set_name(body.name);
  out.set_vertex_count(static_cast<std::uint32_t>(body.positions.size()));
  if (options.quantized) {
    put_quantized(body, positions ? *positions : positions_as_floats(body), options.normals, base,
                  record, out);
    record.body_id = body.body_id;
  } else {
    put_floats(body.positions, *out.mutable_positions());
    if (options.normals) put_floats(normals_of(body), *out.mutable_normals());
  }
  if (options.scalars) {
    thread_local std::vector<float> scalars;
    vertex_scalars(body, scalars);
    out.mutable_scalars()->Assign(scalars.begin(), scalars.end());
  }
  if (triangles) {
    auto& corners = *out.mutable_triangles();
    corners.Reserve(static_cast<int>(3 * body.triangles().size()));
    for (const Triangle& t : body.triangles()) {
      for (std::uint32_t corner : t) corners.AddAlreadyReserved(corner);
    }
  }
}

/// The bytes `value` takes as a base-128 varint.
std::size_t varint_size(std::uint64_t value) {
  std::size_t bytes = 1;
  for (; value >= 0x80; value >>= 7) ++bytes;
  return bytes;
}

bool wanted(const FrameOptions& options, BodyId id) {
  return options.bodies.empty() ||
         std::binary_search(options.bodies.begin(), options.bodies.end(), id);
}

}  // namespace

const FrameStream::BodyRecord* FrameStream::FrameRecord::find(BodyId id) const {
  for (const BodyRecord& body : bodies) {
    if (body.body_id == id) return &body;
  }
  return nullptr;
}

void FrameStream::start(const FrameOptions& options) {
  active_ = true;
  options_ = options;
  restart();
}

void FrameStream::stop() {
  active_ = false;
  restart();
}

void FrameStream::restart() {
  last_version_ = ~std::uint64_t{0};
  topology_sent_.clear();
  building_topology_.clear();
  building_ = {};
  written_.clear();
  base_.reset();
  unacknowledged_.clear();
}

FrameStream::Plan FrameStream::plan(std::shared_ptr<const SceneSnapshot> snapshot, SceneId scene,
                                    std::uint64_t skipped) {
  building_ = {};
  building_topology_.clear();
  last_version_ = snapshot->version;
  Plan plan;
  plan.scene = scene;
  plan.skipped = skipped;
  plan.sequence = next_sequence_++;
  plan.options = options_;
  if (base_ && plan.sequence - base_->sequence > kMaxBaseAge) base_.reset();
  if (options_.quantized && options_.deltas) plan.base = base_;
  for (const BodySnapshot& body : snapshot->bodies) {
    if (!wanted(options_, body.body_id)) continue;
    const Topology topology{body.body_id, body.surface};
    if (std::find(topology_sent_.begin(), topology_sent_.end(), topology) != topology_sent_.end()) {
      continue;
    }
    plan.with_triangles.push_back(body.body_id);
    std::erase_if(topology_sent_, [&](const Topology& t) { return t.body_id == body.body_id; });
    topology_sent_.push_back(topology);
    building_topology_.push_back(topology);
  }
  // bodies that are gone need their triangles again should their id ever come back
  std::erase_if(topology_sent_, [&](const Topology& t) { return !snapshot->find(t.body_id); });
  plan.snapshot = std::move(snapshot);
  return plan;
}

void FrameStream::encode(const Plan& plan, SharedFrameBodies& shared, std::string& out,
                         FrameRecord& record) {
  const SceneSnapshot& snapshot = *plan.snapshot;
  const FrameOptions& options = plan.options;
  record = {};
  record.sequence = plan.sequence;
  // the frame's fields in their numbers' order, as protobuf writes them: those before the bodies
  // (1-4), the bodies (5), those after them (6-8)
  felt::v1::Frame before;
  before.set_scene_id(plan.scene.value());
  before.set_step(snapshot.step);
  before.set_sim_time(snapshot.sim_time);
  before.set_skipped(plan.skipped);
  felt::v1::Frame after;
  after.set_sequence(plan.sequence);
  if (plan.base) after.set_base_sequence(plan.base->sequence);
  put_proxies(plan.proxies, after);
  // the bodies' bytes, shared or this client's own, written out once below
  std::vector<std::shared_ptr<const EncodedBody>> bodies;
  for (std::size_t i = 0; i < snapshot.bodies.size(); ++i) {
    const BodySnapshot& body = snapshot.bodies[i];
    if (!wanted(options, body.body_id)) continue;
    const bool triangles = std::find(plan.with_triangles.begin(), plan.with_triangles.end(),
                                     body.body_id) != plan.with_triangles.end();
    const BodyRecord* base =
        options.quantized && plan.base ? plan.base->find(body.body_id) : nullptr;
    if (base) {
      // a delta is this client's own; a body that moved out of its base's bounds, or has other
      // vertices now, gets a key frame, which is everyone's
      const std::vector<float>& positions = positions_as_floats(body);
      if (base->positions.size() == positions.size() && wire::fits(positions, base->bounds)) {
        auto own = std::make_shared<EncodedBody>();
        felt::v1::Frame one;
        put_body(body, &positions, options, triangles, base, record.bodies.emplace_back(), one);
        own->bytes = one.SerializeAsString();
        bodies.push_back(std::move(own));
        continue;
      }
    }
    bodies.push_back(shared.get(
        plan.snapshot, i, {options.quantized, options.normals, options.scalars, triangles}, [&] {
          EncodedBody fresh;
          felt::v1::Frame one;
          put_body(body, nullptr, options, triangles, nullptr, fresh.record, one);
          fresh.bytes = one.SerializeAsString();
          return fresh;
        }));
    if (options.quantized) record.bodies.push_back(bodies.back()->record);
  }
  // a ServerMessage whose one field is the frame, behind its length: written in one go
  const std::string head = before.SerializeAsString();
  const std::string tail = after.SerializeAsString();
  std::size_t frame_size = head.size() + tail.size();
  for (const auto& body : bodies) frame_size += body->bytes.size();
  const std::uint64_t tag = (felt::v1::ServerMessage::kFrameFieldNumber << 3) | kLengthDelimited;
  const std::size_t message_size = varint_size(tag) + varint_size(frame_size) + frame_size;
  out.reserve(out.size() + varint_size(message_size) + message_size);
  wire::append_varint(out, message_size);
  wire::append_varint(out, tag);
  wire::append_varint(out, frame_size);
  out += head;
  for (const auto& body : bodies) out += body->bytes;
  out += tail;
}

void FrameStream::put_proxies(const std::vector<ProxyView>& proxies, felt::v1::Frame& frame) {
  for (const ProxyView& proxy : proxies) {
    felt::v1::ProxyPresence& out = *frame.add_proxies();
    out.set_client_id(proxy.state.key.client.value());
    out.set_client_name(proxy.client_name);
    out.set_proxy_id(proxy.state.key.proxy.value());
    out.set_own(proxy.own);
    const ProxyPresenceEntry& state = proxy.state;
    put_vec3(state.position, *out.mutable_position());
    out.set_radius(state.radius);
    out.set_in_contact(state.in_contact);
    put_vec3(state.force, *out.mutable_force());
    if (state.in_contact) put_vec3(state.contact_point, *out.mutable_contact_point());
    out.set_grabbing(state.grabbing);
  }
}

void FrameStream::build(std::shared_ptr<const SceneSnapshot> snapshot, SceneId scene,
                        std::uint64_t skipped, felt::v1::Frame& frame) {
  const Plan planned = plan(std::move(snapshot), scene, skipped);
  SharedFrameBodies shared;
  std::string bytes;
  FrameRecord record;
  encode(planned, shared, bytes, record);
  const std::optional<wire::FrameView> message = wire::first_frame(bytes);
  felt::v1::ServerMessage parsed;
  if (!message || !parsed.ParseFromString(std::string(message->payload))) {
    throw std::logic_error("FrameStream::encode wrote no ServerMessage");
  }
  frame = std::move(*parsed.mutable_frame());
  encoded(std::move(record));
}

void FrameStream::dropped() {
  for (const Topology& t : building_topology_) std::erase(topology_sent_, t);
  building_topology_.clear();
  building_ = {};
}

std::size_t FrameStream::FrameRecord::bytes() const {
  std::size_t total = 0;
  for (const BodyRecord& body : bodies) {
    total += (body.positions.size() + body.normals.size()) * sizeof(std::uint16_t);
  }
  return total;
}

std::size_t FrameStream::history_bytes() const {
  std::size_t total = base_ ? base_->bytes() : 0;
  for (const auto& frame : written_) total += frame->bytes();
  return total;
}

void FrameStream::written() {
  building_topology_.clear();
  if (options_.max_unacknowledged != 0) unacknowledged_.push_back(building_.sequence);
  if (!options_.quantized || !options_.deltas) return;
  written_.push_back(std::make_shared<const FrameRecord>(std::move(building_)));
  building_ = {};
  // the oldest go first: an acknowledgement names a recent frame
  while (!written_.empty() &&
         (written_.size() > kKeptFrames || history_bytes() > max_history_bytes_)) {
    written_.pop_front();
  }
}

bool FrameStream::acknowledge(std::uint64_t sequence) {
  if (sequence == 0 || sequence >= next_sequence_) return false;
  while (!unacknowledged_.empty() && unacknowledged_.front() <= sequence) {
    unacknowledged_.pop_front();
  }
  const auto it = std::find_if(written_.begin(), written_.end(), [sequence](const auto& frame) {
    return frame->sequence == sequence;
  });
  // a frame already forgotten (acknowledged late) or dropped unsent cannot be a base
  if (it == written_.end()) return true;
  if (!base_ || base_->sequence < sequence) base_ = *it;  // shared, not copied
  written_.erase(written_.begin(), it);
  while (!written_.empty() && history_bytes() > max_history_bytes_) written_.pop_front();
  if (base_ && base_->bytes() > max_history_bytes_) base_.reset();
  return true;
}

}  // namespace felt::net
