#include "core/world/world.hpp"

#include <algorithm>
#include <cmath>

#include "core/math/check.hpp"

namespace felt {

World::World(WorldSettings settings, SolidStepSettings solid_settings)
    : settings_(settings), solids_(solid_settings) {}

namespace {

constexpr std::uint32_t kSlotBits = 16;
constexpr std::uint32_t kSlotMask = (1u << kSlotBits) - 1;
// a slot whose generation reaches this is retired, so that no id is ever reused
constexpr std::uint16_t kLastGeneration = 0xffff;

std::uint32_t slot_of(BodyId id) {
  return id & kSlotMask;
}
std::uint16_t generation_of(BodyId id) {
  return static_cast<std::uint16_t>(id >> kSlotBits);
}

}  // namespace

BodyId World::allocate(BodyRef ref) {
  auto free = std::find_if(slots_.begin(), slots_.end(),
                           [](const Slot& s) { return !s.live && s.issued < kLastGeneration; });
  if (free == slots_.end()) {
    FELT_CHECK(slots_.size() <= kSlotMask);
    free = slots_.insert(slots_.end(), Slot{});
  } else {
    // every free slot held a body before: the new one is the next generation
    free->generation = ++free->issued;
  }
  free->live = true;
  free->ref = ref;
  ++live_;
  return (BodyId{free->generation} << kSlotBits) | static_cast<BodyId>(free - slots_.begin());
}

BodyId World::add_body(ClothBody body) {
  body.set_gravity(settings_.gravity);
  cloths_.push_back(std::move(body));
  self_collision_.emplace_back();
  energy_valid_ = false;
  cloth_ids_.push_back(
      allocate({BodyRef::Kind::kCloth, static_cast<std::uint32_t>(cloths_.size() - 1)}));
  return cloth_ids_.back();
}

BodyId World::add_body(SolidBody body) {
  solid_ids_.push_back(allocate({BodyRef::Kind::kSolid, solids_.add_body(std::move(body))}));
  return solid_ids_.back();
}

BodyId World::add_collider(const Collider& collider) {
  colliders_.push_back(collider);
  collider_ids_.push_back(
      allocate({BodyRef::Kind::kCollider, static_cast<std::uint32_t>(colliders_.size() - 1)}));
  return collider_ids_.back();
}

void World::shift_indices(BodyRef::Kind kind, std::uint32_t index) {
  for (Slot& slot : slots_) {
    if (slot.live && slot.ref.kind == kind && slot.ref.index > index) --slot.ref.index;
  }
}

void World::remove_body(BodyId id) {
  const BodyRef ref = body_ref(id);
  const auto at = [&](auto& v) { return v.begin() + ref.index; };
  switch (ref.kind) {
    case BodyRef::Kind::kCloth:
      cloths_.erase(at(cloths_));
      self_collision_.erase(at(self_collision_));
      cloth_ids_.erase(at(cloth_ids_));
      energy_valid_ = false;
      break;
    case BodyRef::Kind::kSolid:
      solids_.remove_body(ref.index);
      solid_ids_.erase(at(solid_ids_));
      break;
    case BodyRef::Kind::kCollider:
      colliders_.erase(at(colliders_));
      collider_ids_.erase(at(collider_ids_));
      break;
  }
  shift_indices(ref.kind, ref.index);
  slots_[slot_of(id)].live = false;
  --live_;
}

void World::continue_ids_from(const World& previous) {
  for (std::size_t s = 0; s < previous.slots_.size(); ++s) {
    if (s == slots_.size()) slots_.push_back(Slot{previous.slots_[s].generation, 0, false, {}});
    slots_[s].issued = std::max(slots_[s].issued, previous.slots_[s].issued);
  }
}

bool World::contains(BodyId id) const {
  const std::uint32_t slot = slot_of(id);
  return slot < slots_.size() && slots_[slot].live && slots_[slot].generation == generation_of(id);
}

std::vector<BodyId> World::body_ids() const {
  std::vector<BodyId> ids;
  ids.reserve(live_);
  for (std::uint32_t s = 0; s < slots_.size(); ++s) {
    if (slots_[s].live) ids.push_back((BodyId{slots_[s].generation} << kSlotBits) | s);
  }
  return ids;
}

const BodyRef& World::body_ref(BodyId id) const {
  FELT_CHECK(contains(id));
  return slots_[slot_of(id)].ref;
}

const BodyRef* World::live(BodyId id, BodyRef::Kind kind) const {
  return contains(id) && body_ref(id).kind == kind ? &body_ref(id) : nullptr;
}

ClothBody* World::cloth(BodyId id) {
  const BodyRef* ref = live(id, BodyRef::Kind::kCloth);
  return ref ? &cloths()[ref->index] : nullptr;
}

const ClothBody* World::cloth(BodyId id) const {
  const BodyRef* ref = live(id, BodyRef::Kind::kCloth);
  return ref ? &cloths_[ref->index] : nullptr;
}

SolidBody* World::solid(BodyId id) {
  const BodyRef* ref = live(id, BodyRef::Kind::kSolid);
  return ref ? &solids_.bodies()[ref->index] : nullptr;
}

const SolidBody* World::solid(BodyId id) const {
  const BodyRef* ref = live(id, BodyRef::Kind::kSolid);
  return ref ? &solids_.bodies()[ref->index] : nullptr;
}

std::size_t World::surface_vertex_count(BodyId id) const {
  if (const ClothBody* body = cloth(id)) return body->surface_vertex_count();
  const SolidBody* solid_body = solid(id);
  return solid_body ? solid_body->surface_vertex_count() : 0;
}

void World::add_surface_force(BodyId id, std::uint32_t vertex, const Vec3& force) {
  // straight to the body: an external force does not change the energies the health check
  // carries over, so it must not make the next step recompute them (as cloths() would)
  if (const BodyRef* ref = live(id, BodyRef::Kind::kCloth)) {
    cloths_[ref->index].add_external_force(vertex, force);
    return;
  }
  SolidBody* solid_body = solid(id);
  FELT_CHECK(solid_body != nullptr);
  const SolidBody::SurfacePoint point = solid_body->surface_point(vertex);
  for (int c = 0; c < 4; ++c) {
    if (point.weights[c] != 0)
      solid_body->add_external_force(point.nodes[c], point.weights[c] * force);
  }
}

void World::set_surface_anchor(BodyId id, std::uint32_t vertex, const Vec3& target, Real stiffness,
                               Real damping) {
  if (ClothBody* cloth_body = cloth(id)) {
    cloth_body->set_anchor({vertex, target, stiffness, damping});
    return;
  }
  SolidBody* solid_body = solid(id);
  FELT_CHECK(solid_body != nullptr);
  solid_body->set_anchor({vertex, solid_body->surface_point(vertex), target, stiffness, damping});
}

void World::remove_surface_anchor(BodyId id, std::uint32_t vertex) {
  if (ClothBody* cloth_body = cloth(id)) {
    cloth_body->remove_anchor(vertex);
  } else if (SolidBody* solid_body = solid(id)) {
    solid_body->remove_anchor(vertex);
  }
}

void World::set_step_count(std::uint64_t steps) {
  step_count_ = steps;
  time_ = static_cast<Real>(step_count_) * settings_.time_step;
}

StepReport World::step(const std::function<void()>& yield_point) {
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
    bool ok = try_step(b, substeps, energy_[b], yield_point);
    for (int retry = 0; !ok && retry < settings_.max_substep_doublings; ++retry) {
      body.state().x = backup_.x;
      body.state().v = backup_.v;
      body.integrator().reset();
      substeps *= 2;
      ok = try_step(b, substeps, energy_[b], yield_point);
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
    if (yield_point) yield_point();
    const SolidStepStats& solid =
        solids_.step(settings_.time_step, settings_.gravity, step_colliders_, yield_point);
    if (solid.rescued) report.flags |= kStepRescued;
    if (solid.unrecoverable) {
      // the solids step together, so all of them were rolled back
      report.flags |= kStepUnrecoverable;
      report.unrecoverable_bodies.insert(report.unrecoverable_bodies.end(), solid_ids_.begin(),
                                         solid_ids_.end());
    }
    report.max_substeps = std::max(report.max_substeps, solid.substeps);
  }
  ++step_count_;
  // advance by multiplication, not accumulation, so long runs keep an exact clock
  time_ = static_cast<Real>(step_count_) * settings_.time_step;
  return report;
}

bool World::try_step(std::size_t cloth, int substeps, Real& energy,
                     const std::function<void()>& yield_point) {
  ClothBody& body = cloths_[cloth];
  const Real h = settings_.time_step / substeps;
  for (int s = 0; s < substeps; ++s) {
    body.integrator().step(body, body.state(), time_ + s * h, h);
    if (yield_point) yield_point();
    limit_stretch(body.model(), body.inv_mass(), body.params().stretch, h, body.state());
    resolve_collisions(step_colliders_, body.inv_mass(), body.params().thickness, body.state());
    if (body.params().self_collision) {
      self_collision_[cloth].resolve(body.model().triangles, body.inv_mass(),
                                     body.params().thickness, body.state());
    }
    apply_constraints(body.constraints(), body.state());
    if (yield_point) yield_point();
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
