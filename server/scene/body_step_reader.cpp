#include "scene/body_step_reader.hpp"

#include <limits>
#include <sstream>

#include "core/step/substeps_for.hpp"

namespace felt::scene_json {

Real read_max_step(const ObjectReader& body, Real time_step, const HealthSettings& health,
                   int internal_steps) {
  const bool given = body.has("max_step");
  const Real max_step = given ? body.ranged("max_step", 0, kMinBodyStep, kMaxBodyStep, "s")
                              : std::numeric_limits<Real>::infinity();
  const std::int64_t substeps = given ? substeps_for(time_step, max_step) : 1;
  if (substeps * internal_steps > health.step_budget) {
    std::ostringstream text;
    if (given) {
      text << "would take " << substeps << " substeps of the time step " << time_step << " s";
      if (internal_steps > 1) text << ", each of " << internal_steps << " internal steps,";
    } else {
      text << "takes " << internal_steps << " internal steps a step,";
    }
    text << " beyond the step budget of " << health.step_budget << " (health.step_budget)";
    fail(given ? body.path_of("max_step") : body.path_of("integrator"), text.str());
  }
  return max_step;
}

}  // namespace felt::scene_json
