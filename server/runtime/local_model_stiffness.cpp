#include "runtime/local_model_stiffness.hpp"

#include <algorithm>
#include <limits>
#include <vector>

namespace felt {
namespace {

/// The point of the body a stiffness is asked at: the nodes carrying it and the direction.
struct LoadedPoint {
  std::vector<WeightedNode> load;
  Vec3 direction = Vec3::Zero();
};

/// The touched point: triangle `triangle` at `barycentric`, along the normal interpolated there.
LoadedPoint touched_point(const BodySnapshot& body, std::int32_t triangle,
                          const Vec3& barycentric) {
  LoadedPoint point;
  if (triangle < 0 || static_cast<std::size_t>(triangle) >= body.triangles().size()) return point;
  const Triangle& corners = body.triangles()[static_cast<std::size_t>(triangle)];
  for (int i = 0; i < 3; ++i) {
    if (corners[i] >= body.normals.size()) return {};
    body.add_load(corners[i], barycentric[i], point.load);
    point.direction += barycentric[i] * body.normals[corners[i]];
  }
  return point;
}

/// The vertex of `cut` nearest `centre`, along its normal.
LoadedPoint nearest_point(const BodySnapshot& body, const LocalModelBody& cut, const Vec3& centre) {
  LoadedPoint point;
  Real nearest = std::numeric_limits<Real>::infinity();
  for (std::size_t i = 0; i < cut.vertex_ids.size(); ++i) {
    const Real distance = (cut.positions[i] - centre).squaredNorm();
    if (distance < nearest) {
      nearest = distance;
      point.direction = cut.normals[i];
      point.load.clear();
      body.add_load(cut.vertex_ids[i], 1, point.load);
    }
  }
  return point;
}

}  // namespace

std::optional<Real> own_stiffness(const BodySnapshot& body, const LocalModelBody& cut,
                                  const Vec3& centre, const LocalContact* touched) {
  if (!body.prompt_compliance.known()) return std::nullopt;
  const LoadedPoint point = touched && touched->in_contact && touched->body_id == cut.body_id
                                ? touched_point(body, touched->triangle, touched->barycentric)
                                : nearest_point(body, cut, centre);
  if (!(point.direction.norm() > 0)) return std::nullopt;
  const Vec3 n = point.direction.normalized();
  const Real at_rest = body.compliance.stiffness(point.load, n);
  const Real prompt = body.prompt_compliance.stiffness(point.load, n);
  if (!(prompt > 0)) return std::nullopt;  // a point on no free node
  // a point that a push held for the horizon moves by less than half its static give (or that
  // has no static stiffness: nothing holds its body) answers it by its inertia: no spring
  // stands for that
  return prompt <= kInertialRatio * at_rest ? at_rest : 0;
}

void set_local_model_stiffness(LocalModel& model, const SceneSnapshot& snapshot, const Vec3& centre,
                               const LocalContact* touched, std::uint32_t estimated,
                               Real estimate) {
  for (LocalModelBody& cut : model.bodies) {
    const BodySnapshot* body = snapshot.find(cut.body_id);
    const std::optional<Real> own =
        body ? own_stiffness(*body, cut, centre, touched) : std::nullopt;
    const Real fitted = cut.body_id == estimated ? estimate : 0;
    if (!own) {
      cut.stiffness = fitted;
    } else if (*own == 0) {
      cut.stiffness = 0;  // inertial: the fit to its swing is no spring either
    } else {
      cut.stiffness = std::max(*own, fitted);
    }
  }
}

}  // namespace felt
