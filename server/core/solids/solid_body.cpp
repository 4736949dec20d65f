#include "core/solids/solid_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>
#include <variant>

#include "core/integrate/stability_limit.hpp"
#include "core/math/check.hpp"
#include "core/solids/corotated_fem.hpp"
#include "core/solids/generalized_mass_spring.hpp"
#include "core/solids/shape_matching.hpp"

namespace felt {
namespace {

using Model = std::variant<GeneralizedMassSpring, ShapeMatching, CorotatedFem>;

Model make_model(const TetMesh& rest, const TetTopology& topology, const SolidMaterial& material) {
  switch (material.model) {
    case SolidModel::kMassSpring:
      return GeneralizedMassSpring(rest, topology, material.mass_spring);
    case SolidModel::kShapeMatching:
      return ShapeMatching(rest, material.shape_matching);
    case SolidModel::kCorotatedFem:
      return CorotatedFem(rest, material.fem);
  }
  check_failed("unknown solid model");
}

/// The eigenvalues are those of the rest state, and a deformed body is stiffer: a stretched
/// spring gains transverse stiffness, a tetrahedron whose faces grow gains volume stiffness.
/// Sampled every 0.1 s over the first 3 s, the limit at the deformed states fell to 0.84 of
/// its rest value in the thesis's three-cube stack and to 0.89 in the four bunnies (by brute
/// force on the Jacobians). 0.7 keeps a step at most 0.83 of the limit of those states; with
/// 0.8 (0.95 of it) a cube dropped on a cube bounced higher and sank 0.11 of a cell into it on
/// landing again, against 0.04 at 0.7. A step that still fails is redone with more substeps by
/// the solid system.
constexpr Real kDeformationMargin = 0.7;

}  // namespace

struct SolidBody::ModelState {
  Model model;
  std::vector<Vec3> force;  ///< scratch for advance()
};

class SolidBody::Dynamics final : public DynamicSystem {
 public:
  Dynamics(const SolidBody& body, const Vec3& gravity) : body_(body), gravity_(gravity) {}

  std::span<const Real> inv_mass() const override { return body_.inv_mass_; }

  void compute_forces(std::span<const Vec3> x, std::span<const Vec3> v, Real /*t*/,
                      std::span<Vec3> f) const override {
    std::ranges::fill(f, Vec3::Zero());
    std::visit(
        [&](const auto& model) {
          if constexpr (!std::is_same_v<std::decay_t<decltype(model)>, ShapeMatching>) {
            model.add_forces(x, v, f);
          }
        },
        body_.model_state_->model);
    const Vec3 weight = body_.material_.node_mass * gravity_;
    for (std::size_t n = 0; n < f.size(); ++n) f[n] += weight + body_.external_force_[n];
    body_.add_anchor_forces(x, v, f);
  }

  bool linear_force_pairs(std::vector<LinearPair>& pairs) const override {
    pairs.clear();
    const auto* springs = std::get_if<GeneralizedMassSpring>(&body_.model_state_->model);
    if (springs) springs->linear_pairs(pairs);
    return !pairs.empty();
  }

