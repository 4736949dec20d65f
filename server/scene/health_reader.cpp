#include "scene/health_reader.hpp"

namespace felt::scene_json {

void read_health(const ObjectReader& health, WorldSettings& settings) {
  HealthSettings& h = settings.health;
  h.enabled = health.boolean("enabled", h.enabled);
  if (!health.boolean("energy_check", true)) {
    h.energy_tolerance = std::numeric_limits<Real>::infinity();
  } else {
    h.energy_tolerance = health.ranged("energy_tolerance", h.energy_tolerance, 1e-3, 1e3);
  }
  h.energy_window = health.ranged("energy_window", h.energy_window, 1e-3, 1e3, "s");
  settings.max_energy_growth =
      health.ranged("max_energy_growth", settings.max_energy_growth, 1.01, 1e6);
  h.speed_growth = health.ranged("speed_growth", h.speed_growth, 1.1, 1e6);
  settings.max_substep_doublings = static_cast<int>(
      health.count("max_substep_doublings", settings.max_substep_doublings, 0, 10));
  h.relax_after = health.ranged("relax_after", h.relax_after, 0, 1e6, "s");
  h.auto_substeps = health.boolean("auto_substeps", h.auto_substeps);
  h.step_budget = static_cast<int>(health.count("step_budget", h.step_budget, 1, kMaxStepBudget));
}

}  // namespace felt::scene_json
