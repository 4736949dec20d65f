// XPBD with small steps (Macklin et al. 2016, 2019) against the analytic oscillator and static
// stretch of a hanging spring chain, the equilibrium the force-based integrators reach on a
// hanging cloth, energy bounds, and steps at which symplectic Euler blows up.

#include "core/integrate/xpbd_integrator.hpp"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/cloth/cloth_body.hpp"
#include "core/cloth/cloth_fixtures.hpp"
#include "core/cloth/cloth_grid.hpp"
#include "core/integrate/oscillator.hpp"
#include "core/world/world.hpp"

namespace felt::test {
namespace {

const Vec3 kGravity(0, -9.81, 0);

/// Largest error of (x, v/ω) over one period of the spring oscillator m ẍ + c ẋ + k (x − r) = 0
/// from x = r + a, v = 0 (ω = 2π, ζ = c/(2mω)), stepped with h in `substeps` substeps.
Real oscillator_error(Real h, int substeps, Real zeta) {
  const Real rest = 1, amplitude = 0.5;
  ClothBody body = spring_pair(kMass, kStiffness, rest, 2 * zeta * kMass * kOmega, "xpbd");
  body.state().x[1].x() = rest + amplitude;
  XpbdIntegrator xpbd(substeps);
  Real worst = 0;
  const long steps = std::lround(1 / h);
  for (long n = 0; n < steps; ++n) {
    xpbd.step(body, body.state(), n * h, h);
    const Exact exact = exact_oscillator((n + 1) * h, zeta);
    const Vec3 x = body.state().x[1], v = body.state().v[1];
    worst = std::max(worst, std::hypot(x.x() - rest - amplitude * exact.x,
                                       (v.x() - amplitude * exact.v) / kOmega));
  }
  return worst / amplitude;
}

TEST(Xpbd, IsNamedAsScenesSelectItAndRefusesNoSubsteps) {
  const auto made = make_integrator("xpbd");
  ASSERT_NE(made, nullptr);
  EXPECT_EQ(made->name(), "xpbd");
  EXPECT_EQ(integrator_needs("xpbd"), IntegratorNeeds::kDistanceConstraints);
  EXPECT_EQ(XpbdIntegrator(7).substeps(), 7);
  EXPECT_THROW(XpbdIntegrator(0), std::logic_error);
}

TEST(Xpbd, SpringOscillatorConvergesWithOrderOneUndampedAndDamped) {
  // on one spring the substep is backward Euler: x − r shrinks by 1/(1 + (ωh)²) per prediction
  for (const Real zeta : {0.0, 0.1}) {
    const Real e1 = oscillator_error(1e-3, 1, zeta), e2 = oscillator_error(5e-4, 1, zeta),
               e4 = oscillator_error(2.5e-4, 1, zeta);
    std::printf("  ζ %g: errors %.3e %.3e %.3e\n", zeta, e1, e2, e4);
    EXPECT_NEAR(0.5 * (std::log2(e1 / e2) + std::log2(e2 / e4)), 1.0, 0.05) << zeta;
    // n substeps of h/n are the same scheme as steps of h/n
    EXPECT_NEAR(oscillator_error(1e-3, 4, zeta), e4, 1e-12) << zeta;
  }
}

/// A vertical chain of `links` springs (k, rest 0.1 m, no damping) hanging from its pinned top
/// particle, each particle 10 g with drag 0.05 N·s/m (at rest it acts not), in a world of step
/// h (in `substeps`) stepped for `seconds` (returned); `push` is an external force on the bottom
/// particle every step (as a haptic proxy's reaction).
World settled_chain(int links, Real k, Real h, int substeps, Real seconds,
                    const Vec3& push = Vec3::Zero()) {
  auto model = std::make_shared<ClothModel>();
  for (int i = 0; i <= links; ++i) {
    model->rest_positions.push_back(Vec3(0, -0.1 * i, 0));
    model->uv.push_back(Vec2::Zero());
    model->mass.push_back(0.01);
  }
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(links); ++i) {
    model->springs.push_back({i, i + 1, 0.1, SpringKind::kStructural});
  }
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, k, 0};
  params.drag = 0.05;
  World world(WorldSettings{kGravity, h, 100, 0});
  world.add_body(ClothBody("chain", model, params, std::make_unique<XpbdIntegrator>(substeps)));
  world.cloths()[0].pin(0);
  const auto steps = std::lround(seconds / h);
  for (long n = 0; n < steps; ++n) {
    world.add_surface_force(world.body_ids()[0], static_cast<std::uint32_t>(links), push);
    EXPECT_EQ(world.step().flags, StepFlags{});
  }
  return world;
}

