#include "core/shape_matching.hpp"

#include <gtest/gtest.h>

#include "solid_fixtures.hpp"

namespace felt {
namespace {

using Mode = ShapeMatchingMaterial::Mode;
using test::box;

ShapeMatchingMaterial matching(Mode mode, Real beta, bool clusters) {
  ShapeMatchingMaterial m;
  m.mode = mode;
  m.beta = beta;
  m.clusters = clusters;
  return m;
}

SolidMaterial body_material(const ShapeMatchingMaterial& matching, Real node_mass) {
  SolidMaterial m;
  m.model = SolidModel::kShapeMatching;
  m.node_mass = node_mass;
  m.shape_matching = matching;
  return m;
}

std::vector<Vec3> goals(const ShapeMatching& model, std::span<const Vec3> x) {
  std::vector<Vec3> g(x.size());
  model.goals(x, g);
  return g;
}

Real largest_distance(std::span<const Vec3> a, std::span<const Vec3> b) {
  Real d = 0;
  for (std::size_t n = 0; n < a.size(); ++n) d = std::max(d, (a[n] - b[n]).norm());
  return d;
}

// Every mode, with one cluster or many, matches a rigidly moved body exactly: no force.
TEST(ShapeMatching, RigidMotionHasNoForce) {
  const TetMesh mesh = box({3, 2, 2}, 0.5);
  const std::vector<Vec3> x =
      test::moved(mesh.nodes, test::rotation(Vec3(1, -2, 1), 2.5), Vec3(3, 1, -2));
  const Vec3 omega(1, 0.5, -2);
  std::vector<Vec3> v;
  for (const Vec3& p : x) v.push_back(Vec3(0.3, 0, 1) + omega.cross(p));
  for (Mode mode : {Mode::kRigid, Mode::kLinear, Mode::kQuadratic}) {
    for (bool clusters : {false, true}) {
      const ShapeMatching model(mesh, matching(mode, 0.5, clusters));
      std::vector<Vec3> f(x.size(), Vec3::Zero());
      model.add_forces(x, v, 0.05, f);
      EXPECT_LT(largest_distance(goals(model, x), x), 1e-12);
      for (const Vec3& fn : f) EXPECT_LT(fn.norm(), 1e-8);
    }
  }
}

// With β = 1 the linear fit reproduces a volume-preserving linear map exactly (least squares
// of an exact fit), and the quadratic fit a quadratic map whose quadratic part has no mean over
// the nodes (the paper's basis q̃ has no constant term to absorb one).
TEST(ShapeMatching, FullFitReproducesLinearAndQuadraticMaps) {
  const TetMesh mesh = box({3, 3, 3}, 1.0 / 3);
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 0.4;  // det 1
  const std::vector<Vec3> linear = test::moved(mesh.nodes, shear, Vec3(1, 2, 3));
  EXPECT_LT(largest_distance(goals(ShapeMatching(mesh, matching(Mode::kLinear, 1, false)), linear),
                             linear),
            1e-12);

  std::vector<Vec3> bent;
  for (const Vec3& p : mesh.nodes) {
    const Vec3 q = p - Vec3::Constant(0.5);  // about the centre of the symmetric lattice
    bent.push_back(p + Vec3(0.3 * q.x() * q.y(), 0.2 * q.y() * q.z(), -0.3 * q.z() * q.x()));
  }
  EXPECT_LT(largest_distance(goals(ShapeMatching(mesh, matching(Mode::kQuadratic, 1, false)), bent),
                             bent),
            1e-10);
  // the linear fit cannot follow the bend
  EXPECT_GT(
      largest_distance(goals(ShapeMatching(mesh, matching(Mode::kLinear, 1, false)), bent), bent),
      1e-3);
}

// A mirrored body is matched by a proper rotation, not by the mirror: the rigid goals are the
// rest shape moved rigidly, with its positive volume.
TEST(ShapeMatching, MirroredBodyIsPulledBackToItsOrientation) {
  const TetMesh mesh = box({3, 2, 1}, 0.5);
  const Real rest_volume = total_volume(mesh.nodes, mesh.tets);
  for (int axis = 0; axis < 3; ++axis) {
    Mat3 mirror = Mat3::Identity();
    mirror(axis, axis) = -1;
    const std::vector<Vec3> x = test::moved(mesh.nodes, mirror, Vec3::Zero());
    ASSERT_LT(total_volume(x, mesh.tets), 0);
    const std::vector<Vec3> g = goals(ShapeMatching(mesh, matching(Mode::kRigid, 0, false)), x);
    EXPECT_NEAR(total_volume(g, mesh.tets), rest_volume, 1e-12);
  }
}

// Lattice cells (five tetrahedra, eight corners) become clusters; other meshes get one
// cluster per tetrahedron.
TEST(ShapeMatching, ClustersAreLatticeCellsOrTetrahedra) {
  EXPECT_EQ(ShapeMatching(box({3, 2, 2}, 1), matching(Mode::kLinear, 0.5, true)).cluster_count(),
            12u);
  EXPECT_EQ(ShapeMatching(box({3, 2, 2}, 1), matching(Mode::kLinear, 0.5, false)).cluster_count(),
            1u);
  TetMesh pair;
  pair.nodes = {Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
  pair.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  orient_positive(pair);
  EXPECT_EQ(ShapeMatching(pair, matching(Mode::kLinear, 0.5, true)).cluster_count(), 2u);
}

/// A bar pinned at x = 0, sagging under gravity from rest, after `duration` at steps of h.
std::vector<Vec3> sagging_bar(const ShapeMatchingMaterial& material, Real h, Real duration) {
  SolidBody body("bar", box({4, 1, 1}, 0.25), body_material(material, 0.05));
  for (std::uint32_t n = 0; n < body.node_count(); ++n) {
    if (body.rest().nodes[n].x() == 0) body.pin(n);
  }
  const int steps = static_cast<int>(std::lround(duration / h));
  for (int s = 0; s < steps; ++s) test::step(body, h, Vec3(0, -9.81, 0));
  return body.positions();
}

// τ sets the behaviour, not the step: halving the step changes the motion only slightly, in
// the middle of the swing and at rest.
TEST(ShapeMatching, MotionDoesNotDependOnTheStep) {
  for (Mode mode : {Mode::kRigid, Mode::kLinear, Mode::kQuadratic}) {
    for (bool clusters : {false, true}) {
      ShapeMatchingMaterial material = matching(mode, 0.3, clusters);
      material.time_constant = 0.03;
      for (Real duration : {0.05, 0.5}) {
        const std::vector<Vec3> coarse = sagging_bar(material, 0.002, duration);
        const std::vector<Vec3> fine = sagging_bar(material, 0.001, duration);
        const std::vector<Vec3> rest = box({4, 1, 1}, 0.25).nodes;
        const Real sag = largest_distance(fine, rest);
        EXPECT_GT(sag, 1e-3);
        EXPECT_LT(largest_distance(coarse, fine), 0.05 * sag)
            << static_cast<int>(mode) << clusters << duration;
      }
    }
  }
}

// In rigid mode a body thrown with a spin and released deformed returns to its shape within
// a few τ and keeps it while it flies and turns.
TEST(ShapeMatching, RigidModeKeepsTheShapeOfAThrownBody) {
  ShapeMatchingMaterial material = matching(Mode::kRigid, 0, false);
  material.time_constant = 0.01;
  SolidBody body("cube", box({2, 2, 2}, 0.5), body_material(material, 0.05));
  const std::vector<Vec3> offsets = test::random_vectors(body.node_count(), 0.05, 9);
  const Vec3 omega(0.5, 2, -1);
  for (std::size_t n = 0; n < body.node_count(); ++n) {
    body.positions()[n] += offsets[n];
    body.velocities()[n] = Vec3(2, 5, 0) + omega.cross(body.positions()[n] - Vec3(0.5, 0.5, 0.5));
  }
  for (int s = 0; s < 100; ++s) test::step(body, 0.005, Vec3(0, -9.81, 0));
  const std::vector<Vec3>& x = body.positions();
  const std::vector<Vec3>& x0 = body.rest().nodes;
  for (std::size_t a = 0; a < x.size(); ++a) {
    for (std::size_t b = a + 1; b < x.size(); ++b) {
      EXPECT_NEAR((x[a] - x[b]).norm(), (x0[a] - x0[b]).norm(), 2e-3);
    }
  }
  EXPECT_GT((x[0] - x0[0]).norm(), 1);  // it did fly
}

/// Length of a bar pinned at x = 0 and pulled along x at its far end for 0.3 s, then left
/// alone for 0.7 s (no gravity).
Real length_after_pull(const ShapeMatchingMaterial& material) {
  SolidBody body("bar", box({4, 1, 1}, 0.25), body_material(material, 0.05));
  std::vector<std::uint32_t> far_end;
  for (std::uint32_t n = 0; n < body.node_count(); ++n) {
    if (body.rest().nodes[n].x() == 0) body.pin(n);
    if (body.rest().nodes[n].x() == 1) far_end.push_back(n);
  }
  constexpr Real kStep = 0.002;
  for (int s = 0; s < 500; ++s) {
    if (s < 150) {
      for (std::uint32_t n : far_end) body.add_external_force(n, Vec3(2, 0, 0));
    }
    test::step(body, kStep, Vec3::Zero());
  }
  Real x = 0;
  for (std::uint32_t n : far_end) x += body.positions()[n].x();
  return x / static_cast<Real>(far_end.size());
}

TEST(ShapeMatching, PlasticBodyKeepsItsDeformationElasticReturns) {
  ShapeMatchingMaterial material = matching(Mode::kLinear, 0.5, false);
  material.time_constant = 0.02;
  EXPECT_NEAR(length_after_pull(material), 1, 0.005);
  material.plastic_yield = 0.02;
  material.plastic_creep = 10;
  material.plastic_max = 1;
  EXPECT_GT(length_after_pull(material), 1.02);
}

}  // namespace
}  // namespace felt