 private:
  const SolidBody& body_;
  Vec3 gravity_;
};

std::optional<std::string> solid_integrator_refusal(SolidModel model, std::string_view name) {
  if (model == SolidModel::kShapeMatching) {
    return "shape matching moves its nodes by its own update and takes no integrator";
  }
  if (name == kTimeCorrectedVerlet) return std::nullopt;
  const std::optional<IntegratorNeeds> needs = integrator_needs(name);
  if (!needs) {
    std::string known(kTimeCorrectedVerlet);
    for (std::string_view n : integrator_names()) known += ", " + std::string(n);
    return "unknown integrator \"" + std::string(name) + "\" (known: " + known + ")";
  }
  if (*needs == IntegratorNeeds::kJacobian) {
    return std::string(name) +
           " needs a force Jacobian, which the solid models do not give (imex, desbrun and kang "
           "take a mass-spring solid's edges implicitly)";
  }
  if (*needs == IntegratorNeeds::kDistanceConstraints) {
    return std::string(name) + " takes a cloth's springs as constraints; solids have none";
  }
  if (*needs == IntegratorNeeds::kLinearPairs && model != SolidModel::kMassSpring) {
    return std::string(name) +
           " takes springs implicitly and corotated_fem has none; the explicit integrators apply";
  }
  return std::nullopt;
}

SolidBody::SolidBody(std::string name, TetMesh mesh, SolidMaterial material)
    : name_(std::move(name)),
      rest_(std::make_shared<const TetMesh>(std::move(mesh))),
      topology_(build_topology(*rest_)),
      material_(material),
      rest_volume_(total_volume(rest_->nodes, rest_->tets)),
      x_(rest_->nodes),
      x_prev_(rest_->nodes),
      v_(rest_->nodes.size(), Vec3::Zero()),
      external_force_(rest_->nodes.size(), Vec3::Zero()) {
  set_material(material);
}

const Eigen::SparseMatrix<Real>* SolidBody::rest_stiffness() const {
  return std::visit(
      [](const auto& model) -> const Eigen::SparseMatrix<Real>* {
        if constexpr (std::is_same_v<std::decay_t<decltype(model)>, ShapeMatching>) {
          return nullptr;
        } else {
          return &model.rest_stiffness();
        }
      },
      model_state_->model);
}

SolidBody::~SolidBody() = default;
SolidBody::SolidBody(SolidBody&&) noexcept = default;
SolidBody& SolidBody::operator=(SolidBody&&) noexcept = default;

void SolidBody::set_material(const SolidMaterial& material) {
  FELT_CHECK(material.node_mass > 0 && material.friction >= 0);
  FELT_CHECK(material.crease_angle >= 0 && material.crease_angle <= std::numbers::pi);
  material_ = material;
  // a new model starts from the rest shape again (a shape-matching body forgets its plastic flow)
  model_state_ = std::make_unique<ModelState>(
      ModelState{make_model(*rest_, topology_, material_), std::vector<Vec3>(x_.size())});
  if (integrator_ && solid_integrator_refusal(material_.model, integrator_->name())) {
    integrator_.reset();  // it does not apply to the new model
  }
  const bool first = inv_mass_.empty();
  inv_mass_.resize(x_.size());
  for (Real& inv : inv_mass_) {
    if (first || inv > 0) inv = 1 / material_.node_mass;  // pinned nodes stay pinned
  }
}

Real SolidBody::mass(std::uint32_t n) const {
  FELT_CHECK(n < x_.size());
  return material_.node_mass;
}

void SolidBody::pin(std::uint32_t n) {
  FELT_CHECK(n < x_.size());
  inv_mass_[n] = 0;
  v_[n].setZero();
}

void SolidBody::unpin(std::uint32_t n) {
  FELT_CHECK(n < x_.size());
  inv_mass_[n] = 1 / material_.node_mass;
}

SolidBody::SurfacePoint SolidBody::surface_point(std::uint32_t vertex) const {
  if (!embedded_) {
    FELT_CHECK(vertex < x_.size());
    return {{vertex, vertex, vertex, vertex}, {1, 0, 0, 0}};
  }
  const Tetrahedron& tet = rest_->tets[embedded_->tet[vertex]];
  SurfacePoint point;
  for (int c = 0; c < 4; ++c) {
    point.nodes[c] = tet[c];
    point.weights[c] = embedded_->weights[vertex][c];
  }
  return point;
}

void SolidBody::set_anchor(const Anchor& anchor) {
  for (int c = 0; c < 4; ++c) {
    FELT_CHECK(anchor.point.nodes[c] < x_.size() && anchor.point.weights[c] >= 0);
  }
  FELT_CHECK(anchor.target.allFinite() && anchor.stiffness >= 0 && anchor.damping >= 0);
  remove_anchor(anchor.key);
  anchors_.push_back(anchor);
}

void SolidBody::remove_anchor(std::uint32_t key) {
  std::erase_if(anchors_, [key](const Anchor& a) { return a.key == key; });
}

void SolidBody::add_anchor_forces(std::span<const Vec3> x, std::span<const Vec3> v,
                                  std::span<Vec3> f) const {
  for (const Anchor& a : anchors_) {
    Vec3 p = Vec3::Zero(), p_rate = Vec3::Zero();
    const auto& [nodes, weights] = a.point;
    for (int c = 0; c < 4; ++c) {
      p += weights[c] * x[nodes[c]];
      p_rate += weights[c] * v[nodes[c]];
    }
    const Vec3 pull = a.stiffness * (a.target - p) - a.damping * p_rate;
    for (int c = 0; c < 4; ++c) f[nodes[c]] += weights[c] * pull;
  }
}

void SolidBody::set_integrator(std::unique_ptr<Integrator> integrator) {
  FELT_CHECK(!integrator || !solid_integrator_refusal(material_.model, integrator->name()));
  integrator_ = std::move(integrator);
  integrated_motion_.clear();
}

void SolidBody::set_max_step(Real max_step) {
  FELT_CHECK(max_step > 0);
  max_step_ = max_step;
}

void SolidBody::restore_step_state(const StepState& state) {
  x_ = state.x;
  x_prev_ = state.x_prev;
  v_ = state.v;
  external_force_ = state.external_force;
  previous_step_ = state.previous_step;
  forget_history();
}

void SolidBody::forget_history() {
  if (integrator_) integrator_->reset();
  integrated_motion_.clear();
}

void SolidBody::clear_external_forces() {
  std::ranges::fill(external_force_, Vec3::Zero());
}

void SolidBody::internal_forces(std::span<Vec3> f, NodeMask mask) const {
  FELT_CHECK(f.size() == x_.size());
  std::ranges::fill(f, Vec3::Zero());
  std::visit(
      [&](const auto& model) {
        if constexpr (std::is_same_v<std::decay_t<decltype(model)>, ShapeMatching>) {
          model.add_forces(x_, v_, material_.node_mass, f);
        } else {
          model.add_forces(x_, v_, f, mask);
        }
      },
      model_state_->model);
}

void SolidBody::advance(Real h, const Vec3& gravity) {
  FELT_CHECK(h > 0);
  x_prev_ = x_;
  std::vector<Vec3>& force = model_state_->force;
  if (auto* matching = std::get_if<ShapeMatching>(&model_state_->model)) {
    std::ranges::fill(force, Vec3::Zero());
    add_anchor_forces(x_, v_, force);
    for (std::size_t n = 0; n < x_.size(); ++n) {
      force[n] = gravity + inv_mass_[n] * (external_force_[n] + force[n]);  // accelerations
    }
    matching->step(x_, v_, inv_mass_, force, h);
  } else if (integrator_) {
    // the integrator steps a ParticleState: the nodes' vectors are lent to it, not copied
    integrated_.x.swap(x_);
    integrated_.v.swap(v_);
    integrator_->step(Dynamics(*this, gravity), integrated_, 0, h);
    integrated_.x.swap(x_);
    integrated_.v.swap(v_);
    integrated_motion_.resize(x_.size());
    for (std::size_t n = 0; n < x_.size(); ++n) integrated_motion_[n] = x_[n] - x_prev_[n];
  } else {
    internal_forces(force);
    add_anchor_forces(x_, v_, force);
    // v is (x − x_prev)/h_prev (finish_step), so x + h v + ½h(h + h_prev) a is the time-corrected
    // Verlet step x + (x − x_prev) h/h_prev + a h² of thesis 2 §4.5 with the acceleration term
    // of an uneven grid, which equals a h² at a constant step and makes the first step (no
    // history, v the initial velocity) the Taylor step x + h v + ½h² a.
    const Real accel_scale = 0.5 * h * (h + previous_step_);
    for (std::size_t n = 0; n < x_.size(); ++n) {
      if (inv_mass_[n] == 0) continue;
      const Vec3 a = gravity + inv_mass_[n] * (force[n] + external_force_[n]);
      x_[n] += h * v_[n] + accel_scale * a;
    }
  }
  previous_step_ = h;
}

void SolidBody::finish_step(Real h) {
  FELT_CHECK(h > 0);
  if (integrator_ && integrated_motion_.size() == x_.size()) {
    // a node collision handling left alone keeps the integrator's velocity; one it moved (or
    // whose velocity it changed, by moving the previous position: contact_surface.cpp) gets
    // the backward difference it means. (Adding its change to the integrator's end velocity
    // instead leaves a resting node of a multi-stage scheme falling: RK4's x − x_prev is
    // h v + h² g/2, not h v_end, so zeroing it left −g h/2 and the body never came to rest.)
    for (std::size_t n = 0; n < x_.size(); ++n) {
      const Vec3 motion = x_[n] - x_prev_[n];
      if (motion != integrated_motion_[n]) v_[n] = motion / h;
    }
    return;
  }
  // the backward difference: the mean velocity over the step, including what collision
  // handling did; it is also the velocity the damping forces see in the next step
  for (std::size_t n = 0; n < x_.size(); ++n) v_[n] = (x_[n] - x_prev_[n]) / h;
}

Real SolidBody::stable_time_step() const {
  // the anchors' springs act on one point each: they raise λ_max of K and D by at most the sum
  // of their coefficients (each is a rank-3 term k w wᵀ with |w| ≤ 1)
  Real anchor_stiffness = 0, anchor_damping = 0;
  for (const Anchor& a : anchors_) {
    anchor_stiffness += a.stiffness;
    anchor_damping += a.damping;
  }
  const Real inv_mass = 1 / material_.node_mass;
  return std::visit(
      [&](const auto& model) -> Real {
        if constexpr (std::is_same_v<std::decay_t<decltype(model)>, ShapeMatching>) {
          // unconditionally stable, but an anchor is an explicit spring
          return anchors_.empty()
                     ? std::numeric_limits<Real>::infinity()
                     : kDeformationMargin * verlet_step_limit({inv_mass * anchor_stiffness,
                                                               inv_mass * anchor_damping});
        } else {
          // the masses are uniform, so M⁻¹K has the eigenvalues of K over the node mass (the
          // limit is exact when K and D share their modes, FEM's D = β K; the mass-spring
          // damping acts along the edges only, and the tests check its bodies at the estimate);
          // pinning nodes removes rows and columns, which cannot raise the largest one
          const OscillatorMode fastest{
              inv_mass * (model.largest_stiffness_eigenvalue() + anchor_stiffness),
              inv_mass * (model.largest_damping_eigenvalue() + anchor_damping)};
          // the thesis's Verlet, or an integrator whose limit is tighter: explicit Euler and
          // the midpoint rule grow an undamped mode at any step (0), so that a step chosen
          // by Verlet's limit let them grow 10¹⁰⁵ times in a second
          Real limit = verlet_step_limit(fastest);
          if (integrator_) limit = std::min(limit, integrator_->step_limit(fastest));
          return kDeformationMargin * limit;
        }
      },
      model_state_->model);
}

Real SolidBody::kinetic_energy() const {
  Real sum = 0;
  for (const Vec3& v : v_) sum += v.squaredNorm();
  return 0.5 * material_.node_mass * sum;
}

Real SolidBody::gravitational_energy(const Vec3& gravity) const {
  Real sum = 0;
  for (const Vec3& x : x_) sum -= gravity.dot(x);
  return material_.node_mass * sum;
}

Real SolidBody::elastic_energy() const {
  Real anchors = 0;
  for (const Anchor& a : anchors_) {
    Vec3 p = Vec3::Zero();
    for (int c = 0; c < 4; ++c) p += a.point.weights[c] * x_[a.point.nodes[c]];
    anchors += 0.5 * a.stiffness * (a.target - p).squaredNorm();
  }
  return anchors +
         std::visit(
             [&](const auto& model) -> Real {
               if constexpr (std::is_same_v<std::decay_t<decltype(model)>, ShapeMatching>) {
                 return model.energy(x_, material_.node_mass);
               } else {
                 return model.energy(x_);
               }
             },
             model_state_->model);
}

}  // namespace felt
