#pragma once
// All the soft solids of a world and the per-step pipeline that moves them and resolves their
// contacts (thesis 2 §4.1, in the order of Table 7.4): internal forces, integration, collision
// detection, triangle collection, penetration vectors, contact resolution.

#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include "core/collision/collider.hpp"
#include "core/solids/contact_surface.hpp"
#include "core/solids/penetration_depth.hpp"
#include "core/solids/solid_body.hpp"
#include "core/solids/solid_collision_detection.hpp"
#include "core/step/body_step_counts.hpp"
#include "core/step/energy_balance.hpp"
#include "core/step/health_settings.hpp"
#include "core/step/step_profile.hpp"
#include "core/step/sticky_substeps.hpp"

namespace felt {

struct SolidStepSettings {
  Real max_step = 0.015;       ///< s, the thesis's cap on the adaptive step
  int contact_iterations = 3;  ///< pressure comparisons after the first half step (§3.3 h)
  Real min_depth = 1e-6;       ///< m; shallower penetration depths are taken as zero (§3.3 e)
  SolidFriction friction = SolidFriction::kRelativeCoulomb;  ///< between bodies
  /// m/s; a node faster than this after a step is taken as an exploding state, besides the
  /// limit scaled from the scene (HealthSettings::speed_growth). None by default.
  Real max_speed = std::numeric_limits<Real>::infinity();
  /// A step after which the solids' kinetic plus elastic energy exceeds this factor times what
  /// it was plus the work gravity and external forces did is taken as exploding (the world's
  /// WorldSettings::max_energy_growth).
  Real max_energy_growth = 2;
  HealthSettings health{};  ///< the world's (WorldSettings::health)
};

struct SolidStepStats {
  int substeps = 0;
  std::size_t colliding_nodes = 0;      ///< in the last substep (Table 7.3 PKU)
  std::size_t colliding_triangles = 0;  ///< in the last substep (Table 7.3 PKT)
  bool rescued = false;        ///< a substep left a non-finite or exploding state and was redone
  bool unrecoverable = false;  ///< redoing did not help; the bodies were rolled back and stopped
  /// the step reached its budget (HealthSettings::step_budget): its stable step asked for
  /// more substeps, or a retry was due that it could not afford
  bool over_budget = false;
  StepProfile profile;  ///< the stages of Table 7.4, and the health check
};

/// The soft solids of a world, stepped together because they collide with each other.
class SolidSystem {
 public:
  /// The stages a solid step goes through, in order (Table 7.4).
  static constexpr std::array kStages{StepStage::kIntegration, StepStage::kDetection,
                                      StepStage::kTriangles,   StepStage::kPenetration,
                                      StepStage::kResolution,  StepStage::kColliders,
                                      StepStage::kFinish,      StepStage::kHealth};

  explicit SolidSystem(SolidStepSettings settings = {});

  /// Adds a body and returns its index.
  std::uint32_t add_body(SolidBody body);
  /// Removes the body at `index`; the later ones move down by one. The contact caches start
  /// over, as they hold positions in the list of bodies.
  void remove_body(std::uint32_t index);
  /// Mutable access: anything that edits a solid through it (an anchor moved, a material
  /// changed) makes the next step recompute the energy its health check starts from.
  std::vector<SolidBody>& bodies() {
    energy_valid_ = false;
    return bodies_;
  }
  const std::vector<SolidBody>& bodies() const { return bodies_; }
  /// A force on node `node` of solid `index` for the next step. An external force does not
  /// change the energy the health check carries over, so unlike bodies() this keeps it.
  void add_external_force(std::uint32_t index, std::uint32_t node, const Vec3& force) {
    bodies_[index].add_external_force(node, force);
  }

  const SolidStepSettings& settings() const { return settings_; }
  void set_settings(const SolidStepSettings& settings);

