#include "core/world/world.hpp"

#include <algorithm>
#include <utility>

#include "core/math/check.hpp"

namespace felt {

namespace {

/// The solids judge their health as the world's settings say.
SolidStepSettings with_health(SolidStepSettings solid_settings, const WorldSettings& world) {
  solid_settings.health = world.health;
  solid_settings.max_energy_growth = world.max_energy_growth;
  return solid_settings;
}

}  // namespace

World::World(WorldSettings settings, SolidStepSettings solid_settings)
    : settings_(settings),
      cloths_(ClothStepSettings{settings.max_speed, settings.max_energy_growth,
                                settings.max_substep_doublings, settings.health}),
      solids_(with_health(solid_settings, settings)) {}

namespace {

constexpr std::uint32_t kSlotBits = 16;
constexpr std::uint32_t kSlotMask = (1u << kSlotBits) - 1;
// a slot whose generation reaches this is retired, so that no id is ever reused
constexpr std::uint16_t kLastGeneration = 0xffff;

std::uint32_t slot_of(BodyId id) {
  return id.value() & kSlotMask;
}
std::uint16_t generation_of(BodyId id) {
  return static_cast<std::uint16_t>(id.value() >> kSlotBits);
}
BodyId id_of(std::uint16_t generation, std::uint32_t slot) {
  return (std::uint32_t{generation} << kSlotBits) | slot;
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
  return id_of(free->generation, static_cast<std::uint32_t>(free - slots_.begin()));
}

BodyId World::add_body(ClothBody body) {
  body.set_gravity(settings_.gravity);
  cloth_ids_.push_back(allocate({BodyRef::Kind::kCloth, cloths_.add_body(std::move(body))}));
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
      cloths_.remove_body(ref.index);
      cloth_ids_.erase(at(cloth_ids_));
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
    if (slots_[s].live) ids.push_back(id_of(slots_[s].generation, s));
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
  return ref ? &cloths_.bodies()[ref->index] : nullptr;
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

Vec3 World::surface_position(BodyId id, std::uint32_t vertex) const {
  if (const ClothBody* body = cloth(id)) return body->state().x[vertex];
  const SolidBody* solid_body = solid(id);
  FELT_CHECK(solid_body != nullptr);
  const SolidBody::SurfacePoint point = solid_body->surface_point(vertex);
  Vec3 x = Vec3::Zero();
  for (int c = 0; c < 4; ++c) {
    if (point.weights[c] != 0) x += point.weights[c] * solid_body->positions()[point.nodes[c]];
  }
  return x;
}

Real World::surface_inverse_mass(BodyId id, std::uint32_t vertex) const {
  if (const ClothBody* body = cloth(id)) return body->inv_mass()[vertex];
  const SolidBody* solid_body = solid(id);
  FELT_CHECK(solid_body != nullptr);
  const SolidBody::SurfacePoint point = solid_body->surface_point(vertex);
  Real w = 0;
  for (int c = 0; c < 4; ++c) {
    w += point.weights[c] * point.weights[c] * solid_body->inv_mass()[point.nodes[c]];
  }
  return w;
}

void World::add_surface_force(BodyId id, std::uint32_t vertex, const Vec3& force) {
  if (const BodyRef* ref = live(id, BodyRef::Kind::kCloth)) {
    cloths_.add_external_force(ref->index, vertex, force);
    return;
  }
  const BodyRef* ref = live(id, BodyRef::Kind::kSolid);
  FELT_CHECK(ref != nullptr);
  // through the system, not solid(id): a force is no edit, and keeps the health check's energy
  const SolidBody::SurfacePoint point =
      std::as_const(solids_).bodies()[ref->index].surface_point(vertex);
  for (int c = 0; c < 4; ++c) {
    if (point.weights[c] != 0)
      solids_.add_external_force(ref->index, point.nodes[c], point.weights[c] * force);
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

const StickySubsteps& World::substeps(BodyId id) const {
  const BodyRef& ref = body_ref(id);
  FELT_CHECK(ref.kind != BodyRef::Kind::kCollider);
  return ref.kind == BodyRef::Kind::kCloth ? cloths_.substeps(ref.index) : solids_.substeps();
}

const BodyStepCounts& World::step_counts(BodyId id) const {
  const BodyRef& ref = body_ref(id);
  FELT_CHECK(ref.kind != BodyRef::Kind::kCollider);
  return ref.kind == BodyRef::Kind::kCloth ? cloths_.step_counts(ref.index) : solids_.step_counts();
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
  const ClothStepStats& cloth =
      cloths_.step(time_, settings_.time_step, step_colliders_, yield_point);
  if (cloth.rescued) report.flags.set(StepFlag::kRescued);
  for (std::uint32_t index : cloth.rescued_bodies)
    report.rescued_bodies.push_back(cloth_ids_[index]);
  if (!cloth.unrecoverable.empty()) {
    report.flags.set(StepFlag::kUnrecoverable);
    for (std::uint32_t index : cloth.unrecoverable) {
      report.unrecoverable_bodies.push_back(cloth_ids_[index]);
    }
  }
  if (!cloth.over_budget.empty()) {
    report.flags.set(StepFlag::kOverBudget);
    for (std::uint32_t index : cloth.over_budget) {
      report.over_budget_bodies.push_back(cloth_ids_[index]);
    }
  }
  report.max_substeps = cloth.substeps;
  report.cloth_profile = cloth.profile;
  if (!std::as_const(solids_).bodies().empty()) {
    if (yield_point) yield_point();
    const SolidStepStats& solid =
        solids_.step(settings_.time_step, settings_.gravity, step_colliders_, yield_point);
    if (solid.rescued) {
      report.flags.set(StepFlag::kRescued);
      report.rescued_bodies.insert(report.rescued_bodies.end(), solid_ids_.begin(),
                                   solid_ids_.end());
    }
    if (solid.unrecoverable) {
      // the solids step together, so all of them were rolled back
      report.flags.set(StepFlag::kUnrecoverable);
      report.unrecoverable_bodies.insert(report.unrecoverable_bodies.end(), solid_ids_.begin(),
                                         solid_ids_.end());
    }
    if (solid.over_budget) {
      report.flags.set(StepFlag::kOverBudget);
      report.over_budget_bodies.insert(report.over_budget_bodies.end(), solid_ids_.begin(),
                                       solid_ids_.end());
    }
    report.max_substeps = std::max(report.max_substeps, solid.substeps);
    report.solid_profile = solid.profile;
  }
  ++step_count_;
  // advance by multiplication, not accumulation, so long runs keep an exact clock
  time_ = static_cast<Real>(step_count_) * settings_.time_step;
  return report;
}

}  // namespace felt
