#include "scene/body_step_reader.hpp"

#include <limits>
#include <sstream>

#include "core/step/substeps_for.hpp"

namespace felt::scene_json {

Real read_max_step(const ObjectReader& body, Real time_step, const HealthSettings& health) {
  if (!body.has("max_step")) return std::numeric_limits<Real>::infinity();
  const Real max_step = body.ranged("max_step", 0, kMinBodyStep, kMaxBodyStep, "s");
  const std::int64_t substeps = substeps_for(time_step, max_step);
  if (substeps > health.step_budget) {
    std::ostringstream text;
    text << "would take " << substeps << " substeps of the time step " << time_step
         << " s, beyond the step budget of " << health.step_budget << " (health.step_budget)";
    fail(body.path_of("max_step"), text.str());
  }
  return max_step;
}

}  // namespace felt::scene_json
