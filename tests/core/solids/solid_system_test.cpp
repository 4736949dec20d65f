// The soft-solid step pipeline against physics: a cube dropped on the floor comes to rest on
// it, a cube dropped on another stays on top without sinking in, colliding cubes keep their
// momentum, a cube on an incline sticks with high friction and slides with g sin θ without,
// a column of the thesis's material buckles as Greenhill predicts, and unstable or broken
// steps never leave a non-finite state.
//
// Over 500 lines: one scenario per physical law of the solid step pipeline, each with its scene
// set up in full where the reader can check it.

#include "core/solids/solid_system.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/solids/solid_contact_fixtures.hpp"

namespace felt::test {
namespace {

constexpr Real kStep = 0.015;  // the thesis's largest step
const Vec3 kGravity(0, -9.81, 0);
// the thesis's 5 × 5 × 5 cube with cells of 1 m (Table 7.1, Appendix C material)
constexpr int kCells = 5;
constexpr Real kCell = 1;

SolidBody thesis_cube(const Vec3& origin, const SolidMaterial& material = thesis_material()) {
  return box_body({kCells, kCells, kCells}, Vec3::Constant(kCell), origin, material);
}

Collider floor_plane() {
  Collider floor;
  floor.friction = 0.5;
  return floor;
}

bool system_finite(const SolidSystem& system) {
  return std::ranges::all_of(system.bodies(), [](const SolidBody& b) { return all_finite(b); });
}

Real system_energy(const SolidSystem& system) {
  Real energy = 0;
  for (const SolidBody& body : system.bodies()) energy += total_energy(body, kGravity);
  return energy;
}

Vec3 mean(const std::vector<Vec3>& v) {
  return sum(v) / static_cast<Real>(v.size());
}

Real lowest(const SolidBody& body) {
  Real y = std::numeric_limits<Real>::infinity();
  for (const Vec3& x : body.positions()) y = std::min(y, x.y());
  return y;
}

// Dropped from 0.5 m, the cube must come to rest (kinetic energy below 1 mJ, an rms speed of
// about 1 cm/s for its 10.8 kg, and staying there) within a few seconds, never sinking into
// the floor by more than 5% of a cell.
void expect_dropped_cube_comes_to_rest(SolidBody cube) {
  SolidSystem system;
  system.add_body(std::move(cube));
  const Collider floor = floor_plane();
  std::optional<Real> settled_at;
  Real deepest = 0;
  constexpr int kSteps = 400;  // 6 s
  for (int s = 1; s <= kSteps; ++s) {
    system.step(kStep, kGravity, {&floor, 1});
    deepest = std::max(deepest, -lowest(system.bodies()[0]));
    const Real kinetic = system.bodies()[0].kinetic_energy();
    if (kinetic >= 1e-3) settled_at.reset();
    if (kinetic < 1e-3 && !settled_at) settled_at = s * kStep;
  }
  ASSERT_TRUE(settled_at.has_value());
  std::printf("settled after %.3f s, deepest below the floor %.2e m, final kinetic %.2e J\n",
              *settled_at, deepest, system.bodies()[0].kinetic_energy());
  EXPECT_LT(*settled_at, 4.0);
  EXPECT_LT(deepest, 0.05 * kCell);
  EXPECT_LT(system.bodies()[0].kinetic_energy(), 1e-4);
  // resting on the floor, squeezed a little by its weight, not floating
  EXPECT_LT(lowest(system.bodies()[0]), 1e-3);
  EXPECT_NEAR(mean(system.bodies()[0].positions()).y(), kCells * kCell / 2, 0.1 * kCell);
}

TEST(SolidSystem, CubeDroppedOnTheFloorComesToRest) {
  expect_dropped_cube_comes_to_rest(thesis_cube(Vec3(0, 0.5, 0)));
}

// The same with a cloth integrator: contact handling changes the velocities it integrates.
class SolidSystemIntegrator : public ::testing::TestWithParam<const char*> {};

TEST_P(SolidSystemIntegrator, CubeDroppedOnTheFloorComesToRest) {
  SolidBody cube = thesis_cube(Vec3(0, 0.5, 0));
  cube.set_integrator(make_integrator(GetParam()));
  expect_dropped_cube_comes_to_rest(std::move(cube));
}

INSTANTIATE_TEST_SUITE_P(Integrators, SolidSystemIntegrator,
                         ::testing::Values("symplectic_euler", "rk4", "kang"));

// A light cube (27 nodes of 10 g) held by a stiff grab spring on its top centre node, at the
// thesis's longest step: the spring is an anchor evaluated at every substep and counted in the
// stable step, so the cube settles where the spring carries its whole weight, k (target − p) = M g.
// The same spring as a force held over each step (how grabs on solids were applied) cannot hold
// it: ω h = √(k/m) h = 3 for the node.
TEST(SolidSystem, AGrabSpringHoldsALightBodyAtALongStep) {
  constexpr Real kStiffness = 400, kDamping = 2, kNodeMass = 0.01;
  const auto hanging = [&](bool anchored) {
    SolidSystem system;
    system.add_body(box_body({2, 2, 2}, Vec3::Constant(0.1), Vec3(-0.1, 0, -0.1),
                             test::mass_spring(kNodeMass, 60, 20, 2)));
    SolidBody& cube = system.bodies()[0];
    const std::uint32_t top = node_at(cube, Vec3(0, 0.2, 0));
    const Vec3 target(0, 0.25, 0);
    bool failed = false;
    for (int s = 0; s < 200 && !failed; ++s) {  // 3 s
      if (anchored) {
        cube.set_anchor({7, cube.surface_point(top), target, kStiffness, kDamping});
      } else {
        cube.add_external_force(
            top, kStiffness * (target - cube.positions()[top]) - kDamping * cube.velocities()[top]);
      }
      failed = system.step(kStep, kGravity, {}).unrecoverable;
      cube.remove_anchor(7);
    }
    // a Vec3, not the Eigen expression, which would point into `system` and `target`
    return std::pair{failed, Vec3(cube.positions()[top] - target)};
  };
  const auto [anchor_failed, offset] = hanging(true);
  ASSERT_FALSE(anchor_failed);
  const Real weight = 27 * kNodeMass * 9.81;
  EXPECT_NEAR(offset.y(), -weight / kStiffness, 2e-4) << "the spring carries the weight";
  EXPECT_LT(offset.head<1>().norm() + std::abs(offset.z()), 1e-6);
  const auto [held_failed, held_offset] = hanging(false);
  EXPECT_TRUE(held_failed || std::abs(held_offset.y() + weight / kStiffness) > 5e-3)
      << "a held force settled too: " << held_offset.transpose();
}

// Heights where a vertical line through (x, z) crosses the surface of `body`, lowest and
// highest, found by brute force over its surface triangles; none when it misses.
std::optional<std::pair<Real, Real>> surface_span(const SolidBody& body, Real x, Real z) {
  std::optional<std::pair<Real, Real>> span;
  const std::vector<Vec3>& p = body.positions();
  for (const Triangle& t : body.topology().surface) {
    const Vec2 a(p[t[0]].x(), p[t[0]].z()), b(p[t[1]].x(), p[t[1]].z()),
        c(p[t[2]].x(), p[t[2]].z());
    const auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
    const Real area = cross(b - a, c - a);
    if (std::abs(area) < 1e-12) continue;  // a vertical face
    const Vec2 q(x, z);
    const Real u = cross(c - b, q - b) / area, v = cross(a - c, q - c) / area;
    const Real w = 1 - u - v;
    if (u < 0 || v < 0 || w < 0) continue;
    const Real y = u * p[t[0]].y() + v * p[t[1]].y() + w * p[t[2]].y();
    span = span ? std::pair(std::min(span->first, y), std::max(span->second, y)) : std::pair(y, y);
  }
  return span;
}

// How deep the nodes of `upper` lie below the top of `lower` and those of `lower` above the
// bottom of `upper`, the largest over both: the interpenetration of a stack.
Real stack_overlap(const SolidBody& lower, const SolidBody& upper) {
  Real overlap = 0;
  for (const Vec3& x : upper.positions()) {
    if (const auto span = surface_span(lower, x.x(), x.z())) {
      overlap = std::max(overlap, span->second - x.y());
    }
  }
  for (const Vec3& x : lower.positions()) {
    if (const auto span = surface_span(upper, x.x(), x.z())) {
      overlap = std::max(overlap, x.y() - span->first);
    }
  }
  return overlap;
}

// A cube dropped from 0.5 m onto another resting on the floor, shifted off its lattice: it must
// end on top of it, both cubes finite, sunk into each other by a small fraction of a cell, with
// either friction model. Nothing but damping and friction acts inside the pair, so their
// energy (kinetic, elastic and potential) must never exceed what they started with.
void drop_cube_on_cube(SolidFriction friction) {
  SolidStepSettings settings;
  settings.friction = friction;
  SolidSystem system(settings);
  system.add_body(thesis_cube(Vec3(0, 0, 0)));
  system.add_body(thesis_cube(Vec3(0.37, kCells * kCell + 0.5, 0.21)));
  const Collider floor = floor_plane();
  const Real initial_energy = system_energy(system);
  Real worst = 0;
  Real most_energy = initial_energy;
  std::size_t most_colliding = 0;
  constexpr int kSteps = 300;  // 4.5 s
  for (int s = 0; s < kSteps; ++s) {
    const SolidStepStats& stats = system.step(kStep, kGravity, {&floor, 1});
    ASSERT_FALSE(stats.unrecoverable);
    ASSERT_TRUE(system_finite(system));
    most_colliding = std::max(most_colliding, stats.colliding_nodes);
    most_energy = std::max(most_energy, system_energy(system));
    if (s * kStep > 1) {
      worst = std::max(worst, stack_overlap(system.bodies()[0], system.bodies()[1]));
    }
  }
  const SolidBody& lower = system.bodies()[0];
  const SolidBody& upper = system.bodies()[1];
  const Real overlap = stack_overlap(lower, upper);
  std::printf(
      "final overlap %.4f m, worst after landing %.4f m, most colliding nodes %zu, "
      "kinetic %.2e J, energy %.1f J -> %.1f J (highest %.1f J)\n",
      overlap, worst, most_colliding, lower.kinetic_energy() + upper.kinetic_energy(),
      initial_energy, system_energy(system), most_energy);
  EXPECT_GT(most_colliding, 0u);
  EXPECT_NEAR(mean(upper.positions()).y() - mean(lower.positions()).y(), kCells * kCell,
              0.1 * kCells * kCell);
  EXPECT_LT(overlap, 0.1 * kCell);
  EXPECT_LT(worst, 0.1 * kCell);
  EXPECT_LE(most_energy, initial_energy);
}

// Three cubes five times stiffer than the thesis's stay stacked for 15 s and come to rest:
// static friction holds each on the one below, no cube drifts sideways by more than a tenth of
// a cell, and over the last 2 s none moves by more than 0.2 mm. (With smooth vertex normals
// at the boxes' edges, crease_angle 180°, the vectors near the faces' borders tilt sideways
// and the cubes creep by 4 mm in those 2 s. At the thesis's softness the stack topples, its
// top cube 6.4 m off after 15 s: its material buckles under its weight, as the column test
// below shows.)
TEST(SolidSystem, AStackOfThreeStiffCubesComesToRest) {
  SolidSystem system;
  for (int level = 0; level < 3; ++level) {
    system.add_body(thesis_cube(Vec3(0, level * (kCells * kCell + 0.1), 0),
                                test::mass_spring(0.05, 300, 100, 10)));
  }
  const Collider floor = floor_plane();
  std::vector<Vec3> settled;
  for (int s = 0; s < 1500; ++s) {  // 15 s at 10 ms
    ASSERT_FALSE(system.step(0.01, kGravity, {&floor, 1}).unrecoverable) << "step " << s;
    if (s == 1300) {
      for (const SolidBody& cube : system.bodies()) settled.push_back(mean(cube.positions()));
    }
  }
  for (int level = 0; level < 3; ++level) {
    const Vec3 centre = mean(system.bodies()[level].positions());
    EXPECT_LT(Vec2(centre.x() - 2.5, centre.z() - 2.5).norm(), 0.1 * kCell) << "cube " << level;
    EXPECT_NEAR(centre.y(), (level + 0.5) * kCells * kCell, 0.05 * kCells * kCell)
        << "cube " << level;
    EXPECT_LT((centre - settled[level]).norm(), 2e-4) << "cube " << level << " still moves";
  }
}

// Why the thesis's stack topples: its material buckles under its own weight. A free-standing
// column clamped at its base buckles under its weight when q L³ / (E I) exceeds 7.837
// (Greenhill 1881), q the weight per length. Its weight shortens the column by
// δ = q L² / (2 E A), so for a square section of side a the ratio is 24 δ L / a², read here
// from the settled column itself. Standing on the floor, a 5 × 15 × 5 column of the thesis's
// material has a ratio of about 9, and a push of 1 cm/s at its top grows a hundredfold into a
// fall; twice as stiff (about 4.3) the same push dies away.
struct ColumnBuckling {
  Real greenhill_ratio = 0;
  Real first_tilt = 0;  ///< the largest sideways offset of the top in the second after the push
  Real last_tilt = 0;   ///< the offset of the top 14 s later
};

ColumnBuckling push_column(Real stiffness_factor) {
  constexpr Real kSide = 5, kHeight = 15;
  SolidSystem system;
  system.add_body(box_body(
      {5, 15, 5}, Vec3::Constant(kCell), Vec3::Zero(),
      test::mass_spring(0.05, 60 * stiffness_factor, 20 * stiffness_factor, 2 * stiffness_factor)));
  SolidBody& column = system.bodies()[0];
  const Collider floor = floor_plane();
  for (int s = 0; s < 800; ++s) system.step(0.01, kGravity, {&floor, 1});  // settles, straight
  const auto height = [](const Vec3& x) { return x.y(); };
  const auto [low, high] = std::ranges::minmax(column.positions(), {}, height);
  ColumnBuckling result;
  result.greenhill_ratio = 24 * (kHeight - (high.y() - low.y())) * kHeight / (kSide * kSide);
  const auto top_offset = [&] {
    Real offset = 0;
    int count = 0;
    const Real top = std::ranges::max(column.positions(), {}, height).y();
    for (const Vec3& x : column.positions()) {
      if (x.y() > top - 0.5 * kCell) {
        offset += x.x() - kSide / 2;
        ++count;
      }
    }
    return std::abs(offset / count);
  };
  for (std::uint32_t n = 0; n < column.node_count(); ++n) {
    column.velocities()[n].x() += 0.01 * column.positions()[n].y() / kHeight;
  }
  for (int s = 0; s < 1500; ++s) {
    system.step(0.01, kGravity, {&floor, 1});
    if (s < 100) result.first_tilt = std::max(result.first_tilt, top_offset());
  }
  result.last_tilt = top_offset();
  std::printf("k x %.0f: Greenhill ratio %.2f, tilt %.4f m -> %.4f m\n", stiffness_factor,
              result.greenhill_ratio, result.first_tilt, result.last_tilt);
  return result;
}

TEST(SolidSystem, AColumnOfTheThesisMaterialBucklesUnderItsWeightAsGreenhillPredicts) {
  constexpr Real kGreenhill = 7.837;
  const ColumnBuckling thesis = push_column(1);
  EXPECT_GT(thesis.greenhill_ratio, kGreenhill);
  EXPECT_GT(thesis.last_tilt, 10 * thesis.first_tilt);
  const ColumnBuckling stiff = push_column(2);
  EXPECT_LT(stiff.greenhill_ratio, kGreenhill);
  EXPECT_LT(stiff.last_tilt, 2 * stiff.first_tilt);
}

TEST(SolidSystem, CubeDroppedOnACubeStaysOnTop) {
  drop_cube_on_cube(SolidFriction::kRelativeCoulomb);
}

TEST(SolidSystem, CubeDroppedOnACubeStaysOnTopWithTheThesisFriction) {
  drop_cube_on_cube(SolidFriction::kThesis);
}

Vec3 momentum(const SolidSystem& system) {
  Vec3 p = Vec3::Zero();
  for (const SolidBody& body : system.bodies()) {
    for (std::uint32_t n = 0; n < body.node_count(); ++n) p += body.mass(n) * body.velocities()[n];
  }
  return p;
}

// Two cubes meet off-centre in free space at 1 and 0.7 m/s. Nothing outside acts on them, so
// their total momentum must stay what it was through the contact, which must really happen.
TEST(SolidSystem, CollidingCubesKeepTheirMomentum) {
  SolidSystem system;
  system.add_body(thesis_cube(Vec3(-kCells * kCell - 0.3, 0, 0)));
  system.add_body(thesis_cube(Vec3(0.3, 1.3, 0.4)));
  for (Vec3& v : system.bodies()[0].velocities()) v = Vec3(1, 0, 0);
  for (Vec3& v : system.bodies()[1].velocities()) v = Vec3(-0.7, 0, 0);
  const Vec3 before = momentum(system);
  const Real scale = system.bodies()[0].node_count() * 0.05;  // one cube at 1 m/s
  Real worst = 0;
  bool touched = false;
  for (int s = 0; s < 150; ++s) {  // 2.25 s: they meet after about 0.35 s
    touched |= system.step(kStep, Vec3::Zero(), {}).colliding_nodes > 0;
    worst = std::max(worst, (momentum(system) - before).norm());
  }
  std::printf("largest momentum change %.2e kg m/s of %.2f, first cube now %.3f m/s\n", worst,
              before.norm(), mean(system.bodies()[0].velocities()).x());
  EXPECT_TRUE(touched);
  EXPECT_LT(mean(system.bodies()[0].velocities()).x(), 0.5);  // the contact slowed it
  EXPECT_LT(worst, 1e-9 * scale);
}

// A cube resting on a plane tilted by θ = 20° about z, its downhill direction (cos θ, −sin θ, 0).
struct Incline {
  static constexpr Real kAngle = 20 * std::numbers::pi / 180;
  const Vec3 downhill = Vec3(std::cos(kAngle), -std::sin(kAngle), 0);
  Collider plane;
  SolidSystem system;

