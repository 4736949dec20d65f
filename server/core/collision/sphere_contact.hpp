#pragma once
// Contact between a sphere (a haptic proxy of finite radius) and a triangle surface.

#include <cstdint>
#include <optional>
#include <span>

#include "core/math/types.hpp"

namespace felt {

struct SphereContact {
  std::uint32_t triangle = 0;
  Vec3 point;        ///< the surface point nearest to the sphere's centre
  Vec3 barycentric;  ///< of `point` in `triangle`
  Vec3 normal;       ///< unit vector from `point` toward the centre: the direction to push out
  Real depth = 0;    ///< radius − distance, > 0
};

/// The deepest contact of a sphere with the surface, or none. Brute force over all triangles:
/// the reference the acceleration structures are checked against. A centre lying exactly on
/// the surface is pushed out along the triangle's face normal.
std::optional<SphereContact> find_sphere_contact(std::span<const Vec3> positions,
                                                 std::span<const Triangle> triangles,
                                                 const Vec3& center, Real radius);

}  // namespace felt
