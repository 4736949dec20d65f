// Cost of the 3×3 polar decomposition F = R S, the inner loop of corotated FEM (one per element
// per force evaluation) and of shape matching (one per cluster per step): the Newton iteration
// that polar_decomposition uses against the singular value decomposition it falls back on,
// on the kinds of F the models see, and the FEM forces of a whole lattice.

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "core/math/polar_decomposition.hpp"
#include "core/solids/corotated_fem.hpp"
#include "core/solids/tet_lattice.hpp"

namespace felt {
namespace {

constexpr int kMatrices = 1024;

Mat3 random_rotation(std::mt19937& random) {
  std::normal_distribution<Real> normal;
  const Eigen::Quaternion<Real> q(normal(random), normal(random), normal(random), normal(random));
  return q.normalized().toRotationMatrix();
}

/// R (I + E) with E symmetric, its entries uniform in [−strain, strain]: an element or a
/// cluster turned by R and strained by about `strain`, times `scale` (cluster moments Σ x qᵀ
/// are in m², not dimensionless); `mirror` reflects it through a plane (an inverted element).
std::vector<Mat3> deformations(Real strain, Real scale, bool mirror) {
  std::mt19937 random(7);
  std::uniform_real_distribution<Real> uniform(-strain, strain);
  std::vector<Mat3> f(kMatrices);
  for (Mat3& m : f) {
    Mat3 e;
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) e(i, j) = e(j, i) = uniform(random);
    }
    m = scale * random_rotation(random) * (Mat3::Identity() + e);
    if (mirror) m.col(0) = -m.col(0);
  }
  return f;
}

struct Kind {
  const char* name;
  Real strain, scale;
  bool mirror;
};

// typical elements of a stiff body (strain 0.1 %), large deformations (10 %, 30 %: never inverted),
// shape matching's cluster moments (m², strain 5 %), and inverted elements
constexpr Kind kKinds[] = {{"strain_0.1_percent", 1e-3, 1, false},
                           {"strain_10_percent", 0.1, 1, false},
                           {"strain_30_percent", 0.3, 1, false},
                           {"cluster_moment", 0.05, 0.02, false},
                           {"inverted", 0.1, 1, true}};

void decompose(benchmark::State& state, PolarDecomposition (*decomposition)(const Mat3&),
               const Kind& kind) {
  const std::vector<Mat3> f = deformations(kind.strain, kind.scale, kind.mirror);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(decomposition(f[i]));
    i = (i + 1) % f.size();
  }
  state.SetItemsProcessed(state.iterations());
}

const bool kRegistered = [] {
  for (const Kind& kind : kKinds) {
    benchmark::RegisterBenchmark((std::string("newton/") + kind.name).c_str(), decompose,
                                 polar_decomposition, kind);
    benchmark::RegisterBenchmark((std::string("svd/") + kind.name).c_str(), decompose,
                                 polar_decomposition_svd, kind);
  }
  return true;
}();

/// The elastic and damping forces of a 5 × 5 × 5-cell lattice (625 tetrahedra) turned by 30°
/// and deformed by up to 2 % of a cell, moving: one force evaluation of a FEM body.
void fem_forces(benchmark::State& state) {
  LatticeGrid grid;
  grid.cells = {5, 5, 5};
  grid.cell_size = Vec3::Constant(0.1);
  const TetMesh mesh = make_box_lattice(grid);
  FemMaterial material;
  material.young_modulus = 2e6;
  material.damping = 1e-4;
  const CorotatedFem model(mesh, material);

  std::mt19937 random(3);
  std::uniform_real_distribution<Real> uniform(-0.002, 0.002);
  const Mat3 turn = Eigen::AngleAxis<Real>(0.52, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<Vec3> x, v;
  for (const Vec3& p : mesh.nodes) {
    x.push_back(turn * p + Vec3(uniform(random), uniform(random), uniform(random)));
    v.push_back(Vec3(uniform(random), uniform(random), uniform(random)) * 100);
  }
  std::vector<Vec3> f(x.size());
  for (auto _ : state) {
    std::ranges::fill(f, Vec3::Zero());
    model.add_forces(x, v, f);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(mesh.tets.size()));
}
BENCHMARK(fem_forces);

}  // namespace
}  // namespace felt
