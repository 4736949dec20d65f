#pragma once
// Rectangular cloth on an (i, j) particle grid (thesis 1 §3 and §8.1).

#include <cstdint>
#include <vector>

#include "core/cloth/cloth_model.hpp"
#include "core/geometry/triangle_mesh.hpp"

namespace felt {

/// A rectangle of width × height metres with nx × ny particles and the given total mass,
/// centred on `center`. In plane kXY it hangs vertically (rows go down along −y); in kXZ it lies
/// horizontally (rows go along +z).
struct GridClothSpec {
  enum class Plane : std::uint8_t { kXY, kXZ };
  Real width = 1;
  Real height = 1;
  std::uint32_t nx = 2;
  std::uint32_t ny = 2;
  Real total_mass = 1;
  Vec3 center = Vec3::Zero();
  Plane plane = Plane::kXY;
  /// applied to the laid-out grid (about the origin, after `center`), before rest lengths are
  /// measured
  Transform transform;
};

/// Builds the particles, the structural (±1), shear (diagonal) and bend (±2) springs and two
/// triangles per grid cell. Particle (i, j) has index j·nx + i; row j = 0 is the top edge.
ClothModel make_grid_cloth(const GridClothSpec& spec);

/// The pin presets of thesis 1 §8.1, as particle indices of a grid cloth.
enum class GridPinPreset : std::uint8_t { kNone, kFourCorners, kTopCorners, kTopRow };
std::vector<std::uint32_t> grid_pin_indices(const GridClothSpec& spec, GridPinPreset preset);

}  // namespace felt
