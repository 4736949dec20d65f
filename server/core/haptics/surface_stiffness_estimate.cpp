#include "core/haptics/surface_stiffness_estimate.hpp"

#include <cmath>

namespace felt {

void SurfaceStiffnessEstimate::add(Real force, Real position) {
  if (!std::isfinite(force) || !std::isfinite(position)) return;
  w_ = forgetting_ * w_ + 1;
  f_ = forgetting_ * f_ + force;
  u_ = forgetting_ * u_ + position;
  ff_ = forgetting_ * ff_ + force * force;
  fu_ = forgetting_ * fu_ + force * position;
}

Real SurfaceStiffnessEstimate::stiffness() const {
  if (!(w_ > 0)) return 0;
  // the weighted covariances of F with F and with u: slope du/dF = cov(F, u) / var(F)
  const Real mean_f = f_ / w_;
  const Real var_f = ff_ / w_ - mean_f * mean_f;
  if (!(var_f >= min_spread_ * min_spread_)) return 0;
  const Real cov_fu = fu_ / w_ - mean_f * u_ / w_;
  const Real slope = cov_fu / var_f;
  return slope < 0 ? -1 / slope : 0;
}

}  // namespace felt
