#pragma once
// What the scene targets check of a scene the loader accepted: it stays within a client's
// particle budget and, stepped, leaves nothing non-finite in its bodies.

#include <cmath>
#include <cstddef>

#include "fuzz_target.hpp"
#include "scene/scene_loader.hpp"

namespace felt::fuzz {

/// What the server allows a client's scene (ServerOptions::max_particles_per_scene).
inline constexpr std::size_t kClientParticleBudget = 250'000;
/// Scenes up to this size are stepped: bigger ones would slow every run to a crawl for no
/// coverage a smaller one does not give.
inline constexpr std::size_t kSteppedParticles = 20'000;

/// The options the server loads a client's scene with, meshes from scenes/.
inline SceneLoadOptions client_load_options() {
  SceneLoadOptions options;
  options.max_particles = kClientParticleBudget;
  options.asset_root = FELT_SCENE_DIR;
  return options;
}

inline bool all_finite(const std::vector<Vec3>& points) {
  for (const Vec3& p : points) {
    if (!p.allFinite()) return false;
  }
  return true;
}

inline void check_loaded_scene(Scene& scene) {
  std::size_t particles = 0;
  for (const ClothBody& cloth : scene.world.cloths()) particles += cloth.state().size();
  for (const SolidBody& solid : scene.world.solids().bodies())
    particles += solid.positions().size();
  check(particles <= kClientParticleBudget, "a loaded scene keeps to the particle budget");
  if (particles > kSteppedParticles) return;
  for (int step = 0; step < 3; ++step) scene.world.step();
  for (const ClothBody& cloth : scene.world.cloths()) {
    check(all_finite(cloth.state().x), "a cloth's positions stay finite");
  }
  for (const SolidBody& solid : scene.world.solids().bodies()) {
    check(all_finite(solid.positions()), "a solid's positions stay finite");
  }
}

}  // namespace felt::fuzz
