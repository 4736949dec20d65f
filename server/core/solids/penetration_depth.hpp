#pragma once
// Consistent penetration vectors for colliding nodes (Heidelberger et al. 2004, thesis 2
// §3.1, §3.3 a–f, Algorithm 6.3): estimated at border nodes from where their edges cross the
// penetrated surface and propagated inward front by front, so depths do not jump over time.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/geometry/surface_normals.hpp"
#include "core/solids/solid_collision_detection.hpp"

namespace felt {

struct PenetrationContact {
  std::uint32_t body = 0;
  std::uint32_t node = 0;
  std::uint32_t penetrated_body = 0;
  Vec3 depth = Vec3::Zero();  ///< d_i = y_i − x_i: from the node to where it entered
  /// the penetrated body's surface triangle (index into its topology().surface) that the ray
  /// x_i + t d_i, t ∈ [0, 2], hits first, or -1 when none does (the node is left in place)
  std::int64_t triangle = -1;
  Vec3 barycentric = Vec3::Zero();  ///< where the ray hits that triangle
};

/// What the last estimation found, for stats and diagnosis.
struct PenetrationCounts {
  std::size_t intersection_edges = 0;  ///< (edge, inside end, penetrated body) triples
  std::size_t crossings = 0;           ///< intersection edges whose surface crossing was found
  std::size_t border_nodes = 0;        ///< contacts estimated from their own crossings (§3.3 c)
  std::size_t propagated_nodes = 0;    ///< contacts estimated from their neighbours (§3.3 d)
  std::size_t contact_triangles = 0;   ///< contacts whose ray hit a triangle (§3.3 f)
};

/// Algorithm 6.3 and the contact triangles of §6.4.2. Keeps, from step to step, the triangle
/// each intersection edge last crossed and each node's last contact triangle (temporal
/// coherence: they are tried before scanning the colliding triangles).
class PenetrationDepthEstimator {
 public:
  /// One contact per entry of collisions.nodes, in the same order; `collisions` must come from
  /// the detector with its triangles collected for the same bodies.
  ///
  /// The surface normal where an edge crosses a triangle interpolates the triangle's corner
  /// normals barycentrically (as Heidelberger et al. 2004 do with vertex normals; the thesis
  /// leaves it open), so it varies continuously across triangles, except across a sharp edge
  /// (one turning by more than the penetrated body's SolidMaterial::crease_angle): there each
  /// side keeps its own normal. With smooth vertex normals everywhere a node near the edge of
  /// a box's face gets a vector tilted by up to 45° toward the side face, and a stack of boxes
  /// creeps sideways on it. Depths below `min_depth` (and estimates that point the wrong way)
  /// become zero; distances in the 1/d² weights are floored at `min_depth` so a crossing at the
  /// node itself cannot overflow them. A contact that no estimate reaches (no border node of
  /// its region found a crossing) and a zero depth give depth zero and no triangle.
  void compute(std::span<const SolidBody> bodies, const CollisionSet& collisions, Real min_depth,
               std::vector<PenetrationContact>& out);

  const PenetrationCounts& counts() const { return counts_; }

 private:
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};

  /// A triangle remembered from an earlier step: which body's surface, and which face of it.
  struct CachedTriangle {
    std::uint32_t body = kNone;
    std::uint32_t triangle = kNone;
  };
  /// Where a segment or ray met a surface triangle.
  struct SurfaceHit {
    std::uint32_t triangle = kNone;
    Real t = 0;
    Vec3 barycentric = Vec3::Zero();
  };

  /// The boxes of a body's colliding triangles, in the order of CollisionSet::triangles.
  struct TriangleBoxes {
    std::vector<Vec3> lo, hi;
    Real largest = 0;  ///< the longest box diagonal
  };

  static void compute_triangle_boxes(const SolidBody& body,
                                     std::span<const std::uint32_t> triangles, TriangleBoxes& out);
  std::uint32_t entry_for(std::size_t flat_node, std::uint32_t penetrated_body) const;
  /// The hit of x + t·direction, t ∈ [0, t_max], with the surface of body `penetrated`: the
  /// cached triangle when it is still hit, else the nearest among the colliding triangles
  /// (the first of them in their order on a tie).
  /// Triangles with a corner in `exclude` (nodes of the same body) are skipped.
  SurfaceHit cast(std::span<const SolidBody> bodies, const CollisionSet& collisions,
                  std::uint32_t penetrated, const Vec3& x, const Vec3& direction, Real t_max,
                  std::span<const std::uint32_t> exclude, CachedTriangle& cache) const;
  void add_crossing_estimates(std::span<const SolidBody> bodies, const CollisionSet& collisions,
                              Real weight_floor_sq);
  void propagate(std::span<const SolidBody> bodies, const CollisionSet& collisions,
                 Real weight_floor_sq, Real min_depth);
  /// Turns the weighted sums of an entry into h and r; false when they give no direction.
  bool finish_estimate(std::uint32_t entry, std::uint32_t round, Real min_depth);

  PenetrationCounts counts_;
  std::vector<std::size_t> node_offset_, edge_offset_;  ///< flat indices of each body's first
  /// the collision entries of each flat node, linked: first_entry_[node], next_entry_[entry]
  std::vector<std::uint32_t> first_entry_, next_entry_;
  std::vector<std::uint32_t> penetrated_;  ///< per entry, its penetrated body
  /// per entry: the weighted sums of §3.3 c–d, the estimate, and the propagation round that
  /// produced it (kNone while unprocessed)
  std::vector<Real> weight_sum_, depth_sum_, depth_;
  std::vector<Vec3> direction_sum_, direction_;
  std::vector<std::uint32_t> round_, queued_round_;
  std::vector<std::uint32_t> front_, next_front_;
  std::vector<std::uint8_t> penetrated_bodies_;  ///< per body: is it penetrated
  /// A body's face and corner normals, each computed when a crossing first needs it in a
  /// compute (its stamp equals stamp_ then): few triangles are crossed in a step.
  struct NormalCache {
    std::vector<FaceNormal> faces;
    std::vector<std::array<Vec3, 3>> corners;
    std::vector<std::uint32_t> face_stamp, corner_stamp;
    Real cos_crease = 0;  ///< of the body's crease angle
  };
  std::vector<NormalCache> normals_;  ///< per body
  std::uint32_t stamp_ = 0;
  const std::array<Vec3, 3>& corner_normals_of(const SolidBody& body, std::uint32_t b,
                                               std::uint32_t triangle);
  std::vector<TriangleBoxes> triangle_boxes_;   ///< per body, of the penetrated bodies
  std::vector<CachedTriangle> crossing_cache_;  ///< per flat edge and inside end
  std::vector<CachedTriangle> contact_cache_;   ///< per flat node
};

}  // namespace felt