  explicit Incline(Real friction) {
    plane.normal = Vec3(std::sin(kAngle), std::cos(kAngle), 0);
    plane.friction = friction;
    // ten times the thesis's stiffness: the jelly cube would rock its uphill edge off the plane
    SolidMaterial material = mass_spring(0.05, 600, 200, 2);
    material.friction = friction;
    TetMesh cube = thesis_cube(Vec3(0, 0, 0)).rest();
    // turn the cube by −θ about z so its bottom face lies on the plane
    for (Vec3& p : cube.nodes) {
      p = Vec3(p.x() * std::cos(kAngle) + p.y() * std::sin(kAngle),
               -p.x() * std::sin(kAngle) + p.y() * std::cos(kAngle), p.z());
    }
    system.add_body(SolidBody("cube", cube, material));
  }
  /// Steps for `steps` steps of kStep.
  void run(int steps) {
    for (int s = 0; s < steps; ++s) system.step(kStep, kGravity, {&plane, 1});
  }
  const SolidBody& cube() const { return system.bodies()[0]; }
};

// μ = 1 > tan 20° ≈ 0.36: once the cube has found its footing (released undeformed, it shears
// and spreads a little at first), the nodes on the plane must not slide any further, where
// without friction the cube would slide g sin θ t²/2, metres.
TEST(SolidSystem, CubeOnAnInclineWithHighFrictionStaysPut) {
  Incline incline(1);
  std::vector<std::uint32_t> bottom;
  for (std::uint32_t n = 0; n < incline.cube().node_count(); ++n) {
    if (std::abs(incline.plane.normal.dot(incline.cube().positions()[n])) < 1e-9) {
      bottom.push_back(n);
    }
  }
  ASSERT_EQ(bottom.size(), 36u);
  const std::vector<Vec3> start = incline.cube().positions();
  incline.run(100);
  const std::vector<Vec3> footing = incline.cube().positions();
  incline.run(100);
  Real settling = 0;
  Real slid = 0;
  for (std::uint32_t n : bottom) {
    const Vec3& x = incline.cube().positions()[n];
    settling = std::max(settling, std::abs((footing[n] - start[n]).dot(incline.downhill)));
    slid = std::max(slid, std::abs((x - footing[n]).dot(incline.downhill)));
  }
  std::printf("bottom nodes moved at most %.2e m in the first 1.5 s, %.2e m in the next 1.5 s\n",
              settling, slid);
  EXPECT_LT(settling, 0.1 * kCell);
  EXPECT_LT(slid, 1e-3);
}

// Without friction the cube's mean velocity along the slope grows at g sin θ: the plane pushes
// only along its normal, and the internal forces sum to zero.
TEST(SolidSystem, CubeOnAFrictionlessInclineSlidesWithGSinTheta) {
  Incline incline(0);
  incline.run(30);
  const Real v1 = mean(incline.cube().velocities()).dot(incline.downhill);
  incline.run(70);
  const Real v2 = mean(incline.cube().velocities()).dot(incline.downhill);
  const Real expected = 9.81 * std::sin(Incline::kAngle);
  const Real acceleration = (v2 - v1) / (70 * kStep);
  std::printf("acceleration along the slope %.6f m/s² (g sin θ = %.6f)\n", acceleration, expected);
  EXPECT_NEAR(acceleration, expected, 1e-6 * expected);
}

// k_D = 10⁶ on nodes of 0.1 g: a 15 ms step is thousands of times what explicit integration
// allows; the system must substep (or rescue) so the body neither explodes nor goes non-finite.
TEST(SolidSystem, StiffLightBodyStaysFiniteAtTheThesisStep) {
  SolidMaterial material = thesis_material();
  material.node_mass = 1e-4;
  material.mass_spring.distance_stiffness = 1e6;
  SolidSystem system;
  system.add_body(box_body({2, 2, 2}, Vec3::Constant(0.5), Vec3(0, 0.2, 0), material));
  const Collider floor = floor_plane();
  const Real rest_volume = system.bodies()[0].rest_volume();
  int most_substeps = 0;
  for (int s = 0; s < 10; ++s) {
    const SolidStepStats& stats = system.step(kStep, kGravity, {&floor, 1});
    most_substeps = std::max(most_substeps, stats.substeps);
    ASSERT_TRUE(system_finite(system));
  }
  std::printf("substeps per step: %d\n", most_substeps);
  EXPECT_GT(most_substeps, 100);
  EXPECT_NEAR(system.bodies()[0].volume(), rest_volume, 0.05 * rest_volume);
}

// A NaN force poisons every attempt: the step must be rolled back and the body stopped where
// it was, with nothing non-finite left.
TEST(SolidSystem, StepThatCannotBeRescuedIsRolledBackAndStopped) {
  SolidSystem system;
  system.add_body(thesis_cube(Vec3(0, 1, 0)));
  const Collider floor = floor_plane();
  system.step(kStep, kGravity, {&floor, 1});
  const std::vector<Vec3> before = system.bodies()[0].positions();
  system.bodies()[0].add_external_force(7, Vec3::Constant(std::numeric_limits<Real>::quiet_NaN()));

  const SolidStepStats& stats = system.step(kStep, kGravity, {&floor, 1});

  EXPECT_TRUE(stats.unrecoverable);
  EXPECT_TRUE(system_finite(system));
  EXPECT_EQ(system.bodies()[0].positions(), before);
  EXPECT_EQ(system.bodies()[0].previous_positions(), before);
  for (const Vec3& v : system.bodies()[0].velocities()) EXPECT_EQ(v, Vec3::Zero());
  // the poisoned force is gone: the next step is an ordinary one
  EXPECT_FALSE(system.step(kStep, kGravity, {&floor, 1}).unrecoverable);
}

// A step no substep can save costs a few ordinary steps, not the 127 a light body's six
// doublings would make of hundreds of substeps: the retries stop within max(512, 4 × the first
// attempt's) substeps, and the whole step within the step budget (health.step_budget).
TEST(SolidSystem, AStepThatCannotBeRescuedStopsRetryingWithinItsBudget) {
  const auto last_attempt = [](int first_substeps, int step_budget = 1000) {
    SolidMaterial material = thesis_material();
    material.model = SolidModel::kShapeMatching;  // max_step alone sets the substeps
    SolidSystem system;
    SolidStepSettings settings = system.settings();
    settings.max_step = kStep / first_substeps;
    settings.health.step_budget = step_budget;
    system.set_settings(settings);
    system.add_body(box_body({1, 1, 1}, Vec3::Ones(), Vec3(0, 2, 0), material));
    system.bodies()[0].add_external_force(0,
                                          Vec3::Constant(std::numeric_limits<Real>::quiet_NaN()));
    const SolidStepStats& stats = system.step(kStep, kGravity, {});
    EXPECT_TRUE(stats.unrecoverable);
    return stats.substeps;
  };
  EXPECT_EQ(last_attempt(2), 2 * 64);              // 4 + 8 + ... + 128 = 252 retried substeps
  EXPECT_EQ(last_attempt(100), 100 * 2);           // 200, and 400 more would pass 512
  EXPECT_EQ(last_attempt(600), 600);               // 1200 more would pass the step budget of 1000
  EXPECT_EQ(last_attempt(600, 100'000), 600 * 2);  // 1200, and 2400 more would pass 4 × 600
}

// A shape-matching body has no step limit of its own, so max_step alone sets the substeps: a
// 40 ms step takes three, and a step of exactly three max_steps too.
TEST(SolidSystem, SubstepsAreNoLongerThanMaxStep) {
  SolidMaterial material = thesis_material();
  material.model = SolidModel::kShapeMatching;
  SolidSystem system;
  system.add_body(box_body({1, 1, 1}, Vec3::Ones(), Vec3(0, 2, 0), material));
  EXPECT_EQ(system.step(0.04, kGravity, {}).substeps, 3);
  EXPECT_EQ(system.step(3 * system.settings().max_step, kGravity, {}).substeps, 3);
}

TEST(SolidSystem, EachSubstepYieldsAfterItsIntegrationAndAfterItsContacts) {
  SolidMaterial material = thesis_material();
  material.model = SolidModel::kShapeMatching;
  const auto run = [&](const std::function<void()>& yield_point) {
    SolidSystem system;
    system.add_body(box_body({1, 1, 1}, Vec3::Ones(), Vec3(0, 0.2, 0), material));
    const Collider floor = floor_plane();
    for (int n = 0; n < 20; ++n)
      EXPECT_EQ(system.step(0.04, kGravity, {&floor, 1}, yield_point).substeps, 3);
    return system.bodies()[0].positions();
  };
  int yields = 0;
  const std::vector<Vec3> yielded = run([&yields] { ++yields; });
  EXPECT_EQ(yields, 20 * 3 * 2);
  EXPECT_EQ(yielded, run({}));  // and yielding changes nothing
}

TEST(SolidSystem, StepWithoutBodiesDoesNothing) {
  SolidSystem system;
  EXPECT_EQ(system.step(kStep, kGravity, {}).substeps, 0);
}

}  // namespace
}  // namespace felt::test
