#include "core/collision/triangle_bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/math/check.hpp"

namespace felt {
namespace {

// A walk down a balanced tree over at most 2^32 triangles (depth ≤ 33) keeps at most
// depth · (branching − 1) + 1 nodes on its stack; the build checks that this fits.
constexpr std::size_t kStackCapacity = 128;

// The fits of a refit's two loops are forced inline: called, each returned its volume through
// memory and a refit of 19,602 triangles took twice as long.

/// The box of a triangle's corners in both states: what every leaf bounds, and what brute force
/// tests, so that each structure answers a superset of brute force's answer.
[[gnu::always_inline]] inline Aabb swept_bounds(const Triangle& t, std::span<const Vec3> from,
                                                std::span<const Vec3> to) {
  const Vec3 &a = from[t[0]], &b = from[t[1]], &c = from[t[2]];
  const Vec3 &d = to[t[0]], &e = to[t[1]], &f = to[t[2]];
  // pairwise, not in a chain: the six loads and the minima overlap
  return {a.cwiseMin(b).cwiseMin(c.cwiseMin(d)).cwiseMin(e.cwiseMin(f)),
          a.cwiseMax(b).cwiseMax(c.cwiseMax(d)).cwiseMax(e.cwiseMax(f))};
}

// --- boxes: a leaf is its triangle's box, a parent the box of its children's boxes

bool encloses(const Aabb& parent, const Aabb& child) {
  return parent.contains(child);
}
void fit(Aabb& leaf, const Aabb& box) {
  leaf = box;
}
[[gnu::always_inline]] inline void fit(Aabb& parent, std::span<const Aabb> children) {
  parent = children.front();
  for (const Aabb& child : children.subspan(1)) parent.grow(child);
}
bool overlaps(const Aabb& box, const Aabb& region) {
  return box.overlaps(region);
}

// --- spheres: centred on the middle of the bounds of what they enclose, radius the farthest
// reach from there (Quinlan's fast approximation as Brown et al. use it: not minimal). A leaf
// encloses its triangle's whole box, not only the six corners, so that it is never tighter than
// brute force's box test; for a cloth triangle it is the same sphere or barely larger.

constexpr Real kRoundingMargin = 64 * std::numeric_limits<Real>::epsilon();

/// Squared distance from `center` to the farthest corner of `box`.
Real farthest_corner_squared(const Vec3& center, const Aabb& box) {
  return (box.lo - center).cwiseAbs().cwiseMax((box.hi - center).cwiseAbs()).squaredNorm();
}

/// How far from `center` the sphere `s` reaches. A parent's radius and the test of whether it
/// still encloses a child use this one expression, so the two agree to the last bit.
Real reach(const Vec3& center, const BoundingSphere& s) {
  return (s.center - center).norm() + s.radius;
}

bool encloses(const BoundingSphere& sphere, const Aabb& box) {
  return farthest_corner_squared(sphere.center, box) <= sphere.radius * sphere.radius;
}
bool encloses(const BoundingSphere& parent, const BoundingSphere& child) {
  return reach(parent.center, child) <= parent.radius;
}
[[gnu::always_inline]] inline void fit(BoundingSphere& leaf, const Aabb& box) {
  leaf.center = (box.lo + box.hi) / 2;
  const Real r2 = farthest_corner_squared(leaf.center, box);
  leaf.radius = std::sqrt(r2);
  // the rounded root may square to just below r2, and encloses() compares squares: the leaf
  // would count as escaped at every refit
  while (leaf.radius * leaf.radius < r2) {
    leaf.radius = std::nextafter(leaf.radius, std::numeric_limits<Real>::infinity());
  }
}
[[gnu::always_inline]] inline void fit(BoundingSphere& parent,
                                       std::span<const BoundingSphere> children) {
  Aabb box;
  for (const BoundingSphere& child : children) {
    box.grow(child.center.array() - child.radius);
    box.grow(child.center.array() + child.radius);
  }
  parent.center = (box.lo + box.hi) / 2;
  Real radius = 0;
  for (const BoundingSphere& child : children) {
    radius = std::max(radius, reach(parent.center, child));
  }
  // a point on a child's surface may, rounded, lie a few ulps outside the parent (a flat cloth
  // puts vertices on many spheres at once): a margin far below any geometric size keeps every
  // point a child holds inside its ancestors
  parent.radius = radius * (1 + kRoundingMargin);
}
bool overlaps(const BoundingSphere& sphere, const Aabb& region) {
  return region.squared_distance(sphere.center) <= sphere.radius * sphere.radius;
}

/// A contiguous run [begin, end) of the build's triangle order and the node that holds it.
struct Range {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
  std::uint32_t node = 0;
  std::uint32_t depth = 0;
};

}  // namespace

TriangleBvh::TriangleBvh(std::span<const Triangle> triangles, std::span<const Vec3> positions,
                         TriangleBvhOptions options)
    : options_(options), triangles_(triangles.begin(), triangles.end()) {
  FELT_CHECK(options.branching == 2 || options.branching == 4);
  FELT_CHECK(triangles.size() < (std::size_t{1} << 31));  // node ids fit in 32 bits
  for (const Triangle& t : triangles) {
    vertex_count_ = std::max(vertex_count_, std::size_t{*std::max_element(t.begin(), t.end())} + 1);
  }
  FELT_CHECK(positions.size() >= vertex_count_);
  if (triangles.empty()) return;

  std::vector<Vec3> centroid(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    centroid[i] = (positions[t[0]] + positions[t[1]] + positions[t[2]]) / 3;
  }
  std::vector<std::uint32_t> order(triangles.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;

  // splits [begin, end) of `order` at its median along the longest axis of its centroids
  const auto split = [&](std::uint32_t begin, std::uint32_t end) {
    Aabb box;
    for (std::uint32_t i = begin; i < end; ++i) box.grow(centroid[order[i]]);
    int axis = 0;
    (box.hi - box.lo).maxCoeff(&axis);
    const std::uint32_t middle = begin + (end - begin) / 2;
    std::nth_element(
        order.begin() + begin, order.begin() + middle, order.begin() + end,
        [&](std::uint32_t a, std::uint32_t b) { return centroid[a][axis] < centroid[b][axis]; });
    return middle;
  };

  // breadth-first: ranges are taken in the order their nodes were made, and a node's children
  // are made together, so ids grow level by level and siblings are consecutive
  nodes_.reserve(2 * triangles.size());
  leaves_.reserve(triangles.size());
  nodes_.push_back(Node{});
  std::vector<Range> ranges{Range{0, static_cast<std::uint32_t>(triangles.size()), 0, 0}};
  std::uint32_t depth = 0;
  for (std::size_t next = 0; next < ranges.size(); ++next) {
    const Range range = ranges[next];
    depth = std::max(depth, range.depth);
    Node& node = nodes_[range.node];
    if (range.end - range.begin == 1) {
      node.first = order[range.begin];
      leaves_.push_back(range.node);
      continue;
    }
    std::array<std::uint32_t, 5> bounds{range.begin, split(range.begin, range.end), range.end};
    std::size_t parts = 2;
    if (options.branching == 4) {
      // each half again along its own longest axis (thesis 1 §8.2); a single triangle stays
      std::array<std::uint32_t, 5> quarters{};
      parts = 0;
      quarters[0] = range.begin;
      for (int half = 0; half < 2; ++half) {
        if (bounds[half + 1] - bounds[half] > 1) {
          quarters[++parts] = split(bounds[half], bounds[half + 1]);
        }
        quarters[++parts] = bounds[half + 1];
      }
      bounds = quarters;
    }
    node.first = static_cast<std::uint32_t>(nodes_.size());
    node.child_count = static_cast<std::uint32_t>(parts);
    for (std::size_t c = 0; c < parts; ++c) {
      const auto id = static_cast<std::uint32_t>(nodes_.size());
      nodes_.push_back(Node{range.node, 0, 0});
      ranges.push_back(Range{bounds[c], bounds[c + 1], id, range.depth + 1});
    }
  }
  FELT_CHECK(std::size_t{depth} * (options.branching - 1) + 1 <= kStackCapacity);

  if (options.volume == BvhVolume::kSphere) {
    spheres_.resize(nodes_.size());
    refit_reverse_order(spheres_, positions, positions);
  } else {
    boxes_.resize(nodes_.size());
    refit_reverse_order(boxes_, positions, positions);
  }
}

void TriangleBvh::refit(std::span<const Vec3> from, std::span<const Vec3> to) {
  FELT_CHECK(from.size() == to.size() && from.size() >= vertex_count_);
  const bool escaped = options_.refit == BvhRefit::kEscaped;
  if (options_.volume == BvhVolume::kSphere) {
    escaped ? refit_escaped(spheres_, from, to) : refit_reverse_order(spheres_, from, to);
  } else {
    escaped ? refit_escaped(boxes_, from, to) : refit_reverse_order(boxes_, from, to);
  }
}

template <class Volume>
void TriangleBvh::refit_escaped(std::vector<Volume>& volumes, std::span<const Vec3> from,
                                std::span<const Vec3> to) {
  std::size_t updates = 0;
  // Thesis 1 §6.1.3's priority queue of parents, highest breadth-first id first, so that every
  // child (a higher id) is done before its parent. It needs no heap: the deformed leaves'
  // parents come out of the scan ascending (taken from the back), and the parents queued while
  // popping come descending (a popped id only falls, and a parent's id grows with its child's),
  // so the queue is the merge of two sorted lists, and copies of an id pop one after another.
  leaf_parents_.clear();
  parents_.clear();
  // the scan of the leaf array (find_deformed_leaves), refitting each deformed leaf on the way
  for (const std::uint32_t leaf : leaves_) {
    const Aabb box = swept_bounds(triangles_[nodes_[leaf].first], from, to);
    if (encloses(volumes[leaf], box)) continue;
    fit(volumes[leaf], box);
    ++updates;
    const std::uint32_t parent = nodes_[leaf].parent;
    if (parent != kNoParent && (leaf_parents_.empty() || leaf_parents_.back() != parent)) {
      leaf_parents_.push_back(parent);
    }
  }
  std::uint32_t last = kNoParent;
  std::size_t head = 0;  // the next of parents_ to pop
  while (!leaf_parents_.empty() || head < parents_.size()) {
    std::uint32_t id = 0;
    if (head == parents_.size() ||
        (!leaf_parents_.empty() && leaf_parents_.back() > parents_[head])) {
      id = leaf_parents_.back();
      leaf_parents_.pop_back();
    } else {
      id = parents_[head++];
    }
    if (id == last) continue;  // the thesis's de-duplication: each node once
    last = id;
    const Node& node = nodes_[id];
    const std::span<const Volume> children(volumes.data() + node.first, node.child_count);
    if (std::all_of(children.begin(), children.end(),
                    [&](const Volume& child) { return encloses(volumes[id], child); })) {
      continue;
    }
    fit(volumes[id], children);
    ++updates;
    if (node.parent != kNoParent) parents_.push_back(node.parent);
  }
  last_refit_updates_ = updates;
}

template <class Volume>
void TriangleBvh::refit_reverse_order(std::vector<Volume>& volumes, std::span<const Vec3> from,
                                      std::span<const Vec3> to) {
  // the leaves first, then the internal nodes: no branch on the kind of node in either loop
  for (const std::uint32_t leaf : leaves_) {
    fit(volumes[leaf], swept_bounds(triangles_[nodes_[leaf].first], from, to));
  }
  for (std::size_t id = nodes_.size(); id-- > 0;) {
    const Node& node = nodes_[id];
    if (node.leaf()) continue;
    fit(volumes[id], std::span<const Volume>(volumes.data() + node.first, node.child_count));
  }
  last_refit_updates_ = nodes_.size();
}

void TriangleBvh::collect(const Aabb& region, std::vector<std::uint32_t>& out) const {
  if (options_.volume == BvhVolume::kSphere) {
    collect_in(spheres_, region, out);
  } else {
    collect_in(boxes_, region, out);
  }
}

template <class Volume>
void TriangleBvh::collect_in(const std::vector<Volume>& volumes, const Aabb& region,
                             std::vector<std::uint32_t>& out) const {
  if (nodes_.empty() || region.empty()) return;
  std::array<std::uint32_t, kStackCapacity> stack;
  std::size_t size = 0;
  stack[size++] = 0;
  while (size > 0) {
    const std::uint32_t id = stack[--size];
    if (!overlaps(volumes[id], region)) continue;
    const Node& node = nodes_[id];
    if (node.leaf()) {
      out.push_back(node.first);
    } else {
      for (std::uint32_t c = 0; c < node.child_count; ++c) stack[size++] = node.first + c;
    }
  }
}

void TriangleBvh::find_deformed_leaves(std::span<const Vec3> from, std::span<const Vec3> to,
                                       DeformedLeafSearch search,
                                       std::vector<std::uint32_t>& out) const {
  FELT_CHECK(from.size() == to.size() && from.size() >= vertex_count_);
  if (options_.volume == BvhVolume::kSphere) {
    find_deformed_leaves_in(spheres_, from, to, search, out);
  } else {
    find_deformed_leaves_in(boxes_, from, to, search, out);
  }
}

template <class Volume>
void TriangleBvh::find_deformed_leaves_in(const std::vector<Volume>& volumes,
                                          std::span<const Vec3> from, std::span<const Vec3> to,
                                          DeformedLeafSearch search,
                                          std::vector<std::uint32_t>& out) const {
  const auto deformed = [&](std::uint32_t leaf) {
    return !encloses(volumes[leaf], swept_bounds(triangles_[nodes_[leaf].first], from, to));
  };
  if (search == DeformedLeafSearch::kLeafArray) {
    for (const std::uint32_t leaf : leaves_) {
      if (deformed(leaf)) out.push_back(leaf);
    }
    return;
  }
  if (nodes_.empty()) return;
  std::array<std::uint32_t, kStackCapacity> stack;
  std::size_t size = 0;
  stack[size++] = 0;
  while (size > 0) {
    const std::uint32_t id = stack[--size];
    const Node& node = nodes_[id];
    if (node.leaf()) {
      if (deformed(id)) out.push_back(id);
    } else {
      for (std::uint32_t c = 0; c < node.child_count; ++c) stack[size++] = node.first + c;
    }
  }
}

std::unique_ptr<TriangleQuery> TriangleBvh::clone() const {
  return std::make_unique<TriangleBvh>(*this);
}

TriangleQueryKind TriangleBvh::kind() const {
  if (options_.volume == BvhVolume::kSphere) {
    return options_.branching == 2 ? TriangleQueryKind::kBvhSphere2
                                   : TriangleQueryKind::kBvhSphere4;
  }
  return options_.branching == 2 ? TriangleQueryKind::kBvhAabb2 : TriangleQueryKind::kBvhAabb4;
}

}  // namespace felt
