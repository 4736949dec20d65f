#pragma once
// Immutable pictures of a scene, published by the physics thread after its steps and read by
// any thread (frames, haptics) without a lock held during a step.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/world/world.hpp"

namespace felt {

struct BodySnapshot {
  BodyId body_id = 0;
  std::string name;
  /// the surface clients see: a cloth's triangles, a solid's fine embedded surface or its
  /// lattice's surface; shared by every snapshot, never copied
  std::shared_ptr<const std::vector<Triangle>> surface;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  ///< per vertex
  /// a cloth's model (springs and rest lengths), shared, for the strain clients may ask for;
  /// null for a solid
  std::shared_ptr<const ClothModel> cloth;
  /// What a solid's volume change per vertex is computed from, when clients ask for it.
  struct SolidShape {
    std::shared_ptr<const TetMesh> rest;  ///< the lattice at rest, shared
    /// the fine surface the vertices lie on, shared; null when the vertices are the nodes
    std::shared_ptr<const EmbeddedSurface> embedded;
    std::vector<Vec3> nodes;  ///< the lattice's nodes now, when `embedded` (else `positions`)
  };
  std::optional<SolidShape> solid;  ///< empty for a cloth

  const std::vector<Triangle>& triangles() const { return *surface; }
};

struct SceneSnapshot {
  /// increases with every publication of the scene: a paused scene's snapshot changes without a
  /// step when a body comes or goes or a state is restored
  std::uint64_t version = 0;
  std::uint64_t step = 0;
  Real sim_time = 0;
  std::vector<BodySnapshot> bodies;

  /// The body with id `id` (looked for at `hint` first), or null.
  const BodySnapshot* find(BodyId id, std::size_t hint = 0) const;
};

/// Copies what clients see of `world` now, sharing the surfaces of `previous` (the last
/// snapshot of the same world, or null).
std::shared_ptr<SceneSnapshot> make_snapshot(const World& world,
                                             const SceneSnapshot* previous = nullptr);

}  // namespace felt
