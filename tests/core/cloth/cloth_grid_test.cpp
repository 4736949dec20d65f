// make_grid_cloth and grid_pin_indices against closed-form counts, a brute-force enumeration of
// neighbour pairs and geometry recomputed from the positions.

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/cloth/cloth_grid.hpp"
#include "core/math/check.hpp"

namespace felt {
namespace {

using Plane = GridClothSpec::Plane;

struct Size {
  std::uint32_t nx;
  std::uint32_t ny;
};
const Size kSizes[] = {{2, 2}, {3, 2}, {2, 3}, {3, 3}, {4, 5}, {7, 3}, {10, 10}, {2, 9}};

GridClothSpec make_spec(Size size, Plane plane) {
  GridClothSpec spec;
  spec.width = 1.5;
  spec.height = 0.8;
  spec.nx = size.nx;
  spec.ny = size.ny;
  spec.total_mass = 0.3;
  spec.center = Vec3(0.25, 2.0, -1.0);
  spec.plane = plane;
  return spec;
}

using Pair = std::pair<std::uint32_t, std::uint32_t>;
Pair unordered(std::uint32_t a, std::uint32_t b) {
  return {std::min(a, b), std::max(a, b)};
}

// Every particle pair whose grid offset makes it a spring of `kind` (thesis 1 §3).
std::set<Pair> expected_pairs(std::uint32_t nx, std::uint32_t ny, SpringKind kind) {
  std::set<Pair> pairs;
  const std::uint32_t n = nx * ny;
  for (std::uint32_t p = 0; p < n; ++p) {
    for (std::uint32_t q = p + 1; q < n; ++q) {
      const int di = std::abs(static_cast<int>(p % nx) - static_cast<int>(q % nx));
      const int dj = std::abs(static_cast<int>(p / nx) - static_cast<int>(q / nx));
      const bool structural = di + dj == 1;
      const bool shear = di == 1 && dj == 1;
      const bool bend = (di == 2 && dj == 0) || (di == 0 && dj == 2);
      if ((kind == SpringKind::kStructural && structural) ||
          (kind == SpringKind::kShear && shear) || (kind == SpringKind::kBend && bend)) {
        pairs.insert({p, q});
      }
    }
  }
  return pairs;
}

TEST(ClothGrid, CountsMatchClosedForms) {
  for (Size size : kSizes) {
    SCOPED_TRACE(testing::Message() << size.nx << "x" << size.ny);
    const std::size_t nx = size.nx, ny = size.ny;
    const ClothModel m = make_grid_cloth(make_spec(size, Plane::kXY));
    EXPECT_EQ(m.particle_count(), nx * ny);
    EXPECT_EQ(m.uv.size(), nx * ny);
    EXPECT_EQ(m.mass.size(), nx * ny);
    std::size_t counts[kSpringKindCount] = {};
    for (const Spring& s : m.springs) ++counts[static_cast<int>(s.kind)];
    EXPECT_EQ(counts[0], (nx - 1) * ny + nx * (ny - 1));
    EXPECT_EQ(counts[1], 2 * (nx - 1) * (ny - 1));
    EXPECT_EQ(counts[2], (nx - 2) * ny + nx * (ny - 2));
    EXPECT_EQ(m.triangles.size(), 2 * (nx - 1) * (ny - 1));
  }
}

TEST(ClothGrid, SpringsConnectExactlyTheGridNeighbours) {
  for (Size size : kSizes) {
    SCOPED_TRACE(testing::Message() << size.nx << "x" << size.ny);
    const ClothModel m = make_grid_cloth(make_spec(size, Plane::kXY));
    for (SpringKind kind : {SpringKind::kStructural, SpringKind::kShear, SpringKind::kBend}) {
      std::set<Pair> got;
      for (const Spring& s : m.springs) {
        if (s.kind != kind) continue;
        EXPECT_NE(s.i, s.j);
        EXPECT_TRUE(got.insert(unordered(s.i, s.j)).second) << "duplicate " << s.i << "-" << s.j;
      }
      EXPECT_EQ(got, expected_pairs(size.nx, size.ny, kind)) << static_cast<int>(kind);
    }
  }
}

TEST(ClothGrid, RestLengthsAreTheRestDistances) {
  for (Plane plane : {Plane::kXY, Plane::kXZ}) {
    for (Size size : kSizes) {
      SCOPED_TRACE(testing::Message() << size.nx << "x" << size.ny);
      const GridClothSpec spec = make_spec(size, plane);
      const ClothModel m = make_grid_cloth(spec);
      const Real dx = spec.width / (size.nx - 1);
      const Real dy = spec.height / (size.ny - 1);
      for (const Spring& s : m.springs) {
        const Real actual = (m.rest_positions[s.i] - m.rest_positions[s.j]).norm();
        EXPECT_NEAR(s.rest_length, actual, 1e-12);
        // and by hand from the grid spacing
        const Real di = std::abs(static_cast<Real>(s.i % size.nx) - s.j % size.nx);
        const Real dj = std::abs(static_cast<Real>(s.i / size.nx) - s.j / size.nx);
        EXPECT_NEAR(s.rest_length, std::hypot(di * dx, dj * dy), 1e-12);
      }
    }
  }
}

TEST(ClothGrid, MassesAreEqualAndSumToTotal) {
  for (Size size : kSizes) {
    const GridClothSpec spec = make_spec(size, Plane::kXY);
    const ClothModel m = make_grid_cloth(spec);
    Real sum = 0;
    for (Real mass : m.mass) {
      EXPECT_NEAR(mass, spec.total_mass / (size.nx * size.ny), 1e-15);
      sum += mass;
    }
    EXPECT_NEAR(sum, spec.total_mass, 1e-12);
  }
}

TEST(ClothGrid, BoundingBoxIsTheRectangleAroundTheCentre) {
  for (Plane plane : {Plane::kXY, Plane::kXZ}) {
    for (Size size : kSizes) {
      SCOPED_TRACE(testing::Message() << size.nx << "x" << size.ny);
      const GridClothSpec spec = make_spec(size, plane);
      const ClothModel m = make_grid_cloth(spec);
      Vec3 lo = m.rest_positions[0], hi = m.rest_positions[0];
      for (const Vec3& x : m.rest_positions) {
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
      }
      const Vec3 extent =
          plane == Plane::kXY ? Vec3(spec.width, spec.height, 0) : Vec3(spec.width, 0, spec.height);
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(hi[k] - lo[k], extent[k], 1e-12) << k;
        EXPECT_NEAR((hi[k] + lo[k]) / 2, spec.center[k], 1e-12) << k;
      }
    }
  }
}

TEST(ClothGrid, ParticleIndexFollowsRowsAndColumns) {
  // (i, j) has index j·nx + i; i runs along +x, j runs down (−y) or along +z
  const Size size{4, 3};
  for (Plane plane : {Plane::kXY, Plane::kXZ}) {
    const GridClothSpec spec = make_spec(size, plane);
    const ClothModel m = make_grid_cloth(spec);
    const Real dx = spec.width / 3, dy = spec.height / 2;
    for (std::uint32_t j = 0; j < size.ny; ++j) {
      for (std::uint32_t i = 0; i < size.nx; ++i) {
        const Vec3& x = m.rest_positions[j * size.nx + i];
        EXPECT_NEAR(x.x(), spec.center.x() - spec.width / 2 + i * dx, 1e-12);
        if (plane == Plane::kXY) {
          EXPECT_NEAR(x.y(), spec.center.y() + spec.height / 2 - j * dy, 1e-12);
          EXPECT_NEAR(x.z(), spec.center.z(), 1e-15);
        } else {
          EXPECT_NEAR(x.z(), spec.center.z() - spec.height / 2 + j * dy, 1e-12);
          EXPECT_NEAR(x.y(), spec.center.y(), 1e-15);
        }
      }
    }
  }
}

TEST(ClothGrid, TriangleNormalsFaceTheViewer) {
  for (Plane plane : {Plane::kXY, Plane::kXZ}) {
    const Vec3 want = plane == Plane::kXY ? Vec3(0, 0, 1) : Vec3(0, 1, 0);
    for (Size size : kSizes) {
      SCOPED_TRACE(testing::Message() << size.nx << "x" << size.ny);
      const GridClothSpec spec = make_spec(size, plane);
      const ClothModel m = make_grid_cloth(spec);
      Real area = 0;
      for (const Triangle& t : m.triangles) {
        ASSERT_LT(t[0], m.particle_count());
        ASSERT_LT(t[1], m.particle_count());
        ASSERT_LT(t[2], m.particle_count());
        const Vec3& a = m.rest_positions[t[0]];
        const Vec3& b = m.rest_positions[t[1]];
        const Vec3& c = m.rest_positions[t[2]];
        // cross product written out, not Eigen's, so the check does not share code
        const Vec3 u = b - a, v = c - a;
        const Vec3 n(u.y() * v.z() - u.z() * v.y(), u.z() * v.x() - u.x() * v.z(),
                     u.x() * v.y() - u.y() * v.x());
        ASSERT_GT(n.norm(), 0);
        EXPECT_NEAR((n / n.norm() - want).norm(), 0, 1e-12);
        area += n.norm() / 2;
      }
      // the triangles tile the rectangle without overlap
      EXPECT_NEAR(area, spec.width * spec.height, 1e-12);
    }
  }
}

TEST(ClothGrid, EveryCellEdgeIsSharedByAtMostTwoTriangles) {
  const ClothModel m = make_grid_cloth(make_spec({5, 4}, Plane::kXY));
  std::multiset<Pair> edges;
  for (const Triangle& t : m.triangles) {
    for (int k = 0; k < 3; ++k) edges.insert(unordered(t[k], t[(k + 1) % 3]));
  }
  // V − E + F = 1 for a disc: 20 − E + 24 = 1
  const std::set<Pair> unique(edges.begin(), edges.end());
  EXPECT_EQ(unique.size(), 43u);
  for (const Pair& e : unique) EXPECT_LE(edges.count(e), 2u);
}

TEST(ClothGrid, UvCoversTheUnitSquare) {
  for (Size size : kSizes) {
    const ClothModel m = make_grid_cloth(make_spec(size, Plane::kXY));
    for (std::uint32_t p = 0; p < m.particle_count(); ++p) {
      const Vec2& uv = m.uv[p];
      EXPECT_GE(uv.x(), 0);
      EXPECT_LE(uv.x(), 1);
      EXPECT_GE(uv.y(), 0);
      EXPECT_LE(uv.y(), 1);
      EXPECT_NEAR(uv.x(), static_cast<Real>(p % size.nx) / (size.nx - 1), 1e-15);
      EXPECT_NEAR(uv.y(), static_cast<Real>(p / size.nx) / (size.ny - 1), 1e-15);
    }
    EXPECT_EQ(m.uv.front(), Vec2(0, 0));
    EXPECT_EQ(m.uv.back(), Vec2(1, 1));
  }
}

// Indices, in increasing order, of the particles whose rest position satisfies `predicate`.
std::vector<std::uint32_t> particles_where(const ClothModel& m, auto predicate) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t p = 0; p < m.particle_count(); ++p) {
    if (predicate(m.rest_positions[p])) out.push_back(p);
  }
  return out;
}

