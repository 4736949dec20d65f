// The springs' colouring (Fratarcangeli et al. 2016): every spring in exactly one class, no two
// springs of a class on one particle, and no more classes than greedy colouring needs at most
// (2Δ − 1, Δ the most springs on a particle) nor fewer than that particle needs (Δ); on a grid,
// on irregular meshes, and as ClothBody hands the classes to XPBD.

#include "core/cloth/spring_colouring.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "core/cloth/cloth_body.hpp"
#include "core/cloth/cloth_grid.hpp"
#include "core/cloth/mesh_cloth.hpp"
#include "core/geometry/procedural_surfaces.hpp"

namespace felt::test {
namespace {

/// The most springs on one particle.
std::size_t max_degree(const ClothModel& model) {
  std::vector<std::size_t> degree(model.particle_count(), 0);
  for (const Spring& s : model.springs) {
    ++degree[s.i];
    ++degree[s.j];
  }
  return *std::max_element(degree.begin(), degree.end());
}

/// Whether no two of the pairs (i, j) share a particle.
template <typename Pair>
bool independent(std::span<const Pair> pairs, std::size_t particle_count) {
  std::vector<bool> used(particle_count, false);
  for (const Pair& p : pairs) {
    if (used[p.i] || used[p.j]) return false;
    used[p.i] = used[p.j] = true;
  }
  return true;
}

void expect_valid_colouring(const ClothModel& model) {
  const SpringColouring colouring = colour_springs(model.springs, model.particle_count());
  // every spring once
  std::vector<std::uint32_t> sorted = colouring.order;
  std::sort(sorted.begin(), sorted.end());
  ASSERT_EQ(sorted.size(), model.springs.size());
  for (std::uint32_t s = 0; s < sorted.size(); ++s) ASSERT_EQ(sorted[s], s);
  ASSERT_EQ(colouring.class_ends.back(), model.springs.size());
  std::uint32_t begin = 0;
  for (const std::uint32_t end : colouring.class_ends) {
    ASSERT_LT(begin, end);  // no empty class
    std::vector<Spring> members;
    for (std::uint32_t k = begin; k < end; ++k)
      members.push_back(model.springs[colouring.order[k]]);
    EXPECT_TRUE(independent<Spring>(members, model.particle_count())) << "class ending " << end;
    begin = end;
  }
  const std::size_t degree = max_degree(model);
  std::printf("  %zu springs, %zu particles: %zu classes (most springs on a particle %zu)\n",
              model.springs.size(), model.particle_count(), colouring.class_count(), degree);
  EXPECT_GE(colouring.class_count(), degree);
  EXPECT_LE(colouring.class_count(), 2 * degree - 1);
}

TEST(SpringColouring, GridWithStructuralShearAndBendSpringsColoursIntoAHandfulOfClasses) {
  GridClothSpec spec;
  spec.nx = 40;
  spec.ny = 30;
  const ClothModel model = make_grid_cloth(spec);
  expect_valid_colouring(model);
  // 12 springs on an inner particle; greedy in the grid's order needs one class more
  EXPECT_LE(colour_springs(model.springs, model.particle_count()).class_count(), 13u);
}

TEST(SpringColouring, IrregularMeshesColourValidly) {
  // an icosphere (particles with 5 and 6 neighbours and bend springs across every edge) and a
  // box (corners, edges and faces meeting differently)
  expect_valid_colouring(make_mesh_cloth(make_sphere_surface(1, 3), 1));
  expect_valid_colouring(make_mesh_cloth(make_box_surface(Vec3(1, 2, 3), 4), 1));
  // a fan of 100 triangles around one particle: 200 springs there, beyond any fixed-width mask
  TriangleMesh fan;
  fan.positions.push_back(Vec3::Zero());
  for (int k = 0; k <= 100; ++k) {
    fan.positions.push_back(Vec3(std::cos(k * 0.06), std::sin(k * 0.06), 0));
  }
  for (std::uint32_t k = 1; k <= 100; ++k) fan.triangles.push_back({0, k, k + 1});
  expect_valid_colouring(make_mesh_cloth(fan, 1));
}

TEST(SpringColouring, ClothBodyGivesXpbdTheEnabledSpringsInIndependentClasses) {
  GridClothSpec spec;
  spec.nx = spec.ny = 12;
  const auto model = std::make_shared<const ClothModel>(make_grid_cloth(spec));
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, 100, 0.1};
  params.spring(SpringKind::kShear) = {false, 20, 0};
  params.spring(SpringKind::kBend) = {true, 5, 0.01};
  ClothBody body("c", model, params, make_integrator("xpbd"));
  ConstraintClasses classes;
  ASSERT_TRUE(body.distance_constraints(classes));
  const auto enabled = std::count_if(model->springs.begin(), model->springs.end(),
                                     [](const Spring& s) { return s.kind != SpringKind::kShear; });
  EXPECT_EQ(classes.constraints.size(), static_cast<std::size_t>(enabled));
  EXPECT_EQ(classes.class_ends.back(), classes.constraints.size());
  std::size_t begin = 0;
  for (const std::size_t end : classes.class_ends) {
    ASSERT_LT(begin, end);  // the classes of disabled springs only are left out
    EXPECT_TRUE(independent<DistanceConstraint>(
        std::span(classes.constraints).subspan(begin, end - begin), model->particle_count()));
    begin = end;
  }
  for (const DistanceConstraint& c : classes.constraints) {
    EXPECT_TRUE(c.stiffness == 100 || c.stiffness == 5);
  }
}

}  // namespace
}  // namespace felt::test
