#include "scene/cloth_integrator_reader.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "core/cloth/cloth_stable_step.hpp"
#include "core/integrate/implicit_euler.hpp"
#include "core/integrate/projective_dynamics.hpp"
#include "core/integrate/runge_kutta_integrators.hpp"
#include "core/integrate/xpbd_integrator.hpp"

namespace felt::scene_json {

std::unique_ptr<Integrator> read_cloth_integrator(const ObjectReader& body) {
  std::string name = "symplectic_euler";
  std::string name_path = body.path_of("integrator");
  std::uint32_t substeps = XpbdIntegrator::kDefaultSubsteps;
  std::uint32_t iterations = ProjectiveDynamics::kDefaultIterations;
  Real chebyshev_rho = 0;
  Real tolerance = AdaptiveRungeKutta::kDefaultTolerance;
  Real solve_tolerance = FilteredConjugateGradient().tolerance;
  if (body.has("integrator") && body.at("integrator").is_object()) {
    const ObjectReader integrator(
        body.at("integrator"), body.path_of("integrator"),
        {"name", "substeps", "iterations", "chebyshev_rho", "tolerance", "solve_tolerance"});
    name = integrator.string("name", name);
    name_path = integrator.path_of("name");
    substeps = integrator.count("substeps", substeps, 1, XpbdIntegrator::kMaxSubsteps);
    if (integrator.has("substeps") && name != "xpbd") {
      fail(integrator.path_of("substeps"), "applies to xpbd only");
    }
    iterations = integrator.count("iterations", iterations, 1, ProjectiveDynamics::kMaxIterations);
    chebyshev_rho = integrator.ranged("chebyshev_rho", chebyshev_rho, 0,
                                      ProjectiveDynamics::kMaxChebyshevRho, "");
    for (const char* key : {"iterations", "chebyshev_rho"}) {
      if (integrator.has(key) && name != "projective_dynamics") {
        fail(integrator.path_of(key), "applies to projective_dynamics only");
      }
    }
    // below 1e-9 m the error control asks for more internal steps than any budget affords
    // (each one's error is then rounding); above 0.1 m it controls nothing a cloth shows
    tolerance = integrator.ranged("tolerance", tolerance, 1e-9, 0.1, "m");
    if (integrator.has("tolerance") && name != "adaptive_rk") {
      fail(integrator.path_of("tolerance"), "applies to adaptive_rk only");
    }
    // the conjugate gradients' residual relative to the right-hand side: below 1e-12 it is
    // rounding, above 1e-2 the step is barely implicit
    solve_tolerance = integrator.ranged("solve_tolerance", solve_tolerance, 1e-12, 1e-2, "");
    if (integrator.has("solve_tolerance") && name != "implicit_euler") {
      fail(integrator.path_of("solve_tolerance"), "applies to implicit_euler only");
    }
  } else {
    name = body.string("integrator", name);
  }
  if (name == "xpbd") return std::make_unique<XpbdIntegrator>(static_cast<int>(substeps));
  if (name == "adaptive_rk") return std::make_unique<AdaptiveRungeKutta>(tolerance);
  if (name == "implicit_euler") {
    auto euler = std::make_unique<ImplicitEuler>();
    euler->solver().tolerance = solve_tolerance;
    return euler;
  }
  if (name == "projective_dynamics") {
    return std::make_unique<ProjectiveDynamics>(static_cast<int>(iterations), chebyshev_rho);
  }
  auto integrator = make_integrator(name);
  if (!integrator) {
    std::string known;
    for (std::string_view known_name : integrator_names()) {
      known += (known.empty() ? "" : ", ") + std::string(known_name);
    }
    fail(name_path, "unknown integrator \"" + name + "\" (known: " + known + ")");
  }
  return integrator;
}

namespace {

/// Refuses a cloth whose stable `step` (s) divides the time step into more than `most` of
/// them: no step of it could be stable. `steps` names them ("substeps", "internal steps"),
/// `beyond` what bounds them.
void refuse_beyond(const ObjectReader& body, const ClothBody& cloth, Real step, Real time_step,
                   std::int64_t most, const char* steps, const std::string& beyond) {
  if (!(time_step / step > static_cast<Real>(most))) return;
  std::ostringstream text;
  text << "too stiff for " << cloth.integrator().name() << ": a stable step would be " << step
       << " s, " << std::ceil(time_step / step) << " " << steps << " of the time step, beyond "
       << beyond << "; lower the stiffness, raise the mass or choose an implicit integrator";
  fail(body.path_of("integrator"), text.str());
}

std::string step_budget(const HealthSettings& health) {
  return "the step budget of " + std::to_string(health.step_budget) + " (health.step_budget)";
}

}  // namespace

void check_stable_step(const ObjectReader& body, const ClothBody& cloth, Real time_step,
                       const HealthSettings& health) {
  if (const auto* adaptive = dynamic_cast<const AdaptiveRungeKutta*>(&cloth.integrator())) {
    // its error control picks its internal steps; the budget (and its own cap) can force
    // longer ones, beyond its stability when the cloth is stiff and light: every step then
    // grows and is stopped as unrecoverable
    const Real internal = stable_cloth_step(
        cloth, [&](const OscillatorMode& mode) { return adaptive->internal_step_limit(mode); });
    const int cap = adaptive->max_internal_steps();
    if (cap < health.step_budget) {
      refuse_beyond(body, cloth, internal, time_step, cap, "internal steps",
                    "its own cap of " + std::to_string(cap));
    } else {
      refuse_beyond(body, cloth, internal, time_step, health.step_budget, "internal steps",
                    step_budget(health));
    }
    return;
  }
  const Real limit = stable_cloth_step(cloth);
  const std::string name(cloth.integrator().name());
  if (!(limit > 0)) {
    fail(body.path_of("integrator"),
         name +
             " gains energy at every step on springs without damping: no step is stable. "
             "Give every spring kind damping (explicit_euler needs a step of at most "
             "damping/stiffness), or choose symplectic_euler, leapfrog or implicit_euler");
  }
  if (health.auto_substeps) {
    refuse_beyond(body, cloth, limit, time_step, health.step_budget, "substeps",
                  step_budget(health));
  }
}

}  // namespace felt::scene_json
