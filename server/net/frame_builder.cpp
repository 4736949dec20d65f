#include "net/frame_builder.hpp"

namespace felt::net {
namespace {

void put_vectors(const std::vector<Vec3>& vectors, google::protobuf::RepeatedField<float>& out) {
  out.Reserve(static_cast<int>(3 * vectors.size()));
  for (const Vec3& v : vectors) {
    for (int k = 0; k < 3; ++k) out.AddAlreadyReserved(static_cast<float>(v[k]));
  }
}

}  // namespace

std::vector<std::uint32_t> build_frame(const SceneSnapshot& snapshot, SceneId scene_id,
                                       bool normals, std::vector<bool>& topology_sent,
                                       std::uint64_t skipped, felt::v1::Frame& frame) {
  std::vector<std::uint32_t> with_topology;
  frame.set_scene_id(scene_id);
  frame.set_step(snapshot.step);
  frame.set_sim_time(snapshot.sim_time);
  frame.set_skipped(skipped);
  if (topology_sent.size() < snapshot.bodies.size()) topology_sent.resize(snapshot.bodies.size());
  for (const BodySnapshot& body : snapshot.bodies) {
    felt::v1::BodyFrame* out = frame.add_bodies();
    out->set_body_id(body.body_id);
    out->set_name(body.name);
    put_vectors(body.positions, *out->mutable_positions());
    if (normals) put_vectors(body.normals, *out->mutable_normals());
    if (!topology_sent[body.body_id]) {
      auto& triangles = *out->mutable_triangles();
      triangles.Reserve(static_cast<int>(3 * body.triangles().size()));
      for (const Triangle& t : body.triangles()) {
        for (std::uint32_t corner : t) triangles.AddAlreadyReserved(corner);
      }
      topology_sent[body.body_id] = true;
      with_topology.push_back(body.body_id);
    }
  }
  return with_topology;
}

}  // namespace felt::net
