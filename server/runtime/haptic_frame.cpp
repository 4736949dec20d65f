#include "runtime/haptic_frame.hpp"

#include <algorithm>
#include <atomic>
#include <utility>

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
  surface.storage = storage;
  surface.bodies.reserve(to->bodies.size());
  for (std::size_t b = 0; b < to->bodies.size(); ++b) {
    const BodySnapshot& newer = to->bodies[b];
    const BodySnapshot& older = *this->older[b];
    HapticBody& body = surface.bodies.emplace_back();
    body.body_id = newer.body_id.value();
    body.triangles = newer.triangles();
    body.from = older.positions;
    body.to = newer.positions;
    body.normals_from = older.normals;
    body.normals_to = newer.normals;
    body.query = queries[b].get();
    body.motion = motion[b];
  }
  return surface;
}

namespace {

/// The body `body` of a snapshot, if `in` has it with the same surface.
const BodySnapshot* same_body(const SceneSnapshot& in, const BodySnapshot& body, std::size_t hint) {
  const BodySnapshot* found = in.find(body.body_id, hint);
  return found && found->surface == body.surface ? found : nullptr;
}

std::size_t index_in(const SceneSnapshot& snapshot, const BodySnapshot* body) {
  return static_cast<std::size_t>(body - snapshot.bodies.data());
}

/// A new chain of snapshot pairs, for a body whose motion from the previous frame is unknown.
std::uint64_t new_chain() {
  static std::atomic<std::uint64_t> chains{0};
  return chains.fetch_add(1, std::memory_order_relaxed) + 1;
}

}  // namespace

std::shared_ptr<HapticFrame> make_haptic_frame(std::shared_ptr<const SceneSnapshot> to,
                                               const HapticFrame* previous,
                                               std::shared_ptr<HapticFrame> recycled,
                                               TriangleQueryKind kind,
                                               SteadyClock::time_point now) {
  auto frame = recycled ? std::move(recycled) : std::make_shared<HapticFrame>();
  const auto& bodies = to->bodies;
  // a recycled frame's structures are refitted for the same bodies instead of copied
  std::vector<std::unique_ptr<TriangleQuery>> queries(bodies.size());
  if (frame->to) {
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (const BodySnapshot* old = same_body(*frame->to, bodies[b], b)) {
        queries[b] = std::move(frame->queries[index_in(*frame->to, old)]);
      }
    }
  }
  frame->queries = std::move(queries);
  frame->from = previous ? previous->to : to;
  frame->to = std::move(to);
  frame->published = now;
  frame->interval = previous ? now - previous->published : SteadyClock::duration{0};
  frame->storage = std::make_shared<
      const std::pair<std::shared_ptr<const SceneSnapshot>, std::shared_ptr<const SceneSnapshot>>>(
      frame->from, frame->to);
  frame->older.assign(bodies.size(), nullptr);
  frame->motion.assign(bodies.size(), SurfaceMotion{});
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodySnapshot* before = previous ? same_body(*previous->to, bodies[b], b) : nullptr;
    frame->older[b] = before ? before : &bodies[b];
    const std::vector<Vec3>& older = frame->older[b]->positions;
    const std::vector<Vec3>& newer = bodies[b].positions;
    std::unique_ptr<TriangleQuery>& query = frame->queries[b];
    if (!query && before) query = previous->queries[index_in(*previous->to, before)]->clone();
    if (!query) query = make_triangle_query(kind, bodies[b].triangles(), newer);
    query->refit(older, newer);
    // on the chain of the body's previous pair, or a new one
    const SurfaceMotion chain = before ? previous->motion[index_in(*previous->to, before)]
                                       : SurfaceMotion{0, 0, new_chain()};
    frame->motion[b] = chain.then(older, newer);
  }
  return frame;
}

}  // namespace felt
