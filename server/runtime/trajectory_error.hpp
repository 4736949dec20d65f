#pragma once
// How far a run's bodies are from a reference run of the same scene (`feltd compare`, `feltd
// sweep`): both are sampled at the same simulated times, the reference's positions are kept, and
// each sample of the run is measured against them as it is taken.

#include <cstddef>
#include <expected>
#include <string>
#include <vector>

#include "core/world/world.hpp"

namespace felt {

/// Every body's positions at each sample of a reference run.
class ReferenceTrajectory {
 public:
  /// Keeps the positions of `world`'s bodies as the next sample; the first names the bodies.
  void add(const World& world);
  std::size_t samples() const { return samples_.size(); }
  const std::vector<std::string>& names() const { return names_; }
  /// Body b's positions at sample k.
  const std::vector<Vec3>& positions(std::size_t k, std::size_t b) const { return samples_[k][b]; }

 private:
  std::vector<std::string> names_;
  std::vector<std::vector<std::vector<Vec3>>> samples_;  ///< [sample][body][particle]
};

/// One body's distance from the reference over the samples: d = |x − x_ref| per particle (or
/// node) and sample.
struct BodyError {
  std::string name;
  Real rms = 0;  ///< √(mean d²) over all particles and samples, m
  Real max = 0;  ///< max d over all particles and samples, m (NaN when a position was)
  Real end = 0;  ///< max d over the particles at the last sample, m
};

/// Accumulates a run's distance from a reference, sample by sample.
class TrajectoryError {
 public:
  explicit TrajectoryError(const ReferenceTrajectory& reference) : reference_(reference) {}

  /// Measures `world` against the reference's sample `k`; an error when the bodies differ
  /// (in number or size) from the reference's.
  std::expected<void, std::string> add(const World& world, std::size_t k);
  /// Per body, over the samples added so far.
  std::vector<BodyError> errors() const;

 private:
  struct Sums {
    Real squares = 0;
    std::size_t count = 0;
    Real max = 0;
    Real end = 0;
  };
  const ReferenceTrajectory& reference_;
  std::vector<Sums> sums_;
};

}  // namespace felt
