#pragma once
// The cloth of the peer benchmark (issue 29), the same for Felt and Bullet: 1 m × 1 m, 0.2 kg,
// n × n particles laid out in the vertical xy plane about the origin (row 0 on top, particle
// (i, j) at index j·n + i in both engines), hung by its two top corners, released from rest and
// simulated for 2 s, with a mass-proportional damping of kDampingRate. And what is measured of
// it, from the final positions, the same way for both engines.

#include <cstdint>
#include <span>
#include <string>

#include "core/math/types.hpp"

namespace felt::peers {

inline constexpr Real kSide = 1;        ///< m
inline constexpr Real kMass = 0.2;      ///< kg
inline constexpr Real kSeconds = 2;     ///< simulated time, s
inline constexpr Real kGravity = 9.81;  ///< m/s², along −y
/// γ, 1/s: every particle's velocity decays as e^(−γ t) besides the springs (Felt: drag γ m per
/// particle; Bullet: kDP = 1 − e^(−γ h) per step)
inline constexpr Real kDampingRate = 1;

/// What one run of one configuration gives.
struct Outcome {
  double wall_per_sim_s = 0;  ///< wall seconds per simulated second
  double max_strain = 0;      ///< max_structural_strain at the end
  double sag_error = 0;       ///< sag_error at the end
  bool ok = true;             ///< intact, and (Felt) no step given up by the health check
  std::string note;           ///< Felt: "rescued" when the health check added substeps
};

/// Where particle (i, j) starts: x = −½ + i·s, y = ½ − j·s, z = 0, s = kSide/(n − 1).
Vec3 rest_position(std::uint32_t n, std::uint32_t i, std::uint32_t j);

/// The largest relative elongation |x_a − x_b|/r − 1 over the structural edges (grid
/// neighbours along rows and columns, rest length r = kSide/(n − 1)).
Real max_structural_strain(std::uint32_t n, std::span<const Vec3> x);

/// (sag − kSide)/kSide, where sag is the height of the pins (½) above the lowest particle. The
/// reference, kSide, is the converged inextensible cloth: with its structural and shear edges
/// rigid the grid is a rigid truss, so hung by its top corners it stays as laid out and its
/// lowest particles stay 1 m below the pins.
Real sag_error(std::span<const Vec3> x);

/// A structural edge stretched beyond this many times its rest length is a blown-up cloth.
inline constexpr Real kBlownUpStrain = 10;

/// Whether the cloth is still a cloth: every coordinate finite and every structural edge
/// within kBlownUpStrain (a blown-up run measures nothing).
bool intact(Real max_strain, std::span<const Vec3> x);

}  // namespace felt::peers
