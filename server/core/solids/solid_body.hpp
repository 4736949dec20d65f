#pragma once
// A simulated soft solid (thesis 2): an immutable tetrahedral mesh and its topology, the
// material of one of three models, and the state of its nodes.

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/SparseCore>

#include "core/geometry/tet_mesh.hpp"
#include "core/integrate/integrator.hpp"
#include "core/solids/embedded_surface.hpp"
#include "core/solids/node_mask.hpp"

namespace felt {

enum class SolidModel : std::uint8_t {
  kMassSpring,     ///< generalized mass-spring (Teschner et al. 2004), the thesis's choice
  kShapeMatching,  ///< meshless shape matching (Müller et al. 2005)
  kCorotatedFem,   ///< corotated linear finite elements, the accurate reference
};

/// Generalized mass-spring coefficients, Table B.1 defaults (thesis 2 §3.2.2, §6.2.1).
struct MassSpringMaterial {
  Real distance_stiffness = 20;  ///< k_D, N
  Real volume_stiffness = 10;    ///< k_V, N (the thesis folds 1/(6V₀) into it)
  Real damping = 1;              ///< d_C on the edges, N·s
  Real area_stiffness = 0;       ///< k_A on the surface triangles, N; 0 switches the term off
};

/// Shape matching (Müller et al. 2005, thesis 2 §1.4).
struct ShapeMatchingMaterial {
  enum class Mode : std::uint8_t { kRigid, kLinear, kQuadratic };
  Mode mode = Mode::kLinear;
  Real beta = 0.5;  ///< how far the linear or quadratic fit replaces the rotation, 0..1
  /// τ, s: each node is pulled to its goal by a spring m/τ², critically damped relative to the
  /// cluster's rigid motion, so a deformation dies out within a few τ whatever the step size
  /// (shape_matching.hpp says why not α = h/τ, and where a steady load still depends on it).
  Real time_constant = 0.01;
  bool clusters = false;  ///< one cluster per lattice cell (five tetrahedra) instead of one
  /// Opt-in plasticity (O'Brien et al. 2002 strain split applied to the fit): deformation
  /// beyond `yield` creeps into the rest shape at rate `creep` up to `max`.
  Real plastic_yield = 0;  ///< 0 switches plasticity off
  Real plastic_creep = 0;  ///< 1/s
  Real plastic_max = 0;
};

/// Corotated linear elasticity, lumped masses.
struct FemMaterial {
  Real young_modulus = 1e4;  ///< Pa
  Real poisson_ratio = 0.3;
  Real damping = 0;  ///< stiffness-proportional Rayleigh damping, s
};

/// The default SolidMaterial::crease_angle, 60°: a box's 90° edges are sharp, the gentle edges
/// of a tessellated curved surface are not.
constexpr Real kDefaultCreaseAngle = std::numbers::pi / 3;

struct SolidMaterial {
  SolidModel model = SolidModel::kMassSpring;
  Real node_mass = 1;   ///< kg per node (Table B.1 "Mass")
  Real friction = 0.5;  ///< Coulomb μ at contacts with other bodies and colliders
  bool self_collision = false;
  /// rad; edges of the body's surface that turn by more are sharp for the penetration vectors
  /// of nodes inside it (penetration_depth.hpp): a box's are, a smooth shape's are not
  Real crease_angle = kDefaultCreaseAngle;
  MassSpringMaterial mass_spring;
  ShapeMatchingMaterial shape_matching;
  FemMaterial fem;
};

/// The integrator name that stands for the thesis's own scheme (thesis 2 §4.5): position Verlet
/// in its time-corrected form for a step length that changes, the default of the force models.
constexpr std::string_view kTimeCorrectedVerlet = "time_corrected_verlet";

/// Why the cloth integrator `name` (or kTimeCorrectedVerlet) does not apply to a solid of
/// `model`, or nothing when it does. The explicit and symplectic schemes apply to the force
/// models (mass-spring, FEM); IMEX, Desbrun and Kang to the mass-spring model, whose edges are
/// springs; implicit Euler to neither (no force Jacobian); shape matching has its own update.
std::optional<std::string> solid_integrator_refusal(SolidModel model, std::string_view name);

class SolidBody {
 public:
  /// `mesh` must have positively oriented tetrahedra; its node positions are the rest shape
  /// and the initial state (at rest).
  SolidBody(std::string name, TetMesh mesh, SolidMaterial material);
  ~SolidBody();
  SolidBody(SolidBody&&) noexcept;
  SolidBody& operator=(SolidBody&&) noexcept;

