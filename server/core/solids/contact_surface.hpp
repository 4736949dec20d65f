#pragma once
// The contact surface between touching soft solids, found by comparing pressures (Spillmann &
// Teschner 2005, thesis 2 §3.2, §3.3 g–i), and the friction along it.

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/solids/penetration_depth.hpp"

namespace felt {

enum class SolidFriction : std::uint8_t {
  /// Coulomb friction on the motion of a node relative to the point of its contact triangle it
  /// touches (the thesis's future work): the tangential part is reduced by μ times the normal
  /// motion the contact stopped, never reversed, as equal and opposite impulses.
  kRelativeCoulomb,
  /// Thesis 2 (6.3): f_i^r = −μ |f_i| v_i/|v_i| on the own velocity of every node of the
  /// deformation region, f_i its internal force and weight; it may stop a node, not reverse it.
  kThesis,
};

/// μ of a contact between two surfaces of friction μ_a and μ_b: sqrt(μ_a μ_b) (Box2D's rule),
/// so either surface being frictionless makes the contact frictionless.
inline Real mixed_friction(Real a, Real b) {
  return std::sqrt(a * b);
}

/// Moves the nodes of the deformation region (colliding nodes and the corners of their contact
/// triangles) onto the surface where the pressures of the touching bodies balance, then stops
/// their approach and applies friction.
///
/// Decisions on the thesis's open questions:
/// - w_j is the barycentric weight of node i at the point where j's ray hits T_j.
/// - s_i of a node that does not collide itself averages only the −d_j of the nodes whose
///   contact triangles contain it, by max(1, Σ w_j): the thesis's zero d_i with weight 1 would
///   move a triangle that a node hits at a corner by half the depth only, and max(1, ·) keeps
///   s_i continuous as a hit leaves the triangles around the node.
/// - Pressures are the internal forces (re-evaluated every iteration, at the region nodes)
///   divided by the area of the surface triangles around each node, at the start of the
///   resolution; interior nodes take the mean of their body's surface nodes. p_i^B averages
///   the pressures of the nodes j ∈ J_i ∩ B by w_j; when J_i ∩ B is empty it interpolates the
///   pressures at the corners of T_i barycentrically at i's hit point.
/// - Internal forces point against the compression, so the thesis's comparison of the two
///   pressures' sizes along s_i reads: step along +s_i when (p_i^A + p_i^B)·s_i > 0, i.e. the
///   node follows the net pressure on it; on a tie (to rounding) it stays.
/// - A node touching several bodies gets one displacement per body; they are combined by
///   taking, along each displacement's direction, only what the others do not already
///   provide: displacements in different directions add, equal ones count once.
/// - A contact without a contact triangle (the thesis leaves its node in place, where it can
///   stay stuck for good) moves its node by the whole d_i, as against an immovable surface; so
///   do nodes pressed only by pinned nodes, which do not give way. Pinned nodes do not move.
/// - The move onto the contact surface corrects positions only: the previous positions move
///   with the nodes, so it adds no velocity and no momentum. Each contact then stops the
///   relative approach of its node and T_i with an equal and opposite, perfectly inelastic
///   impulse (Verlet keeps the velocity in x − x_prev, so impulses move the previous
///   positions); the bodies' elasticity is what pushes them apart again.
class ContactSurface {
 public:
  /// Resolves `contacts` (one per colliding node and penetrated body) with `iterations`
  /// pressure comparisons after the first half step (thesis: 3), then stops the approach and
  /// applies `friction` to the motion over the step of length h from the previous positions.
  void resolve(std::span<SolidBody> bodies, std::span<const PenetrationContact> contacts,
               int iterations, SolidFriction friction, Real h, const Vec3& gravity);

