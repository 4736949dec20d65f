#include "core/solids/solid_collision_detection.hpp"

#include <algorithm>
#include <cmath>

#include "core/math/bounds_of.hpp"
#include "core/math/check.hpp"

namespace felt {
namespace {

constexpr std::uint32_t kNoBody = ~std::uint32_t{0};

using BoundingBox = Eigen::AlignedBox<Real, 3>;

/// Whether p lies in the closed tetrahedron (a, b, c, d), by the barycentric coordinates
/// V_k / V (§6.3.2): p replaces each corner in turn, and p is inside when no sub-volume has
/// the sign opposite to V's. Comparing signs instead of dividing keeps the test independent
/// of the orientation and free of division; a flat tetrahedron contains nothing.
bool tetrahedron_contains(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                          const Vec3& p) {
  const Real volume = signed_volume(a, b, c, d);
  if (!(volume != 0)) return false;
  const Real sub_volumes[] = {signed_volume(p, b, c, d), signed_volume(a, p, c, d),
                              signed_volume(a, b, p, d), signed_volume(a, b, c, p)};
  return std::ranges::all_of(sub_volumes, [volume](Real v) { return v * volume >= 0; });
}

/// Whether node n is a corner of tet or shares an edge with one of its corners.
bool touches_tetrahedron(const TetTopology& topology, const Tetrahedron& tet, std::uint32_t n) {
  for (std::uint32_t corner : tet) {
    if (corner == n ||
        std::ranges::find(topology.neighbours(corner), n) != topology.neighbours(corner).end()) {
      return true;
    }
  }
  return false;
}

/// Per axis, whether x lies below (bit 2a) or above (bit 2a + 1) the box (not empty).
std::uint8_t outcode(const Vec3& x, const BoundingBox& box) {
  std::uint8_t code = 0;
  for (int a = 0; a < 3; ++a) {
    code |= static_cast<std::uint8_t>((x[a] < box.min()[a]) << (2 * a));
    code |= static_cast<std::uint8_t>((x[a] > box.max()[a]) << (2 * a + 1));
  }
  return code;
}

BoundingBox bounding_box(const SolidBody& body) {
  return bounds_of(body.positions());
}

}  // namespace

Real mean_rest_edge_length(std::span<const SolidBody> bodies) {
  Real sum = 0;
  std::size_t count = 0;
  for (const SolidBody& body : bodies) {
    for (const Edge& e : body.topology().edges) {
      sum += (body.rest().nodes[e[1]] - body.rest().nodes[e[0]]).norm();
    }
    count += body.topology().edges.size();
  }
  return count > 0 ? sum / static_cast<Real>(count) : 0;
}

void SolidCollisionDetector::set_cell_size(Real cell_size) {
  FELT_CHECK(cell_size > 0 && std::isfinite(cell_size));
  cell_size_ = cell_size;
}

void SolidCollisionDetector::detect(std::span<const SolidBody> bodies, CollisionSet& out) {
  FELT_CHECK(cell_size_ > 0);
  node_offset_.resize(bodies.size() + 1);
  node_offset_[0] = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    node_offset_[b + 1] = node_offset_[b] + bodies[b].node_count();
  }
  const std::size_t node_total = node_offset_.back();
  colliding_.assign(node_total, 0);
  participating_.assign(node_total, 0);
  last_penetrated_.assign(node_total, kNoBody);
  out.nodes.clear();
  counts_ = CollisionCounts{};

