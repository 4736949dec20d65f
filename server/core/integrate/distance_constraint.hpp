#pragma once

#include <cstdint>
#include <vector>

#include "core/math/types.hpp"

namespace felt {

/// A damped spring between particles i and j given to a position-based integrator as the
/// constraint C = |x_i − x_j| − r with compliance α = 1/k (XPBD, Macklin, Müller & Chentanez
/// 2016): the same stiffness k and damping c the spring's force −[k C + c (v_i − v_j)·l̂] l̂ has.
struct DistanceConstraint {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
  Real rest_length = 0;  ///< r, m
  Real stiffness = 0;    ///< k, N/m; 0 leaves the damping alone
  Real damping = 0;      ///< c, N·s/m, along the constraint
};

/// A system's distance constraints in classes none of which has two constraints on one
/// particle, so that projecting them class by class is the same in any order within a class.
struct ConstraintClasses {
  std::vector<DistanceConstraint> constraints;  ///< class by class
  std::vector<std::size_t>
      class_ends;  ///< class c is constraints[class_ends[c − 1], class_ends[c])

  void clear() {
    constraints.clear();
    class_ends.clear();
  }
};

}  // namespace felt
