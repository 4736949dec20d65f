#include "core/solids/corotated_fem.hpp"

#include <Eigen/LU>

#include "core/math/check.hpp"
#include "core/math/largest_eigenvalue.hpp"
#include "core/math/polar_decomposition.hpp"

namespace felt {
namespace {

/// The isotropic linear stress of a small strain.
Mat3 linear_stress(const Mat3& strain, Real mu, Real lambda) {
  return 2 * mu * strain + lambda * strain.trace() * Mat3::Identity();
}

}  // namespace

CorotatedFem::CorotatedFem(const TetMesh& rest, const FemMaterial& material)
    : damping_(material.damping), node_count_(rest.nodes.size()) {
  const Real e = material.young_modulus;
  const Real nu = material.poisson_ratio;
  FELT_CHECK(e > 0 && nu > -1 && nu < 0.5 && material.damping >= 0);
  mu_ = e / (2 * (1 + nu));
  lambda_ = e * nu / ((1 + nu) * (1 - 2 * nu));

  elements_.reserve(rest.tets.size());
  std::vector<Eigen::Triplet<Real>> stiffness;
  for (const Tetrahedron& t : rest.tets) {
    const std::span<const Vec3> x = rest.nodes;
    Mat3 shape;
    shape << x[t[1]] - x[t[0]], x[t[2]] - x[t[0]], x[t[3]] - x[t[0]];
    const Real volume = shape.determinant() / 6;
    FELT_CHECK(volume > 0);
    const Element element{t, shape.inverse(), volume};
    elements_.push_back(element);

    // shape-function gradients; K_ab = V₀ (μ (g_a·g_b) I + μ g_b g_aᵀ + λ g_a g_bᵀ)
    std::array<Vec3, 4> g;
    for (int a = 0; a < 3; ++a) g[a + 1] = element.rest_inverse.row(a).transpose();
    g[0] = -(g[1] + g[2] + g[3]);
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        const Mat3 block =
            volume * (mu_ * g[a].dot(g[b]) * Mat3::Identity() + mu_ * g[b] * g[a].transpose() +
                      lambda_ * g[a] * g[b].transpose());
        add_block(stiffness, t[a], t[b], block);
      }
    }
  }
  rest_stiffness_ = block_matrix(node_count_, stiffness);
  largest_stiffness_ = largest_eigenvalue(rest_stiffness_);
}

Mat3 CorotatedFem::deformation_gradient(const Element& e, std::span<const Vec3> x) {
  const Tetrahedron& t = e.nodes;
  Mat3 shape;
  shape << x[t[1]] - x[t[0]], x[t[2]] - x[t[0]], x[t[3]] - x[t[0]];
  return shape * e.rest_inverse;
}

void CorotatedFem::add_forces(std::span<const Vec3> x, std::span<const Vec3> v, std::span<Vec3> f,
                              NodeMask mask) const {
  FELT_CHECK(x.size() == node_count_ && v.size() == x.size() && f.size() == x.size());
  FELT_CHECK(mask.empty() || mask.size() == x.size());
  for (const Element& e : elements_) {
    if (!acts_on_selected(mask, e.nodes)) continue;
    const Mat3 deformation = deformation_gradient(e, x);
    const PolarDecomposition polar = polar_decomposition(deformation);
    Mat3 piola = polar.rotation * linear_stress(polar.stretch - Mat3::Identity(), mu_, lambda_);
    if (damping_ > 0) {
      // Kelvin–Voigt on the Green strain rate sym(Fᵀ Ḟ): β K at rest like β R K Rᵀ v, but blind
      // to rigid spin and free of net torque in any deformed state, which R K Rᵀ v is not
      const Mat3 rate = deformation.transpose() * deformation_gradient(e, v);
      piola +=
          damping_ * deformation * linear_stress(0.5 * (rate + rate.transpose()), mu_, lambda_);
    }
    const Mat3 forces = -e.rest_volume * piola * e.rest_inverse.transpose();
    const Tetrahedron& t = e.nodes;
    for (int a = 0; a < 3; ++a) f[t[a + 1]] += forces.col(a);
    f[t[0]] -= forces.rowwise().sum();
  }
}

Real CorotatedFem::energy(std::span<const Vec3> x) const {
  FELT_CHECK(x.size() == node_count_);
  Real energy = 0;
  for (const Element& e : elements_) {
    const Mat3 strain = polar_decomposition(deformation_gradient(e, x)).stretch - Mat3::Identity();
    const Real trace = strain.trace();
    energy += e.rest_volume * (mu_ * strain.squaredNorm() + 0.5 * lambda_ * trace * trace);
  }
  return energy;
}

}  // namespace felt