/// The largest relative error of the chain's link extensions against the static value: link s
/// (from the top) carries the weight of the links − s particles below it and the push, so it
/// stretches by ((links − s) m g + F)/k.
Real chain_error(const ClothBody& chain, int links, Real k, const Vec3& push) {
  Real worst = 0;
  for (int s = 0; s < links; ++s) {
    const Real extension = (chain.state().x[s + 1] - chain.state().x[s]).norm() - 0.1;
    const Real expected = ((links - s) * 0.01 * 9.81 - push.y()) / k;
    worst = std::max(worst, std::abs(extension / expected - 1));
  }
  return worst;
}

TEST(Xpbd, ChainConvergesToTheAnalyticStaticStretchAsTheSubstepShrinks) {
  // One Gauss–Seidel pass per substep leaves a bias at rest of about 2 k h_s² w (w = 1/m; the
  // upper links are softer by it; the chain's links come in two classes, even and odd, so the
  // weight reaches down one link every class rather than the whole chain in one top-down
  // sweep): 2 % at h_s = 1 ms, 0.13 % at 0.25 ms, second order. The result depends on h_s
  // only: ten world steps of 1 ms and one of 10 ms in 10 substeps agree.
  const int links = 10;
  const Real k = 100;
  const Vec3 push(0, -0.05, 0);
  const World coarse = settled_chain(links, k, 1e-3, 1, 20, push);
  const World split = settled_chain(links, k, 1e-2, 10, 20, push);
  const World fine = settled_chain(links, k, 1e-2, 40, 20, push);
  const Real e_coarse = chain_error(coarse.cloths()[0], links, k, push);
  const Real e_split = chain_error(split.cloths()[0], links, k, push);
  const Real e_fine = chain_error(fine.cloths()[0], links, k, push);
  std::printf("  relative extension error: h_s 1 ms %.2e (as 10 substeps %.2e), 0.25 ms %.2e\n",
              e_coarse, e_split, e_fine);
  for (const World* w : {&coarse, &split, &fine}) EXPECT_LT(w->cloths()[0].kinetic_energy(), 1e-12);
  EXPECT_NEAR(e_split, e_coarse, 1e-9);
  EXPECT_LT(e_coarse, 2.5 * k * 1e-6 / 0.01);  // k h_s² w
  EXPECT_LT(e_fine, 2.5e-3);
  EXPECT_NEAR(std::log2(e_coarse / e_fine) / 2, 2, 0.2);  // second order in h_s
}

/// A 1 m², 0.2 kg cloth of n × n particles with the given spring constants and drag, hanging
/// from its top corners, stepped in a world of step h for `seconds`.
World hanging_cloth(std::unique_ptr<Integrator> integrator, std::uint32_t n, Real h, Real seconds,
                    Real damping = 0.02) {
  GridClothSpec spec;
  spec.nx = spec.ny = n;
  spec.total_mass = 0.2;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 250, damping};
  params.spring(SpringKind::kShear) = {true, 50, damping / 5};
  params.spring(SpringKind::kBend) = {true, 5, damping / 50};
  params.drag = damping / 10;
  World world(WorldSettings{kGravity, h, 100, 0});
  world.add_body(ClothBody("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                           std::move(integrator)));
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) {
    world.cloths()[0].pin(p);
  }
  const auto steps = std::lround(seconds / h);
  for (long s = 0; s < steps; ++s) world.step();
  return world;
}

Real max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  Real worst = 0;
  for (std::size_t p = 0; p < a.size(); ++p) worst = std::max(worst, (a[p] - b[p]).norm());
  return worst;
}

TEST(Xpbd, HangingClothSettlesWhereImplicitEulerDoes) {
  // the equilibrium is the force balance, whatever the integrator: compare with implicit
  // Euler's at its rest (its own convergence is checked in implicit_euler_test)
  const World reference = hanging_cloth(make_integrator("implicit_euler"), 10, 2e-3, 15);
  // 40 substeps of 0.1 ms: k h_s² w ≈ 1.4e-3, the bias one pass leaves (see the chain)
  const World xpbd = hanging_cloth(std::make_unique<XpbdIntegrator>(40), 10, 1.0 / 240, 15);
  const ClothBody& r = reference.cloths()[0];
  const ClothBody& x = xpbd.cloths()[0];
  ASSERT_LT(r.kinetic_energy(), 1e-10);
  ASSERT_LT(x.kinetic_energy(), 1e-9);
  const Real distance = max_distance(x.state().x, r.state().x);
  std::printf("  max distance %.3g mm; max strain %.4f (xpbd) %.4f (implicit Euler)\n",
              distance * 1e3, x.max_strain(), r.max_strain());
  EXPECT_LT(distance, 1e-4);  // on a sag of tens of cm
  EXPECT_NEAR(x.max_strain(), r.max_strain(), 1e-3);
}

