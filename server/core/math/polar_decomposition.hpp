#pragma once
// F = R S, R a rotation and S symmetric: the rotation of a deformation with its stretch removed,
// as corotated elements and shape matching need it (thesis 2 §1.4).

#include "core/math/types.hpp"

namespace felt {

struct PolarDecomposition {
  Mat3 rotation;  ///< det = +1 always
  Mat3 stretch;   ///< symmetric; a negative eigenvalue when F reflects (an inverted element)
};

/// The decomposition polar_decomposition_svd defines, computed by Higham's scaled Newton
/// iteration X ← (ζ X + X⁻ᵀ/ζ)/2 from X = F (Higham 1986, "Computing the polar decomposition —
/// with applications", SIAM J. Sci. Stat. Comput. 7(4), eq. 3.1 with the Frobenius-norm scaling
/// of §3): 2–4 iterations of a cofactor inverse for the elements a simulation sees, several
/// times cheaper than the SVD. An F that reflects or is nearly flat (det F ≤ 10⁻⁵ ‖F‖³, about
/// σ_min < 3·10⁻⁵ σ_max) goes to the SVD, where the iteration has no proper rotation to find.
/// Stateless: the result depends on F alone, to rounding the same as the SVD's.
PolarDecomposition polar_decomposition(const Mat3& f);

/// From the singular value decomposition, so that a reflecting F gives a proper rotation (the
/// smallest singular direction is flipped into S) and a flat or collinear F (rank below 3)
/// still gives a rotation, completed arbitrarily in the directions F collapses. R is the
/// rotation that maximizes tr(Rᵀ F).
PolarDecomposition polar_decomposition_svd(const Mat3& f);

}  // namespace felt
