#pragma once
// The surface a client renders forces against between the local models the server sends
// (local_model.hpp): each model's vertices moved on by their velocities to the time of each
// haptic tick, for at most kMaxExtrapolation. Each tick's surface runs from the previous
// tick's state to this one's, on one chain per body (SurfaceMotion), so the god-object tests
// its carried leg against that motion, including the blend to a newly arrived model (below); a
// vertex new in a model starts where the model has it, at the server's time, and moves on to
// its extrapolation over the blend, so a triangle moving in is seen to move. A body
// keeps its vertex and triangle ids (the server's) in arrays of its whole surface's size:
// vertices not in the model are not finite and triangles not in it have the spare
// non-finite vertex for corners, so the god-object finds them "not there"; only the model's
// triangles are listed for its broad phase.
//
// A new model does not replace the surface in one tick: the previous model's extrapolation and
// the new one differ by as much as velocities guess wrong over the time between them (a
// crumpling curtain's vertices at 2 m/s with opposite signs, 16 ms without a model while the
// server's physics thread stalls: 3 cm), and a triangle turned that far in one tick carries the
// god-object through its neighbours to the surface's far side. The difference is blended out
// over kModelBlend instead, the way networked simulations converge a dead-reckoned state on a
// newly received one: continuous at the model's arrival, the new model's own from then on.

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "core/collision/listed_triangle_query.hpp"
#include "core/haptics/haptic_surface.hpp"
#include "core/haptics/local_model.hpp"

namespace felt {

/// s: how far a model is moved on by its velocities (before or after its time), at most. A
/// model older than this is held where this puts it: velocities are a guess that grows worse.
inline constexpr Real kMaxExtrapolation = 0.25;
/// s: how long a newly taken model takes to replace the surface shown until then (above). Every
/// value from 5 to 20 ms kept the god-object on its side through the recorded crossings; a
/// longer blend shows a model's news later.
inline constexpr Real kModelBlend = 0.01;
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
    std::vector<Vec3> normals;  ///< the whole surface's, zero where unknown
    /// per vertex of the model: where the surface was shown when the blend began (a vertex new
    /// in the model: where the model has it), less where the model's extrapolation puts it then
    std::vector<Vec3> correction;
    std::array<std::vector<Vec3>, 3> ring;  ///< the last states handed out, and the next
    std::array<std::vector<std::uint32_t>, 3> written;  ///< the vertices set in each
    std::size_t turn = 0;                               ///< ring[turn] is the latest state
    std::unique_ptr<ListedTriangleQuery> query;
    SurfaceMotion motion;
  };

  std::shared_ptr<Body> body_for(const LocalModelBody& model);
  /// s: how far the model is moved on by its velocities at `time`.
  Real ahead(Real time) const;

  std::vector<std::shared_ptr<Body>> bodies_;
  Real model_time_ = 0;
  std::optional<Real> last_advance_;  ///< the time of the last advance
  std::optional<Real> blend_start_;   ///< the latest model's blend: from the advance before it
  bool blend_begins_ = false;         ///< at the next advance
  std::uint64_t ticks_ = 0;
  std::uint64_t chains_ = 0;
  bool has_model_ = false;
};

}  // namespace felt
