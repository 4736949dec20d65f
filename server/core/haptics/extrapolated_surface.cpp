#include "core/haptics/extrapolated_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace felt {
namespace {

constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();

}  // namespace

std::shared_ptr<ExtrapolatedSurface::Body> ExtrapolatedSurface::body_for(
    const LocalModelBody& model) {
  for (const std::shared_ptr<Body>& body : bodies_) {
    if (body->body_id == model.body_id && body->normals.size() == model.vertex_count + 1 &&
        body->triangles.size() == model.triangle_count) {
      return body;
    }
  }
  // new, or a new surface under its id: a chain of its own, nothing known yet
  auto body = std::make_shared<Body>();
  body->body_id = model.body_id;
  const Triangle spare{model.vertex_count, model.vertex_count, model.vertex_count};
  body->triangles.assign(model.triangle_count, spare);
  body->normals.assign(model.vertex_count + 1, Vec3::Zero());
  for (std::vector<Vec3>& state : body->ring)
    state.assign(model.vertex_count + 1, Vec3::Constant(kNaN));
  body->motion = SurfaceMotion{0, 0, ++chains_};
  return body;
}

void ExtrapolatedSurface::take(const LocalModel& model, Real time) {
  std::vector<std::shared_ptr<Body>> bodies;
  for (const LocalModelBody& cut : model.bodies) {
    std::shared_ptr<Body> body = body_for(cut);
    const Triangle spare{cut.vertex_count, cut.vertex_count, cut.vertex_count};
    for (const std::uint32_t t : body->listed) body->triangles[t] = spare;
    for (const std::uint32_t v : body->vertices) body->normals[v] = Vec3::Zero();
    body->listed = cut.triangle_ids;
    for (std::size_t i = 0; i < cut.triangle_ids.size(); ++i) {
      body->triangles[cut.triangle_ids[i]] = cut.corners[i];
    }
    body->vertices = cut.vertex_ids;
    body->positions = cut.positions;
    body->velocities = cut.velocities;
    for (std::size_t i = 0; i < cut.vertex_ids.size(); ++i) {
      body->normals[cut.vertex_ids[i]] = cut.normals[i];
    }
    body->query = std::make_unique<ListedTriangleQuery>(body->triangles, body->listed);
    bodies.push_back(std::move(body));
  }
  bodies_ = std::move(bodies);
  model_time_ = time;
  blend_start_ = last_advance_;
  blend_begins_ = true;
  has_model_ = true;
}

Real ExtrapolatedSurface::ahead(Real time) const {
  return std::clamp(time - model_time_, -kMaxExtrapolation, kMaxExtrapolation);
}

HapticSurface ExtrapolatedSurface::advance(Real time) {
  const Real ahead_now = ahead(time);
  // the share of the difference at the blend's start still shown: 1 then, 0 after kModelBlend
  const Real blend =
      blend_start_ ? std::clamp(1 - (time - *blend_start_) / kModelBlend, Real(0), Real(1)) : 0;
  const Real ahead_then = blend_start_ ? ahead(*blend_start_) : 0;  // at the blend's start
  HapticSurface surface;
  surface.step = ++ticks_;
  surface.alpha = 1;
  for (const std::shared_ptr<Body>& body : bodies_) {
    const std::size_t next = (body->turn + 1) % body->ring.size();
    std::vector<Vec3>& state = body->ring[next];
    // what this slot held three ticks ago is not there now unless the model says so
    for (const std::uint32_t v : body->written[next]) state[v] = Vec3::Constant(kNaN);
    std::vector<Vec3>& from = body->ring[body->turn];
    if (blend_begins_) body->correction.assign(body->vertices.size(), Vec3::Zero());
    for (std::size_t i = 0; blend_begins_ && blend_start_ && i < body->vertices.size(); ++i) {
      Vec3& shown = from[body->vertices[i]];
      if (!shown.allFinite()) {
        // new in this model: it was where the server saw it, and moves on from there. Put
        // where it is extrapolated to, a surface swinging fast toward a free proxy (a curtain at
        // 5 m/s, 28 ms ahead) would appear on its far side with nothing seen to pass it
        shown = body->positions[i];
        body->written[body->turn].push_back(body->vertices[i]);
      }
      body->correction[i] = shown - (body->positions[i] + ahead_then * body->velocities[i]);
    }
    // only the model's vertices move: the rest are not there, before or now
    Real largest_sq = 0;
    for (std::size_t i = 0; i < body->vertices.size(); ++i) {
      const std::uint32_t v = body->vertices[i];
      state[v] = body->positions[i] + ahead_now * body->velocities[i] + blend * body->correction[i];
      if (!from[v].allFinite()) {
        // in the first model: it was where it is now, so that its triangles are there at once
        // (a state in between would not be finite) and did not move
        from[v] = state[v];
        body->written[body->turn].push_back(v);
      }
      largest_sq = std::max(largest_sq, (state[v] - from[v]).squaredNorm());
    }
    body->written[next] = body->vertices;
    body->turn = next;
    body->query->refit(from, state);
    body->motion = body->motion.moved(std::sqrt(largest_sq));
    surface.bodies.push_back(HapticBody{body->body_id, body->triangles, from, state, body->normals,
                                        body->normals, body->query.get(), body->motion});
  }
  blend_begins_ = false;
  last_advance_ = time;
  // the bodies, with their arrays and queries, live while the surface is kept
  surface.storage = std::make_shared<const std::vector<std::shared_ptr<Body>>>(bodies_);
  return surface;
}

}  // namespace felt
