// IMEX (Eberhardt et al. 2000, thesis 1 §4.4) against the analytic spring oscillator and
// circular orbit, a cloth too stiff for explicit schemes, and backward Euler.

#include "core/integrate/imex_integrator.hpp"

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "core/cloth/cloth_body.hpp"
#include "core/cloth/cloth_fixtures.hpp"
#include "core/cloth/cloth_grid.hpp"
#include "core/integrate/implicit_euler.hpp"
#include "core/integrate/oscillator.hpp"
#include "core/world/world.hpp"

namespace felt::test {
namespace {

ClothBody spring_pair(Real mass, Real stiffness, Real rest, Real damping = 0) {
  return test::spring_pair(mass, stiffness, rest, damping, "imex");
}

ImexIntegrator& imex_of(ClothBody& body) {
  return dynamic_cast<ImexIntegrator&>(body.integrator());
}

/// Largest error of (x, v/ω) over one period of the spring oscillator m ẍ + c ẋ + k (x − r) = 0
/// from x = r + a, v = 0 (ω = 2π, ζ = c/(2mω)), stepped with h.
Real oscillator_error(Real h, Real rest, Real amplitude, Real zeta) {
  ClothBody body = spring_pair(kMass, kStiffness, rest, 2 * zeta * kMass * kOmega);
  body.state().x[1].x() = rest + amplitude;
  ImexIntegrator imex;
  Real worst = 0;
  const long steps = std::lround(1 / h);
  for (long n = 0; n < steps; ++n) {
    imex.step(body, body.state(), n * h, h);
    const Exact exact = exact_oscillator((n + 1) * h, zeta);
    const Vec3 x = body.state().x[1], v = body.state().v[1];
    EXPECT_EQ(x.y(), 0);  // nothing pushes it off the axis
    worst = std::max(worst, std::hypot(x.x() - rest - amplitude * exact.x,
                                       (v.x() - amplitude * exact.v) / kOmega));
  }
  return worst / amplitude;
}

Real oscillator_order(Real rest, Real amplitude, Real zeta) {
  const Real e1 = oscillator_error(1e-3, rest, amplitude, zeta);
  const Real e2 = oscillator_error(5e-4, rest, amplitude, zeta);
  const Real e4 = oscillator_error(2.5e-4, rest, amplitude, zeta);
  std::printf("  rest %g, ζ %g: errors %.3e %.3e %.3e\n", rest, zeta, e1, e2, e4);
  return 0.5 * (std::log2(e1 / e2) + std::log2(e2 / e4));
}

TEST(Imex, LinearOscillatorConvergesWithOrderOne) {
  // rest length 0: f = −k x − c v exactly, all of it implicit (a linearly implicit scheme)
  EXPECT_NEAR(oscillator_order(0, 1, 0), 1.0, 0.05);
  EXPECT_NEAR(oscillator_order(0, 1, 0.1), 1.0, 0.05);
}

TEST(Imex, StretchedSpringWithExplicitRestLengthTermConvergesWithOrderOne) {
  // −k (x − r) = −k x (implicit) + k r (explicit); amplitude ½ r keeps the spring from
  // collapsing, where its direction and so the force would flip. Along a line k r is constant,
  // so the errors match the rest-length-0 case; the whirling spring below turns it.
  EXPECT_NEAR(oscillator_order(1, 0.5, 0), 1.0, 0.05);
}

/// Largest error over one revolution of a particle whirling on a spring (rest r, length R)
/// around a pin: uniform circular motion with m Ω² R = k (R − r). The explicit part k r l̂
/// turns with the spring, so it is not constant as on the 1-D spring.
Real orbit_error(Real h) {
  const Real radius = 2, rest = 1, omega = 2 * M_PI;
  ClothBody body = spring_pair(1, omega * omega * radius / (radius - rest), rest);
  body.state().x[1] = Vec3(radius, 0, 0);
  body.state().v[1] = Vec3(0, omega * radius, 0);
  ImexIntegrator imex;
  Real worst = 0;
  const long steps = std::lround(1 / h);
  for (long n = 0; n < steps; ++n) {
    imex.step(body, body.state(), n * h, h);
    const Real angle = omega * (n + 1) * h;
    const Vec3 x = radius * Vec3(std::cos(angle), std::sin(angle), 0);
    const Vec3 v = omega * radius * Vec3(-std::sin(angle), std::cos(angle), 0);
    worst = std::max(
        worst, std::hypot((body.state().x[1] - x).norm(), (body.state().v[1] - v).norm() / omega));
  }
  return worst / radius;
}

TEST(Imex, WhirlingSpringConvergesWithOrderOne) {
  const Real e1 = orbit_error(1e-3), e2 = orbit_error(5e-4), e4 = orbit_error(2.5e-4);
  std::printf("  orbit: errors %.3e %.3e %.3e\n", e1, e2, e4);
  EXPECT_NEAR(0.5 * (std::log2(e1 / e2) + std::log2(e2 / e4)), 1.0, 0.05);
}

TEST(Imex, LinearSpringIsBackwardEulerAndStableAtAnyStep) {
  // with rest length 0, eq. 4.25 is backward Euler, which divides the oscillator's energy by
  // 1 + (ωh)² every step
  for (const Real h : {1e-3, 0.1, 10 / kOmega, 100 / kOmega}) {
    ClothBody body = spring_pair(kMass, kStiffness, 0);
    body.state().x[1].x() = 1;
    ImexIntegrator imex;
    const Real start = body.kinetic_energy() + body.elastic_energy();
    const Real factor = 1 / (1 + kOmega * kOmega * h * h);
    Real energy = start;
    for (int n = 0; n < 500; ++n) {
      imex.step(body, body.state(), n * h, h);
      const Real next = body.kinetic_energy() + body.elastic_energy();
      ASSERT_TRUE(std::isfinite(next)) << "h " << h << " step " << n;
      // only far above the 1e-12 m below which ClothBody drops a spring (E ~ 1e-23 J)
      if (energy > 1e-12 * start) {
        ASSERT_NEAR(next / energy, factor, 1e-9 * factor) << "h " << h << " step " << n;
      }
      if (energy > 1e-18) {
        ASSERT_LE(next, energy * (1 + 1e-12)) << "h " << h << " step " << n;
      }
      energy = next;
    }
    EXPECT_LE(energy, start * std::pow(factor, 500) * (1 + 1e-6) + 1e-18) << h;
    EXPECT_EQ(imex.factorizations(), 1);
  }
}

TEST(Imex, OneStepSolvesEquation425AsWritten) {
  // eq. 4.25 assembled densely from its definitions, f_a = f − H x − D v, with the pinned rows
  // replaced by v = 0; the integrator solves the Δv form instead
  ClothBody body = test::small_grid_body(4, 3, 3e3, 0.7, "imex");
  body.set_gravity(Vec3(0, -9.81, 0));
  body.pin(0);
  body.pin(3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> noise(-0.05, 0.05);
  for (std::size_t p = 0; p < body.state().size(); ++p) {
    if (body.is_pinned(static_cast<std::uint32_t>(p))) continue;
    body.state().x[p] += Vec3(noise(rng), noise(rng), noise(rng));
    body.state().v[p] = 10 * Vec3(noise(rng), noise(rng), noise(rng));
  }
  const ParticleState before = body.state();
  const Real h = 0.02;
  const auto n = static_cast<Eigen::Index>(before.size());

  std::vector<LinearPair> pairs;
  ASSERT_TRUE(body.linear_force_pairs(pairs));
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n), D = Eigen::MatrixXd::Zero(n, n);
  for (const LinearPair& pair : pairs) {
    for (const auto& [a, b] : {std::pair{pair.i, pair.j}, std::pair{pair.j, pair.i}}) {
      H(a, b) += pair.k;
      H(a, a) -= pair.k;
      D(a, b) += pair.c;
      D(a, a) -= pair.c;
    }
  }
  std::vector<Vec3> f(before.size());
  body.compute_forces(before.x, before.v, 0, f);
  Eigen::MatrixXd x(n, 3), v(n, 3), force(n, 3);
  for (Eigen::Index p = 0; p < n; ++p) {
    x.row(p) = before.x[p].transpose();
    v.row(p) = before.v[p].transpose();
    force.row(p) = f[p].transpose();
  }
  const Eigen::MatrixXd f_a = force - H * x - D * v;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index p = 0; p < n; ++p) M(p, p) = body.model().mass[p];
  Eigen::MatrixXd A = M - h * h * H - h * D;
  Eigen::MatrixXd rhs = M * v + h * f_a + h * H * x;
  for (Eigen::Index p = 0; p < n; ++p) {
    if (!body.is_pinned(static_cast<std::uint32_t>(p))) continue;
    A.row(p).setZero();
    A(p, p) = 1;
    rhs.row(p).setZero();
  }
  const Eigen::MatrixXd v1 = A.partialPivLu().solve(rhs);
  const Eigen::MatrixXd x1 = x + h * v1;

