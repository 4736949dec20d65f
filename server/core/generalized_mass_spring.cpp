#include "core/generalized_mass_spring.hpp"

#include <array>

#include "core/check.hpp"

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

/// Adds the Gershgorin row sums of the rank-one matrix k ∇C ∇Cᵀ, whose blocks have the norms
/// k |∇_a C| |∇_b C|.
template <std::size_t N>
void add_rank_one_bound(const std::array<Vec3, N>& gradient,
                        const std::array<std::uint32_t, N>& nodes, Real k,
                        std::vector<Real>& bound) {
  Real sum = 0;
  for (const Vec3& g : gradient) sum += g.norm();
  for (std::size_t a = 0; a < N; ++a) bound[nodes[a]] += k * gradient[a].norm() * sum;
}

}  // namespace

GeneralizedMassSpring::GeneralizedMassSpring(const TetMesh& rest, const TetTopology& topology,
                                             const MassSpringMaterial& material)
    : material_(material),
      stiffness_bound_(rest.nodes.size(), 0),
      damping_bound_(rest.nodes.size(), 0) {
  FELT_CHECK(material.distance_stiffness >= 0 && material.volume_stiffness >= 0 &&
             material.damping >= 0 && material.area_stiffness >= 0);
  const std::span<const Vec3> x = rest.nodes;

  springs_.reserve(topology.edges.size());
  for (const Edge& e : topology.edges) {
    const Real length = (x[e[1]] - x[e[0]]).norm();
    FELT_CHECK(length > 0);
    springs_.push_back({e, length});
    const Vec3 unit = (x[e[1]] - x[e[0]]) / (length * length);  // |∂C/∂x| = 1/l₀
    const std::array<Vec3, 2> gradient = {-unit, unit};
    add_rank_one_bound(gradient, e, material.distance_stiffness, stiffness_bound_);
    add_rank_one_bound(gradient, e, material.damping, damping_bound_);
  }

  volumes_.reserve(rest.tets.size());
  for (const Tetrahedron& t : rest.tets) {
    const Real volume = signed_volume(x, t);
    FELT_CHECK(volume > 0);
    volumes_.push_back({t, volume});
    // energy 3 k_V V₀ C² with ∇C = ∇(6V)/(6V₀): K = k_V ∇(6V) ∇(6V)ᵀ / (6V₀)
    add_rank_one_bound(six_volume_gradient(x, t), t, material.volume_stiffness / (6 * volume),
                       stiffness_bound_);
  }

  if (material.area_stiffness > 0) {
    areas_.reserve(topology.surface.size());
    for (const Triangle& t : topology.surface) {
      const Real area = triangle_area(x, t);
      FELT_CHECK(area > 0);
      areas_.push_back({t, area});
      add_rank_one_bound(area_gradient(x, t), t, material.area_stiffness / (area * area),
                         stiffness_bound_);
    }
  }
}

void GeneralizedMassSpring::add_forces(std::span<const Vec3> x, std::span<const Vec3> v,
                                       std::span<Vec3> f) const {
  FELT_CHECK(x.size() == stiffness_bound_.size() && v.size() == x.size() && f.size() == x.size());
  const Real k_d = material_.distance_stiffness;
  const Real d_c = material_.damping;
  for (const Spring& s : springs_) {
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
    const std::array<Vec3, 4> grad = six_volume_gradient(x, vol.nodes);
    const Real c = (signed_volume(x, vol.nodes) - vol.rest_volume) / vol.rest_volume;
    for (int m = 0; m < 4; ++m) f[vol.nodes[m]] -= k_v * c * grad[m];  // (6.2) as printed
  }

  const Real k_a = material_.area_stiffness;
  for (const Area& a : areas_) {
    const std::array<Vec3, 3> grad = area_gradient(x, a.nodes);
    const Real c = (triangle_area(x, a.nodes) - a.rest_area) / a.rest_area;
    for (int m = 0; m < 3; ++m) f[a.nodes[m]] -= k_a * c / a.rest_area * grad[m];
  }
}

Real GeneralizedMassSpring::energy(std::span<const Vec3> x) const {
  FELT_CHECK(x.size() == stiffness_bound_.size());
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