  const std::string& name() const { return name_; }
  const TetMesh& rest() const { return *rest_; }
  /// The rest shape, shared with snapshots (it never changes).
  const std::shared_ptr<const TetMesh>& shared_rest() const { return rest_; }
  const TetTopology& topology() const { return topology_; }
  const SolidMaterial& material() const { return material_; }
  /// A new material keeps the integrator only when it still applies.
  void set_material(const SolidMaterial& material);
  /// The integrator of a force model; null for kTimeCorrectedVerlet.
  const Integrator* integrator() const { return integrator_.get(); }
  /// `integrator` must apply to the model (solid_integrator_refusal); null: kTimeCorrectedVerlet.
  void set_integrator(std::unique_ptr<Integrator> integrator);

  /// The longest step this body takes (the solids step together: the shortest
  /// of all theirs), s: a longer world step is taken in equal substeps
  /// (the user's trade of speed for accuracy; a stable step may ask for more). Infinite: none.
  Real max_step() const { return max_step_; }
  void set_max_step(Real max_step);

  std::size_t node_count() const { return x_.size(); }
  std::vector<Vec3>& positions() { return x_; }
  const std::vector<Vec3>& positions() const { return x_; }
  /// Positions one step ago, for position Verlet.
  std::vector<Vec3>& previous_positions() { return x_prev_; }
  const std::vector<Vec3>& previous_positions() const { return x_prev_; }
  std::vector<Vec3>& velocities() { return v_; }
  const std::vector<Vec3>& velocities() const { return v_; }
  std::span<const Real> inv_mass() const { return inv_mass_; }
  Real mass(std::uint32_t n) const;

  /// What a step changes and the external forces that drive it, so that a step that failed can
  /// be undone and redone. Saving into the same object again reuses its storage.
  struct StepState {
    std::vector<Vec3> x, x_prev, v, external_force;
    Real previous_step = 0;
  };
  void save_step_state(StepState& out) const {
    out.x = x_;
    out.x_prev = x_prev_;
    out.v = v_;
    out.external_force = external_force_;
    out.previous_step = previous_step_;
  }
  /// Also forgets what the integrator kept from earlier steps.
  void restore_step_state(const StepState& state);
  /// Has the integrator forget what it kept from earlier steps, after the state was changed
  /// from outside.
  void forget_history();

  void pin(std::uint32_t n);
  void unpin(std::uint32_t n);

  /// A point of the body (a node, or a fine surface vertex: weights over a tetrahedron's
  /// nodes) tied to a target by a damped zero-length spring, f = k (target − p) − c ṗ, spread
  /// over the nodes by the weights (a grab). Unlike an external force it is evaluated at every
  /// substep and counted in the stable step: a spring held fixed over a step overshoots on a
  /// light node at a long step.
  /// Nodes and their weights (non-negative, summing to 1) that carry a point of the body.
  struct SurfacePoint {
    std::array<std::uint32_t, 4> nodes{};
    std::array<Real, 4> weights{};
  };
  /// Surface vertex `vertex` as clients see it (surface_vertex_count): its tetrahedron's nodes
  /// with its barycentric coordinates, or without a fine surface the node itself.
  SurfacePoint surface_point(std::uint32_t vertex) const;

  struct Anchor {
    std::uint32_t key = 0;  ///< who set it (the surface vertex): setting it again replaces it
    SurfacePoint point;
    Vec3 target = Vec3::Zero();
    Real stiffness = 0;  ///< N/m
    Real damping = 0;    ///< N·s/m
  };
  void set_anchor(const Anchor& anchor);
  void remove_anchor(std::uint32_t key);
  const std::vector<Anchor>& anchors() const { return anchors_; }