  ImexIntegrator imex;
  imex.step(body, body.state(), 0, h);
  for (Eigen::Index p = 0; p < n; ++p) {
    EXPECT_LT((body.state().v[p] - v1.row(p).transpose()).norm(), 1e-9) << p;
    EXPECT_LT((body.state().x[p] - x1.row(p).transpose()).norm(), 1e-11) << p;
  }
}

TEST(Imex, WithoutLinearForcesItIsSymplecticEuler) {
  // the Oscillator offers no linear pairs: A = M, v₁ = v₀ + h f/m, x₁ = x₀ + h v₁
  Oscillator system(std::vector<Real>{0.5, 0}, kStiffness, Vec3(0, 1, 0), 0.3);
  ParticleState a{{Vec3(1, 0, 0), Vec3(2, 0, 0)}, {Vec3(0, 0, 1), Vec3::Zero()}}, b = a;
  ImexIntegrator imex;
  auto symplectic = make_integrator("symplectic_euler");
  for (int n = 0; n < 100; ++n) {
    imex.step(system, a, n * 1e-2, 1e-2);
    symplectic->step(system, b, n * 1e-2, 1e-2);
  }
  for (std::size_t p = 0; p < 2; ++p) {
    EXPECT_LT((a.x[p] - b.x[p]).norm(), 1e-12);
    EXPECT_LT((a.v[p] - b.v[p]).norm(), 1e-12);
  }
  EXPECT_EQ(a.x[1], Vec3(2, 0, 0));  // pinned
}

TEST(Imex, ClothOffersItsStructuralSpringsOnly) {
  GridClothSpec spec;
  spec.nx = 4;
  spec.ny = 3;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 300, 0.3};
  params.spring(SpringKind::kShear) = {true, 70, 0.1};
  params.spring(SpringKind::kBend) = {true, 9, 0.02};
  ClothBody body("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                 make_integrator("imex"));
  std::vector<LinearPair> pairs;
  ASSERT_TRUE(body.linear_force_pairs(pairs));
  ASSERT_EQ(pairs.size(), 3u * 3 + 4u * 2);  // (nx − 1) ny + nx (ny − 1)
  for (const LinearPair& pair : pairs) {
    EXPECT_EQ(pair.k, 300);
    EXPECT_EQ(pair.c, 0.3);
    // neighbours on the grid: index j·nx + i
    const auto d = pair.i > pair.j ? pair.i - pair.j : pair.j - pair.i;
    EXPECT_TRUE(d == 1 || d == spec.nx) << pair.i << " " << pair.j;
  }

  params.spring(SpringKind::kStructural).enabled = false;
  ClothBody loose("c", body.shared_model(), params, make_integrator("imex"));
  EXPECT_FALSE(loose.linear_force_pairs(pairs));
  EXPECT_TRUE(pairs.empty());
}

/// A 1 kg, 1 m² cloth of 12 × 12 particles with stiff structural springs (k = 1e5 N/m, as in
/// ImplicitEuler.StiffClothThatExplicitSchemesCannotStep), hanging from its top corners and
/// stepped 300 times at h = 10 ms. Returns the step flags seen and the final strain.
std::pair<StepFlags, Real> run_stiff_cloth(std::string_view integrator, Real shear, Real bend) {
  GridClothSpec spec;
  spec.nx = spec.ny = 12;
  spec.total_mass = 1;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 1e5, 1};
  params.spring(SpringKind::kShear) = {true, shear, 0.01};
  params.spring(SpringKind::kBend) = {true, bend, 0.001};
  params.drag = 0.01;
  ClothBody body("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                 make_integrator(integrator));
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) body.pin(p);
  WorldSettings settings{Vec3(0, -9.81, 0), 1e-2, 100, 0};
  settings.health.auto_substeps = false;  // the integrators' own stability is tested
  World world(settings);
  world.add_body(std::move(body));
  StepFlags flags;
  for (int n = 0; n < 300; ++n) flags |= world.step().flags;
  return {flags, world.cloths()[0].max_strain()};
}