  // A node can only be inside a tetrahedron of a body whose box contains it. What matters of
  // each body is its reach, the hull of the overlaps of its box with the boxes of the bodies it
  // can touch: only nodes inside their body's reach are hashed, and only tetrahedra whose box
  // meets their body's reach query the table. Resting bodies touch in thin slabs, so this
  // leaves out most of both; chains and cells keep their order, so the result is the same.
  const auto can_touch = [&](std::size_t node_body, std::size_t tet_body) {
    return node_body != tet_body || bodies[tet_body].material().self_collision;
  };
  body_boxes_.resize(bodies.size());
  reach_.resize(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) body_boxes_[b] = bounding_box(bodies[b]);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    reach_[b].setEmpty();
    for (std::size_t t = 0; t < bodies.size(); ++t) {
      const BoundingBox overlap = body_boxes_[b].intersection(body_boxes_[t]);
      if (can_touch(b, t) && !overlap.isEmpty()) reach_[b].extend(overlap);
    }
  }

  // phase 1: the nodes in their body's reach into the table; each node's outcode against it
  // (Cohen–Sutherland: which faces of the reach it lies beyond) for phase 2
  hash_.begin(cell_size_, node_total);
  outcodes_.resize(node_total);
  for (std::uint32_t b = 0; b < bodies.size(); ++b) {
    const std::vector<Vec3>& x = bodies[b].positions();
    const bool reaches = !reach_[b].isEmpty();
    for (std::uint32_t n = 0; n < x.size(); ++n) {
      // beyond every face of an empty reach
      const std::uint8_t code = reaches ? outcode(x[n], reach_[b]) : std::uint8_t{0x3f};
      outcodes_[node_offset_[b] + n] = code;
      if (code == 0) hash_.insert(b, n, x[n]);
    }
  }
  counts_.hashed_nodes = hash_.point_count();

  // phase 2: the nodes in the cells each tetrahedron's box overlaps
  for (std::uint32_t tet_body = 0; tet_body < bodies.size(); ++tet_body) {
    const SolidBody& body = bodies[tet_body];
    const std::vector<Vec3>& x = body.positions();
    const bool self_collision = body.material().self_collision;
    const std::span<const std::uint8_t> codes(outcodes_.data() + node_offset_[tet_body], x.size());
    const std::vector<Tetrahedron>& tets = body.rest().tets;
    for (std::uint32_t t = 0; t < tets.size(); ++t) {
      const Tetrahedron& tet = tets[t];
      // all corners beyond the same face of the reach: the box misses it
      if ((codes[tet[0]] & codes[tet[1]] & codes[tet[2]] & codes[tet[3]]) != 0) continue;
      const Vec3 &a = x[tet[0]], &b = x[tet[1]], &c = x[tet[2]], &d = x[tet[3]];
      const Vec3 lo = a.cwiseMin(b).cwiseMin(c).cwiseMin(d);
      const Vec3 hi = a.cwiseMax(b).cwiseMax(c).cwiseMax(d);
      // a node it can contain lies in its box and in its own body's box: only the cells of
      // those overlaps are visited, in the same order
      const BoundingBox box(lo, hi);
      BoundingBox query;  // empty
      for (std::size_t n = 0; n < bodies.size(); ++n) {
        if (!can_touch(n, tet_body)) continue;
        const BoundingBox overlap = box.intersection(body_boxes_[n]);
        if (!overlap.isEmpty()) query.extend(overlap);
      }
      if (query.isEmpty()) continue;
      hash_.for_each_in_box(
          query.min(), query.max(), [&](std::uint32_t node_body, std::uint32_t n) {
            if (node_body == tet_body && !self_collision) return;
            ++counts_.candidates;
            const Vec3& p = bodies[node_body].positions()[n];
            if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) return;
            if (!tetrahedron_contains(a, b, c, d, p)) return;
            if (node_body == tet_body && touches_tetrahedron(body.topology(), tet, n)) return;

            for (std::uint32_t corner : tet) participating_[node_offset_[tet_body] + corner] = 1;
            const std::size_t flat = node_offset_[node_body] + n;
            if (last_penetrated_[flat] == tet_body) return;  // already inside another of its tets
            last_penetrated_[flat] = tet_body;
            colliding_[flat] = 1;
            out.nodes.push_back(CollidingNode{node_body, n, tet_body, t});
          });
    }
  }
  counts_.colliding_nodes = out.nodes.size();
}

void SolidCollisionDetector::collect_triangles(std::span<const SolidBody> bodies,
                                               CollisionSet& out) {
  FELT_CHECK(node_offset_.size() == bodies.size() + 1);
  out.triangles.resize(bodies.size());
  counts_.colliding_triangles = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    FELT_CHECK(node_offset_[b + 1] - node_offset_[b] == bodies[b].node_count());
    const std::vector<Triangle>& surface = bodies[b].topology().surface;
    std::vector<std::uint32_t>& triangles = out.triangles[b];
    triangles.clear();
    for (std::uint32_t s = 0; s < surface.size(); ++s) {
      const bool touched = std::ranges::any_of(surface[s], [&](std::uint32_t corner) {
        const std::size_t flat = node_offset_[b] + corner;
        return colliding_[flat] != 0 || participating_[flat] != 0;
      });
      if (touched) triangles.push_back(s);
    }
    counts_.colliding_triangles += triangles.size();
  }
}

}  // namespace felt
