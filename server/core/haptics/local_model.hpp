#pragma once
// A local model of the surface near a haptic proxy (Mark et al. 1996, "Adding force feedback
// to graphics systems"; Schuwerk, Xu, Freund & Steinbach, WHC 2015: an intermediate
// representation): the triangles within a radius of the proxy, with their vertices' positions,
// velocities and normals, cut from the surfaces the server renders against and sent to a
// client that renders forces against it at its device's rate (ExtrapolatedSurface), advancing
// it by the velocities until the next model comes.

#include <cstdint>
#include <vector>

#include "core/haptics/haptic_surface.hpp"
#include "core/math/types.hpp"

namespace felt {

struct LocalModelBody {
  std::uint32_t body_id = 0;
  std::uint32_t vertex_count = 0;    ///< of the body's whole surface
  std::uint32_t triangle_count = 0;  ///< of the body's whole surface
  std::vector<std::uint32_t> triangle_ids;
  std::vector<Triangle> corners;          ///< per triangle of triangle_ids: its corners' vertex ids
  std::vector<std::uint32_t> vertex_ids;  ///< the corners' vertices, each once
  std::vector<Vec3> positions;            ///< per vertex of vertex_ids
  std::vector<Vec3> velocities;           ///< m/s
  std::vector<Vec3> normals;              ///< unit
  /// N/m: how stiff the surface near the proxy is under a push (SurfaceStiffnessEstimate);
  /// 0: unknown
  Real stiffness = 0;
};

struct LocalModel {
  std::vector<LocalModelBody> bodies;
  bool truncated = false;  ///< more triangles were near than max_triangles
  /// N: the force on the device whose opposite the bodies took when the positions hold
  Vec3 push = Vec3::Zero();
};

/// The triangles of `surface` whose nearest point to `centre` is within `radius`, at most
/// `max_triangles` of them (in the bodies' order), at the surface's newer snapshot
/// (`to`), with the velocities its vertices move at from `from` to `to` over `interval`
/// seconds (zero when the interval is not positive).
LocalModel cut_local_model(const HapticSurface& surface, Real interval, const Vec3& centre,
                           Real radius, std::size_t max_triangles);

/// Whether every number of `model` is finite and every id in range: what a client accepts.
bool well_formed(const LocalModel& model);

}  // namespace felt