TEST(Xpbd, SwingDoesNotDependOnTheSubstepCountBeyondItsError) {
  // a swinging cloth at 1/60 s per step: the motion at 0.5 s with 8, 16, 32 and 64 substeps.
  // Compliance fixes the material, so the runs converge to one motion with error ∝ h_s (first
  // order or better); plain PBD would stiffen with the substeps instead.
  std::vector<std::vector<Vec3>> x;
  for (int substeps : {8, 16, 32, 64}) {
    x.push_back(hanging_cloth(std::make_unique<XpbdIntegrator>(substeps), 10, 1.0 / 60, 0.5)
                    .cloths()[0]
                    .state()
                    .x);
  }
  const Real d1 = max_distance(x[0], x[1]), d2 = max_distance(x[1], x[2]),
             d3 = max_distance(x[2], x[3]);
  std::printf("  differences 8-16 %.3g mm, 16-32 %.3g mm, 32-64 %.3g mm\n", d1 * 1e3, d2 * 1e3,
              d3 * 1e3);
  EXPECT_LT(d3, 1e-3);
  EXPECT_GT(d1 / d2, 2);  // first order or better
  EXPECT_GT(d2 / d3, 2);
}

struct Swing {
  Real highest_energy;  ///< J, from 0 at the start
  Real final_energy;    ///< J
  Real max_strain;
  bool finite;
};

/// A 10 × 10, 0.2 kg cloth without any damping (springs 1000/200/20 N/m) released flat from one
/// pinned corner under gravity, stepped 300 times at 1/60 s: its kinetic, elastic and
/// gravitational energy from the start.
Swing undamped_swing(int substeps) {
  GridClothSpec spec;
  spec.nx = spec.ny = 10;
  spec.total_mass = 0.2;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 1000, 0};
  params.spring(SpringKind::kShear) = {true, 200, 0};
  params.spring(SpringKind::kBend) = {true, 20, 0};
  params.drag = 0;
  ClothBody body("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                 std::make_unique<XpbdIntegrator>(substeps));
  body.pin(0);
  body.set_gravity(kGravity);
  const std::vector<Vec3> start = body.state().x;
  Swing swing{0, 0, 0, true};
  const Real h = 1.0 / 60;
  for (int n = 0; n < 300; ++n) {
    body.integrator().step(body, body.state(), n * h, h);
    swing.final_energy = total_energy(body, start);
    swing.highest_energy = std::max(swing.highest_energy, swing.final_energy);
    swing.max_strain = std::max(swing.max_strain, body.max_strain());
    swing.finite = swing.finite && all_finite(body.state());
  }
  std::printf("  %d substeps: highest energy %.3g J, final %.3g J, max strain %.3f\n", substeps,
              swing.highest_energy, swing.final_energy, swing.max_strain);
  return swing;
}

TEST(Xpbd, UndampedEnergyStaysBelowItsStart) {
  // The exact motion keeps its energy (0); XPBD's passes dissipate, and the under-converged
  // pass leaves elastic energy of order k (strain bias)², small once k h_s² w ≪ 1. The swing
  // releases ~0.5 J of potential energy; the bound is 0.1 % of it.
  for (int substeps : {40, 160}) {
    const Swing swing = undamped_swing(substeps);
    EXPECT_LT(swing.highest_energy, 5e-4) << substeps;
    EXPECT_LT(swing.final_energy, 0) << substeps;
  }
}

struct Hang {
  Real highest_energy;         ///< kinetic + elastic + gravitational, J, from 0 at rest
  Real highest_motion_energy;  ///< kinetic + gravitational, J, from 0 at rest
  /// kinetic + gravitational + elastic at the stiffness the projection applies
  /// (ClothBody::elastic_energy of the substep), J, from 0 at rest
  Real highest_projected_energy;
  Real final_kinetic_energy;  ///< J
};

