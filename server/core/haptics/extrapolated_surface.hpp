#pragma once
// The surface a client renders forces against between the local models the server sends
// (local_model.hpp): each model's vertices moved on by their velocities to the time of each
// haptic tick, for at most kMaxExtrapolation. Each tick's surface runs from the previous
// tick's state to this one's, on one chain per body (SurfaceMotion), so the god-object tests
// its carried leg against that motion, including the jump to a newly arrived model; a vertex new
// in a model was where it is from the previous tick on (it does not move in from nowhere). A body
// keeps its vertex and triangle ids (the server's) in arrays of its whole surface's size:
// vertices not in the model are not finite and triangles not in it have the spare
// non-finite vertex for corners, so the god-object finds them "not there"; only the model's
// triangles are listed for its broad phase.

#include <array>
#include <memory>
#include <vector>

#include "core/collision/listed_triangle_query.hpp"
#include "core/haptics/haptic_surface.hpp"
#include "core/haptics/local_model.hpp"

namespace felt {

/// s: how far a model is moved on by its velocities (before or after its time), at most. A
/// model older than this is held where this puts it: velocities are a guess that grows worse.
inline constexpr Real kMaxExtrapolation = 0.25;
/// The largest surface a local model may describe (vertices, triangles): the arrays a client
/// allocates for it.
inline constexpr std::uint32_t kMaxLocalModelSurface = 1u << 20;

class ExtrapolatedSurface {
 public:
  /// Takes `model` (well_formed, within kMaxLocalModelSurface) as the surface at `time` (s, the
  /// caller's clock). Bodies it does not have are dropped.
  void take(const LocalModel& model, Real time);

  /// The surface at `time` (s), from where the previous call put it. Valid, with the previous
  /// call's, until the call after next: a god-object keeps the surface of its last update.
  HapticSurface advance(Real time);

  /// Whether a model was taken.
  bool has_model() const { return has_model_; }

 private:
  struct Body {
    std::uint32_t body_id = 0;
    std::vector<Triangle> triangles;    ///< the whole surface's; unlisted ones at the spare vertex
    std::vector<std::uint32_t> listed;  ///< the model's triangles
    std::vector<std::uint32_t> vertices;  ///< the model's vertices
    std::vector<Vec3> positions;          ///< per vertex of the model, at the model's time
    std::vector<Vec3> velocities;
    std::vector<Vec3> normals;              ///< the whole surface's, zero where unknown
    std::array<std::vector<Vec3>, 3> ring;  ///< the last states handed out, and the next
    std::array<std::vector<std::uint32_t>, 3> written;  ///< the vertices set in each
    std::size_t turn = 0;                               ///< ring[turn] is the latest state
    std::unique_ptr<ListedTriangleQuery> query;
    SurfaceMotion motion;
  };

  std::shared_ptr<Body> body_for(const LocalModelBody& model);

  std::vector<std::shared_ptr<Body>> bodies_;
  Real model_time_ = 0;
  std::uint64_t ticks_ = 0;
  std::uint64_t chains_ = 0;
  bool has_model_ = false;
};

}  // namespace felt
