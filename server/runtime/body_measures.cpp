#include "runtime/body_measures.hpp"

#include <cmath>
#include <limits>
#include <span>

namespace felt {
namespace {

constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();

/// Folds one edge's length l over rest length r into the largest strain and compression.
void add_edge(Real length, Real rest_length, BodyMeasures& out) {
  const Real ratio = length / rest_length;
  if (!std::isfinite(ratio)) {
    out.max_strain = out.max_compression = kNaN;
    return;
  }
  // once NaN, stays NaN: every comparison with it is false
  if (ratio - 1 > out.max_strain) out.max_strain = ratio - 1;
  if (1 - ratio > out.max_compression) out.max_compression = 1 - ratio;
}

/// Centre of mass, bounding box and largest speed of points with masses `mass(i)`.
template <typename Mass>
void add_motion(std::span<const Vec3> x, std::span<const Vec3> v, Mass mass, BodyMeasures& out) {
  if (x.empty()) return;
  out.lower = out.upper = x[0];
  Vec3 moment = Vec3::Zero();
  Real total = 0;
  bool finite = true;
  for (std::size_t i = 0; i < x.size(); ++i) {
    moment += mass(i) * x[i];
    total += mass(i);
    out.lower = out.lower.cwiseMin(x[i]);
    out.upper = out.upper.cwiseMax(x[i]);
    finite = finite && x[i].allFinite();
    const Real speed = v[i].norm();
    if (!(speed <= out.max_speed)) out.max_speed = speed;  // NaN wins
  }
  out.centre_of_mass = moment / total;
  // cwiseMin and cwiseMax may drop a NaN coordinate
  if (!finite) out.lower = out.upper = Vec3::Constant(kNaN);
}

}  // namespace

BodyMeasures measure_body(const ClothBody& body) {
  BodyMeasures out;
  out.kinetic = body.kinetic_energy();
  out.elastic = body.elastic_energy();
  out.gravitational = body.gravitational_energy();
  const ClothModel& model = body.model();
  add_motion(
      body.state().x, body.state().v, [&](std::size_t p) { return model.mass[p]; }, out);
  for (const Spring& s : model.springs) {
    if (is_limited(s))
      add_edge((body.state().x[s.i] - body.state().x[s.j]).norm(), s.rest_length, out);
  }
  return out;
}

BodyMeasures measure_body(const SolidBody& body, const Vec3& gravity) {
  BodyMeasures out;
  out.kinetic = body.kinetic_energy();
  out.elastic = body.elastic_energy();
  out.gravitational = body.gravitational_energy(gravity);
  const std::vector<Vec3>& x = body.positions();
  add_motion(
      x, body.velocities(), [&](std::size_t n) { return body.mass(static_cast<std::uint32_t>(n)); },
      out);
  const std::vector<Vec3>& rest = body.rest().nodes;
  for (const Edge& e : body.topology().edges) {
    add_edge((x[e[0]] - x[e[1]]).norm(), (rest[e[0]] - rest[e[1]]).norm(), out);
  }
  return out;
}

Real mechanical_energy(const World& world) {
  Real energy = 0;
  for (const ClothBody& body : world.cloths()) {
    energy += body.kinetic_energy() + body.elastic_energy() + body.gravitational_energy();
  }
  for (const SolidBody& body : world.solids().bodies()) {
    energy += body.kinetic_energy() + body.elastic_energy() +
              body.gravitational_energy(world.settings().gravity);
  }
  return energy;
}

std::vector<std::span<const Vec3>> body_positions(const World& world) {
  std::vector<std::span<const Vec3>> out;
  for (BodyId id : world.body_ids()) {
    if (const ClothBody* cloth = world.cloth(id)) out.emplace_back(cloth->state().x);
    if (const SolidBody* solid = world.solid(id)) out.emplace_back(solid->positions());
  }
  return out;
}

}  // namespace felt
