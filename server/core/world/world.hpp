#pragma once
// The simulated world: its bodies, its clock and the step that advances them.

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "core/cloth/cloth_system.hpp"
#include "core/collision/collider.hpp"
#include "core/solids/solid_system.hpp"
#include "core/step/step_flags.hpp"
#include "ids/strong_id.hpp"

namespace felt {

struct WorldSettings {
  Vec3 gravity = Vec3(0, -9.81, 0);
  Real time_step = 1e-3;  ///< s
  /// m/s; a particle faster than this is taken as an exploding state and the step is retried,
  /// besides the limit scaled from the scene (HealthSettings::speed_growth). None by default.
  Real max_speed = std::numeric_limits<Real>::infinity();
  /// How many times a failed step is retried, each time with twice the substeps.
  int max_substep_doublings = 6;
  /// A step after which kinetic plus elastic energy exceeds this factor times what it was plus
  /// the work gravity and external forces did is taken as exploding (an unstable mode grows
  /// geometrically; a passive cloth can only lose energy).
  Real max_energy_growth = 2;
  HealthSettings health{};
};

/// Names a body of a world: its slot in the low 16 bits and the slot's generation in the high
/// 16 (Box2D's b2BodyId), so the id of a removed body never names a later one. The bodies a
/// world starts with take slots 0, 1, 2, ... at generation 0: their ids are their indices.
using BodyId = StrongId<struct BodyIdTag, std::uint32_t>;

/// What a body id names: a cloth, a soft solid or a static collider, and its index among its
/// kind.
struct BodyRef {
  enum class Kind : std::uint8_t { kCloth, kSolid, kCollider };
  Kind kind = Kind::kCloth;
  std::uint32_t index = 0;
};

struct StepReport {
  StepFlags flags;
  int max_substeps = 1;                      ///< the most substeps any body needed
  std::vector<BodyId> rescued_bodies;        ///< empty (no allocation) when none
  std::vector<BodyId> unrecoverable_bodies;  ///< empty (no allocation) when none
  std::vector<BodyId> over_budget_bodies;    ///< empty (no allocation) when none
  StepProfile cloth_profile;  ///< where the cloths' step spent its time (ClothSystem::kStages)
  StepProfile solid_profile;  ///< and the solids' (SolidSystem::kStages)
};

class World {
 public:
  explicit World(WorldSettings settings = {}, SolidStepSettings solid_settings = {});

  const WorldSettings& settings() const { return settings_; }

  /// Adds a cloth, a solid or a static collider and returns its body id: the lowest free slot.
  BodyId add_body(ClothBody body);
  BodyId add_body(SolidBody body);
  BodyId add_collider(const Collider& collider);
  /// Removes a body; its id is never valid again.
  void remove_body(BodyId id);
  /// For a world built again to replace `previous` (a reset): its bodies keep their ids, and
  /// every slot continues previous's generations, so no id `previous` handed out ever names a
  /// later body.
  void continue_ids_from(const World& previous);
  bool contains(BodyId id) const;
  /// Live bodies, colliders included.
  std::size_t body_count() const { return live_; }
  /// The ids of the live bodies, in slot order.
  std::vector<BodyId> body_ids() const;
  /// What `id` names; `id` must be live.
  const BodyRef& body_ref(BodyId id) const;
  /// The cloth with body id `id`, or null when it is not a live cloth.
  ClothBody* cloth(BodyId id);
  const ClothBody* cloth(BodyId id) const;
  /// The solid with body id `id`, or null when it is not a live solid.
  SolidBody* solid(BodyId id);
  const SolidBody* solid(BodyId id) const;
  /// Applies `force` at vertex `vertex` of what clients see of body `id` (the cloth's particle;
  /// for a solid, its fine surface vertex spread over the nodes that carry it) for the next step.
  void add_surface_force(BodyId id, std::uint32_t vertex, const Vec3& force);
  /// Ties surface vertex `vertex` of cloth or solid `id` to `target` by a damped zero-length
  /// spring (a grab) until remove_surface_anchor, replacing the one it had.
  void set_surface_anchor(BodyId id, std::uint32_t vertex, const Vec3& target, Real stiffness,
                          Real damping);
  void remove_surface_anchor(BodyId id, std::uint32_t vertex);
  /// How many vertices clients see of body `id`: a cloth's particles, a solid's fine surface
  /// vertices or, without one, its nodes; 0 for a collider.
  std::size_t surface_vertex_count(BodyId id) const;
  /// Where surface vertex `vertex` of cloth or solid `id` is now: a solid's from the nodes that
  /// carry it, by their weights.
  Vec3 surface_position(BodyId id, std::uint32_t vertex) const;
  /// The inverse mass surface vertex `vertex` of cloth or solid `id` answers a force with: a
  /// solid's Σ w² / m over the nodes that carry it, since add_surface_force spreads a force by
  /// the weights and surface_position reads the motion back by them.
  Real surface_inverse_mass(BodyId id, std::uint32_t vertex) const;