  /// Advances every solid by h in equal substeps no longer than max_step and every body's
  /// stable_time_step(). A step that leaves a non-finite node, one faster than max_speed, or
  /// the solids with more energy than they may have (the cloth's health check, applied to all
  /// the solids together: they trade energy in contact) is undone and redone with twice the
  /// substeps, up to 6 times and within a budget of substeps (solid_system.cpp); if none
  /// works, the bodies are
  /// put back where they were, at rest. External forces are cleared afterwards. `yield_point`,
  /// if given, is called after each substep's integration and after its contacts (as in
  /// World::step).
  const SolidStepStats& step(Real h, const Vec3& gravity, std::span<const Collider> colliders,
                             const std::function<void()>& yield_point = {});
  const SolidStepStats& last_stats() const { return stats_; }
  /// The substeps a rescue left the solids with (they step together) and how many of their
  /// steps were rescued.
  const StickySubsteps& substeps() const { return sticky_; }
  /// The substeps of the last step and how many steps reached their budget.
  const BodyStepCounts& step_counts() const { return counts_; }

 private:
  /// Runs `substeps` substeps of length h; false as soon as the state is not healthy.
  bool attempt(Real h, int substeps, const Vec3& gravity, std::span<const Collider> colliders,
               Real max_speed, const std::function<void()>& yield_point);
  /// What a step's energy check compares its end with.
  struct StepStart {
    Real energy = 0;    ///< kinetic + elastic, of all the solids
    bool first = true;  ///< the attempt is the first of the step, not a retry
    /// the solids were set (added, edited) since the last step, maybe inside each other or a
    /// collider
    bool set_now = false;
  };
  /// Whether the solids' energy after a step of length h from `start` (the state in saved_)
  /// stays within what gravity and the external forces could give them, and, on the first
  /// attempt, within the energy balance; if so, keeps the energies for accept_energy().
  bool energy_healthy(Real h, const Vec3& gravity, const StepStart& start);
  /// After a rescue: takes the growth of the balance since it started out of the solids'
  /// motion about their centres of mass, as ClothSystem::take_back_growth does.
  void take_back_growth();
  /// Kinetic, elastic and gravitational energy of all the solids, J.
  Real mechanical_energy(const Vec3& gravity) const;
  /// The solids' kinetic and elastic energy (`kinetic_elastic`, J) plus their weight times
  /// their size: what the energy balance's tolerance is a fraction of.
  Real energy_scale(Real kinetic_elastic, const Vec3& gravity) const;
  void substep(Real h, const Vec3& gravity, std::span<const Collider> colliders);
  /// Every position finite and, when `check_speed`, every speed under `max_speed`.
  bool healthy(bool check_speed, Real max_speed) const;
  void restore();
  /// A step of `substeps` substeps without the health check (HealthSettings::enabled off): a
  /// non-finite state is still caught, and every body starts over from its rest shape.
  void step_unchecked(Real h, int substeps, const Vec3& gravity,
                      std::span<const Collider> colliders,
                      const std::function<void()>& yield_point);
  /// Brings every body to rest where it is and reports the step unrecoverable.
  void stop();

  SolidStepSettings settings_;
  std::vector<SolidBody> bodies_;
  SolidCollisionDetector detector_;
  PenetrationDepthEstimator penetration_;
  ContactSurface contact_surface_;
  CollisionSet collisions_;
  std::vector<PenetrationContact> contacts_;
  std::vector<SolidBody::StepState> saved_;  ///< per body, the state before the step
  SolidStepStats stats_;
  StickySubsteps sticky_;
  BodyStepCounts counts_;
  Real size_ = 0;  ///< m, the diagonal of the bodies' bounding box when the last was added
  Real mass_ = 0;  ///< kg, of all the solids
  /// the solids' kinetic + elastic energy after the last step, the next step's starting energy
  /// unless bodies() was handed out in between
  Real energy_ = 0;
  bool energy_valid_ = false;
  EnergyBalance balance_;
  int window_ = HealthSettings::kMinWindowSteps;  ///< steps of the balance's window
  /// kept by the check of the last healthy attempt: the work of the external forces, and the
  /// gravitational energy it left
  Real work_ = 0, gravitational_ = 0;
};

}  // namespace felt
