#pragma once
// How stiff a body's surface is under a haptic push, estimated from the pushes themselves (issue
// 26): a local model carries it so that a client predicts how far the surface gives under its
// own force before the server's answer comes back (Schuwerk, Xu, Freund & Steinbach 2015 send
// the object's local stiffness with the model). Near the contact the surface is taken as a
// spring: its position along the push, u, falls with the normal force F as u = u₀ − F / k.
// k is fitted by least squares of u against F over the contact's samples, older samples
// weighted down by `forgetting` per sample (exponentially weighted recursive least squares,
// e.g. Ljung & Söderström 1983, ch. 2), and is unknown until the force has varied enough to
// tell (a steady push says nothing of the slope) or when the fit says the surface comes toward
// the push (motion of the whole body, not give).

#include "core/math/types.hpp"

namespace felt {

class SurfaceStiffnessEstimate {
 public:
  /// `forgetting` in (0, 1]: the weight a sample keeps per sample after it; `min_spread` (N):
  /// the weighted standard deviation of F below which the slope is unknown.
  explicit SurfaceStiffnessEstimate(Real forgetting = 0.995, Real min_spread = 0.05)
      : forgetting_(forgetting), min_spread_(min_spread) {}

  /// One sample: normal force `force` (N, >= 0: pushing) with the surface at `position` (m,
  /// along the push's direction reversed: larger is further out).
  void add(Real force, Real position);
  /// Forgets every sample (a new contact).
  void reset() { *this = SurfaceStiffnessEstimate(forgetting_, min_spread_); }
  /// k (N/m), or 0 while unknown.
  Real stiffness() const;

 private:
  Real forgetting_;
  Real min_spread_;
  Real w_ = 0, f_ = 0, u_ = 0, ff_ = 0, fu_ = 0;  ///< weighted sums of 1, F, u, F², F·u
};

}  // namespace felt
