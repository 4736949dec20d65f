#pragma once
// Meshless shape matching (Müller et al. 2005; thesis 2 §1.4): each cluster of nodes finds the
// rigid, linear or quadratic transform of its rest shape that best fits the current positions,
// and every node is pulled towards its goal position, averaged over its clusters.
//
// The update is (3.4), v += α/h (g − x) + h a, x += h v, with two changes so that the motion does
// not depend on the step size: the pull α/h² tends to 1/τ² (a goal spring of stiffness m/τ²),
// and the velocity relative to the cluster's rigid motion is critically damped (2m/τ), both
// integrated implicitly. With α = h/τ as the paper's stiffness, the pull α/h² = 1/(τh) grows
// without bound as h shrinks; undamped, (3.4) oscillates about the goal forever. Here a
// deformation decays like (1 + t/τ) e^(−t/τ) at any step, and a body in rigid mode snaps back
// to its shape within a few τ. Unconditionally stable.
//
// A steady load a is step-independent for a body held by pins. Entering as h a outside the
// solve (the paper's form), it stops a held node where α/h (g − x) = −(1 + s)² h a: τ_eff² a
// from its goal, τ_eff = h (1 + s)/s = h / (1 − e^(−h/τ)), which is τ only for h ≪ τ (25 τ² a
// at h = 5τ). Inside the solve, as a goal shifted by τ² a (where the spring m/τ² holds m a), the
// node stops at g − x = −τ² a at any h, the continuous equilibrium; but a shifted goal moves a
// node only as far as its spring pulls, and when the load moves the body rigidly the goals move
// along: a free body would fall at (τ/τ_eff)² g, not g. So the load is split. Its rigid share
// a_R, the acceleration field of the whole body moving as one rigid body under the load with its
// pinned nodes held (Gauss's principle of least constraint: the rigid field nearest the load
// that leaves the pins at rest), enters beside the rigid velocity as before, so a free body
// falls and turns as a rigid body would; the rest shifts the goal:
//   v' = r + h a_R + (v − r + α/h (g + τ² (a − a_R) − x)) / (1 + s)².
// Pinned at three nodes off a line, a body has a_R = 0, and at rest each free node hangs τ² a
// from its goal at any step. The split cannot be per cluster: uniform gravity is all rigid share
// for any one cluster; what holds a cluster is its neighbours and the pins, which only the whole
// body sees.
//
// Still step-dependent: a body held by contact (the floor, another body) is free as far as this
// update knows, so it still sinks τ_eff² a into its goals. A slow mode of a clustered body
// (bending, where the goals move almost with the nodes) feels its stiffness through the per-node
// implicit spring, (τ/τ_eff)² of its value, and its share of the load is weakened alike: it
// settles where it should but swings τ_eff/τ times slower (about h/τ for h ≫ τ), as it did before
// the split, when it also settled (τ_eff/τ)² too far (docs/results/solid_models.md).

#include <cstdint>
#include <span>
#include <vector>

#include "core/geometry/tet_mesh.hpp"
#include "core/solids/solid_body.hpp"

namespace felt {

class ShapeMatching {
 public:
  /// One cluster for the whole body, or, with material.clusters, one per lattice cell when the
  /// tetrahedra come five per cell with eight corners (make_cell_lattice), else one per
  /// tetrahedron. All nodes weigh the same (a body's node masses are uniform).
  ShapeMatching(const TetMesh& rest, const ShapeMatchingMaterial& material);

  std::size_t cluster_count() const { return clusters_.size(); }

  /// Goal positions at positions x, each node's averaged over its clusters; a node in no
  /// cluster is its own goal.
  void goals(std::span<const Vec3> x, std::span<Vec3> goal) const;
  /// Velocities of the clusters' rigid motions (their linear and angular momentum) at the
  /// nodes, averaged like the goals.
  void rigid_velocities(std::span<const Vec3> x, std::span<const Vec3> v,
                        std::span<Vec3> rigid) const;

  /// One step of length h: plastic flow of the rest shapes, then the update (3.4) of the nodes
  /// with nonzero inverse mass under the external accelerations `acceleration`, split into
  /// their rigid share and the rest as above (nodes with zero inverse mass are the pins).
  void step(std::span<Vec3> x, std::span<Vec3> v, std::span<const Real> inv_mass,
            std::span<const Vec3> acceleration, Real h);

  /// Adds the goal-spring forces m (g − x)/τ² + 2m/τ (v_rigid − v) to f.
  void add_forces(std::span<const Vec3> x, std::span<const Vec3> v, Real node_mass,
                  std::span<Vec3> f) const;
  /// Σ ½ m |g − x|² / τ², the energy of the goal springs.
  Real energy(std::span<const Vec3> x, Real node_mass) const;

 private:
  using Mat9 = Eigen::Matrix<Real, 9, 9>;
  using Mat39 = Eigen::Matrix<Real, 3, 9>;

  struct Cluster {
    std::vector<std::uint32_t> nodes;
    std::vector<Vec3> original_shape;  ///< rest offsets from the rest centre
    std::vector<Vec3> shape;           ///< plastic × original: the rest the fit matches
    Mat3 plastic = Mat3::Identity();   ///< S_p, the permanent deformation
    Mat3 linear_inverse;               ///< (Σ q qᵀ)⁺
    Mat9 quadratic_inverse;            ///< (Σ q̃ q̃ᵀ)⁺, quadratic mode only
  };

  void set_shape(Cluster& cluster) const;
  Vec3 centre(const Cluster& cluster, std::span<const Vec3> x) const;
  /// Σ (x − centre) qᵀ over the cluster: A_pq.
  Mat3 moment(const Cluster& cluster, std::span<const Vec3> x, const Vec3& centre) const;
  /// Adds the cluster's goal for each of its nodes to goal.
  void add_goals(const Cluster& cluster, std::span<const Vec3> x, std::span<Vec3> goal) const;
  /// O'Brien-style split of the linear fit's stretch S: beyond the yield, S − I creeps into S_p.
  void flow_plastically(Cluster& cluster, std::span<const Vec3> x, Real h) const;

  ShapeMatchingMaterial material_;
  std::vector<Cluster> clusters_;
  std::vector<Real> inv_cluster_count_;     ///< per node, 1 / the number of its clusters, or 0
  std::vector<Vec3> goal_, rigid_, share_;  ///< scratch for step()
};

}  // namespace felt
