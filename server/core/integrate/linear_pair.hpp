#pragma once

#include <cstdint>

#include "core/math/types.hpp"

namespace felt {

/// A force between particles i and j that is linear in their states with constant
/// coefficients: f_i += −k (x_i − x_j) − c (v_i − v_j), f_j the opposite. The part of a
/// system's forces an IMEX scheme treats implicitly (Eberhardt et al. 2000, thesis 1 §4.4).
struct LinearPair {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
  Real k = 0;  ///< stiffness, N/m
  Real c = 0;  ///< isotropic damping, N·s/m

  bool operator==(const LinearPair&) const = default;
};

}  // namespace felt
