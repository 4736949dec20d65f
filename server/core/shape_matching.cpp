#include "core/shape_matching.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>
#include <Eigen/QR>

#include "core/check.hpp"
#include "core/polar_decomposition.hpp"

namespace felt {
namespace {

using Vec9 = Eigen::Matrix<Real, 9, 1>;

/// q̃ = (q_x, q_y, q_z, q_x², q_y², q_z², q_x q_y, q_y q_z, q_z q_x).
Vec9 quadratic_terms(const Vec3& q) {
  Vec9 t;
  t << q, q.cwiseProduct(q), q.x() * q.y(), q.y() * q.z(), q.z() * q.x();
  return t;
}

/// Tetrahedra come five per cell with its eight corners, as make_cell_lattice makes them.
bool five_per_cell(const TetMesh& mesh) {
  if (mesh.tets.empty() || mesh.tets.size() % 5 != 0) return false;
  for (std::size_t first = 0; first < mesh.tets.size(); first += 5) {
    std::vector<std::uint32_t> corners;
    for (std::size_t t = first; t < first + 5; ++t) {
      corners.insert(corners.end(), mesh.tets[t].begin(), mesh.tets[t].end());
    }
    std::ranges::sort(corners);
    if (std::ranges::unique(corners).begin() - corners.begin() != 8) return false;
  }
  return true;
}

std::vector<std::vector<std::uint32_t>> make_clusters(const TetMesh& mesh, bool clusters) {
  std::vector<std::vector<std::uint32_t>> result;
  if (!clusters) {
    result.emplace_back(mesh.nodes.size());
    for (std::uint32_t n = 0; n < mesh.nodes.size(); ++n) result[0][n] = n;
    return result;
  }
  const std::size_t tets_per_cluster = five_per_cell(mesh) ? 5 : 1;
  for (std::size_t first = 0; first < mesh.tets.size(); first += tets_per_cluster) {
    std::vector<std::uint32_t> nodes;
    for (std::size_t t = first; t < first + tets_per_cluster; ++t) {
      nodes.insert(nodes.end(), mesh.tets[t].begin(), mesh.tets[t].end());
    }
    std::ranges::sort(nodes);
    nodes.erase(std::ranges::unique(nodes).begin(), nodes.end());
    result.push_back(std::move(nodes));
  }
  return result;
}

}  // namespace

ShapeMatching::ShapeMatching(const TetMesh& rest, const ShapeMatchingMaterial& material)
    : material_(material), inv_cluster_count_(rest.nodes.size(), 0) {
  FELT_CHECK(material.beta >= 0 && material.beta <= 1 && material.time_constant > 0 &&
             material.plastic_yield >= 0 && material.plastic_creep >= 0 &&
             material.plastic_max >= 0);
  for (std::vector<std::uint32_t>& nodes : make_clusters(rest, material.clusters)) {
    Cluster cluster;
    cluster.nodes = std::move(nodes);
    const Vec3 rest_centre = centre(cluster, rest.nodes);
    for (std::uint32_t n : cluster.nodes) {
      cluster.original_shape.push_back(rest.nodes[n] - rest_centre);
      ++inv_cluster_count_[n];
    }
    set_shape(cluster);
    clusters_.push_back(std::move(cluster));
  }
  for (Real& c : inv_cluster_count_) c = c > 0 ? 1 / c : 0;
}

void ShapeMatching::set_shape(Cluster& cluster) const {
  Mat3 linear = Mat3::Zero();
  Mat9 quadratic = Mat9::Zero();
  cluster.shape.clear();
  for (const Vec3& q0 : cluster.original_shape) {
    const Vec3 q = cluster.plastic * q0;
    cluster.shape.push_back(q);
    linear += q * q.transpose();
    if (material_.mode == ShapeMatchingMaterial::Mode::kQuadratic) {
      const Vec9 t = quadratic_terms(q);
      quadratic += t * t.transpose();
    }
  }
  // pseudo-inverses: a flat cluster, or fewer nodes than the nine quadratic terms, leaves the
  // fit underdetermined, and the least-norm fit is the natural choice
  cluster.linear_inverse = linear.completeOrthogonalDecomposition().pseudoInverse();
  if (material_.mode == ShapeMatchingMaterial::Mode::kQuadratic) {
    cluster.quadratic_inverse = quadratic.completeOrthogonalDecomposition().pseudoInverse();
  }
}

Vec3 ShapeMatching::centre(const Cluster& cluster, std::span<const Vec3> x) const {
  Vec3 sum = Vec3::Zero();
  for (std::uint32_t n : cluster.nodes) sum += x[n];
  return sum / static_cast<Real>(cluster.nodes.size());
}

Mat3 ShapeMatching::moment(const Cluster& cluster, std::span<const Vec3> x,
                           const Vec3& centre) const {
  Mat3 a_pq = Mat3::Zero();
  for (std::size_t i = 0; i < cluster.nodes.size(); ++i) {
    a_pq += (x[cluster.nodes[i]] - centre) * cluster.shape[i].transpose();
  }
  return a_pq;
}

void ShapeMatching::add_goals(const Cluster& cluster, std::span<const Vec3> x,
                              std::span<Vec3> goal) const {
  using Mode = ShapeMatchingMaterial::Mode;
  const Vec3 t = centre(cluster, x);
  const Mat3 a_pq = moment(cluster, x, t);
  const Mat3 rotation = polar_decomposition(a_pq).rotation;
  const Real beta = material_.beta;

  if (material_.mode == Mode::kQuadratic) {
    Mat39 a_pq_quadratic = Mat39::Zero();
    for (std::size_t i = 0; i < cluster.nodes.size(); ++i) {
      a_pq_quadratic += (x[cluster.nodes[i]] - t) * quadratic_terms(cluster.shape[i]).transpose();
    }
    Mat39 rotation_quadratic = Mat39::Zero();  // R̃ = [R 0 0]
    rotation_quadratic.leftCols<3>() = rotation;
    const Mat39 transform =
        beta * a_pq_quadratic * cluster.quadratic_inverse + (1 - beta) * rotation_quadratic;
    for (std::size_t i = 0; i < cluster.nodes.size(); ++i) {
      goal[cluster.nodes[i]] += transform * quadratic_terms(cluster.shape[i]) + t;
    }
    return;
  }

  Mat3 transform = rotation;
  if (material_.mode == Mode::kLinear) {
    Mat3 linear = a_pq * cluster.linear_inverse;
    const Real det = linear.determinant();
    // det(A) = 1 preserves the volume; a flat or inverted fit has no such scaling: use R
    linear = det > 1e-12 ? Mat3(linear / std::cbrt(det)) : rotation;
    transform = beta * linear + (1 - beta) * rotation;
  }
  for (std::size_t i = 0; i < cluster.nodes.size(); ++i) {
    goal[cluster.nodes[i]] += transform * cluster.shape[i] + t;
  }
}

void ShapeMatching::goals(std::span<const Vec3> x, std::span<Vec3> goal) const {
  FELT_CHECK(x.size() == inv_cluster_count_.size() && goal.size() == x.size());
  std::ranges::fill(goal, Vec3::Zero());
  for (const Cluster& cluster : clusters_) add_goals(cluster, x, goal);
  for (std::size_t n = 0; n < x.size(); ++n) {
    goal[n] = inv_cluster_count_[n] > 0 ? Vec3(goal[n] * inv_cluster_count_[n]) : x[n];
  }
}

void ShapeMatching::rigid_velocities(std::span<const Vec3> x, std::span<const Vec3> v,
                                     std::span<Vec3> rigid) const {
  FELT_CHECK(x.size() == inv_cluster_count_.size() && v.size() == x.size() &&
             rigid.size() == x.size());
  std::ranges::fill(rigid, Vec3::Zero());
  for (const Cluster& cluster : clusters_) {
    const Vec3 t = centre(cluster, x);
    const Vec3 linear_velocity = centre(cluster, v);
    Vec3 angular_momentum = Vec3::Zero();
    Mat3 inertia = Mat3::Zero();
    for (std::uint32_t n : cluster.nodes) {
      const Vec3 p = x[n] - t;
      angular_momentum += p.cross(v[n] - linear_velocity);
      inertia += p.squaredNorm() * Mat3::Identity() - p * p.transpose();
    }
    // a collinear cluster cannot spin about its axis: the least-norm ω leaves that out
    const Vec3 omega = inertia.completeOrthogonalDecomposition().solve(angular_momentum);
    for (std::uint32_t n : cluster.nodes) rigid[n] += linear_velocity + omega.cross(x[n] - t);
  }
  for (std::size_t n = 0; n < x.size(); ++n) {
    rigid[n] = inv_cluster_count_[n] > 0 ? Vec3(rigid[n] * inv_cluster_count_[n]) : v[n];
  }
}

void ShapeMatching::flow_plastically(Cluster& cluster, std::span<const Vec3> x, Real h) const {
  const Vec3 t = centre(cluster, x);
  const Mat3 elastic = polar_decomposition(moment(cluster, x, t) * cluster.linear_inverse).stretch -
                       Mat3::Identity();
  if (elastic.norm() <= material_.plastic_yield) return;
  const Real creep = std::min<Real>(1, h * material_.plastic_creep);
  Mat3 plastic = (Mat3::Identity() + creep * elastic) * cluster.plastic;
  const Real excess = (plastic - Mat3::Identity()).norm();
  if (excess > material_.plastic_max) {
    plastic = Mat3::Identity() + material_.plastic_max / excess * (plastic - Mat3::Identity());
  }
  const Real det = plastic.determinant();
  if (!(det > 0)) return;  // a flat or inverted rest shape would leave nothing to match
  cluster.plastic = plastic / std::cbrt(det);  // plastic flow keeps the volume
  set_shape(cluster);
}

void ShapeMatching::step(std::span<Vec3> x, std::span<Vec3> v, std::span<const Real> inv_mass,
                         std::span<const Vec3> acceleration, Real h) {
  const std::size_t n = inv_cluster_count_.size();
  FELT_CHECK(h > 0 && x.size() == n && v.size() == n && inv_mass.size() == n &&
             acceleration.size() == n);
  if (material_.plastic_yield > 0) {
    for (Cluster& cluster : clusters_) flow_plastically(cluster, x, h);
  }
  goal_.resize(n);
  rigid_.resize(n);
  goals(x, goal_);
  rigid_velocities(x, v, rigid_);
  // Implicit in the goal spring and the damper with the goal held: with s = e^(h/τ) − 1 the
  // relative motion's double eigenvalue is 1/(1 + s) = e^(−h/τ), the exact decay of the
  // critically damped spring, at any h; α = s² → (h/τ)² as h → 0.
  const Real s = std::expm1(h / material_.time_constant);
  const Real alpha = s * s;
  const Real divisor = (1 + s) * (1 + s);
  for (std::size_t i = 0; i < n; ++i) {
    if (inv_mass[i] == 0) continue;
    const Vec3 relative = v[i] - rigid_[i];
    v[i] = rigid_[i] + h * acceleration[i] + (relative + alpha / h * (goal_[i] - x[i])) / divisor;
    x[i] += h * v[i];
  }
}

void ShapeMatching::add_forces(std::span<const Vec3> x, std::span<const Vec3> v, Real node_mass,
                               std::span<Vec3> f) const {
  FELT_CHECK(f.size() == x.size());
  std::vector<Vec3> goal(x.size()), rigid(x.size());
  goals(x, goal);
  rigid_velocities(x, v, rigid);
  const Real tau = material_.time_constant;
  for (std::size_t i = 0; i < x.size(); ++i) {
    f[i] += node_mass * ((goal[i] - x[i]) / (tau * tau) + 2 / tau * (rigid[i] - v[i]));
  }
}

Real ShapeMatching::energy(std::span<const Vec3> x, Real node_mass) const {
  std::vector<Vec3> goal(x.size());
  goals(x, goal);
  Real sum = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sum += (goal[i] - x[i]).squaredNorm();
  const Real tau = material_.time_constant;
  return 0.5 * node_mass * sum / (tau * tau);
}

}  // namespace felt
