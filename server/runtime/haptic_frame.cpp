#include "runtime/haptic_frame.hpp"

#include <algorithm>

namespace felt {

HapticSurface HapticFrame::surface(SteadyClock::time_point now) const {
  if (interval.count() <= 0) return surface_at(1);
  const double elapsed = std::chrono::duration<double>(now - published).count();
  return surface_at(elapsed / std::chrono::duration<double>(interval).count());
}

HapticSurface HapticFrame::surface_at(Real alpha) const {
  HapticSurface surface;
  surface.step = to->step;
  surface.alpha = std::clamp<Real>(alpha, 0, 1);
  surface.bodies.reserve(to->bodies.size());
  for (std::size_t b = 0; b < to->bodies.size(); ++b) {
    const BodySnapshot& newer = to->bodies[b];
    const BodySnapshot& older = from->bodies[b];
    HapticBody& body = surface.bodies.emplace_back();
    body.body_id = newer.body_id;
    body.triangles = newer.triangles();
    body.from = older.positions;
    body.to = newer.positions;
    body.normals_from = older.normals;
    body.normals_to = newer.normals;
    body.query = queries[b].get();
    body.max_displacement = max_displacement[b];
  }
  return surface;
}

std::shared_ptr<HapticFrame> make_haptic_frame(std::shared_ptr<const SceneSnapshot> to,
                                               const HapticFrame* previous,
                                               std::shared_ptr<HapticFrame> recycled,
                                               TriangleQueryKind kind,
                                               SteadyClock::time_point now) {
  auto frame = recycled ? std::move(recycled) : std::make_shared<HapticFrame>();
  // bodies keep their ids and surfaces for a scene's life; a changed count starts over
  const bool continues = previous && previous->to->bodies.size() == to->bodies.size();
  frame->from = continues ? previous->to : to;
  frame->to = std::move(to);
  frame->published = now;
  frame->interval = continues ? now - previous->published : SteadyClock::duration{0};

  const auto& bodies = frame->to->bodies;
  if (frame->queries.size() != bodies.size()) frame->queries.clear();
  frame->queries.resize(bodies.size());
  frame->max_displacement.assign(bodies.size(), 0);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::vector<Vec3>& older = frame->from->bodies[b].positions;
    const std::vector<Vec3>& newer = bodies[b].positions;
    std::unique_ptr<TriangleQuery>& query = frame->queries[b];
    if (!query && continues) query = previous->queries[b]->clone();
    if (!query) query = make_triangle_query(kind, bodies[b].triangles(), newer);
    query->refit(older, newer);
    Real largest_sq = 0;
    for (std::size_t i = 0; i < newer.size(); ++i) {
      largest_sq = std::max(largest_sq, (newer[i] - older[i]).squaredNorm());
    }
    frame->max_displacement[b] = std::sqrt(largest_sq);
  }
  return frame;
}

}  // namespace felt
