#pragma once
// The simulated world: its bodies, its clock and the step that advances them.

#include <cstdint>
#include <vector>

#include "core/cloth_body.hpp"
#include "core/collider.hpp"

namespace felt {

struct WorldSettings {
  Vec3 gravity = Vec3(0, -9.81, 0);
  Real time_step = 1e-3;  ///< s
  /// A particle faster than this is taken as an exploding state and the step is retried.
  Real max_speed = 100;
  /// How many times a failed step is retried, each time with twice the substeps.
  int max_substep_doublings = 6;
  /// A step after which kinetic plus elastic energy exceeds this factor times what it was plus
  /// the work gravity and external forces did is taken as exploding (an unstable mode grows
  /// geometrically; a passive cloth can only lose energy).
  Real max_energy_growth = 2;
};

/// What happened in one step, as bit flags (DESIGN "numerical health").
enum StepFlag : std::uint32_t {
  kStepOk = 0,
  kStepRescued = 1u << 0,        ///< a body's step failed and was redone with substeps
  kStepUnrecoverable = 1u << 1,  ///< a body could not be rescued; it was rolled back and stopped
};

struct StepReport {
  std::uint32_t flags = kStepOk;
  int max_substeps = 1;  ///< the most substeps any body needed
};

class World {
 public:
  explicit World(WorldSettings settings = {});

  const WorldSettings& settings() const { return settings_; }

  /// Adds a body and returns its index.
  std::uint32_t add_body(ClothBody body);
  /// Mutable access; anything that edits a body through it makes the next step recompute the
  /// energies its health check starts from.
  std::vector<ClothBody>& bodies() {
    energy_valid_ = false;
    return bodies_;
  }
  void add_collider(const Collider& collider) { colliders_.push_back(collider); }
  const std::vector<Collider>& colliders() const { return colliders_; }
  const std::vector<ClothBody>& bodies() const { return bodies_; }

  /// Advances every body by one time step. A body whose step leaves a non-finite or exploding
  /// state is rolled back and stepped again with 2, 4, ... substeps; if none works it is rolled
  /// back and brought to rest. Nothing non-finite survives a step.
  StepReport step();

  Real time() const { return time_; }
  std::uint64_t step_count() const { return step_count_; }

 private:
  /// Steps one body over [time_, time_ + h] in `substeps` equal parts; false when unhealthy.
  /// `energy` holds the body's kinetic plus elastic energy at the start, and at the end when
  /// the step was healthy.
  bool try_step(ClothBody& body, int substeps, Real& energy);
  bool healthy(const ClothBody& body, Real& energy) const;

  WorldSettings settings_;
  std::vector<ClothBody> bodies_;
  std::vector<Collider> colliders_;
  /// kinetic + elastic energy of each body after the last step, reused as the next step's
  /// starting energy unless bodies() was handed out in between
  std::vector<Real> energy_;
  bool energy_valid_ = false;
  ParticleState backup_;
  Real time_ = 0;
  std::uint64_t step_count_ = 0;
};

}  // namespace felt