TEST(Imex, StiffClothThatExplicitSchemesCannotStep) {
  // Only the structural springs are implicit; shear and bend are explicit. Per mode, with
  // implicit stiffness κ_I and explicit κ_E, the scheme is stable iff h² κ_E ≤ 4 m + h² κ_I
  // (and κ_I + κ_E ≥ 0: the explicit k r l̂ has a transverse stiffness −k r/|l| that the
  // implicit −k l outweighs unless the spring is compressed). Ignoring κ_I this is the explicit
  // bound h² λ_max(M⁻¹ K_explicit) < 4, λ_max ≤ max_p 2 Σ_s k_s / m_p (Gershgorin): interior
  // particles (m = 1/144 kg) with 4 shear and 4 bend springs give 2·4·(20 + 2)·144·1e-4 = 2.5.
  const auto [imex_flags, imex_strain] = run_stiff_cloth("imex", 20, 2);
  EXPECT_EQ(imex_flags, StepFlags{});
  EXPECT_LT(imex_strain, 0.05);  // stiff springs barely stretch
  const auto [explicit_flags, explicit_strain] = run_stiff_cloth("symplectic_euler", 20, 2);
  EXPECT_TRUE(explicit_flags.has(StepFlag::kUnrecoverable));
  // But κ_I helps: the isotropic structural Laplacian outweighs the shear (≤ 2 k_sh/k_st times
  // it on a grid) and bend (≤ 4 k_b/k_st) ones, so the stiff shear of the implicit Euler test
  // (2·4·2.1e4·144·1e-4 = 242 by Gershgorin alone) still steps, while shear and bend beyond the
  // structural stiffness do not.
  EXPECT_EQ(run_stiff_cloth("imex", 2e4, 1e3).first, StepFlags{});
  EXPECT_TRUE(run_stiff_cloth("imex", 1e6, 1e5).first.has(StepFlag::kUnrecoverable));
}

