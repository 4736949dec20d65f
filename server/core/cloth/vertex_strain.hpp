#pragma once
// How stretched a cloth is at each particle, for clients to colour: the strain
// (length - rest) / rest of its structural and shear springs, averaged over the springs at the
// particle. Bend springs measure folding, not stretch, and are left out, as in
// ClothBody::max_strain.

#include <span>
#include <vector>

#include "core/cloth/cloth_model.hpp"

namespace felt {

/// One value per particle of `model` at positions `x` (0 where no such spring meets).
void vertex_strain(const ClothModel& model, std::span<const Vec3> x, std::vector<float>& out);

}  // namespace felt
