#pragma once
// What a god-object update returns: the force to render on the device and the contact it comes
// from.

#include <cstdint>

#include "core/math/types.hpp"

namespace felt {

struct HapticContact {
  bool in_contact = false;
  Vec3 force = Vec3::Zero();          ///< N, to render on the device
  Vec3 proxy = Vec3::Zero();          ///< the god-object's centre
  Vec3 contact_point = Vec3::Zero();  ///< the touched surface point (the device when free)
  Vec3 normal = Vec3::Zero();         ///< the surface normal the force is shaded along
  std::uint32_t body_id = 0;          ///< the touched body and triangle, when in contact
  std::int32_t triangle = -1;
  Vec3 barycentric = Vec3::Zero();  ///< of contact_point in the touched triangle
  int constraints = 0;    ///< active constraint planes: 0 free, 1 face, 2 crease, 3 corner
  bool slipping = false;  ///< friction state: false = sticking (or free)

  /// Whether every vector is finite: what an update returns always is.
  bool finite() const {
    return force.allFinite() && proxy.allFinite() && contact_point.allFinite() &&
           normal.allFinite() && barycentric.allFinite();
  }
};

}  // namespace felt
