// The reaction of a proxy's contact on the body it touches: the contact spring applied against
// the surface as each step finds it, with the surface's motion counted at no more stiffness than
// the step can take, and the passivity controller that withholds a held push the contact has no
// energy for. Each case steps a sheet twice over, once with the contact and once with the
// plain push (or none) the contact must come to, and compares where every particle went.

#include "runtime/reaction_accumulator.hpp"

#include <gtest/gtest.h>

#include "runner_fixtures.hpp"
#include "runtime/snapshot.hpp"

namespace felt {
namespace {

constexpr Real kStretch = 0.01;  // m: 4 N at the proxy's 400 N/m
const Vec3 kPush(0, -4, 0);      // on the body: down, away from a proxy above it
constexpr Real kMaxForce = 10;   // N
const ProxyKey kProxy{0, 1};     // the accumulator's key

/// A flat sheet (y = 0, no gravity) and one triangle in its middle, touched at its centroid.
struct Sheet {
  Scene scene;
  BodyId body = 0;
  Triangle corners{};
  Vec3 barycentric = Vec3::Constant(1.0 / 3);

  explicit Sheet(Real time_step = 1e-3) : scene(flat_cloth_scene(Vec3::Zero(), time_step)) {
    const auto snapshot = make_snapshot(scene.world);
    body = snapshot->bodies[0].body_id;
    corners = snapshot->bodies[0].triangles()[snapshot->bodies[0].triangles().size() / 2];
  }
  Vec3 touched() const {
    Vec3 point = Vec3::Zero();
    for (int c = 0; c < 3; ++c) point += barycentric[c] * particles()[corners[c]];
    return point;
  }
  const std::vector<Vec3>& particles() const { return scene.world.cloths()[0].state().x; }
  /// Moves the triangle's corners `dy` up (the surface pressed into the proxy) or down.
  void move(Real dy) {
    for (std::uint32_t corner : corners) scene.world.cloths()[0].state().x[corner].y() += dy;
  }
  /// `force` on the triangle as the reaction of the proxy's spring stretched by kStretch now.
  ProxySample contact(const Vec3& force) const {
    ProxySample sample;
    const Vec3 up(0, 1, 0);
    sample.push = ProxySample::Push{
        body, corners, barycentric, force,
        ContactSpring{400, touched() + up * (0.05 - kStretch), up, kStretch, touched(), kMaxForce}};
    return sample;
  }
  ProxySample plain(const Vec3& force) const {
    ProxySample sample;
    sample.push = ProxySample::Push{body, corners, barycentric, force, std::nullopt};
    return sample;
  }
  void step(ReactionAccumulator& reactions) {
    reactions.apply_and_clear(scene.world);
    EXPECT_EQ(scene.world.step().flags, StepFlags{});
  }
};

void expect_same(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR((a[i] - b[i]).norm(), 0, 1e-12) << "particle " << i;
  }
}

// A push rendered for where the surface was is applied as its spring against where the surface
// is: a surface that gave way by half the stretch gets half the push, one that gave way by more
// gets none, one pressed further in gets more, up to the proxy's largest force.
TEST(ReactionAccumulator, AContactPushesAsItsSpringAgainstTheSurfaceTheStepFinds) {
  struct Case {
    Real moved;  // m, up: into the proxy
    Real scale;  // of the push rendered
  };
  for (const Case& c : {Case{0, 1}, Case{-0.005, 0.5}, Case{-0.02, 0}, Case{0.01, 2},
                        Case{0.05, kMaxForce / kPush.norm()}}) {
    SCOPED_TRACE(c.moved);
    Sheet contact;
    ReactionAccumulator springs;
    springs.record(kProxy, contact.contact(kPush));
    contact.move(c.moved);
    contact.step(springs);

    Sheet plain;
    ReactionAccumulator pushes;
    pushes.record(kProxy, plain.plain(c.scale * kPush));
    plain.move(c.moved);
    plain.step(pushes);
    expect_same(contact.particles(), plain.particles());
  }
}

// At a 10 ms step the touched point (a third of a 1.65 g particle at each corner: an inverse
// mass w of 202 /kg) takes at most 1 / (w h²) = 49.5 N/m explicitly, not the proxy's 400: the
// surface's motion counts with that stiffness, so a surface that gave way by 5 mm keeps 94 % of
// the push, not the 50 % that would overshoot.
TEST(ReactionAccumulator, AtALongStepTheMotionCountsWithTheStiffnessTheTouchedPointTakes) {
  const Real h = 0.01;
  Sheet contact(h);
  const Real mass = 0.2 / 121;  // the sheet's particles
  const Real inverse_mass = 3 * (1.0 / 9) / mass;
  const Real stiffness = 1 / (inverse_mass * h * h);
  ASSERT_NEAR(stiffness, 49.5, 0.1);
  ReactionAccumulator springs;
  springs.record(kProxy, contact.contact(kPush));
  contact.move(-0.005);
  contact.step(springs);

  Sheet plain(h);
  ReactionAccumulator pushes;
  pushes.record(kProxy, plain.plain((kStretch - stiffness / 400 * 0.005) / kStretch * kPush));
  plain.move(-0.005);
  plain.step(pushes);
  expect_same(contact.particles(), plain.particles());
}

// A held push (no update since the last step) whose contact took in no energy (the device was
// still, the spring already stretched when the contact was seen) and whose first step moved the
// sheet away: the sheet took energy out of the contact, so the push is withheld from the sheet
// while it goes on giving way. Pressed back into the proxy, it is pushed again.
TEST(ReactionAccumulator, AHeldContactInDeficitDoesNotPushASurfaceThatGivesWayUnderIt) {
  Sheet contact;
  ReactionAccumulator springs;
  springs.record(kProxy, contact.contact(kPush));
  contact.step(springs);  // pushed: the corners move down
  contact.step(springs);  // held, and withheld

  Sheet twin;  // the same first step, and no push at the second
  ReactionAccumulator first;
  first.record(kProxy, twin.plain(kPush));
  twin.step(first);
  ReactionAccumulator none;
  twin.step(none);
  expect_same(contact.particles(), twin.particles());

  // pressed 5 mm back up into the proxy: the spring pushes down again
  contact.move(0.005);
  twin.move(0.005);
  contact.step(springs);
  twin.step(none);
  EXPECT_LT(contact.touched().y(), twin.touched().y() - 1e-9);
}

}  // namespace
}  // namespace felt
