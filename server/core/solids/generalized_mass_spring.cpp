#include "core/solids/generalized_mass_spring.hpp"

#include <array>

#include "core/math/check.hpp"
#include "core/math/largest_eigenvalue.hpp"

namespace felt {
namespace {

/// ∂(6V)/∂x_m for the four corners of a tetrahedron (thesis 2 (6.2)).
std::array<Vec3, 4> six_volume_gradient(std::span<const Vec3> x, const Tetrahedron& t) {
  const Vec3 xij = x[t[1]] - x[t[0]];
  const Vec3 xik = x[t[2]] - x[t[0]];
  const Vec3 xil = x[t[3]] - x[t[0]];
  const Vec3 gj = xik.cross(xil);
  const Vec3 gk = xil.cross(xij);
  const Vec3 gl = xij.cross(xik);
  return {-(gj + gk + gl), gj, gk, gl};
}

/// ∂A/∂x_m for the three corners of a triangle; zero for a degenerate one.
std::array<Vec3, 3> area_gradient(std::span<const Vec3> x, const Triangle& t) {
  const Vec3 a = x[t[1]] - x[t[0]];
  const Vec3 b = x[t[2]] - x[t[0]];
  const Vec3 normal = a.cross(b);
  const Real length = normal.norm();
  if (length == 0) return {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  const Vec3 unit = normal / length;
  const Vec3 gj = 0.5 * b.cross(unit);
  const Vec3 gk = 0.5 * unit.cross(a);
  return {-(gj + gk), gj, gk};
}

Real triangle_area(std::span<const Vec3> x, const Triangle& t) {
  return 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
}

/// Adds the blocks k ∇_a C ∇_b Cᵀ of the rank-one matrix k ∇C ∇Cᵀ: an element's stiffness (or
/// damping) at rest, where C = 0 leaves only this term of the Hessian of ½ k C².
template <std::size_t N>
void add_rank_one_blocks(const std::array<Vec3, N>& gradient,
                         const std::array<std::uint32_t, N>& nodes, Real k,
                         std::vector<Eigen::Triplet<Real>>& triplets) {
  for (std::size_t a = 0; a < N; ++a) {
    for (std::size_t b = 0; b < N; ++b) {
      add_block(triplets, nodes[a], nodes[b], k * gradient[a] * gradient[b].transpose());
    }
  }
}

}  // namespace

GeneralizedMassSpring::GeneralizedMassSpring(const TetMesh& rest, const TetTopology& topology,
                                             const MassSpringMaterial& material)
    : material_(material), node_count_(rest.nodes.size()) {
  FELT_CHECK(material.distance_stiffness >= 0 && material.volume_stiffness >= 0 &&
             material.damping >= 0 && material.area_stiffness >= 0);
  const std::span<const Vec3> x = rest.nodes;
  std::vector<Eigen::Triplet<Real>> stiffness, damping;

  springs_.reserve(topology.edges.size());
  for (const Edge& e : topology.edges) {
    const Real length = (x[e[1]] - x[e[0]]).norm();
    FELT_CHECK(length > 0);
    springs_.push_back({e, length});
    const Vec3 unit = (x[e[1]] - x[e[0]]) / (length * length);  // |∂C/∂x| = 1/l₀
    const std::array<Vec3, 2> gradient = {-unit, unit};
    add_rank_one_blocks(gradient, e, material.distance_stiffness, stiffness);
    add_rank_one_blocks(gradient, e, material.damping, damping);
  }

  volumes_.reserve(rest.tets.size());
  for (const Tetrahedron& t : rest.tets) {
    const Real volume = signed_volume(x, t);
    FELT_CHECK(volume > 0);
    volumes_.push_back({t, volume});
    // energy 3 k_V V₀ C² with ∇C = ∇(6V)/(6V₀): K = k_V ∇(6V) ∇(6V)ᵀ / (6V₀)
    add_rank_one_blocks(six_volume_gradient(x, t), t, material.volume_stiffness / (6 * volume),
                        stiffness);
  }

  if (material.area_stiffness > 0) {
    areas_.reserve(topology.surface.size());
    for (const Triangle& t : topology.surface) {
      const Real area = triangle_area(x, t);
      FELT_CHECK(area > 0);
      areas_.push_back({t, area});
      add_rank_one_blocks(area_gradient(x, t), t, material.area_stiffness / (area * area),
                          stiffness);
    }
  }
  rest_stiffness_ = block_matrix(node_count_, stiffness);
  largest_stiffness_ = largest_eigenvalue(rest_stiffness_);
  largest_damping_ = largest_eigenvalue(block_matrix(node_count_, damping));
}

void GeneralizedMassSpring::add_forces(std::span<const Vec3> x, std::span<const Vec3> v,
                                       std::span<Vec3> f, NodeMask mask) const {
  FELT_CHECK(x.size() == node_count_ && v.size() == x.size() && f.size() == x.size());
  FELT_CHECK(mask.empty() || mask.size() == x.size());
  const Real k_d = material_.distance_stiffness;
  const Real d_c = material_.damping;
  for (const Spring& s : springs_) {
    if (!acts_on_selected(mask, s.nodes)) continue;
    const auto [i, j] = s.nodes;
    const Vec3 xij = x[j] - x[i];
    const Real length = xij.norm();
    if (length == 0) continue;                           // no direction to push along
    const Vec3 grad_j = xij / (length * s.rest_length);  // ∂C/∂x_j; ∂C/∂x_i = −∂C/∂x_j
    const Real c = (length - s.rest_length) / s.rest_length;
    const Real c_rate = (v[j] - v[i]).dot(grad_j);
    // (3.8): (−k C − d Ċ) ∂C/∂x, the damping sign the printed (6.1) gets wrong
    const Vec3 fj = (-k_d * c - d_c * c_rate) * grad_j;
    f[j] += fj;
    f[i] -= fj;
  }

  const Real k_v = material_.volume_stiffness;
  for (const Volume& vol : volumes_) {
    if (!acts_on_selected(mask, vol.nodes)) continue;
    const std::array<Vec3, 4> grad = six_volume_gradient(x, vol.nodes);
    // 6V = x_ij·(x_ik × x_il) = x_ij·∂(6V)/∂x_j: signed_volume's arithmetic, without redoing it
    const Real volume = (x[vol.nodes[1]] - x[vol.nodes[0]]).dot(grad[1]) / 6;
    const Real c = (volume - vol.rest_volume) / vol.rest_volume;
    for (int m = 0; m < 4; ++m) f[vol.nodes[m]] -= k_v * c * grad[m];  // (6.2) as printed
  }

  const Real k_a = material_.area_stiffness;
  for (const Area& a : areas_) {
    if (!acts_on_selected(mask, a.nodes)) continue;
    const std::array<Vec3, 3> grad = area_gradient(x, a.nodes);
    const Real c = (triangle_area(x, a.nodes) - a.rest_area) / a.rest_area;
    for (int m = 0; m < 3; ++m) f[a.nodes[m]] -= k_a * c / a.rest_area * grad[m];
  }
}

void GeneralizedMassSpring::linear_pairs(std::vector<LinearPair>& pairs) const {
  pairs.clear();
  for (const Spring& s : springs_) {
    const Real inv_sq = 1 / (s.rest_length * s.rest_length);
    pairs.push_back({s.nodes[0], s.nodes[1], material_.distance_stiffness * inv_sq,
                     material_.damping * inv_sq});
  }
}

Real GeneralizedMassSpring::energy(std::span<const Vec3> x) const {
  FELT_CHECK(x.size() == node_count_);
  Real e = 0;
  for (const Spring& s : springs_) {
    const Real c = ((x[s.nodes[1]] - x[s.nodes[0]]).norm() - s.rest_length) / s.rest_length;
    e += 0.5 * material_.distance_stiffness * c * c;
  }
  for (const Volume& vol : volumes_) {
    const Real c = (signed_volume(x, vol.nodes) - vol.rest_volume) / vol.rest_volume;
    e += 3 * material_.volume_stiffness * vol.rest_volume * c * c;
  }
  for (const Area& a : areas_) {
    const Real c = (triangle_area(x, a.nodes) - a.rest_area) / a.rest_area;
    e += 0.5 * material_.area_stiffness * c * c;
  }
  return e;
}

}  // namespace felt
