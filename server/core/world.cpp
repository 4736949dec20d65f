#include "core/world.hpp"

#include <algorithm>
#include <cmath>

namespace felt {

World::World(WorldSettings settings, SolidStepSettings solid_settings)
    : settings_(settings), solids_(solid_settings) {}

std::uint32_t World::add_body(ClothBody body) {
  body.set_gravity(settings_.gravity);
  cloths_.push_back(std::move(body));
  self_collision_.emplace_back();
  energy_valid_ = false;
  refs_.push_back({BodyRef::Kind::kCloth, static_cast<std::uint32_t>(cloths_.size() - 1)});
  cloth_ids_.push_back(static_cast<std::uint32_t>(refs_.size() - 1));
  return cloth_ids_.back();
}

std::uint32_t World::add_body(SolidBody body) {
  refs_.push_back({BodyRef::Kind::kSolid, solids_.add_body(std::move(body))});
  return static_cast<std::uint32_t>(refs_.size() - 1);
}

ClothBody* World::cloth(std::uint32_t id) {
  const BodyRef& ref = body_ref(id);
  return ref.kind == BodyRef::Kind::kCloth ? &cloths()[ref.index] : nullptr;
}

const ClothBody* World::cloth(std::uint32_t id) const {
  const BodyRef& ref = body_ref(id);
  return ref.kind == BodyRef::Kind::kCloth ? &cloths_[ref.index] : nullptr;
}

std::size_t World::surface_vertex_count(std::uint32_t id) const {
  const BodyRef& ref = body_ref(id);
  if (ref.kind == BodyRef::Kind::kCloth) return cloths_[ref.index].model().particle_count();
  const SolidBody& solid = solids_.bodies()[ref.index];
  const EmbeddedSurface* surface = solid.embedded_surface();
  return surface ? surface->vertex_count() : solid.node_count();
}

void World::add_surface_force(std::uint32_t id, std::uint32_t vertex, const Vec3& force) {
  const BodyRef& ref = body_ref(id);
  if (ref.kind == BodyRef::Kind::kCloth) {
    cloths_[ref.index].add_external_force(vertex, force);
    return;
  }
  SolidBody& solid = solids_.bodies()[ref.index];
  const EmbeddedSurface* surface = solid.embedded_surface();
  if (!surface) {
    solid.add_external_force(vertex, force);
    return;
  }
  const Tetrahedron& tet = solid.rest().tets[surface->tet[vertex]];
  for (int c = 0; c < 4; ++c) solid.add_external_force(tet[c], surface->weights[vertex][c] * force);
}

StepReport World::step() {
  StepReport report;
  step_colliders_.assign(colliders_.begin(), colliders_.end());
  step_colliders_.insert(step_colliders_.end(), moving_colliders_.begin(), moving_colliders_.end());
  moving_colliders_.clear();
  if (!energy_valid_) {
    energy_.resize(cloths_.size());
    for (std::size_t b = 0; b < cloths_.size(); ++b) {
      energy_[b] = cloths_[b].kinetic_energy() + cloths_[b].elastic_energy();
    }
  }
  for (std::size_t b = 0; b < cloths_.size(); ++b) {
    ClothBody& body = cloths_[b];
    // copy-assignment into equally sized vectors reuses their storage: no allocation
    backup_.x = body.state().x;
    backup_.v = body.state().v;
    int substeps = 1;
    bool ok = try_step(b, substeps, energy_[b]);
    for (int retry = 0; !ok && retry < settings_.max_substep_doublings; ++retry) {
      body.state().x = backup_.x;
      body.state().v = backup_.v;
      body.integrator().reset();
      substeps *= 2;
      ok = try_step(b, substeps, energy_[b]);
    }
    if (ok && substeps > 1) report.flags |= kStepRescued;
    if (!ok) {
      body.state().x = backup_.x;
      for (Vec3& v : body.state().v) v.setZero();
      body.integrator().reset();
      energy_[b] = body.elastic_energy();
      report.flags |= kStepUnrecoverable;
      report.unrecoverable_bodies.push_back(cloth_ids_[b]);
    }
    report.max_substeps = std::max(report.max_substeps, substeps);
    body.clear_external_forces();
  }
  energy_valid_ = true;
  if (!solids_.bodies().empty()) {
    const SolidStepStats& solid =
        solids_.step(settings_.time_step, settings_.gravity, step_colliders_);
    if (solid.rescued) report.flags |= kStepRescued;
    if (solid.unrecoverable) {
      // the solids step together, so all of them were rolled back
      report.flags |= kStepUnrecoverable;
      for (std::uint32_t id = 0; id < refs_.size(); ++id) {
        if (refs_[id].kind == BodyRef::Kind::kSolid) report.unrecoverable_bodies.push_back(id);
      }
    }
    report.max_substeps = std::max(report.max_substeps, solid.substeps);
  }
  ++step_count_;
  // advance by multiplication, not accumulation, so long runs keep an exact clock
  time_ = static_cast<Real>(step_count_) * settings_.time_step;
  return report;
}

bool World::try_step(std::size_t cloth, int substeps, Real& energy) {
  ClothBody& body = cloths_[cloth];
  const Real h = settings_.time_step / substeps;
  for (int s = 0; s < substeps; ++s) {
    body.integrator().step(body, body.state(), time_ + s * h, h);
    limit_stretch(body.model(), body.inv_mass(), body.params().stretch, h, body.state());
    resolve_collisions(step_colliders_, body.inv_mass(), body.params().thickness, body.state());
    if (body.params().self_collision) {
      self_collision_[cloth].resolve(body.model().triangles, body.inv_mass(),
                                     body.params().thickness, body.state());
    }
    apply_constraints(body.constraints(), body.state());
  }
  return healthy(body, energy);
}

bool World::healthy(const ClothBody& body, Real& energy) const {
  const ParticleState& state = body.state();
  const Real max_speed_sq = settings_.max_speed * settings_.max_speed;
  // work by gravity and external forces over the step, estimated from the displacement and
  // from the mean of the start and end velocities, whichever is larger: the first misses the
  // energy explicit Euler gains in a step from rest (positions have not moved yet), the second
  // misjudges a step in which substeps turned a velocity around
  Real work_by_displacement = 0;
  Real work_by_velocity = 0;
  const Real h = settings_.time_step;
  for (std::size_t p = 0; p < state.size(); ++p) {
    if (!state.x[p].allFinite()) return false;
    const Real speed_sq = state.v[p].squaredNorm();
    if (!std::isfinite(speed_sq) || speed_sq > max_speed_sq) return false;
    const Vec3 force = body.model().mass[p] * body.gravity() + body.external_forces()[p];
    work_by_displacement += force.dot(state.x[p] - backup_.x[p]);
    work_by_velocity += force.dot(0.5 * h * (state.v[p] + backup_.v[p]));
  }
  const Real work = std::max({work_by_displacement, work_by_velocity, Real{0}});
  const Real energy_after = body.kinetic_energy() + body.elastic_energy();
  const Real growth = settings_.max_energy_growth;
  // the floor keeps rounding noise of a body at rest from counting as growth
  constexpr Real kEnergyFloor = 1e-9;
  if (energy_after > growth * (energy + work) + kEnergyFloor) return false;
  energy = energy_after;
  return true;
}

}  // namespace felt