  /// Cloths by index among cloths. Mutable access: anything that edits a cloth through it makes
  /// the next step recompute the energies its health check starts from.
  std::vector<ClothBody>& cloths() { return cloths_.bodies(); }
  const std::vector<ClothBody>& cloths() const { return cloths_.bodies(); }
  const ClothSystem& cloth_system() const { return cloths_; }
  /// The substeps body `id` (a live cloth or solid) steps with now and how many of its steps
  /// were rescued; solids share theirs.
  const StickySubsteps& substeps(BodyId id) const;
  /// The substeps body `id` (a live cloth or solid) took in its last step and how many of its
  /// steps reached their budget; solids share theirs.
  const BodyStepCounts& step_counts(BodyId id) const;
  SolidSystem& solids() { return solids_; }
  const SolidSystem& solids() const { return solids_; }
  const std::vector<Collider>& colliders() const { return colliders_; }
  /// Colliders for the next step only, besides the scene's: the haptic proxies' spheres, so
  /// that a cloth wraps around a finger pressing into it instead of folding into the sphere.
  void set_moving_colliders(std::vector<Collider> colliders) {
    moving_colliders_ = std::move(colliders);
  }

  /// Advances every body by one time step. A cloth whose step leaves a non-finite or exploding
  /// state is rolled back and stepped again with 2, 4, ... substeps; if none works it is rolled
  /// back and brought to rest. The solids step together (they collide with each other) under
  /// the same rule. Nothing non-finite survives a step. `yield_point`, if given, is called
  /// between the step's phases (a few hundred microseconds apart for a 100 x 100 cloth), where
  /// the stepping thread may let another thread of its core run first: the scene runner passes
  /// sched_yield, so that a network thread woken onto the physics thread's core waits for one
  /// phase, not for the whole step.
  StepReport step(const std::function<void()>& yield_point = {});

  Real time() const { return time_; }
  std::uint64_t step_count() const { return step_count_; }
  /// Sets the clock to `steps` steps (restoring a saved state); time is steps · time_step.
  void set_step_count(std::uint64_t steps);

 private:
  struct Slot {
    std::uint16_t generation = 0;  ///< of the body in it (or the last one)
    std::uint16_t issued = 0;      ///< the highest generation ever handed out for the slot
    bool live = false;
    BodyRef ref;
  };
  BodyId allocate(BodyRef ref);
  /// What `id` names if it is a live body of `kind`, else null.
  const BodyRef* live(BodyId id, BodyRef::Kind kind) const;
  /// After element `index` of a kind's vector was erased, the later ones moved down by one.
  void shift_indices(BodyRef::Kind kind, std::uint32_t index);

  WorldSettings settings_;
  ClothSystem cloths_;
  std::vector<BodyId> cloth_ids_;  ///< body id of each cloth
  SolidSystem solids_;
  std::vector<BodyId> solid_ids_;  ///< body id of each solid
  std::vector<Collider> colliders_;
  std::vector<BodyId> collider_ids_;  ///< body id of each collider
  std::vector<Slot> slots_;
  std::size_t live_ = 0;
  std::vector<Collider> moving_colliders_;
  std::vector<Collider> step_colliders_;  ///< the scene's and the moving ones, for one step
  Real time_ = 0;
  std::uint64_t step_count_ = 0;
};

}  // namespace felt