/// The peer benchmark's cloth (docs/results/peers.md: 1 m², 0.2 kg, n × n, structural k, shear
/// k/4, bend k/40 with their damping, drag 1/s of the mass) released flat at rest and hung by
/// its top corners, stepped `seconds` at 1/240 s in `substeps` substeps without the world's
/// health check.
Hang hang(std::uint32_t n, Real k, int substeps, Real seconds) {
  GridClothSpec spec;
  spec.nx = spec.ny = n;
  spec.total_mass = 0.2;
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, k, 0.05};
  params.spring(SpringKind::kShear) = {true, k / 4, 0.02};
  params.spring(SpringKind::kBend) = {true, k / 40, 0.005};
  params.drag = 0.2 / (static_cast<Real>(n) * n);
  ClothBody body("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                 std::make_unique<XpbdIntegrator>(substeps));
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) body.pin(p);
  body.set_gravity(kGravity);
  const Real start = body.gravitational_energy();  // kinetic and elastic are 0
  Hang hang{-1e300, -1e300, -1e300, 0};
  const Real h = 1.0 / 240;
  const long steps = std::lround(seconds / h);
  for (long s = 0; s < steps; ++s) {
    body.integrator().step(body, body.state(), s * h, h);
    const Real motion = body.kinetic_energy() + body.gravitational_energy() - start;
    hang.highest_motion_energy = std::max(hang.highest_motion_energy, motion);
    hang.highest_energy = std::max(hang.highest_energy, motion + body.elastic_energy());
    hang.highest_projected_energy =
        std::max(hang.highest_projected_energy, motion + body.elastic_energy(h / substeps));
  }
  hang.final_kinetic_energy = body.kinetic_energy();
  std::printf(
      "  %u x %u, k %g, %d substeps: highest energy %.3g J (without the elastic %.3g J), "
      "final kinetic %.3g J, max strain %.4f\n",
      n, n, k, substeps, hang.highest_energy, hang.highest_motion_energy, hang.final_kinetic_energy,
      body.max_strain());
  return hang;
}

TEST(Xpbd, StiffHangingClothComesToRestWithoutGainingEnergy) {
  // docs/results/peers.md: projected in the grid's row-by-row order this cloth gained energy
  // without bound at k >= 4000 with 1-16 substeps (kinetic energy 4-46 J at 2 s, where its
  // whole potential energy is m g × 1 m = 2 J); projected class by class it comes to rest.
  // Where one pass per substep is far from converged (k h_s² w = 35-550 here) the cloth is
  // softer than its material: the elastic energy ½ k (l − r)² of the strain it rests at exceeds
  // the gravitational energy it released (0.85 J at 4 substeps), not a gain of the motion, so
  // there the bound is on the kinetic + gravitational energy (below the mechanical energy, so
  // it may never exceed the start either): 34-470 J over it in the row-by-row order. Counted
  // at the stiffness the projection pushes with, k / (1 + k w h_s²), the springs hold what the
  // cloth released, and the whole mechanical energy never rises (what the world's health check
  // counts for xpbd, where ½ k (l − r)² had a light stiff cloth flagged at every step).
  for (const int substeps : {1, 4, 16}) {
    const Hang h = hang(40, 4000, substeps, 2);
    EXPECT_LE(h.highest_motion_energy, 1e-6) << substeps;
    EXPECT_LE(h.highest_projected_energy, 1e-6) << substeps;
    EXPECT_LT(h.final_kinetic_energy, 1e-2) << substeps;
  }
  const Hang stiffer = hang(40, 1e4, 4, 2);
  EXPECT_LE(stiffer.highest_motion_energy, 1e-6);
  EXPECT_LT(stiffer.final_kinetic_energy, 1e-3);
  // with k h_s² w = 0.14 the pass nearly converges, and the whole mechanical energy stays
  // within 1 mJ (0.05 % of m g × 1 m) of its start
  EXPECT_LT(hang(40, 4000, 64, 0.5).highest_energy, 1e-3);
}

TEST(Xpbd, StaysFiniteAtOneSubstepOfASixtiethOfASecond) {
  // k h² w = 139: one pass cannot hold the springs, so the cloth is soft, but nothing blows up
  const Swing swing = undamped_swing(1);
  EXPECT_TRUE(swing.finite);
  EXPECT_LT(swing.max_strain, 1.5);
}

