#pragma once
// Long range attachments (Kim, Chentanez & Müller 2012, "Long Range Attachments — A Method to
// Simulate Inextensible Clothing in Computer Games", SCA): every free particle of a pinned cloth
// may be no farther from its nearest pin than (1 + max strain) times the rest length of the
// path between them. Each spring within its limit implies it, so the attachments never
// contradict the springs' limits; they carry a pin's hold to the far end of the cloth in one
// pass, where Gauss–Seidel over the springs needs a sweep per spring of the way.

#include <cstdint>
#include <span>
#include <vector>

#include "core/cloth/cloth_model.hpp"

namespace felt {

struct Attachment {
  std::uint32_t particle = 0;
  std::uint32_t pin = 0;  ///< the nearest pinned particle along the limited springs
  Real path_length = 0;   ///< rest length of the shortest path of limited springs to it
};

/// One attachment per free particle connected to a pin (inverse mass 0) by structural and shear
/// springs: the nearest pin by rest length along those springs (Dijkstra from every pin at
/// once). A path along springs is never shorter than the geodesic, so the bound is never
/// tighter than the springs' own.
std::vector<Attachment> long_range_attachments(const ClothModel& model,
                                               std::span<const Real> inv_mass);

}  // namespace felt
