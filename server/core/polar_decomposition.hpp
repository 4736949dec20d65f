#pragma once
// F = R S, R a rotation and S symmetric: the rotation of a deformation with its stretch removed,
// as corotated elements and shape matching need it (thesis 2 §1.4).

#include "core/types.hpp"

namespace felt {

struct PolarDecomposition {
  Mat3 rotation;  ///< det = +1 always
  Mat3 stretch;   ///< symmetric; a negative eigenvalue when F reflects (an inverted element)
};

/// From the singular value decomposition, so that a reflecting F gives a proper rotation (the
/// smallest singular direction is flipped into S) and a flat or collinear F (rank below 3)
/// still gives a rotation, completed arbitrarily in the directions F collapses.
PolarDecomposition polar_decomposition(const Mat3& f);

}  // namespace felt
