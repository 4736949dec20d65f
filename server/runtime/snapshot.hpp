#pragma once
// Immutable pictures of a scene, published by the physics thread after its steps and read by
// any thread (frames, haptics) without a lock held during a step.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/cloth_model.hpp"
#include "core/world.hpp"

namespace felt {

struct BodySnapshot {
  std::uint32_t body_id = 0;
  std::string name;
  std::shared_ptr<const ClothModel> model;  ///< triangles and uv; shared, never copied
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  ///< per vertex

  const std::vector<Triangle>& triangles() const { return model->triangles; }
};

struct SceneSnapshot {
  std::uint64_t step = 0;
  Real sim_time = 0;
  std::vector<BodySnapshot> bodies;
};

/// Copies what clients see of `world` now.
std::shared_ptr<const SceneSnapshot> make_snapshot(const World& world);

}  // namespace felt
