#pragma once

#include <vector>

#include "core/math/types.hpp"

namespace felt {

/// A plain indexed triangle mesh, as read from a file, before it becomes a body.
struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Vec2> uv;  ///< one per position, or empty
  std::vector<Triangle> triangles;
};

/// Rotation (degrees about x, then y, then z), then scale, then translation: the order of the
/// second thesis's scene files.
struct Transform {
  Vec3 rotate_degrees = Vec3::Zero();
  Vec3 scale = Vec3::Ones();
  Vec3 translate = Vec3::Zero();

  Vec3 apply(const Vec3& p) const;
};

}  // namespace felt
