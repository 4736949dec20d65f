#include "core/world/state_hash.hpp"

#include <cstring>

namespace felt {
namespace {

constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;

void mix(std::uint64_t& hash, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * kFnvPrime;
}

void mix(std::uint64_t& hash, const std::vector<Vec3>& values) {
  for (const Vec3& v : values) mix(hash, v.data(), 3 * sizeof(Real));
}

}  // namespace

std::uint64_t state_hash(const World& world) {
  std::uint64_t hash = kFnvOffset;
  const std::uint64_t steps = world.step_count();
  mix(hash, &steps, sizeof steps);
  for (const ClothBody& body : world.cloths()) {
    mix(hash, body.state().x);
    mix(hash, body.state().v);
  }
  for (const SolidBody& body : world.solids().bodies()) {
    mix(hash, body.positions());
    mix(hash, body.previous_positions());
    mix(hash, body.velocities());
  }
  return hash;
}

}  // namespace felt
