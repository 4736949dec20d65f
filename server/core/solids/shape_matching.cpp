#include "core/solids/shape_matching.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>

#include "core/math/check.hpp"
#include "core/math/polar_decomposition.hpp"

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

using Mat6 = Eigen::Matrix<Real, 6, 6>;
using Vec6 = Eigen::Matrix<Real, 6, 1>;

/// Relative eigenvalue below which a rigid motion counts as one the pinned nodes leave free.
constexpr Real kFreeMotion = 1e-9;

/// [r]×, so that [r]× w = r × w.
Mat3 cross_matrix(const Vec3& r) {
  Mat3 m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

/// Adds a unit mass at offset r to the rigid-body mass matrix of rigid motions (t, w), whose
/// field is t + w × r: [[I, −[r]×], [[r]×, |r|² I − r rᵀ]] (mass, first moment, inertia).
void add_unit_mass(Mat6& mass, const Vec3& r) {
  const Mat3 cross = cross_matrix(r);
  mass.topLeftCorner<3, 3>() += Mat3::Identity();
  mass.topRightCorner<3, 3>() -= cross;
  mass.bottomLeftCorner<3, 3>() += cross;
  mass.bottomRightCorner<3, 3>() += r.squaredNorm() * Mat3::Identity() - r * r.transpose();
}

/// The rigid share of the load (see shape_matching.hpp): the acceleration field of the body
/// moving as one rigid body under the accelerations `load` with its pinned nodes held. By
/// Gauss's principle of least constraint it is the rigid field nearest the load over the free
/// nodes (equal masses) among those that leave every pinned node at rest.
void rigid_share(std::span<const Vec3> x, std::span<const Real> inv_mass,
                 std::span<const Vec3> load, std::span<Vec3> share) {
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : x) centre += p;
  centre /= static_cast<Real>(x.size());
  Real radius_squared = 0;
  for (const Vec3& p : x) radius_squared += (p - centre).squaredNorm();
  // offsets in units of the body's radius weigh turning and moving alike in the eigenvalues
  Real radius = std::sqrt(radius_squared / static_cast<Real>(x.size()));
  if (!(radius > 0)) radius = 1;  // every node at one point: no turning to speak of

  Mat6 free_mass = Mat6::Zero(), held_mass = Mat6::Zero();
  Vec6 free_load = Vec6::Zero();  // the load's force and torque on the free nodes
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec3 r = (x[i] - centre) / radius;
    if (inv_mass[i] == 0) {
      add_unit_mass(held_mass, r);
    } else {
      add_unit_mass(free_mass, r);
      free_load.head<3>() += load[i];
      free_load.tail<3>() += r.cross(load[i]);
    }
  }
  // the motions the pins allow move no pinned node: the null space of the pinned nodes' mass
  // matrix (all six without pins, turning about the pin or the line of pins, none from three
  // pins off a line)
  const Eigen::SelfAdjointEigenSolver<Mat6> held(held_mass);
  const Vec6& eigenvalues = held.eigenvalues();  // ascending
  int free_motions = 0;
  while (free_motions < 6 && eigenvalues(free_motions) <= kFreeMotion * eigenvalues(5)) {
    ++free_motions;
  }
  if (free_motions == 0) {
    std::ranges::fill(share, Vec3::Zero());  // held still
    return;
  }
  const auto allowed = held.eigenvectors().leftCols(free_motions);
  const Eigen::MatrixXd mass = allowed.transpose() * free_mass * allowed;
  // least norm where the free nodes leave a motion undetermined (collinear, or a single one)
  const Vec6 motion =
      allowed * mass.completeOrthogonalDecomposition().solve(allowed.transpose() * free_load);
  for (std::size_t i = 0; i < x.size(); ++i) {
    share[i] = motion.head<3>() + motion.tail<3>().cross((x[i] - centre) / radius);
  }
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
  share_.resize(n);
  goals(x, goal_);
  rigid_velocities(x, v, rigid_);
  rigid_share(x, inv_mass, acceleration, share_);
  // Implicit in the goal spring and the damper with the goal held: with s = e^(h/τ) − 1 the
  // relative motion's double eigenvalue is 1/(1 + s) = e^(−h/τ), the exact decay of the
  // critically damped spring, at any h; α = s² → (h/τ)² as h → 0. The load's rigid share moves
  // the rigid motion; the rest shifts the goal by τ² a, where the spring m/τ² holds it.
  const Real tau = material_.time_constant;
  const Real s = std::expm1(h / tau);
  const Real alpha = s * s;
  const Real divisor = (1 + s) * (1 + s);
  for (std::size_t i = 0; i < n; ++i) {
    if (inv_mass[i] == 0) continue;
    const Vec3 relative = v[i] - rigid_[i];
    const Vec3 loaded_goal = goal_[i] + tau * tau * (acceleration[i] - share_[i]);
    v[i] = rigid_[i] + h * share_[i] + (relative + alpha / h * (loaded_goal - x[i])) / divisor;
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