TEST(Xpbd, StiffClothWhereSymplecticEulerBlowsUp) {
  // k = 1e4 N/m on 1/144 kg particles: ω_max ≈ 2√(k/m) = 2400 rad/s, symplectic Euler needs
  // h < 0.83 ms; at 10 ms it blows up, XPBD in 10 substeps holds the cloth with little stretch
  auto run = [](std::unique_ptr<Integrator> integrator) {
    GridClothSpec spec;
    spec.nx = spec.ny = 12;
    spec.total_mass = 1;
    ClothParams params;
    params.spring(SpringKind::kStructural) = {true, 1e4, 1};
    params.spring(SpringKind::kShear) = {true, 2e3, 0.2};
    params.spring(SpringKind::kBend) = {true, 1e2, 0.02};
    params.drag = 0.01;
    WorldSettings settings{kGravity, 1e-2, 100, 0};
    settings.health.auto_substeps = false;  // the integrators' own stability is tested
    World world(settings);
    world.add_body(ClothBody("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                             std::move(integrator)));
    for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) {
      world.cloths()[0].pin(p);
    }
    StepFlags flags;
    for (int n = 0; n < 300; ++n) flags |= world.step().flags;
    return std::pair{flags, world.cloths()[0].max_strain()};
  };
  const auto [xpbd_flags, xpbd_strain] = run(std::make_unique<XpbdIntegrator>(10));
  EXPECT_EQ(xpbd_flags, StepFlags{});
  std::printf("  xpbd max strain %.4f\n", xpbd_strain);
  EXPECT_LT(xpbd_strain, 0.05);
  const auto [explicit_flags, explicit_strain] = run(make_integrator("symplectic_euler"));
  EXPECT_TRUE(explicit_flags.has(StepFlag::kUnrecoverable));
}

TEST(Xpbd, PinsHoldExactly) {
  test::expect_top_row_pins_hold("xpbd", true);
}

/// A soft 12 × 12 cloth (k = 20 N/m), its stretch limited to `max_strain` or not (0), dropped
/// flat from 0.5 m onto a 0.3 m sphere at the origin and stepped 2 s at 1/60 s. Expects every
/// step to be `healthy` and no particle inside the sphere's shell; returns the final max strain.
Real drape(std::unique_ptr<Integrator> integrator, Real max_strain, bool healthy = true) {
  GridClothSpec spec;
  spec.nx = spec.ny = 12;
  spec.plane = GridClothSpec::Plane::kXZ;
  spec.center = Vec3(0, 0.5, 0);
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 20, 0.01};
  params.spring(SpringKind::kShear) = {true, 5, 0.01};
  params.stretch.enabled = max_strain > 0;
  params.stretch.max_strain = max_strain;
  World world(WorldSettings{kGravity, 1.0 / 60, 100, 0});
  world.add_body(ClothBody("c", std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                           std::move(integrator)));
  Collider sphere;
  sphere.shape = Collider::Shape::kSphere;
  sphere.radius = 0.3;
  world.add_collider(sphere);
  for (int n = 0; n < 120; ++n) {
    const StepFlags flags = world.step().flags;
    if (healthy) {
      EXPECT_EQ(flags, StepFlags{}) << "step " << n;
    }
  }
  const ClothBody& body = world.cloths()[0];
  for (const Vec3& x : body.state().x) {
    EXPECT_GE(x.norm(), sphere.radius + params.thickness - 1e-9);
  }
  EXPECT_LT(body.state().x[6 * 12 + 6].y(), 0.5);  // it fell onto the sphere
  return body.max_strain();
}

TEST(Xpbd, CollidersAndStretchLimitsApplyAfterItsStep) {
  // the world applies both after any integrator's step: the limited drape stretches less than
  // the free one. Symplectic Euler, for comparison, is beyond its stable step on this cloth
  // (ω h ≈ 2.2 > 2 at 1/60 s); the limiter holds its strain, but the energy check of the health
  // check sees the growth it takes away (issue 27), so its steps are not expected healthy
  const Real free = drape(std::make_unique<XpbdIntegrator>(8), 0);
  const Real limited = drape(std::make_unique<XpbdIntegrator>(8), 0.05);
  const Real symplectic = drape(make_integrator("symplectic_euler"), 0.05, false);
  std::printf("  max strain: free %.3f, limited %.3f, symplectic Euler limited %.3f\n", free,
              limited, symplectic);
  EXPECT_LT(limited, 0.5 * free);
}

}  // namespace
}  // namespace felt::test