TEST(Imex, DampsTheTurningOfStiffSprings) {
  // The price of the split (Etzmuß et al. 2003 add corotation against it): the implicit −k l
  // takes a turning spring for a stretched one, and k r l̂, which cancels it, lags a step. A
  // velocity u across the spring follows (m + h² k) u₁ = m u₀ + h f_t, so a stiff pendulum
  // released horizontally creeps at u* = m g/(h k) instead of swinging down.
  const Real mass = 1, k = 1e5, h = 1e-2, g = 9.81;
  auto speed_after = [&](Integrator& integrator, int steps) {
    ClothBody body = spring_pair(mass, k, 1);
    body.set_gravity(Vec3(0, -g, 0));
    for (int n = 0; n < steps; ++n) integrator.step(body, body.state(), n * h, h);
    return body.state().v[1].norm();
  };
  ImexIntegrator imex;
  EXPECT_NEAR(speed_after(imex, 30), mass * g / (h * k), 0.01 * mass * g / (h * k));
  // backward Euler with the full Jacobian swings: a rigid pendulum moves at ≈ 2.9 m/s after
  // 0.3 s
  ImplicitEuler implicit;
  EXPECT_GT(speed_after(implicit, 30), 2.0);
}

TEST(Imex, PinsHoldExactlyAndTheMatrixIsFactorizedOnce) {
  World world = test::expect_top_row_pins_hold("imex", true);
  ClothBody& body = world.cloths()[0];
  ImexIntegrator& imex = imex_of(body);
  EXPECT_EQ(imex.factorizations(), 1);

  // a new h, then the old one again: once each
  const Real t = world.time();
  for (int n = 0; n < 10; ++n) imex.step(body, body.state(), t + n * 1e-3, 1e-3);
  EXPECT_EQ(imex.factorizations(), 2);
  for (int n = 0; n < 10; ++n) imex.step(body, body.state(), t + n * 5e-3, 5e-3);
  EXPECT_EQ(imex.factorizations(), 3);
  // resetting (a rollback) changes no matrix
  imex.reset();
  imex.step(body, body.state(), t, 5e-3);
  EXPECT_EQ(imex.factorizations(), 3);

  // pinning changes the matrix; the new pin holds where it is
  body.pin(30);
  const Vec3 held = body.state().x[30];
  for (int n = 0; n < 50; ++n) world.step();
  EXPECT_EQ(imex.factorizations(), 4);
  EXPECT_EQ(body.state().x[30], held);
  for (std::uint32_t p = 0; p < 6; ++p) {  // the pinned top row never left its rest position
    EXPECT_EQ(body.state().x[p], body.model().rest_positions[p]);
  }
}

