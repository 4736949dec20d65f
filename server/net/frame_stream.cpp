#include "net/frame_stream.hpp"

#include <algorithm>

#include "core/cloth/vertex_strain.hpp"
#include "net/wire_convert.hpp"

namespace felt::net {
namespace {

// key frames bound each body with this much room around it, so that the frames after it still
// fit the same bounds (and can be deltas) while the body moves
constexpr float kBoundsMargin = 0.25f;
constexpr float kMinBoundsMargin = 0.01f;  // m

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

void put_quantized(const BodySnapshot& body, bool with_normals, const FrameStream::BodyRecord* base,
                   FrameStream::BodyRecord& record, felt::v1::BodyFrame& out) {
  // one buffer per thread that encodes, kept: a frame then allocates nothing for it
  thread_local std::vector<float> scratch;
  to_floats(body.positions, scratch);
  // a delta keeps its base's bounds; a body that moved out of them gets a key frame
  const bool delta =
      base && base->positions.size() == scratch.size() && wire::fits(scratch, base->bounds);
  record.bounds =
      delta ? base->bounds : wire::bounds_around(scratch, kBoundsMargin, kMinBoundsMargin);
  wire::quantize(scratch, record.bounds, record.positions);
  felt::v1::QuantizedVectors& positions = *out.mutable_quantized_positions();
  put_bounds(record.bounds, positions);
  put_values(record.positions, delta ? &base->positions : nullptr, positions);
  if (with_normals) {
    to_floats(body.normals, scratch);
    const wire::QuantizationBounds unit{{-1, -1, -1}, {1, 1, 1}};
    wire::quantize(scratch, unit, record.normals);
    felt::v1::QuantizedVectors& normals = *out.mutable_quantized_normals();
    put_bounds(unit, normals);
    put_values(record.normals, delta ? &base->normals : nullptr, normals);
  }
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

void FrameStream::encode(const Plan& plan, felt::v1::Frame& frame, FrameRecord& record) {
  const SceneSnapshot& snapshot = *plan.snapshot;
  const FrameOptions& options = plan.options;
  record = {};
  record.sequence = plan.sequence;
  frame.set_scene_id(plan.scene);
  frame.set_step(snapshot.step);
  frame.set_sim_time(snapshot.sim_time);
  frame.set_skipped(plan.skipped);
  frame.set_sequence(plan.sequence);
  if (plan.base) frame.set_base_sequence(plan.base->sequence);
  put_proxies(plan.proxies, frame);
  for (const BodySnapshot& body : snapshot.bodies) {
    if (!wanted(options, body.body_id)) continue;
    felt::v1::BodyFrame* out = frame.add_bodies();
    out->set_body_id(body.body_id);
    out->set_name(body.name);
    out->set_vertex_count(static_cast<std::uint32_t>(body.positions.size()));
    if (options.quantized) {
      BodyRecord& quantized = record.bodies.emplace_back();
      put_quantized(body, options.normals, plan.base ? plan.base->find(body.body_id) : nullptr,
                    quantized, *out);
      quantized.body_id = body.body_id;
    } else {
      put_floats(body.positions, *out->mutable_positions());
      if (options.normals) put_floats(body.normals, *out->mutable_normals());
    }
    if (options.scalars && body.cloth) {
      thread_local std::vector<float> strain;
      vertex_strain(*body.cloth, body.positions, strain);
      out->mutable_scalars()->Assign(strain.begin(), strain.end());
    }
    if (std::find(plan.with_triangles.begin(), plan.with_triangles.end(), body.body_id) !=
        plan.with_triangles.end()) {
      auto& triangles = *out->mutable_triangles();
      triangles.Reserve(static_cast<int>(3 * body.triangles().size()));
      for (const Triangle& t : body.triangles()) {
        for (std::uint32_t corner : t) triangles.AddAlreadyReserved(corner);
      }
    }
  }
}

void FrameStream::put_proxies(const std::vector<ProxyView>& proxies, felt::v1::Frame& frame) {
  for (const ProxyView& proxy : proxies) {
    felt::v1::ProxyPresence& out = *frame.add_proxies();
    out.set_client_id(proxy.client);
    out.set_client_name(proxy.client_name);
    out.set_proxy_id(proxy.proxy_id);
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
  FrameRecord record;
  encode(planned, frame, record);
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
