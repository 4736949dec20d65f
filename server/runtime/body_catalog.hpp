#pragma once
// A scene's bodies as requests see them: ids, kinds, sizes and who added each. Published by the
// physics thread whenever bodies come or go, read by any thread, like the snapshots.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/world/world.hpp"
#include "runtime/client_id.hpp"

namespace felt {

/// What a client is told about a body.
struct BodyInfo {
  BodyId body_id = 0;
  std::string name;
  std::string kind;             ///< "cloth", "solid" or "collider"
  std::uint32_t particles = 0;  ///< vertices clients see
  std::uint32_t triangles = 0;
  std::uint32_t nodes = 0;  ///< what pins and states index: a cloth's particles, a solid's nodes
  ClientId owner = 0;       ///< the client that added it (the scene's loader for its own bodies)
  std::optional<SolidModel> solid_model;  ///< a solid's model (which integrators apply)
  std::optional<Collider> collider;       ///< a collider's shape and place
};

struct BodyCatalog {
  std::vector<BodyInfo> bodies;  ///< in body-id slot order

  /// The body with id `id`, or null.
  const BodyInfo* find(BodyId id) const;
  /// Particles over every body.
  std::uint64_t particles() const;
};

/// The catalog entry of live body `id` of `world`.
BodyInfo describe_body(const World& world, BodyId id, ClientId owner);

}  // namespace felt