 private:
  /// A node of the deformation region.
  struct RegionNode {
    std::uint32_t body = 0;
    std::uint32_t node = 0;
    std::int32_t first_entry = -1;
    Vec3 start = Vec3::Zero();  ///< position before the resolution
  };
  /// The displacement of a region node against one other body (the node's own body for
  /// self-collision).
  struct ContactEntry {
    std::uint32_t region_node = 0;
    std::uint32_t partner = 0;
    std::int32_t next = -1;                ///< the node's next entry
    std::int64_t own_contact = -1;         ///< index into the contacts when the node collides
    Vec3 weighted_depths = Vec3::Zero();   ///< Σ w_j (−d_j) + d_i
    Real weight = 0;                       ///< Σ w_j (+ 1 when colliding)
    Vec3 displacement = Vec3::Zero();      ///< s_i
    Real fraction = 0.5;                   ///< how much of s_i is applied
    Vec3 partner_pressure = Vec3::Zero();  ///< Σ_{j∈J_i∩B} w_j p_j
    Real partner_weight = 0;               ///< Σ_{j∈J_i∩B} w_j
    bool has_sources = false;              ///< J_i ∩ B is not empty
    bool partner_gives_way = false;        ///< some partner node it is pressed by is free
  };
  /// j ∈ J_i: node `node` of body `body` hits a triangle around the entry's node with weight w.
  struct PressureSource {
    std::uint32_t entry = 0;
    std::uint32_t body = 0;
    std::uint32_t node = 0;
    Real weight = 0;
  };

  void build_region(std::span<SolidBody> bodies, std::span<const PenetrationContact> contacts);
  std::uint32_t entry_for(std::span<SolidBody> bodies, std::uint32_t body, std::uint32_t node,
                          std::uint32_t partner);
  void compute_areas(std::span<SolidBody> bodies);
  void compare_pressures(std::span<SolidBody> bodies, std::span<const PenetrationContact> contacts,
                         Real step);
  void move_region(std::span<SolidBody> bodies);
  /// How a contact's node moves over the step relative to the point of T_i it touches.
  struct Kinematics {
    Vec3 normal;            ///< d_i / |d_i|
    Vec3 relative;          ///< x − x_prev of the node minus that of the point
    Real inverse_mass = 0;  ///< of the relative motion (node and barycentric corners)
  };
  Kinematics kinematics(std::span<SolidBody> bodies, const PenetrationContact& contact) const;
  /// Changes the motion of the node by `impulse` over its mass and that of the corners of T_i
  /// by the opposite, weighted barycentrically, by moving the positions or the previous
  /// positions: the relative motion changes by impulse × inverse_mass, the momentum not at all.
  void apply_impulse(std::span<SolidBody> bodies, const PenetrationContact& contact,
                     const Vec3& impulse, bool to_previous_positions);
  void stop_approach(std::span<SolidBody> bodies, std::span<const PenetrationContact> contacts);
  void relative_coulomb_friction(std::span<SolidBody> bodies,
                                 std::span<const PenetrationContact> contacts);
  void own_velocity_friction(std::span<SolidBody> bodies, Real h, const Vec3& gravity);
  Vec3 pressure(std::uint32_t body, std::uint32_t node) const {
    return force_[body][node] / area_[body][node];
  }

  std::vector<RegionNode> region_;
  std::vector<ContactEntry> entries_;
  std::vector<PressureSource> sources_;
  std::vector<Real> normal_motion_;  ///< per contact: the approach its impulse stopped
  /// per body: the region node of each of its nodes, or -1
  std::vector<std::vector<std::int32_t>> region_of_;
  /// per body: which of its nodes are region nodes, the only forces the pressures need
  std::vector<std::vector<std::uint8_t>> in_region_;
  std::vector<std::uint8_t> involved_;    ///< per body: has region nodes
  std::vector<std::vector<Real>> area_;   ///< per body and node: area of O_i
  std::vector<std::vector<Vec3>> force_;  ///< per body and node: internal force
  std::vector<Vec3> combined_;            ///< scratch: one node's displacements, largest first
};

}  // namespace felt