std::vector<std::uint32_t> sorted(std::vector<std::uint32_t> v) {
  std::sort(v.begin(), v.end());
  return v;
}

TEST(ClothGrid, PinPresetsSelectTheRightParticles) {
  for (Plane plane : {Plane::kXY, Plane::kXZ}) {
    for (Size size : kSizes) {
      SCOPED_TRACE(testing::Message()
                   << (plane == Plane::kXY ? "XY " : "XZ ") << size.nx << "x" << size.ny);
      const GridClothSpec spec = make_spec(size, plane);
      const ClothModel m = make_grid_cloth(spec);
      const Real x_lo = spec.center.x() - spec.width / 2, x_hi = spec.center.x() + spec.width / 2;
      // "top" is the j = 0 edge: highest y when hanging, lowest z when lying (rows go along +z)
      auto on_top = [&](const Vec3& x) {
        return plane == Plane::kXY ? std::abs(x.y() - (spec.center.y() + spec.height / 2)) < 1e-9
                                   : std::abs(x.z() - (spec.center.z() - spec.height / 2)) < 1e-9;
      };
      auto on_bottom = [&](const Vec3& x) {
        return plane == Plane::kXY ? std::abs(x.y() - (spec.center.y() - spec.height / 2)) < 1e-9
                                   : std::abs(x.z() - (spec.center.z() + spec.height / 2)) < 1e-9;
      };
      auto on_side = [&](const Vec3& x) {
        return std::abs(x.x() - x_lo) < 1e-9 || std::abs(x.x() - x_hi) < 1e-9;
      };

      EXPECT_TRUE(grid_pin_indices(spec, GridPinPreset::kNone).empty());

      const auto top_corners = grid_pin_indices(spec, GridPinPreset::kTopCorners);
      EXPECT_EQ(top_corners.size(), 2u);
      EXPECT_EQ(sorted(top_corners),
                particles_where(m, [&](const Vec3& x) { return on_top(x) && on_side(x); }));

      const auto four = grid_pin_indices(spec, GridPinPreset::kFourCorners);
      EXPECT_EQ(four.size(), 4u);
      EXPECT_EQ(sorted(four), particles_where(m, [&](const Vec3& x) {
                  return (on_top(x) || on_bottom(x)) && on_side(x);
                }));

      const auto row = grid_pin_indices(spec, GridPinPreset::kTopRow);
      EXPECT_EQ(row.size(), size.nx);
      EXPECT_EQ(sorted(row), particles_where(m, on_top));
    }
  }
}

