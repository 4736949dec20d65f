#include "runtime/trajectory_error.hpp"

#include <cmath>
#include <limits>

#include "runtime/body_measures.hpp"

namespace felt {

void ReferenceTrajectory::add(const World& world) {
  if (samples_.empty()) {
    for (BodyId id : world.body_ids()) {
      if (const ClothBody* cloth = world.cloth(id)) names_.push_back(cloth->name());
      if (const SolidBody* solid = world.solid(id)) names_.push_back(solid->name());
    }
  }
  auto& sample = samples_.emplace_back();
  for (std::span<const Vec3> x : body_positions(world)) sample.emplace_back(x.begin(), x.end());
}

std::expected<void, std::string> TrajectoryError::add(const World& world, std::size_t k) {
  const std::vector<std::span<const Vec3>> bodies = body_positions(world);
  if (bodies.size() != reference_.names().size()) {
    return std::unexpected(std::to_string(bodies.size()) + " bodies against the reference's " +
                           std::to_string(reference_.names().size()));
  }
  if (k >= reference_.samples()) return std::unexpected("more samples than the reference has");
  sums_.resize(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::vector<Vec3>& ref = reference_.positions(k, b);
    if (bodies[b].size() != ref.size()) {
      return std::unexpected(reference_.names()[b] + ": " + std::to_string(bodies[b].size()) +
                             " particles or nodes against the reference's " +
                             std::to_string(ref.size()));
    }
    Sums& s = sums_[b];
    s.end = 0;
    for (std::size_t p = 0; p < ref.size(); ++p) {
      const Real d = (bodies[b][p] - ref[p]).norm();
      s.squares += d * d;
      // NaN wins: a body that went non-finite has no error bound
      if (!(d <= s.max)) s.max = d;
      if (!(d <= s.end)) s.end = d;
    }
    s.count += ref.size();
  }
  return {};
}

std::vector<BodyError> TrajectoryError::errors() const {
  std::vector<BodyError> out;
  for (std::size_t b = 0; b < reference_.names().size(); ++b) {
    BodyError e{reference_.names()[b]};
    if (b < sums_.size() && sums_[b].count > 0) {
      e.rms = std::sqrt(sums_[b].squares / static_cast<Real>(sums_[b].count));
      e.max = sums_[b].max;
      e.end = sums_[b].end;
    } else {
      e.rms = e.max = e.end = std::numeric_limits<Real>::quiet_NaN();
    }
    out.push_back(e);
  }
  return out;
}

}  // namespace felt
