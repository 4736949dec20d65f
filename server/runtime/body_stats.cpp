#include "runtime/body_stats.hpp"

#include <cmath>

namespace felt {
namespace {

/// A body's own max_step as GetStats tells it: 0 for none.
Real own_step(Real max_step) {
  return std::isfinite(max_step) ? max_step : 0;
}

}  // namespace

std::vector<BodyStats> body_stats(const World& world) {
  std::vector<BodyStats> out;
  for (BodyId id : world.body_ids()) {
    const BodyRef& ref = world.body_ref(id);
    if (ref.kind == BodyRef::Kind::kCloth) {
      const ClothBody& cloth = world.cloths()[ref.index];
      out.push_back({id, "cloth", std::string(cloth.integrator().name()), cloth.max_strain(), 1,
                     cloth.kinetic_energy(), world.step_counts(id).substeps,
                     world.substeps(id).rescued_steps(), cloth.max_compression(),
                     world.step_counts(id).over_budget_steps, own_step(cloth.max_step())});
    } else if (ref.kind == BodyRef::Kind::kSolid) {
      const SolidBody& solid = world.solids().bodies()[ref.index];
      const Integrator* integrator = solid.integrator();
      const std::string update = solid.material().model == SolidModel::kShapeMatching
                                     ? "shape_matching"
                                     : std::string(kTimeCorrectedVerlet);
      out.push_back({id, "solid", integrator ? std::string(integrator->name()) : update, 0,
                     solid.volume() / solid.rest_volume(), solid.kinetic_energy(),
                     world.step_counts(id).substeps, world.substeps(id).rescued_steps(), 0,
                     world.step_counts(id).over_budget_steps, own_step(solid.max_step())});
    }
  }
  return out;
}

}  // namespace felt
