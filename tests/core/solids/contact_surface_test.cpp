// The pressure-comparison contact surface against what the geometry and the balance of forces
// demand: a node inside two bodies leaves both, equal bodies meet halfway, a stiffer body
// gives way less in the ratio of the stiffnesses, and friction removes μ times the approach
// stopped from the relative slide without changing the momentum.

#include "core/solids/contact_surface.hpp"

#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/solids/solid_contact_fixtures.hpp"

namespace felt::test {
namespace {

constexpr Real kStep = 0.01;

/// A surface triangle of `body` that contains p and faces along ±axis, with p's barycentric
/// coordinates in it, found by brute force.
std::pair<std::int64_t, Vec3> triangle_at(const SolidBody& body, const Vec3& p, int axis) {
  const std::vector<Vec3>& x = body.positions();
  const std::vector<Triangle>& surface = body.topology().surface;
  for (std::size_t t = 0; t < surface.size(); ++t) {
    const Vec3& a = x[surface[t][0]];
    const Vec3& b = x[surface[t][1]];
    const Vec3& c = x[surface[t][2]];
    const Vec3 normal = (b - a).cross(c - a).normalized();
    if (std::abs(std::abs(normal[axis]) - 1) > 1e-12) continue;
    const Real area = (b - a).cross(c - a).dot(normal);
    const Vec3 w((c - b).cross(p - b).dot(normal) / area, (a - c).cross(p - c).dot(normal) / area,
                 (b - a).cross(p - a).dot(normal) / area);
    if (std::abs((p - a).dot(normal)) < 1e-12 && w.minCoeff() > -1e-12) {
      return {static_cast<std::int64_t>(t), w};
    }
  }
  ADD_FAILURE() << "no surface triangle at " << p.transpose();
  return {-1, Vec3::Zero()};
}

/// Node `node` of body `body` inside body `penetrated`, whose surface it entered at `entry`
/// (on a face normal to `axis`).
PenetrationContact contact(const std::vector<SolidBody>& bodies, std::uint32_t body,
                           std::uint32_t node, std::uint32_t penetrated, const Vec3& entry,
                           int axis) {
  PenetrationContact c;
  c.body = body;
  c.node = node;
  c.penetrated_body = penetrated;
  c.depth = entry - bodies[body].positions()[node];
  std::tie(c.triangle, c.barycentric) = triangle_at(bodies[penetrated], entry, axis);
  return c;
}

void pin_all(SolidBody& body) {
  for (std::uint32_t n = 0; n < body.node_count(); ++n) body.pin(n);
}

void resolve(std::vector<SolidBody>& bodies, const std::vector<PenetrationContact>& contacts) {
  ContactSurface surface;
  surface.resolve(bodies, contacts, 3, SolidFriction::kRelativeCoulomb, kStep, Vec3::Zero());
}

// The corner of a cube sits at the origin, inside two fixed blocks whose faces are 0.1 away
// along −x and −y: it must end on both faces, at (−0.1, −0.1, 0), while the blocks stay.
TEST(ContactSurface, NodeInsideTwoBodiesLeavesBoth) {
  std::vector<SolidBody> bodies;
  bodies.push_back(box_body({1, 1, 1}, Vec3::Constant(0.6), Vec3::Constant(-0.6)));
  bodies.push_back(box_body({1, 1, 1}, Vec3(1.1, 2, 2), Vec3(-0.1, -1, -1)));
  bodies.push_back(box_body({1, 1, 1}, Vec3(2, 1.1, 2), Vec3(-1, -0.1, -1)));
  pin_all(bodies[1]);
  pin_all(bodies[2]);
  const std::uint32_t corner = node_at(bodies[0], Vec3::Zero());
  const std::vector<PenetrationContact> contacts = {
      contact(bodies, 0, corner, 1, Vec3(-0.1, 0, 0), 0),
      contact(bodies, 0, corner, 2, Vec3(0, -0.1, 0), 1)};
  const std::vector<Vec3> blocks[] = {bodies[1].positions(), bodies[2].positions()};

  resolve(bodies, contacts);

  const Vec3& x = bodies[0].positions()[corner];
  EXPECT_NEAR(x.x(), -0.1, 1e-12);
  EXPECT_NEAR(x.y(), -0.1, 1e-12);
  EXPECT_NEAR(x.z(), 0, 1e-12);
  EXPECT_EQ(bodies[1].positions(), blocks[0]);
  EXPECT_EQ(bodies[2].positions(), blocks[1]);
}

// Two blocks whose faces lie 0.1 and 0.2 away in the same direction: leaving the deeper one
// leaves both, so the node moves 0.2, not 0.3.
TEST(ContactSurface, NodeInsideTwoBodiesAlongOneDirectionMovesOnce) {
  std::vector<SolidBody> bodies;
  bodies.push_back(box_body({1, 1, 1}, Vec3::Constant(0.6), Vec3::Constant(-0.6)));
  bodies.push_back(box_body({1, 1, 1}, Vec3(1.1, 2, 2), Vec3(-0.1, -1, -1)));
  bodies.push_back(box_body({1, 1, 1}, Vec3(1.2, 2, 2), Vec3(-0.2, -1, -1)));
  pin_all(bodies[1]);
  pin_all(bodies[2]);
  const std::uint32_t corner = node_at(bodies[0], Vec3::Zero());
  const std::vector<PenetrationContact> contacts = {
      contact(bodies, 0, corner, 1, Vec3(-0.1, 0, 0), 0),
      contact(bodies, 0, corner, 2, Vec3(-0.2, 0, 0), 0)};

  resolve(bodies, contacts);

  EXPECT_LT((bodies[0].positions()[corner] - Vec3(-0.2, 0, 0)).norm(), 1e-12);
}

// Two unit cubes, the second the first turned half a turn about z, overlapping by δ along x at
// one corner each: node i of the first and node j of the second are inside each other. The
// half turn maps the five-tetrahedra split onto itself, so the pair is exactly symmetric.
constexpr Real kOverlap = 0.01;

struct CornerPair {
  std::vector<SolidBody> bodies;
  std::uint32_t node = 0;  ///< the same index in both bodies
  std::vector<PenetrationContact> contacts;
};

CornerPair corner_pair(const SolidMaterial& first, const SolidMaterial& second) {
  CornerPair pair;
  pair.bodies.push_back(box_body({1, 1, 1}, Vec3::Ones(), Vec3(-1 + kOverlap / 2, 0, 0), first));
  TetMesh turned = pair.bodies[0].rest();
  for (Vec3& p : turned.nodes) p = Vec3(-p.x(), -p.y(), p.z());
  pair.bodies.emplace_back("turned", turned, second);
  pair.node = node_at(pair.bodies[0], Vec3(kOverlap / 2, 0, 0));
  pair.contacts = {contact(pair.bodies, 0, pair.node, 1, Vec3(-kOverlap / 2, 0, 0), 0),
                   contact(pair.bodies, 1, pair.node, 0, Vec3(kOverlap / 2, 0, 0), 0)};
  return pair;
}

TEST(ContactSurface, EqualBodiesMeetHalfway) {
  CornerPair pair = corner_pair(thesis_material(), thesis_material());
  resolve(pair.bodies, pair.contacts);
  EXPECT_NEAR(pair.bodies[0].positions()[pair.node].x(), 0, 1e-15);
  EXPECT_NEAR(pair.bodies[1].positions()[pair.node].x(), 0, 1e-15);
}

// Forces linear in the stiffnesses: with k_B = 4 k_A the contact surface balances where the
// soft node has moved 4/5 of the overlap and the stiff one 1/5. Three bisections find it to
// within 1/16 of the overlap, and the two nodes still meet.
TEST(ContactSurface, StifferBodyGivesWayLessInTheRatioOfStiffnesses) {
  SolidMaterial soft = thesis_material();
  soft.mass_spring.damping = 0;
  SolidMaterial stiff = soft;
  stiff.mass_spring.distance_stiffness *= 4;
  stiff.mass_spring.volume_stiffness *= 4;
  CornerPair pair = corner_pair(soft, stiff);

  resolve(pair.bodies, pair.contacts);

  const Real soft_share = (kOverlap / 2 - pair.bodies[0].positions()[pair.node].x()) / kOverlap;
  const Real stiff_share = (pair.bodies[1].positions()[pair.node].x() + kOverlap / 2) / kOverlap;
  EXPECT_NEAR(soft_share, 0.8, 1.0 / 16);
  EXPECT_NEAR(soft_share + stiff_share, 1, 1e-12);
}

Vec3 momentum(const std::vector<SolidBody>& bodies) {
  Vec3 p = Vec3::Zero();
  for (const SolidBody& body : bodies) {
    for (std::uint32_t n = 0; n < body.node_count(); ++n) {
      p += body.mass(n) * (body.positions()[n] - body.previous_positions()[n]) / kStep;
    }
  }
  return p;
}

// Over the step the first cube approached the second by 4 mm along x and slid by `slide`
// along z. Stopping the approach is a normal impulse worth 4 mm of relative motion, so Coulomb
// friction takes min(slide, μ·4 mm) off the relative slide, and the equal and opposite
// impulses leave the momentum as it was (the move onto the contact surface adds none).
constexpr Real kApproach = 0.004;

Real relative_slide_after_friction(Real mu, Real slide) {
  SolidMaterial material = thesis_material();
  material.friction = mu;
  CornerPair pair = corner_pair(material, material);
  SolidBody& first = pair.bodies[0];
  for (std::uint32_t n = 0; n < first.node_count(); ++n) {
    first.previous_positions()[n] = first.positions()[n] - Vec3(kApproach, 0, slide);
  }
  const Vec3 before = momentum(pair.bodies);

  resolve(pair.bodies, pair.contacts);

  EXPECT_LT((momentum(pair.bodies) - before).norm(), 1e-12 * before.norm());
  const auto motion = [&](const SolidBody& body) {
    return body.positions()[pair.node] - body.previous_positions()[pair.node];
  };
  const Vec3 relative = motion(pair.bodies[0]) - motion(pair.bodies[1]);
  EXPECT_NEAR(relative.x(), 0, 1e-15);  // the approach is stopped
  return relative.z();
}

TEST(ContactSurface, CoulombFrictionSlowsTheRelativeSlideByMuTimesTheApproachStopped) {
  EXPECT_NEAR(relative_slide_after_friction(0.2, 0.003), 0.003 - 0.2 * kApproach, 1e-15);
}

TEST(ContactSurface, CoulombFrictionStopsASlowSlideWithoutReversingIt) {
  EXPECT_NEAR(relative_slide_after_friction(1, 0.003), 0, 1e-15);
}

}  // namespace
}  // namespace felt::test
