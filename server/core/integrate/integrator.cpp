#include "core/integrate/integrator.hpp"

#include <array>

#include "core/integrate/approximate_implicit_integrators.hpp"
#include "core/integrate/explicit_integrators.hpp"
#include "core/integrate/imex_integrator.hpp"
#include "core/integrate/implicit_euler.hpp"
#include "core/integrate/projective_dynamics.hpp"
#include "core/integrate/runge_kutta_integrators.hpp"
#include "core/integrate/verlet_integrators.hpp"
#include "core/integrate/xpbd_integrator.hpp"

namespace felt {
namespace {

struct Entry {
  std::string_view name;
  std::unique_ptr<Integrator> (*make)();
  IntegratorNeeds needs = IntegratorNeeds::kForces;
};

template <typename T>
std::unique_ptr<Integrator> make_one() {
  return std::make_unique<T>();
}

constexpr std::array kIntegrators{
    Entry{"explicit_euler", &make_one<ExplicitEuler>},
    Entry{"symplectic_euler", &make_one<SymplecticEuler>},
    Entry{"midpoint", &make_one<Midpoint>},
    Entry{"rk4", &make_one<RungeKutta4>},
    Entry{"adaptive_rk", &make_one<AdaptiveRungeKutta>},
    Entry{"verlet", &make_one<PositionVerlet>},
    Entry{"velocity_verlet", &make_one<VelocityVerlet>},
    Entry{"leapfrog", &make_one<Leapfrog>},
    Entry{"implicit_euler", &make_one<ImplicitEuler>, IntegratorNeeds::kJacobian},
    Entry{"imex", &make_one<ImexIntegrator>, IntegratorNeeds::kLinearPairs},
    Entry{"desbrun", &make_one<DesbrunIntegrator>, IntegratorNeeds::kLinearPairs},
    Entry{"kang", &make_one<KangIntegrator>, IntegratorNeeds::kLinearPairs},
    Entry{"xpbd", &make_one<XpbdIntegrator>, IntegratorNeeds::kDistanceConstraints},
    Entry{"projective_dynamics", &make_one<ProjectiveDynamics>,
          IntegratorNeeds::kDistanceConstraints},
};

}  // namespace

std::unique_ptr<Integrator> make_integrator(std::string_view name) {
  for (const Entry& entry : kIntegrators) {
    if (entry.name == name) return entry.make();
  }
  return nullptr;
}

std::vector<std::string_view> integrator_names() {
  std::vector<std::string_view> names;
  for (const Entry& entry : kIntegrators) names.push_back(entry.name);
  return names;
}

std::optional<IntegratorNeeds> integrator_needs(std::string_view name) {
  for (const Entry& entry : kIntegrators) {
    if (entry.name == name) return entry.needs;
  }
  return std::nullopt;
}

}  // namespace felt