TEST(Imex, DiffersFromImplicitEulerByOrderH) {
  // Both are first order: each is exact + h e(t) + O(h²) with its own e, so they differ by
  // O(h). IMEX's e grows with k/m (the damped turning above, at a rate h k/m), so the cloth is
  // soft enough for h k t/m ≪ 1 at these steps.
  GridClothSpec spec;
  spec.nx = spec.ny = 4;
  spec.total_mass = 1;
  spec.plane = GridClothSpec::Plane::kXZ;  // horizontal: it falls and swings in 3-D
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 50, 0.02};
  params.spring(SpringKind::kShear) = {true, 10, 0.005};
  params.spring(SpringKind::kBend) = {true, 1, 0.001};
  params.drag = 0.02;
  const auto model = std::make_shared<const ClothModel>(make_grid_cloth(spec));
  const auto pins = grid_pin_indices(spec, GridPinPreset::kTopCorners);
  auto difference = [&](Real h) {
    ClothBody a("a", model, params, make_integrator("imex"));
    ClothBody b("b", model, params, make_integrator("implicit_euler"));
    dynamic_cast<ImplicitEuler&>(b.integrator()).solver().tolerance = 1e-13;
    for (ClothBody* body : {&a, &b}) {
      body->set_gravity(Vec3(0, -9.81, 0));
      for (std::uint32_t p : pins) body->pin(p);
    }
    Real worst = 0;
    const long steps = std::lround(0.2 / h);
    for (long n = 0; n < steps; ++n) {
      a.integrator().step(a, a.state(), n * h, h);
      b.integrator().step(b, b.state(), n * h, h);
      for (std::size_t p = 0; p < model->particle_count(); ++p) {
        worst = std::max(worst, (a.state().x[p] - b.state().x[p]).norm());
      }
    }
    return worst;
  };
  const Real d1 = difference(1e-3), d2 = difference(5e-4), d4 = difference(2.5e-4);
  std::printf("  |x_imex − x_implicit| over 0.2 s: %.3e %.3e %.3e m\n", d1, d2, d4);
  EXPECT_LT(d1, 0.05);  // the cloth falls ≈ 0.2 m
  EXPECT_NEAR(std::log2(d1 / d2), 1.0, 0.1);
  EXPECT_NEAR(std::log2(d2 / d4), 1.0, 0.1);
}

}  // namespace
}  // namespace felt::test
