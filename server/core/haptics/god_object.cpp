// Over 500 lines: GodObject::update's mechanisms (candidate triangles, the carry by a moving
// surface, the constrained move, friction and force shading, the device limits) still share this
// file; splitting them into a file per stage, each with its own tests, is open work (issue 28).

#include "core/haptics/god_object.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <span>
#include <utility>

#include "core/geometry/triangle_geometry.hpp"
#include "core/math/bounds.hpp"
#include "core/math/clamp_length.hpp"

namespace felt {
namespace {

// The proxy rests this far beyond its radius from what holds it, so rounding never puts it on
// the surface (whose side would then be unknown) and a slide along a face does not meet that
// face again. The reported proxy is moved back onto the radius: the force does not feel it.
constexpr Real kSkin = 1e-6;
// Move-stage sweeps per update: a corner takes four (three planes and the final slide); the
// rest is room for planes that are dropped and met again.
constexpr int kMaxMoveIterations = 8;
constexpr int kMaxPlanes = 3;
// Triangles tried in turn when leg 1 would pass the one before.
constexpr int kMaxReanchors = 2;
// A plane met again (rounding) has the same normal to this cosine.
constexpr Real kSamePlaneCos = 1 - 1e-12;
// A centre whose offset from the nearest point leans less than this (radians) off the face
// normal lies over the face: on a shared edge, the offset's lean is rounding.
constexpr Real kOverFace = 1e-6;
// The distance bound may round above a true distance that ties the nearest one; this slack
// keeps such a triangle in the comparison, where ties are broken by index.
constexpr Real kBoundSlack = 1e-12;
// Below this squared sine of its angle a triangle's frame turns with rounding.
constexpr Real kFlatSinSq = 1e-14;
// A plane counts as satisfied this far on its wrong side (rounding of the projection).
constexpr Real kPlaneTolerance = 1e-3 * kSkin;

Vec3 lerp(const Vec3& x0, const Vec3& x1, Real alpha) {
  return (1 - alpha) * x0 + alpha * x1;
}

/// A triangle of `body` at `alpha` between its snapshots (HapticSurface::vertex's formula).
TriangleCorners corners_at(const HapticBody& body, const Triangle& t, Real alpha) {
  return {lerp(body.from[t[0]], body.to[t[0]], alpha), lerp(body.from[t[1]], body.to[t[1]], alpha),
          lerp(body.from[t[2]], body.to[t[2]], alpha)};
}

bool finite(const TriangleCorners& c) {
  return c.a.allFinite() && c.b.allFinite() && c.c.allFinite();
}

/// How far a vertex of the body moves between its snapshots (0 when it does not say).
Real motion_of(const HapticBody& body) {
  const Real d = body.motion.max_displacement;
  return std::isfinite(d) ? std::max(d, Real{0}) : 0;
}

/// Triangle `triangle` of `body` at `alpha`, unless it is not there (a bad index, a
/// non-finite corner).
std::optional<TriangleCorners> triangle_at(const HapticBody& body, std::uint32_t triangle,
                                           Real alpha) {
  if (triangle >= body.triangles.size()) return std::nullopt;
  const Triangle& t = body.triangles[triangle];
  const std::size_t vertices = std::min(body.from.size(), body.to.size());
  if (t[0] >= vertices || t[1] >= vertices || t[2] >= vertices) return std::nullopt;
  const TriangleCorners c = corners_at(body, t, alpha);
  if (!finite(c)) return std::nullopt;
  return c;
}

/// Whether `then` is `now`'s body as an earlier surface had it: the same id and surface.
bool same_body(const HapticBody& then, const HapticBody& now) {
  return then.body_id == now.body_id && then.triangles.data() == now.triangles.data() &&
         then.triangles.size() == now.triangles.size() && then.from.size() == now.from.size() &&
         then.to.size() == now.to.size();
}

/// A bound on how far any vertex of `now` (rendered at `alpha`) is from where it was in `then`
/// (rendered at `then_alpha`).
Real travel_between(const HapticBody& then, Real then_alpha, const HapticBody& now, Real alpha) {
  const Real motion = motion_of(now);
  if (then.from.data() == now.from.data() && then.to.data() == now.to.data()) {
    return std::abs(alpha - then_alpha) * motion;  // the same snapshot pair
  }
  if (now.motion.chain != 0 && now.motion.chain == then.motion.chain) {
    // along the chain of pairs between them; the slack covers the sums' rounding
    const Real along = (now.motion.travelled - (1 - alpha) * motion) -
                       (then.motion.travelled - (1 - then_alpha) * motion_of(then));
    const Real travel = std::abs(along) + 1e-12 * (1 + std::abs(now.motion.travelled));
    if (std::isfinite(travel)) return travel;
  }
  // unrelated snapshots (the scene went on while nobody touched it): look at every vertex
  Real largest_sq = 0;
  for (std::size_t i = 0; i < now.to.size(); ++i) {
    const Vec3 d = lerp(now.from[i], now.to[i], alpha) - lerp(then.from[i], then.to[i], then_alpha);
    if (d.allFinite()) largest_sq = std::max(largest_sq, d.squaredNorm());
  }
  return std::sqrt(largest_sq);
}

Aabb segment_box(const Vec3& p0, const Vec3& p1, Real margin) {
  Aabb box;
  box.grow(p0);
  box.grow(p1);
  return box.inflated(margin);
}

Vec3 point_at(const TriangleCorners& c, const Vec3& barycentric) {
  return barycentric.x() * c.a + barycentric.y() * c.b + barycentric.z() * c.c;
}

/// Unit normal of a triangle, or none when it is too thin to have a reliable one.
std::optional<Vec3> unit_normal(const TriangleCorners& c) {
  const Vec3 ab = c.b - c.a;
  const Vec3 ac = c.c - c.a;
  const Vec3 normal = ab.cross(ac);
  if (!(normal.squaredNorm() > kFlatSinSq * ab.squaredNorm() * ac.squaredNorm())) {
    return std::nullopt;
  }
  return Vec3(normal.normalized());
}

/// A triangle's orthonormal frame: first edge, its perpendicular in the plane, unit normal.
std::optional<Mat3> frame_of(const TriangleCorners& c) {
  const std::optional<Vec3> normal = unit_normal(c);
  if (!normal) return std::nullopt;
  Mat3 frame;
  frame.col(0) = (c.b - c.a).normalized();
  frame.col(2) = *normal;
  frame.col(1) = normal->cross(frame.col(0));
  return frame;
}

/// A point relative to a triangle: see GodObject::Anchor.
struct Placement {
  Vec3 barycentric;
  Vec3 offset;
};

std::optional<Placement> place(const TriangleCorners& c, const Vec3& p) {
  const std::optional<Mat3> frame = frame_of(c);
  if (!frame) return std::nullopt;
  const ClosestPoint nearest = closest_point_on_triangle(p, c.a, c.b, c.c);
  return Placement{nearest.barycentric, frame->transpose() * (p - nearest.point)};
}

std::optional<Vec3> position_of(const TriangleCorners& c, const Placement& placement) {
  const std::optional<Mat3> frame = frame_of(c);
  if (!frame) return std::nullopt;
  const Vec3 p = point_at(c, placement.barycentric) + *frame * placement.offset;
  if (!p.allFinite()) return std::nullopt;
  return p;
}

/// Unit vector from the triangle's point nearest to `centre` toward it: the face normal on the
/// centre's side when the centre lies over the face (exact however near the centre is, where
/// the direction from the nearest point would carry its rounding), else the direction from an
/// edge or a corner. Zero when the centre is on the triangle.
Vec3 contact_normal(const Vec3& centre, const TriangleCorners& c, const ClosestPoint& nearest) {
  const Vec3 offset = centre - nearest.point;
  const Vec3 face = (c.b - c.a).cross(c.c - c.a);
  const Real face_length = face.norm();
  if (face_length > 0) {
    const Vec3 normal = face / face_length;
    const Real height = normal.dot(offset);
    const Real across = (offset - normal * height).norm();
    if (height != 0 &&
        (nearest.barycentric.minCoeff() > 0 || across <= kOverFace * std::abs(height))) {
      return height > 0 ? normal : Vec3(-normal);
    }
  }
  const Real distance = offset.norm();
  return distance > 0 ? Vec3(offset / distance) : Vec3::Zero();
}

/// The candidate triangles as the stages see them, at the current state: corners, unit
/// normals (zero without area), bounding circles in their planes and boxes. References, so that
/// gathering more shows through.
struct Candidates {
  const std::vector<TriangleCorners>& now;
  const std::vector<Vec3>& normals;
  const std::vector<Vec3>& centres;
  const std::vector<Real>& extents;
  const std::vector<Aabb>& bounds;
  /// each candidate's triangle index: equal hits and distances go to the lower index, so the
  /// result does not depend on the order a broad phase lists candidates in (a replay against
  /// another structure finds the same triangle)
  const std::vector<std::uint32_t>& ids;

