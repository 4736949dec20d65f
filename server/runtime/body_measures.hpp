#pragma once
// What `feltd run --trace` records of a body after a step: its energies, where it is, how fast
// it moves and how far its springs or edges are from their rest lengths.

#include <span>
#include <vector>

#include "core/world/world.hpp"

namespace felt {

struct BodyMeasures {
  Real kinetic = 0;        ///< J
  Real elastic = 0;        ///< J
  Real gravitational = 0;  ///< J, −Σ m g·x: zero at the origin, so only its changes mean anything
  Vec3 centre_of_mass = Vec3::Zero();
  Vec3 lower = Vec3::Zero();  ///< the axis-aligned bounding box of the particles or nodes
  Vec3 upper = Vec3::Zero();
  Real max_speed = 0;  ///< m/s
  /// The largest relative elongation |l|/r − 1 and the largest relative shortening 1 − |l|/r
  /// (a cloth's structural and shear springs, a solid's lattice edges); 0 when none is
  /// stretched, resp. compressed. Any non-finite length makes both NaN: a max that skipped it
  /// would report a broken body as a quiet one.
  Real max_strain = 0;
  Real max_compression = 0;

  Real energy() const { return kinetic + elastic + gravitational; }
};

BodyMeasures measure_body(const ClothBody& body);
BodyMeasures measure_body(const SolidBody& body, const Vec3& gravity);

/// Kinetic, elastic and gravitational energy of every cloth and solid of `world` together, J.
Real mechanical_energy(const World& world);

/// Every cloth's particles and every solid's nodes, body by body in id order.
std::vector<std::span<const Vec3>> body_positions(const World& world);

}  // namespace felt
