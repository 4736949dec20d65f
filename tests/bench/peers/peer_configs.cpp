#include "peer_configs.hpp"

#include <cmath>

#include "../study_output.hpp"

namespace felt::peers {
namespace {

/// The explicit integrators' steps: h = c √(m/k), m a particle's mass, c 0.8 times the largest
/// stable step that docs/results/integrators_stable_step.csv measured on a 40 × 40 cloth of
/// the same particle mass at k = 500 N/m, divided by √(m/k) there.
struct ExplicitStep {
  const char* integrator;
  Real c;
};
constexpr ExplicitStep kExplicitSteps[] = {
    {"symplectic_euler", 0.62}, {"verlet", 0.57}, {"velocity_verlet", 0.57},
    {"leapfrog", 0.57},         {"rk4", 1.13},    {"midpoint", 0.40},
};

/// explicit Euler is only stable by the springs' damping and its step falls like 1/k, not
/// 1/√k: 0.8 times its measured limit at k = 250 (40 × 40); too slow for 100 × 100
constexpr Real kExplicitEulerStep = 7e-5;

constexpr Real kFrame = 1.0 / 240;

struct XpbdSteps {
  Real stiffness;
  int substeps;
};

/// projective_dynamics at one frame a step: plain iterations, and accelerated ones
struct PdIterations {
  int iterations;
  Real chebyshev_rho;
};
constexpr PdIterations kPdIterations[] = {{5, 0}, {10, 0}, {20, 0}, {10, 0.9}, {20, 0.95}};

void add_felt(std::vector<PeerConfig>& out, std::uint32_t n, const std::vector<Real>& stiffnesses,
              const std::vector<XpbdSteps>& xpbd, bool all_explicit) {
  const Real particle_mass = kMass / (static_cast<Real>(n) * n);
  for (const ExplicitStep& e : kExplicitSteps) {
    if (!all_explicit && std::string(e.integrator) != "symplectic_euler") continue;
    for (Real k : stiffnesses) {
      if (!all_explicit && k != stiffnesses.front()) continue;
      out.push_back({n, false, {e.integrator, k, e.c * std::sqrt(particle_mass / k)}, {}});
    }
  }
  if (all_explicit) out.push_back({n, false, {"explicit_euler", 250, kExplicitEulerStep}, {}});
  for (const char* implicit : {"implicit_euler", "imex", "desbrun", "kang", "adaptive_rk"}) {
    if (!all_explicit && std::string(implicit) == "adaptive_rk") continue;
    for (Real k : stiffnesses) out.push_back({n, false, {implicit, k, kFrame}, {}});
  }
  for (const XpbdSteps& x : xpbd) {
    out.push_back({n, false, {"xpbd", x.stiffness, kFrame, x.substeps}, {}});
  }
  for (Real k : stiffnesses) {
    for (const PdIterations& pd : kPdIterations) {
      out.push_back(
          {n, false, {"projective_dynamics", k, kFrame, 1, pd.iterations, pd.chebyshev_rho}, {}});
    }
  }
}

void add_bullet(std::vector<PeerConfig>& out, std::uint32_t n, const std::vector<int>& iterations,
                const std::vector<int>& divisions) {
  for (int it : iterations) out.push_back({n, true, {}, {kFrame, it}});
  for (int d : divisions) out.push_back({n, true, {}, {kFrame / d, 1}});
}

/// a and b merged so that each is spread evenly over the whole: the one further behind its
/// share goes next
std::vector<PeerConfig> interleave(const std::vector<PeerConfig>& a,
                                   const std::vector<PeerConfig>& b) {
  std::vector<PeerConfig> out;
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    const bool take_a =
        j == b.size() || (i < a.size() && (i + 0.5) * b.size() <= (j + 0.5) * a.size());
    out.push_back(take_a ? a[i++] : b[j++]);
  }
  return out;
}

}  // namespace

std::string PeerConfig::label() const {
  if (bullet) {
    return study::format("bullet h=%.3gms it=%d", bullet_config.step * 1e3,
                         bullet_config.iterations);
  }
  if (felt.integrator == "xpbd") {
    return study::format("xpbd k=%g h=%.3gms×%d", felt.stiffness, felt.step * 1e3, felt.substeps);
  }
  if (felt.integrator == "projective_dynamics") {
    return study::format("projective_dynamics k=%g h=%.3gms it=%d rho=%g", felt.stiffness,
                         felt.step * 1e3, felt.iterations, felt.chebyshev_rho);
  }
  return study::format("%s k=%g h=%.3gms", felt.integrator.c_str(), felt.stiffness,
                       felt.step * 1e3);
}

std::vector<PeerConfig> peer_configs(std::uint32_t n) {
  std::vector<PeerConfig> felt, bullet;
  // xpbd from 4 substeps per 1/240 s (with its constraints coloured it comes to rest with 1 to
  // 64 at k = 4000 on 40 × 40, but one pass far from converged leaves the cloth much softer
  // than its material: xpbd_integrator_test)
  if (n >= 100) {
    // each run costs about 15 times the 40 × 40 one: one configuration of every kind but the
    // explicit integrators that never lead at 40 × 40 (midpoint, rk4, the Verlets, explicit
    // Euler, adaptive_rk), one symplectic Euler, one xpbd
    add_felt(felt, n, {600, 2400, 6000}, {{600, 64}}, false);
    add_bullet(bullet, n, {1, 4, 16, 64}, {4, 16});
  } else {
    add_felt(felt, n, {250, 1000, 4000},
             {{250, 4},
              {250, 16},
              {250, 64},
              {1000, 4},
              {1000, 16},
              {1000, 64},
              {4000, 4},
              {4000, 16},
              {4000, 64}},
             n >= 40);
    add_bullet(bullet, n, {1, 2, 4, 8, 16, 32, 64}, {2, 4, 8, 16, 32});
  }
  return interleave(felt, bullet);
}

}  // namespace felt::peers