  /// A lower bound on the distance from p to triangle i, far cheaper than the distance: the
  /// height over its plane, with how far p's foot on the plane lies outside its circle.
  Real distance_bound(std::size_t i, const Vec3& p) const {
    const Vec3 d = p - centres[i];
    const Real height = normals[i].dot(d);
    const Real across =
        std::sqrt(std::max(d.squaredNorm() - height * height, Real{0})) - extents[i];
    return across > 0 ? std::sqrt(height * height + across * across) : std::abs(height);
  }

  /// Whether the whole segment p0 → p1 (of `length`) stays farther than `reach` from
  /// triangle i, by two cheap tests: beyond its plane on one side at both ends (the height is
  /// affine along the segment), or far from it at both ends (the distance changes no faster
  /// than the point moves, so it stays above the mean of the ends less half the length).
  bool out_of_reach(std::size_t i, const Vec3& p0, const Vec3& p1, Real length, Real reach) const {
    const Real h0 = normals[i].dot(p0 - centres[i]);
    const Real h1 = normals[i].dot(p1 - centres[i]);
    if ((h0 > reach && h1 > reach) || (h0 < -reach && h1 < -reach)) return true;
    return distance_bound(i, p0) + distance_bound(i, p1) - length > 2 * reach;
  }
};

/// A constraint of the move stage: the proxy's centre must satisfy normal · x ≥ offset.
struct Plane {
  Vec3 normal;
  Real offset;
};

/// The point nearest to `goal` on the free side of every plane (at most three): the
/// Karush–Kuhn–Tucker point of the subset of planes held as equalities, tried fewest first
/// (Ruspini et al. 1997 solve the same problem). `active` gets that subset as a bit mask. None
/// when no point is free of all (planes facing each other closer than the proxy's size).
std::optional<Vec3> nearest_free_point(const Vec3& goal, std::span<const Plane> planes,
                                       unsigned& active) {
  using Normals = Eigen::Matrix<Real, 3, Eigen::Dynamic, 0, 3, kMaxPlanes>;
  using Small = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxPlanes, kMaxPlanes>;
  using SmallVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxPlanes, 1>;
  const auto count = static_cast<unsigned>(planes.size());
  for (unsigned size = 0; size <= count; ++size) {
    for (unsigned mask = 0; mask < (1u << count); ++mask) {
      if (static_cast<unsigned>(std::popcount(mask)) != size) continue;
      Normals normals(3, size);
      SmallVector rhs(size);
      for (unsigned i = 0, k = 0; i < count; ++i) {
        if (!(mask & (1u << i))) continue;
        normals.col(k) = planes[i].normal;
        rhs(k) = planes[i].offset - planes[i].normal.dot(goal);
        ++k;
      }
      Vec3 x = goal;
      if (size > 0) {
        const Small gram = normals.transpose() * normals;
        if (!(gram.determinant() > 1e-12)) continue;  // parallel planes: no single point
        const SmallVector lambda = gram.partialPivLu().solve(rhs);
        if ((lambda.array() < 0).any()) continue;  // this plane would pull, not hold
        x += normals * lambda;
      }
      bool free = x.allFinite();
      for (const Plane& plane : planes) {
        free = free && plane.normal.dot(x) >= plane.offset - kPlaneTolerance;
      }
      if (!free) continue;
      active = mask;
      return x;
    }
  }
  return std::nullopt;
}

struct Hit {
  std::size_t candidate = 0;
  SweepHit sweep;
};

/// The first triangle the sphere meets on its way from p0 to p1, against the current state.
std::optional<Hit> first_hit(const Candidates& c, const Vec3& p0, const Vec3& p1, Real radius) {
  const Aabb path = segment_box(p0, p1, radius + kSkin);
  const Real length = (p1 - p0).norm();
  std::optional<Hit> best;
  for (std::size_t i = 0; i < c.now.size(); ++i) {
    if (!c.bounds[i].overlaps(path) || c.out_of_reach(i, p0, p1, length, radius)) continue;
    const std::optional<SweepHit> hit =
        sweep_sphere_triangle(p0, p1, radius, c.now[i].a, c.now[i].b, c.now[i].c);
    if (hit && (!best || hit->t < best->sweep.t ||
                (hit->t == best->sweep.t && c.ids[i] < c.ids[best->candidate])))
      best = Hit{i, *hit};
  }
  return best;
}

/// How far the sphere gets from p0 toward p1: all the way, or to where it meets a triangle,
/// backed off along the path until the skin is between them.
struct Stop {
  Vec3 position;
  std::optional<Hit> hit;
};

Stop sweep_to(const Candidates& c, const Vec3& p0, const Vec3& p1, Real radius) {
  const std::optional<Hit> hit = first_hit(c, p0, p1, radius);
  if (!hit) return {p1, hit};
  const Vec3 path = p1 - p0;
  const Real approach = -path.dot(hit->sweep.normal);
  const Real t = approach > 0 ? std::max(Real{0}, hit->sweep.t - kSkin / approach) : hit->sweep.t;
  return {p0 + t * path, hit};
}

/// Whether the sphere at `centre` is within the skin of touching some triangle.
bool touches(const Candidates& c, const Vec3& centre, Real radius) {
  const Real reach = radius + 2 * kSkin;
  const Aabb box = segment_box(centre, centre, reach);
  for (std::size_t i = 0; i < c.now.size(); ++i) {
    if (!c.bounds[i].overlaps(box) || c.distance_bound(i, centre) > reach) continue;
    const TriangleCorners& t = c.now[i];
    const Vec3 nearest = closest_point_on_triangle(centre, t.a, t.b, t.c).point;
    if ((centre - nearest).squaredNorm() <= reach * reach) return true;
  }
  return false;
}

struct Move {
  Vec3 position = Vec3::Zero();
  int constraints = 0;             ///< planes holding the proxy where it stopped
  std::optional<Vec3> first_stop;  ///< where it first met the surface
};

/// The move stage (Zilles & Salisbury 1995, Ruspini et al. 1997): sweep toward the goal; each
/// triangle met becomes a plane, the goal is projected onto the free side of the planes and
/// swept to again; planes the goal is on the free side of are dropped; a fourth plane stops it.
/// `gather(box)` makes the candidates cover a box before it is looked at.
template <class Gather>
Move move_proxy(const Vec3& start, const Vec3& goal, Real radius, const Gather& gather,
                const Candidates& candidates) {
  std::array<Plane, kMaxPlanes> planes{};
  std::size_t count = 0;
  // a plane joins the others unless one has its normal; false when there are three already
  const auto add = [&](const Vec3& normal, const Vec3& touched) {
    const Plane plane{normal, normal.dot(touched) + radius + kSkin};
    for (std::size_t i = 0; i < count; ++i) {
      if (planes[i].normal.dot(normal) >= kSamePlaneCos) {
        planes[i].offset = std::max(planes[i].offset, plane.offset);
        return true;
      }
    }
    if (count == kMaxPlanes) return false;
    planes[count++] = plane;
    return true;
  };
  // what the sphere rests on within `reach` holds it (no sweep into it again), and so does a
  // surface that moved onto it: pushed out to the side its centre is on. Returns the plane of
  // what it rests on.
  const auto hold = [&](const Vec3& centre, Real reach) -> std::optional<Plane> {
    const Aabb box = segment_box(centre, centre, reach);
    gather(box);
    std::optional<std::pair<Vec3, Vec3>> resting;  // normal, touched point
    Real resting_distance = reach;
    std::uint32_t resting_id = ~0u;
    for (std::size_t i = 0; i < candidates.now.size(); ++i) {
      if (!candidates.bounds[i].overlaps(box) || candidates.distance_bound(i, centre) > reach) {
        continue;
      }
      const TriangleCorners& t = candidates.now[i];
      const ClosestPoint nearest = closest_point_on_triangle(centre, t.a, t.b, t.c);
      const Real distance = (centre - nearest.point).norm();
      if (!(distance > 0 && distance <= reach)) continue;  // on it: no side to hold it on
      const Vec3 normal = contact_normal(centre, t, nearest);
      if (distance < radius) add(normal, nearest.point);
      if (distance < resting_distance ||
          (distance == resting_distance && candidates.ids[i] < resting_id)) {
        resting_id = candidates.ids[i];
        resting_distance = distance;
        resting.emplace(normal, nearest.point);
      }
    }
    if (!resting) return std::nullopt;
    add(resting->first, resting->second);
    return Plane{resting->first, resting->first.dot(resting->second) + radius + kSkin};
  };
  hold(start, radius + 2 * kSkin);
  Move move;
  Vec3 position = start;
  for (int iteration = 0; iteration < kMaxMoveIterations; ++iteration) {
    unsigned active = 0;
    const std::optional<Vec3> target =
        nearest_free_point(goal, std::span<const Plane>(planes.data(), count), active);
    if (!target) break;  // squeezed between planes: stay
    std::size_t kept = 0;
    for (std::size_t i = 0; i < count; ++i) {
      if (active & (1u << i)) planes[kept++] = planes[i];
    }
    count = kept;
    const Vec3 path = *target - position;
    if (path.squaredNorm() == 0) break;
    gather(segment_box(position, *target, radius + kSkin));
    const Stop stop = sweep_to(candidates, position, *target, radius);
    position = stop.position;
    if (!stop.hit) {
      if (count == 0) break;
      gather(segment_box(position, position, radius + 2 * kSkin));
      if (touches(candidates, position, radius)) break;
      // the planes ran on past the surface they stood for (over a convex edge, or a curved
      // surface): let go of them for what lies under the proxy now, at most as far below as
      // the slide went, and settle straight down onto it; sweeping on toward the goal instead
      // would float off the next tangent plane again
      count = 0;
      const std::optional<Plane> under = hold(position, radius + 2 * kSkin + path.norm());
      const Real above = under ? under->normal.dot(position) - under->offset : 0;
      if (above > 0) {
        const Vec3 down = position - above * under->normal;
        gather(segment_box(position, down, radius + kSkin));
        const Stop settled = sweep_to(candidates, position, down, radius);
        position = settled.position;
        if (settled.hit) {
          const Hit& hit = *settled.hit;
          add(hit.sweep.normal, point_at(candidates.now[hit.candidate], hit.sweep.barycentric));
        }
      }
      continue;
    }
    if (!move.first_stop) move.first_stop = position;
    const Hit& hit = *stop.hit;
    const Vec3 touched = point_at(candidates.now[hit.candidate], hit.sweep.barycentric);
    if (!add(hit.sweep.normal, touched)) break;  // a corner: nowhere left to go
  }
  move.position = position;
  if (position != goal) {
    for (std::size_t i = 0; i < count; ++i) {
      if (planes[i].normal.dot(position) - planes[i].offset <= 0.5 * kSkin) ++move.constraints;
    }
  }
  return move;
}

/// The nearest triangle to a point, and the nearest that has a frame to anchor to.
struct Nearest {
  std::size_t candidate = 0;
  ClosestPoint point;
  Real distance = 0;
};

/// The force on the device (see GodObject::update) before damping and the device's limits.
/// `held` is how far friction holds the proxy from where it would slide to.
Vec3 spring_force(Real stiffness, const Vec3& offset, const Vec3& shaded, const Vec3& held) {
  if (shaded.isZero()) return stiffness * offset;
  // Ruspini's sub-proxy: the device projected onto the plane through the proxy with the shaded
  // normal, moved along that plane by what friction holds
  return stiffness * (shaded * shaded.dot(offset) + held - shaded * shaded.dot(held));
}

}  // namespace

GodObject::GodObject(const ProxySettings& settings, const Vec3& device)
    : settings_(settings), proxy_(device), rest_(device) {}

std::optional<std::uint32_t> GodObject::find_body(const HapticSurface& surface,
                                                  const Anchor& anchor) const {
  const auto fits = [&](std::uint32_t b) {
    return surface.bodies[b].body_id == anchor.body_id &&
           anchor.triangle < surface.bodies[b].triangles.size();
  };
  if (anchor.body < surface.bodies.size() && fits(anchor.body)) return anchor.body;
  for (std::uint32_t b = 0; b < surface.bodies.size(); ++b) {
    if (fits(b)) return b;
  }
  return std::nullopt;
}

void GodObject::forget_candidates() {
  if (++epoch_ == 0) {  // the stamps wrapped: none may look gathered
    for (std::vector<std::uint32_t>& stamps : stamps_) std::fill(stamps.begin(), stamps.end(), 0);
    epoch_ = 1;
  }
  gathered_.clear();
  gathered_.reserve(kGatheredBoxes);
  candidate_body_.clear();
  candidate_triangle_.clear();
  candidate_now_.clear();
  candidate_normal_.clear();
  candidate_centre_.clear();
  candidate_extent_.clear();
  candidate_bounds_.clear();
}

void GodObject::gather(const HapticSurface& surface, const Aabb& region) {
  for (const Aabb& box : gathered_) {
    if (box.contains(region)) return;
  }
  if (gathered_.size() < gathered_.capacity()) gathered_.push_back(region);  // else: look again
  if (stamps_.size() < surface.bodies.size()) stamps_.resize(surface.bodies.size());
  for (std::uint32_t b = 0; b < surface.bodies.size(); ++b) {
    const HapticBody& body = surface.bodies[b];
    if (body.query == nullptr) continue;
    std::vector<std::uint32_t>& stamps = stamps_[b];
    if (stamps.size() != body.triangles.size()) stamps.assign(body.triangles.size(), 0);
    collected_.clear();
    body.query->collect(region, collected_);
    // in index order whatever the structure, so that every structure feeds the same triangles
    // in the same order and a replay against another structure is bit for bit the same
    std::sort(collected_.begin(), collected_.end());
    for (const std::uint32_t t : collected_) {
      if (t >= body.triangles.size() || stamps[t] == epoch_) continue;  // gathered already
      stamps[t] = epoch_;
      const std::optional<TriangleCorners> corners = triangle_at(body, t, surface.alpha);
      if (!corners) continue;  // a corrupt triangle is not there
      const TriangleCorners& now = *corners;
      const Vec3 centre = (now.a + now.b + now.c) / 3;
      Aabb box;
      box.grow(now.a);
      box.grow(now.b);
      box.grow(now.c);
      candidate_body_.push_back(b);
      candidate_triangle_.push_back(t);
      candidate_now_.push_back(now);
      candidate_normal_.push_back(unit_normal(now).value_or(Vec3::Zero()));
      candidate_centre_.push_back(centre);
      candidate_extent_.push_back(
          std::sqrt(std::max({(now.a - centre).squaredNorm(), (now.b - centre).squaredNorm(),
                              (now.c - centre).squaredNorm()})));
      candidate_bounds_.push_back(box);
    }
  }
}

void GodObject::follow_bodies(const HapticSurface& surface) {
  then_.assign(surface.bodies.size(), Then{});
  travel_.assign(surface.bodies.size(), 0);
  margin_ = 0;
  if (!previous_) return;
  const std::vector<HapticBody>& then = previous_->bodies;
  for (std::uint32_t b = 0; b < surface.bodies.size(); ++b) {
    const HapticBody& body = surface.bodies[b];
    // bodies mostly keep their places; else look for it
    std::optional<std::uint32_t> found;
    if (b < then.size() && same_body(then[b], body)) found = b;
    for (std::uint32_t i = 0; !found && i < then.size(); ++i) {
      if (same_body(then[i], body)) found = i;
    }
    if (!found) continue;  // new, or a new surface under its id: it moved onto nothing
    const HapticBody& was = then[*found];
    travel_[b] = travel_between(was, previous_->alpha, body, surface.alpha);
    if (was.from.data() == body.from.data() && was.to.data() == body.to.data()) {
      then_[b] = {&body, previous_->alpha};  // the same pair
    } else if (was.to.data() == body.from.data() && previous_->alpha == 1) {
      then_[b] = {&body, 0};  // the pair before, at its end
    } else {
      then_[b] = {&was, previous_->alpha};
    }
    margin_ = std::max(margin_, travel_[b]);
  }
}

std::optional<TriangleCorners> GodObject::previous_corners(std::uint32_t b,
                                                           std::uint32_t triangle) const {
  if (!then_[b].body) return std::nullopt;
  return triangle_at(*then_[b].body, triangle, then_[b].alpha);
}

Vec3 GodObject::carry(const HapticSurface& surface, Vec3& before) {
  before = rest_;
  Vec3 start = rest_;
  if (anchor_) {
    if (const std::optional<std::uint32_t> b = find_body(surface, *anchor_)) {
      const Placement placement{anchor_->barycentric, anchor_->offset};
      const std::optional<TriangleCorners> then = previous_corners(*b, anchor_->triangle);
      const std::optional<TriangleCorners> now =
          triangle_at(surface.bodies[*b], anchor_->triangle, surface.alpha);
      const std::optional<Vec3> was = then ? position_of(*then, placement) : std::nullopt;
      const std::optional<Vec3> is = now ? position_of(*now, placement) : std::nullopt;
      if (was && is) {
        before = *was;
        start = *is;
      }
    }
  }
  if (!previous_) return start;

  const Vec3 carried = start;
  for (int attempt = 0;; ++attempt) {
    // the earliest triangle leg 1 passes: a triangle's box now, grown by how far its body
    // moves, holds it at the previous state too
    const Aabb path = segment_box(before, start, kSkin);
    gather(surface, path.inflated(margin_));
    std::optional<TriangleCorners> passed;
    std::optional<std::size_t> passed_candidate;
    Real passed_at = 2;
    for (std::size_t i = 0; i < candidate_now_.size(); ++i) {
      const std::uint32_t b = candidate_body_[i];
      if (!then_[b].body) continue;  // it came from nowhere: nothing to pass
      if (!candidate_bounds_[i].inflated(travel_[b]).overlaps(path)) continue;
      const std::optional<TriangleCorners> was = previous_corners(b, candidate_triangle_[i]);
      if (!was) continue;
      const std::optional<Real> s =
          point_passes_moving_triangle(before, start, *was, candidate_now_[i]);
      if (s && *s < passed_at) {
        passed_at = *s;
        passed = *was;
        passed_candidate = i;
      }
    }
    if (!passed) return start;
    if (attempt == kMaxReanchors) return carried;  // closed in from both sides: see the header
    // keep the placement it had relative to the triangle it would pass
    const std::optional<Placement> placement = place(*passed, before);
    if (!placement) return carried;
    const std::optional<Vec3> is = position_of(candidate_now_[*passed_candidate], *placement);
    if (!is) return carried;
    start = *is;
  }
}

HapticContact GodObject::hold() {
  force_ = Vec3::Zero();
  HapticContact out;
  out.proxy = proxy_;
  out.contact_point = proxy_;
  return out;
}

HapticContact GodObject::update(const HapticSurface& surface, const Vec3& device, Real dt) {
  if (!within_bounds(device)) return hold();
  HapticContact out;
  const Real radius = std::isfinite(settings_.radius) ? std::max(settings_.radius, Real{0}) : 0;
  forget_candidates();
  follow_bodies(surface);
  const auto gather_box = [&](const Aabb& box) { gather(surface, box); };
  // how far the surface may move before the next update, as far as it moved in its last step:
  // the anchor looks that far
  Real motion = 0;
  for (const HapticBody& body : surface.bodies) motion = std::max(motion, motion_of(body));
  // one box for what most updates look at: the proxy carried by the surface's motion since the
  // previous update, its slide toward the device, the surface within the anchor's reach
  gather_box(segment_box(rest_, device, radius + 2 * kSkin + margin_ + motion));

  Vec3 before;
  const Vec3 start = carry(surface, before);

  const Candidates candidates{candidate_now_,    candidate_normal_, candidate_centre_,
                              candidate_extent_, candidate_bounds_, candidate_triangle_};
  const Move frictionless = move_proxy(start, device, radius, gather_box, candidates);
  Vec3 rest = frictionless.position;
  const bool in_contact = rest != device;

  // friction (CHAI3D's finger proxy): the proxy holds where it stuck while the device stays
  // inside the static cone around the frictionless proxy, of radius μ · depth
  bool slipping = false;
  const Real mu_static = std::max(settings_.static_friction, Real{0});
  const Real mu_dynamic = std::max(settings_.dynamic_friction, Real{0});
  if (in_contact && (mu_static > 0 || mu_dynamic > 0)) {
    const Vec3 stuck = in_contact_ ? start : frictionless.first_stop.value_or(start);
    const Real depth = std::max((rest - device).norm() - kSkin, Real{0});  // as felt
    const Real drift = (stuck - rest).norm();
    slipping = mu_dynamic > mu_static || drift > (slipping_ ? mu_dynamic : mu_static) * depth;
    if (!slipping) {
      rest = stuck;
    } else if (drift > mu_dynamic * depth) {
      // dragged until the device lies on the dynamic cone: back from where it would slide
      // toward where it stuck, both places it may be, along the surface between them
      const Vec3 target = rest + (stuck - rest) * (mu_dynamic * depth / drift);
      gather_box(segment_box(rest, target, radius + kSkin));
      rest = sweep_to(candidates, rest, target, radius).position;
    } else {
      rest = stuck;
    }
  }

  // the touched point, and the triangle the proxy is anchored to until the next update
  gather_box(segment_box(rest, rest, radius + 2 * kSkin + motion));
  std::optional<Nearest> nearest;
  std::optional<Nearest> anchor;
  for (std::size_t i = 0; i < candidate_now_.size(); ++i) {
    const HapticBody& body = surface.bodies[candidate_body_[i]];
    const Real reach = radius + 2 * kSkin + motion_of(body);
    // one farther than the nearest anchor so far cannot be the nearest of either kind
    const Real within = anchor ? std::min(reach, anchor->distance) : reach;
    if (!candidate_bounds_[i].overlaps(segment_box(rest, rest, reach)) ||
        candidates.distance_bound(i, rest) > within + kBoundSlack) {
      continue;
    }
    const TriangleCorners& c = candidate_now_[i];
    const ClosestPoint point = closest_point_on_triangle(rest, c.a, c.b, c.c);
    const Real distance = (rest - point.point).norm();
    if (!(distance <= reach)) continue;
    const auto before = [&](const std::optional<Nearest>& n) {
      return !n || distance < n->distance ||
             (distance == n->distance &&
              std::pair(candidate_body_[i], candidate_triangle_[i]) <
                  std::pair(candidate_body_[n->candidate], candidate_triangle_[n->candidate]));
    };
    if (before(nearest)) nearest = Nearest{i, point, distance};
    if (before(anchor) && !candidate_normal_[i].isZero()) {
      anchor = Nearest{i, point, distance};
    }
  }
  std::optional<Anchor> anchored;
  if (anchor) {
    const std::size_t i = anchor->candidate;
    if (const std::optional<Placement> placement = place(candidate_now_[i], rest)) {
      anchored = Anchor{surface.bodies[candidate_body_[i]].body_id, candidate_body_[i],
                        candidate_triangle_[i], placement->barycentric, placement->offset};
    }
  }

  Vec3 proxy = rest;
  Vec3 force = Vec3::Zero();
  Vec3 offset = Vec3::Zero();
  if (in_contact) {
    out.in_contact = true;
    out.constraints = frictionless.constraints;
    out.contact_point = rest;
    Vec3 shaded = Vec3::Zero();
    if (nearest && nearest->distance > 0) {
      const std::size_t i = nearest->candidate;
      const Vec3 normal = contact_normal(rest, candidate_now_[i], nearest->point);
      // drop the skin: the reported proxy touches at exactly the radius
      if (nearest->distance >= radius && nearest->distance <= radius + 2 * kSkin) {
        proxy = nearest->point.point + radius * normal;
      }
      const HapticBody& body = surface.bodies[candidate_body_[i]];
      out.contact_point = nearest->point.point;
      out.normal = normal;
      out.body_id = body.body_id;
      out.triangle = static_cast<std::int32_t>(candidate_triangle_[i]);
      out.barycentric = nearest->point.barycentric;
      if (settings_.force_shading && out.constraints == 1 &&
          body.normals_from.size() == body.from.size() &&
          body.normals_to.size() == body.from.size()) {
        const Triangle& tri = body.triangles[candidate_triangle_[i]];
        shaded = out.barycentric.x() * surface.normal(body, tri[0]) +
                 out.barycentric.y() * surface.normal(body, tri[1]) +
                 out.barycentric.z() * surface.normal(body, tri[2]);
        const Real length = shaded.norm();
        shaded = length > 0 && std::isfinite(length) ? Vec3(shaded / length) : Vec3::Zero();
        if (shaded.dot(normal) < 0) shaded = -shaded;  // two-sided: the proxy's side
      }
    }
    offset = proxy - device;
    force = spring_force(settings_.stiffness, offset, shaded, rest - frictionless.position);
    if (in_contact_ && dt > 0 && std::isfinite(dt)) {
      force += settings_.damping * (offset - previous_offset_) / dt;
    }
    // damping may slow the push, never pull the device into the surface
    if (force.dot(out.normal) < 0) force -= out.normal * force.dot(out.normal);
    if (!shaded.isZero()) out.normal = shaded;
  } else {
    out.contact_point = device;
  }

  // the device's limits
  force = clamp_length(force, settings_.max_force);
  const Vec3 change = force - force_;
  if (settings_.max_force_change > 0 && change.norm() > settings_.max_force_change) {
    force = force_ + clamp_length(change, settings_.max_force_change);
  }
  out.force = force;
  out.proxy = proxy;
  out.slipping = slipping;
  // nothing non-finite leaves (a surface too large for doubles): keep the proxy where it was
  if (!out.finite() || !rest.allFinite()) return hold();

  rest_ = rest;
  proxy_ = proxy;
  anchor_ = anchored;
  previous_ = surface;  // its storage too: kept until the next update
  in_contact_ = in_contact;
  slipping_ = slipping;
  previous_offset_ = offset;
  force_ = force;
  return out;
}

}  // namespace felt