  /// Adds a force on node n for the next step only (user and haptic forces): it acts in every
  /// advance() until clear_external_forces(), which the caller calls after the step's last
  /// substep.
  void add_external_force(std::uint32_t n, const Vec3& force) { external_force_[n] += force; }
  void clear_external_forces();
  const std::vector<Vec3>& external_forces() const { return external_force_; }

  /// Elastic and damping forces of the model at the current positions and velocities,
  /// written (not added) into f. Shape matching reports the force of its goal springs.
  /// With a mask, f is right (bit for bit) at the selected nodes only, and the elements that
  /// act on none of them are skipped (shape matching evaluates everything).
  void internal_forces(std::span<Vec3> f, NodeMask mask = {}) const;

  /// Moves the nodes over one step of length h under the model, gravity and the external
  /// forces, before collisions: position Verlet in the time-corrected form for a step length
  /// that differs from the previous one, the body's integrator, or the shape-matching update.
  /// Keeps the positions before the step as the previous positions.
  void advance(Real h, const Vec3& gravity);
  /// Sets velocities after collision handling moved the nodes (and, through the previous
  /// positions, changed their velocities): the backward difference, or with an integrator its
  /// own velocities for the nodes collision handling did not touch.
  void finish_step(Real h);
  /// The largest step this body's stiffness allows for the explicit integration, s: by
  /// position Verlet's limit, or its integrator's when that is tighter; 0 when no step is
  /// stable (explicit Euler or the midpoint rule without damping).
  Real stable_time_step() const;
  /// K = −∂f/∂x of the model at rest (3n × 3n), or null for shape matching (no force model).
  const Eigen::SparseMatrix<Real>* rest_stiffness() const;

  Real kinetic_energy() const;
  /// The model's elastic energy plus ½ k |target − p|² over the anchors, J.
  Real elastic_energy() const;
  /// −Σ m g·x over the nodes, J: zero at the origin, so only its changes mean anything.
  Real gravitational_energy(const Vec3& gravity) const;
  Real volume() const { return total_volume(x_, rest_->tets); }
  Real rest_volume() const { return rest_volume_; }

  /// How many vertices clients see: the embedded surface's (a body read from a scene always
  /// has one: its fine surface or the lattice's own, embed_lattice_surface), or the nodes.
  std::size_t surface_vertex_count() const {
    return embedded_ ? embedded_->vertex_count() : node_count();
  }

  /// The fine surface clients see, when the body carries one.
  const EmbeddedSurface* embedded_surface() const { return embedded_.get(); }
  const std::shared_ptr<const EmbeddedSurface>& shared_embedded_surface() const {
    return embedded_;
  }
  void set_embedded_surface(std::shared_ptr<const EmbeddedSurface> surface) {
    embedded_ = std::move(surface);
  }

 private:
  struct ModelState;  ///< per-model precomputation (rest lengths, FEM shape matrices, clusters)
  class Dynamics;     ///< the body as a DynamicSystem, for its integrator

  void add_anchor_forces(std::span<const Vec3> x, std::span<const Vec3> v, std::span<Vec3> f) const;

  std::string name_;
  std::shared_ptr<const TetMesh> rest_;
  TetTopology topology_;
  SolidMaterial material_;
  Real rest_volume_ = 0;
  std::vector<Vec3> x_, x_prev_, v_;
  std::vector<Real> inv_mass_;
  std::vector<Vec3> external_force_;
  std::vector<Anchor> anchors_;
  Real previous_step_ = 0;  ///< length of the last step, 0 before the first
  std::unique_ptr<ModelState> model_state_;
  std::unique_ptr<Integrator> integrator_;
  Real max_step_ = std::numeric_limits<Real>::infinity();
  ParticleState integrated_;  ///< the integrator's state; x and v live here during a step
  std::vector<Vec3> integrated_motion_;  ///< per node, how far the integrator moved it
  std::shared_ptr<const EmbeddedSurface> embedded_;
};

}  // namespace felt