TEST(ClothGrid, TopCornersAreHighestWhenHanging) {
  const GridClothSpec spec = make_spec({6, 4}, Plane::kXY);
  const ClothModel m = make_grid_cloth(spec);
  Real max_y = -1e300;
  for (const Vec3& x : m.rest_positions) max_y = std::max(max_y, x.y());
  for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) {
    EXPECT_EQ(m.rest_positions[p].y(), max_y);
  }
  const auto corners = grid_pin_indices(spec, GridPinPreset::kTopCorners);
  ASSERT_EQ(corners.size(), 2u);
  // one at each side: left and right top corners
  EXPECT_NEAR(std::abs(m.rest_positions[corners[0]].x() - m.rest_positions[corners[1]].x()),
              spec.width, 1e-12);
}

// Turns a failed FELT_CHECK into an exception for the duration of a test.
class ThrowingChecks {
 public:
  ThrowingChecks()
      : previous_(set_check_handler([](const char* expression, const std::source_location&) {
          throw std::logic_error(expression);
        })) {}
  ~ThrowingChecks() { set_check_handler(std::move(previous_)); }

 private:
  CheckHandler previous_;
};

TEST(ClothGrid, RejectsInvalidSpecs) {
  ThrowingChecks checks;
  GridClothSpec spec;
  spec.nx = 1;
  EXPECT_THROW(make_grid_cloth(spec), std::logic_error);
  spec = {};
  spec.ny = 1;
  EXPECT_THROW(make_grid_cloth(spec), std::logic_error);
  spec = {};
  spec.width = 0;
  EXPECT_THROW(make_grid_cloth(spec), std::logic_error);
  spec = {};
  spec.height = -1;
  EXPECT_THROW(make_grid_cloth(spec), std::logic_error);
  spec = {};
  spec.total_mass = 0;
  EXPECT_THROW(make_grid_cloth(spec), std::logic_error);
  spec = {};
  EXPECT_NO_THROW(make_grid_cloth(spec));
}

}  // namespace
}  // namespace felt
