#pragma once
// Immutable pictures of a scene, published by the physics thread after its steps and read by
// any thread (frames, haptics) without a lock held during a step.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/math/point_compliance.hpp"
#include "core/world/world.hpp"
#include "runtime/compliance_worker.hpp"

namespace felt {

struct BodySnapshot {
  BodyId body_id = 0;
  std::string name;
  /// the surface clients see: a cloth's triangles, a solid's fine embedded surface or its
  /// lattice's surface; shared by every snapshot, never copied
  std::shared_ptr<const std::vector<Triangle>> surface;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  ///< per vertex; empty when left out (VertexNormals)
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
  /// How stiff the body is at its points (point_compliance; over its nodes: a cloth's particles,
  /// a solid's lattice nodes): at rest (`compliance`) and under a push held for
  /// kComplianceHorizon (`prompt_compliance`), found from its state at simulated time
  /// `compliance_time` and
  /// shared by the snapshots after it until found again (kComplianceRefresh); unknown in a
  /// snapshot made without it (make_snapshot).
  PointCompliance compliance;
  PointCompliance prompt_compliance;
  std::optional<Real> compliance_time;

  /// Adds to `load` the nodes that carry surface vertex `vertex` with `weight` (a solid's fine
  /// vertex: its tetrahedron's nodes by its barycentric coordinates).
  void add_load(std::uint32_t vertex, Real weight, std::vector<WeightedNode>& load) const;

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

/// Simulated seconds a body's point compliance is kept before it is found again: a cloth's
/// stiffness across itself is its tension's, which changes with its shape (a swing, a push), and
/// any body's with its constants, its pins and what it rests on; two sparse factorizations per
/// body this often.
inline constexpr Real kComplianceRefresh = 0.05;

/// Whether a snapshot carries its bodies' vertex normals: haptic rendering reads them; a frame
/// that asks for them finds them itself when they are left out (frame_stream.cpp), on the frame
/// encoder's thread instead of the physics thread (a fifth of a bare step of the 100 × 100 cloth).
enum class VertexNormals : bool { kLeftOut, kComputed };

/// Copies what clients see of `world` now, sharing the surfaces of `previous` (the last
/// snapshot of the same world, or null), with or without `normals`; with a `compliance` worker
/// also each body's point compliance for local models (shared from `previous` while recent,
/// else the latest the worker found, asking it for a new one); without, every body's is unknown.
std::shared_ptr<SceneSnapshot> make_snapshot(const World& world,
                                             const SceneSnapshot* previous = nullptr,
                                             ComplianceWorker* compliance = nullptr,
                                             VertexNormals normals = VertexNormals::kComputed);

}  // namespace felt
