// The soft-solid model study: generalized mass-spring, shape matching and corotated FEM compared
// on error against cost, on two problems.
//
//  (a) A cantilever: a 12 × 3 × 3 lattice bar (cells of 10 cm, 1000 kg/m³) clamped at one end
//      and released at rest under gravity, so it swings down and oscillates about its sag.
//  (b) A cube: the thesis's 5 × 5 × 5 lattice (cells of 10 cm) dropped flat on the floor.
//
// The reference is corotated FEM (E = 2 MPa, ν = 0.3, Rayleigh β = 0.1 ms) at a small step. The
// other two models get one stiffness parameter each, calibrated so that the cantilever's static
// tip deflection at the reference step matches FEM's: k_D for mass-spring (k_V and d_C follow
// it in fixed ratios), τ for shape matching (one cluster per lattice cell); a fourth variant
// re-chooses τ at each step so that shape matching's step-dependent statics match too. Then
// every model runs every requested step through SolidSystem, as the server runs it (substeps
// no longer than the body's stable step), and the study records the error against the
// reference, the oscillation frequency and damping, the static error, the volume change and the
// CPU time per simulated second; per model and problem also the largest fixed step it survives
// without substeps. Not a unit test: machines are shared and noisy, so compare ratios within
// one run.
//
// Usage: solid_model_study OUT_DIR [--quick]
// Writes OUT_DIR/solid_models.csv (one row per problem × model × step), OUT_DIR/
// solid_models_trajectories.csv (the tip and the cube's centre over time, for the plots) and
// the Markdown tables into OUT_DIR/solid_models.md between its markers (the text around them
// is kept; a missing file is created). Progress goes to stderr. --quick runs a small subset (a
// smoke test, not for the results). scripts/bench-solid-models builds it, runs it into
// docs/results/ and draws the plots.
//
// Over 500 lines: one study read top to bottom (the two problems, the calibration, the runs,
// the tables); its parts are used nowhere else.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/solids/solid_collider_contact.hpp"
#include "core/solids/solid_system.hpp"
#include "core/solids/tet_lattice.hpp"
#include "scheduling/thread_cpu_time.hpp"
#include "study_output.hpp"

namespace felt {
namespace {

using study::csv_number;
using study::format;
constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();

// --- the material and the problems -------------------------------------------------------------

constexpr Real kCell = 0.1;      ///< m, the lattice cell of both bodies
constexpr Real kDensity = 1000;  ///< kg/m³, lumped equally on the nodes
constexpr Real kYoung = 2e6;     ///< Pa: the cantilever sags by about 12 % of its length
constexpr Real kPoisson = 0.3;
/// s, FEM's stiffness-proportional damping; mass-spring gets the same, d_C = β k_D. Larger β
/// shrinks the explicit step (ω²h² + 2βω²h < 4): this one by about 8 %.
constexpr Real kRayleigh = 1e-4;
/// k_V c³ / k_D: Table B.1's k_V : k_D = 10 : 20 on the thesis's 1 m cells. The volume force is
/// kept as printed (generalized_mass_spring.hpp), so at a fixed ratio k_V / k_D a finer lattice
/// would weaken it as c³.
constexpr Real kVolumeRatio = 0.5;
constexpr Real kFriction = 0.5;  ///< body and floor
const Vec3 kGravity(0, -9.81, 0);
constexpr std::array<int, 3> kBarCells = {12, 3, 3};
constexpr std::array<int, 3> kCubeCells = {5, 5, 5};
constexpr Real kDropHeight = 0.2;  ///< m, the cube's bottom above the floor at the start

constexpr Real kSampleInterval = 0.03;  ///< s: errors are taken here, a multiple of every step
constexpr Real kPlotInterval = 0.005;   ///< s: the trajectory CSV's resolution (or every step)
/// s: the requested steps whose trajectories are written for the plots
constexpr std::array<Real, 2> kPlottedSteps = {1e-3, 1.5e-2};
constexpr Real kRestWindow = 0.3;    ///< s: the cube's resting height is its mean over the end
constexpr Real kStepCap = 0.015;     ///< s, the thesis's largest step and the server's cap
constexpr Real kMaxSpeed = 100;      ///< m/s: faster is a blow-up, as in SolidStepSettings
constexpr Real kStableRatio = 1.02;  ///< the stable-step bisection stops at hi/lo below this
/// m/s²: a relaxation has converged when a step from rest moves no node further than this
/// acceleration would; the bar's slowest mode (ω ≈ 10/s) then lies within about 1 µm of rest
constexpr Real kResidualAcceleration = 1e-4;
constexpr Real kRelaxTimeLimit = 60;          ///< s of simulated time a relaxation may take
constexpr Real kCalibrationTolerance = 1e-3;  ///< relative tip deflection mismatch
/// Shape matching's stiffest setting at a step h: τ = h / 30, where e^(h/τ) = 10¹³ and the
/// update is the original α = 1 (every node moved onto its goal); a smaller τ changes nothing.
constexpr Real kStiffestStepsPerTau = 30;

/// Shape matching holds a steady load a at the offset τ_eff² a from its goals, not τ² a: the
/// load enters its update as h a outside the implicit goal-spring solve, which balances it at
/// h² (1 + s)²/s² a, s = e^(h/τ) − 1 (shape_matching.cpp). So its statics depend on the step,
/// through τ_eff = h / (1 − e^(−h/τ)), which exceeds both τ and h.
Real effective_time_constant(Real tau, Real h) {
  return h / -std::expm1(-h / tau);
}

/// The τ whose effective time constant at step h is `effective`, or the stiffest setting when
/// h ≥ `effective` (no τ reaches it).
Real time_constant_for(Real effective, Real h) {
  return h < effective ? h / -std::log1p(-h / effective) : h / kStiffestStepsPerTau;
}

struct Plan {
  std::vector<Real> steps;                  ///< s, requested steps, ascending
  Real reference_step = 0;                  ///< s
  Real cantilever_time = 0, cube_time = 0;  ///< s simulated
};

Plan full_plan() {
  return {{2.5e-4, 5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 1.5e-2}, 1e-4, 3, 1.5};
}
Plan quick_plan() {
  return {{1e-3, 5e-3, 1.5e-2}, 2.5e-4, 1, 0.6};
}

/// Steps at which the cloth integrators are compared on the force models.
constexpr std::array kIntegratorSteps = {1e-3, 5e-3, 1.5e-2};
constexpr std::array kIntegratorModels = {SolidModel::kMassSpring, SolidModel::kCorotatedFem};

/// The cloth integrators that apply to a force model (its own scheme is in the main table).
std::vector<std::string_view> integrators_for(SolidModel model) {
  std::vector<std::string_view> names;
  for (std::string_view name : integrator_names()) {
    if (!solid_integrator_refusal(model, name)) names.push_back(name);
  }
  return names;
}

/// kShapeMatchingPerStep: shape matching with τ chosen anew at each step so that its static
/// sag matches the calibration's, or as stiff as it goes where it cannot.
enum class Model { kFem, kMassSpring, kShapeMatching, kShapeMatchingPerStep };
constexpr std::array kModels = {Model::kFem, Model::kMassSpring, Model::kShapeMatching,
                                Model::kShapeMatchingPerStep};

std::string model_name(Model model) {
  switch (model) {
    case Model::kFem:
      return "fem";
    case Model::kMassSpring:
      return "mass_spring";
    case Model::kShapeMatching:
      return "shape_matching";
    case Model::kShapeMatchingPerStep:
      return "shape_matching_per_step";
  }
  return "";
}

/// The calibrated parameters.
struct Stiffness {
  Real distance_stiffness = 0;  ///< k_D
  Real time_constant = 0;       ///< τ, s
  /// s, τ_eff at the calibration's step: what the per-step shape matching keeps
  Real effective_time_constant = 0;
};

/// The material of `model` for a body with node masses `node_mass` run at requested step h
/// (only the per-step shape matching depends on it).
SolidMaterial material(Model model, const Stiffness& stiffness, Real node_mass, Real h) {
  SolidMaterial m;
  m.node_mass = node_mass;
  m.friction = kFriction;
  switch (model) {
    case Model::kFem:
      m.model = SolidModel::kCorotatedFem;
      m.fem.young_modulus = kYoung;
      m.fem.poisson_ratio = kPoisson;
      m.fem.damping = kRayleigh;
      break;
    case Model::kMassSpring:
      m.model = SolidModel::kMassSpring;
      m.mass_spring.distance_stiffness = stiffness.distance_stiffness;
      m.mass_spring.volume_stiffness =
          kVolumeRatio * stiffness.distance_stiffness / (kCell * kCell * kCell);
      m.mass_spring.damping = kRayleigh * stiffness.distance_stiffness;
      break;
    case Model::kShapeMatching:
    case Model::kShapeMatchingPerStep:
      // the defaults (linear, β = 0.5) with a cluster per cell: one cluster for a whole bar
      // makes it a rigid body hinged at its clamp, which swings down instead of bending
      m.model = SolidModel::kShapeMatching;
      m.shape_matching.time_constant =
          model == Model::kShapeMatching ? stiffness.time_constant
                                         : time_constant_for(stiffness.effective_time_constant, h);
      m.shape_matching.clusters = true;
      break;
  }
  return m;
}

/// A lattice body with what is pinned, what it collides with and the faces whose motion is
/// measured.
struct Problem {
  std::string name;
  TetMesh mesh;
  Real node_mass = 0;
  std::vector<std::uint32_t> pinned;
  std::vector<Collider> colliders;
  std::vector<std::uint32_t> top;     ///< cantilever: the free end face; cube: the top face
  std::vector<std::uint32_t> bottom;  ///< cube: the bottom face
  Real duration = 0;                  ///< s simulated
  /// The cantilever is measured by its tip, the cube by all its nodes and its two faces.
  bool is_cantilever() const { return bottom.empty(); }
};

TetMesh lattice(std::array<int, 3> cells, const Vec3& origin) {
  LatticeGrid grid;
  grid.cells = cells;
  grid.cell_size = Vec3::Constant(kCell);
  grid.origin = origin;
  return make_box_lattice(grid);
}

/// The nodes whose rest coordinate `axis` equals `value`.
std::vector<std::uint32_t> face(const TetMesh& mesh, int axis, Real value) {
  std::vector<std::uint32_t> nodes;
  for (std::uint32_t n = 0; n < mesh.nodes.size(); ++n) {
    if (std::abs(mesh.nodes[n][axis] - value) < 1e-9) nodes.push_back(n);
  }
  return nodes;
}

Real lumped_mass(const TetMesh& mesh, std::array<int, 3> cells) {
  const Real volume = cells[0] * cells[1] * cells[2] * kCell * kCell * kCell;
  return kDensity * volume / static_cast<Real>(mesh.nodes.size());
}

Problem cantilever(Real duration) {
  Problem p;
  p.name = "cantilever";
  p.mesh = lattice(kBarCells, Vec3::Zero());
  p.node_mass = lumped_mass(p.mesh, kBarCells);
  p.pinned = face(p.mesh, 0, 0);
  p.top = face(p.mesh, 0, kBarCells[0] * kCell);
  p.duration = duration;
  return p;
}

Problem dropped_cube(Real duration) {
  Problem p;
  p.name = "cube";
  p.mesh = lattice(kCubeCells, Vec3(0, kDropHeight, 0));
  p.node_mass = lumped_mass(p.mesh, kCubeCells);
  Collider floor;  // the plane y = 0
  floor.friction = kFriction;
  p.colliders = {floor};
  p.top = face(p.mesh, 1, kDropHeight + kCubeCells[1] * kCell);
  p.bottom = face(p.mesh, 1, kDropHeight);
  p.duration = duration;
  return p;
}

/// `integrator`: a cloth integrator's name, or empty for the model's own scheme.
SolidBody make_body(const Problem& problem, const SolidMaterial& material,
                    std::string_view integrator = {}) {
  SolidBody body(problem.name, problem.mesh, material);
  for (std::uint32_t n : problem.pinned) body.pin(n);
  if (!integrator.empty()) body.set_integrator(make_integrator(integrator));
  return body;
}

Real mean_y(std::span<const Vec3> x, std::span<const std::uint32_t> nodes) {
  Real sum = 0;
  for (std::uint32_t n : nodes) sum += x[n].y();
  return sum / static_cast<Real>(nodes.size());
}

Real centre_y(std::span<const Vec3> x) {
  Real sum = 0;
  for (const Vec3& p : x) sum += p.y();
  return sum / static_cast<Real>(x.size());
}

/// The cantilever's tip deflection: the mean vertical displacement of the free end face.
Real tip_deflection(const Problem& problem, std::span<const Vec3> x) {
  return mean_y(x, problem.top) - mean_y(problem.mesh.nodes, problem.top);
}

/// How many steps of h make `interval` (at least 1); exits if h does not divide it.
long steps_per(Real interval, Real h) {
  const long n = std::max(1L, std::lround(interval / h));
  if (interval >= h && std::abs(static_cast<Real>(n) * h - interval) > 1e-9 * interval) {
    std::fprintf(stderr, "step %g s does not divide %g s\n", h, interval);
    std::exit(2);
  }
  return n;
}

std::string ms(Real seconds) {
  return format("%g", seconds * 1e3);
}

// --- a run through SolidSystem
// --------------------------------------------------------------------

struct Run {
  Real h = 0;
  int substeps = 0;                        ///< per requested step (the largest, if it changed)
  int rescued_steps = 0;                   ///< steps SolidSystem had to redo with more substeps
  bool failed = false;                     ///< an unrecoverable step; the run stops there
  double cpu_seconds = 0;                  ///< in SolidSystem::step
  double wall_seconds = 0;                 ///< in SolidSystem::step, as its stage times are
  double model_seconds = 0;                ///< its integration stage: the model's forces and update
  Real simulated = 0;                      ///< s
  std::vector<std::vector<Vec3>> samples;  ///< positions every kSampleInterval, from t = 0
  /// every step, from t = 0: the mean heights of the top and bottom faces and of all nodes, and
  /// the volume
  std::vector<Real> t, top_y, bottom_y, centre, volume;
};

Run simulate(const Problem& problem, const SolidMaterial& material, Real h,
             std::string_view integrator = {}) {
  SolidSystem system;
  system.add_body(make_body(problem, material, integrator));
  const SolidBody& body = system.bodies()[0];
  Run run;
  run.h = h;
  const long steps = std::lround(problem.duration / h);
  const long per_sample = steps_per(kSampleInterval, h);
  auto record = [&](long n) {
    const std::vector<Vec3>& x = body.positions();
    run.t.push_back(static_cast<Real>(n) * h);
    run.top_y.push_back(mean_y(x, problem.top));
    run.bottom_y.push_back(problem.is_cantilever() ? kNaN : mean_y(x, problem.bottom));
    run.centre.push_back(centre_y(x));
    run.volume.push_back(body.volume());
    if (n % per_sample == 0) run.samples.push_back(x);
  };
  record(0);
  for (long n = 1; n <= steps; ++n) {
    const double cpu = thread_cpu_seconds();
    const auto wall = std::chrono::steady_clock::now();
    const SolidStepStats& stats = system.step(h, kGravity, problem.colliders);
    run.cpu_seconds += thread_cpu_seconds() - cpu;
    run.wall_seconds += study::seconds_since(wall);
    run.model_seconds += stats.profile[StepStage::kIntegration];
    run.substeps = std::max(run.substeps, stats.substeps);
    run.rescued_steps += stats.rescued ? 1 : 0;
    if (stats.unrecoverable) {
      run.failed = true;
      break;
    }
    run.simulated = static_cast<Real>(n) * h;
    record(n);
  }
  return run;
}

/// The static equilibrium under gravity that SolidSystem reaches at requested step h, by
/// kinetic damping: whenever the kinetic energy falls, every node is stopped where it is. It
/// has converged when the step after such a stop moves no node further than ½ a h² with
/// a = kResidualAcceleration (a Verlet step from rest moves by between ½ and 1 times a h²).
struct Equilibrium {
  std::vector<Vec3> x;
  Real tip = kNaN;  ///< the cantilever's tip deflection
  bool converged = false;
};

Equilibrium relax(const Problem& problem, const SolidMaterial& material, Real h) {
  SolidSystem system;
  system.add_body(make_body(problem, material));
  SolidBody& body = system.bodies()[0];
  Equilibrium eq;
  Real previous_kinetic = 0;
  std::vector<Vec3> stopped_at;  // where the nodes were stopped, before the step that follows
  const Real tolerance = 0.5 * kResidualAcceleration * h * h;
  const long max_steps = std::lround(kRelaxTimeLimit / h);
  for (long n = 0; n < max_steps && !eq.converged; ++n) {
    system.step(h, kGravity, problem.colliders);
    if (!stopped_at.empty()) {
      Real moved = 0;
      for (std::size_t i = 0; i < stopped_at.size(); ++i) {
        moved = std::max(moved, (body.positions()[i] - stopped_at[i]).norm());
      }
      eq.converged = moved < tolerance;
      stopped_at.clear();
    }
    const Real kinetic = body.kinetic_energy();
    if (kinetic >= previous_kinetic) {
      previous_kinetic = kinetic;
      continue;
    }
    for (Vec3& v : body.velocities()) v.setZero();
    body.previous_positions() = body.positions();
    stopped_at = body.positions();
    previous_kinetic = 0;
  }
  eq.x = body.positions();
  eq.tip = tip_deflection(problem, eq.x);
  return eq;
}

// --- calibration --------------------------------------------------------------------------------

/// The parameter p > 0 at which `deflection(p)` (monotonic) equals `target`, to
/// kCalibrationTolerance: bracketed by doubling or halving from `guess`, then regula falsi
/// (Illinois) on ln p ↦ ln deflection, which is nearly linear (deflection ∝ p^±1 or p^±2 in the
/// linear range), so it takes a few relaxations where bisection would take a dozen.
template <typename Deflection>
Real calibrate(Deflection deflection, Real guess, Real target, int& evaluations) {
  auto residual = [&](Real log_p) {
    ++evaluations;
    return std::log(std::abs(deflection(std::exp(log_p))) / target);
  };
  const Real doubling = std::log(2.0);
  Real a = std::log(guess);
  Real fa = residual(a);
  if (std::abs(fa) < kCalibrationTolerance) return guess;
  // which way to go: one probe a factor 2 up tells the slope
  Real b = a + doubling;
  Real fb = residual(b);
  const Real direction = (fb - fa) * fa > 0 ? -1 : 1;  // towards the root
  if (direction < 0) {
    b = a - doubling;
    fb = residual(b);
  }
  for (int i = 0; fa * fb > 0; ++i) {
    if (i == 20) {
      std::fprintf(stderr, "\ncalibration could not bracket the target\n");
      std::exit(1);
    }
    a = b;
    fa = fb;
    b += direction * doubling;
    fb = residual(b);
  }
  int same_side = 0;  // Illinois: halve the residual of an end kept twice in a row
  for (int i = 0; i < 40; ++i) {
    const Real c = b - fb * (b - a) / (fb - fa);
    const Real fc = residual(c);
    if (std::abs(fc) < kCalibrationTolerance) return std::exp(c);
    if (fc * fb < 0) {
      a = b;
      fa = fb;
      same_side = 0;
    } else if (++same_side == 2) {
      fa /= 2;
      same_side = 0;
    }
    b = c;
    fb = fc;
  }
  std::fprintf(stderr, "\ncalibration did not converge\n");
  std::exit(1);
}

// --- the largest step survived without substeps -------------------------------------------------

enum class Bound { kExact, kAtLeast, kBelow };

struct StableStep {
  Real h = kNaN;
  Bound bound = Bound::kExact;
  Real estimate = kNaN;  ///< SolidBody::stable_time_step(), what SolidSystem substeps by
  int trials = 0;
};

/// Fixed steps of h for the whole problem, the body stepped as a SolidSystem substep steps it
/// (update, floor contacts, velocities from the positions; there is no second body), without
/// substeps or rescue. Survived: every node finite and slower than kMaxSpeed after every step.
bool survives(const Problem& problem, const SolidMaterial& material, Real h) {
  SolidBody body = make_body(problem, material);
  const long steps = std::lround(problem.duration / h);
  for (long n = 0; n < steps; ++n) {
    body.advance(h, kGravity);
    resolve_collider_contacts(problem.colliders, body);
    body.finish_step(h);
    for (std::size_t i = 0; i < body.node_count(); ++i) {
      const bool ok = body.positions()[i].allFinite() &&
                      body.velocities()[i].squaredNorm() <= kMaxSpeed * kMaxSpeed;
      if (!ok) return false;
    }
  }
  return true;
}

/// Tries the step cap, then the estimate (halving it while it fails), and bisects in log h
/// between the largest step survived and the smallest failed.
StableStep largest_stable_step(const Problem& problem, const SolidMaterial& material) {
  StableStep s;
  s.estimate = make_body(problem, material).stable_time_step();
  auto stable = [&](Real h) {
    ++s.trials;
    return survives(problem, material, h);
  };
  if (stable(kStepCap)) {
    s.h = kStepCap;
    s.bound = Bound::kAtLeast;
    return s;
  }
  Real lo = std::min(s.estimate, kStepCap / 2);
  Real hi = kStepCap;
  for (int i = 0; !stable(lo); ++i) {
    if (i == 6) {
      s.h = lo;
      s.bound = Bound::kBelow;
      return s;
    }
    hi = lo;
    lo /= 2;
  }
  while (hi / lo > kStableRatio) {
    const Real mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
  }
  s.h = lo;
  return s;
}

// --- metrics
// --------------------------------------------------------------------------------------

/// The oscillation of y about `centre`: the period from its crossings of the centre, and the
/// fraction of the amplitude lost per period from a least-squares fit of ln |y − centre|max
/// over the half periods between the first and the last crossing (the sudden load excites more
/// than the first mode, and single extremes beat by several per cent). A crossing counts once
/// y has gone `band` beyond the centre on the other side, so that ripples of the mesh's fast
/// modes at a crossing do not count. NaN when it crosses fewer than three times (overdamped,
/// or too slow for the run).
struct Oscillation {
  Real period = kNaN;
  Real decay = kNaN;
};

Oscillation oscillation(std::span<const Real> t, std::span<const Real> y, Real centre, Real band) {
  std::vector<Real> crossings;
  std::vector<Real> extremes;  // the largest |y − centre| after each crossing
  int side = 0;                // where y last was beyond the band: −1, +1, or 0 before that
  Real last_zero = kNaN;
  for (std::size_t i = 1; i < y.size(); ++i) {
    const Real a = y[i - 1] - centre, b = y[i] - centre;
    if ((a < 0) != (b < 0)) last_zero = t[i - 1] + (t[i] - t[i - 1]) * a / (a - b);
    const int now = b > band ? 1 : b < -band ? -1 : 0;
    if (now != 0 && now != side) {
      if (side != 0) {
        crossings.push_back(last_zero);
        extremes.push_back(0);
      }
      side = now;
    }
    if (!extremes.empty()) extremes.back() = std::max(extremes.back(), std::abs(b));
  }
  Oscillation o;
  if (crossings.size() < 3) return o;
  const std::size_t halves = crossings.size() - 1;  // complete half periods
  o.period = 2 * (crossings.back() - crossings.front()) / static_cast<Real>(halves);
  const Real mean_k = static_cast<Real>(halves - 1) / 2;
  Real mean_log = 0;
  for (std::size_t k = 0; k < halves; ++k) mean_log += std::log(extremes[k]);
  mean_log /= static_cast<Real>(halves);
  Real covariance = 0, variance = 0;
  for (std::size_t k = 0; k < halves; ++k) {
    const Real dk = static_cast<Real>(k) - mean_k;
    covariance += dk * (std::log(extremes[k]) - mean_log);
    variance += dk * dk;
  }
  o.decay = 1 - std::exp(2 * covariance / variance);
  return o;
}

/// The cantilever's tip deflection at every step of a run, and its oscillation about the
/// equilibrium tip deflection `equilibrium` (a crossing must pass 5 % of the sag beyond it).
Oscillation tip_oscillation(const Problem& problem, const Run& run, Real equilibrium) {
  const Real rest = mean_y(problem.mesh.nodes, problem.top);
  std::vector<Real> tip(run.top_y.size());
  for (std::size_t i = 0; i < tip.size(); ++i) tip[i] = run.top_y[i] - rest;
  return oscillation(run.t, tip, equilibrium, 0.05 * std::abs(equilibrium));
}

Real rms_distance(std::span<const Vec3> a, std::span<const Vec3> b) {
  Real sum = 0;
  for (std::size_t n = 0; n < a.size(); ++n) sum += (a[n] - b[n]).squaredNorm();
  return std::sqrt(sum / static_cast<Real>(a.size()));
}

/// Mean of y over the samples with t within `window` of the last one.
Real tail_mean(std::span<const Real> t, std::span<const Real> y, Real window) {
  Real sum = 0;
  int count = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < t.back() - window) continue;
    sum += y[i];
    ++count;
  }
  return sum / count;
}

/// 1 − the smallest distance between the top and bottom faces over the run / its rest value.
Real peak_compression(const Problem& problem, const Run& run) {
  const Real rest_height =
      mean_y(problem.mesh.nodes, problem.top) - mean_y(problem.mesh.nodes, problem.bottom);
  Real lowest = rest_height;
  for (std::size_t i = 0; i < run.t.size(); ++i) {
    lowest = std::min(lowest, run.top_y[i] - run.bottom_y[i]);
  }
  return 1 - lowest / rest_height;
}

struct Row {
  std::string problem;
  Model model = Model::kFem;
  std::string integrator;  ///< a cloth integrator, or empty: the model's own scheme
  Real h = 0;
  int substeps = 0;
  int rescued_steps = 0;
  bool failed = false;
  Real cpu_ms_per_sim_s = kNaN, wall_ms_per_sim_s = kNaN;
  Real model_share = kNaN;  ///< of the step's wall time, in the model's forces and update
  /// m: cantilever, the tip deflection's; cube, the node positions' (RMS over nodes and samples)
  Real rms_error = kNaN, max_error = kNaN;
  Real centre_rms_error = kNaN;  ///< m, cube: the mean height of all nodes
  Real frequency_ratio = kNaN;   ///< cantilever: f / f_reference
  Real decay = kNaN;             ///< cantilever: fraction of the amplitude lost per period
  /// m: cantilever, the tip deflection at equilibrium minus the reference's; cube, the mean
  /// node height over the last kRestWindow minus the reference's
  Real static_error = kNaN;
  Real static_shape_error = kNaN;    ///< m, cantilever: RMS node distance at equilibrium
  Real peak_compression = kNaN;      ///< cube: 1 − smallest height / rest height
  Real max_volume_change = kNaN;     ///< max |V/V₀ − 1| over the run
  Real static_volume_change = kNaN;  ///< V/V₀ − 1 at equilibrium (cube: over the last window)
  bool relaxed = true;               ///< the cantilever's relaxation converged
};

/// The reference's data the rows are compared with.
struct Reference {
  Run run;
  Equilibrium equilibrium;  ///< cantilever only
  Real period = kNaN;
  Real resting_centre = kNaN;  ///< cube
};

/// `eq`: the equilibrium at the run's step, for the cantilever.
Row make_row(const Problem& problem, Model model, const Run& run, const Reference& ref,
             const Equilibrium& eq) {
  Row row;
  row.problem = problem.name;
  row.model = model;
  row.h = run.h;
  row.substeps = run.substeps;
  row.rescued_steps = run.rescued_steps;
  row.failed = run.failed;
  if (run.simulated > 0) {
    row.cpu_ms_per_sim_s = 1e3 * run.cpu_seconds / run.simulated;
    row.wall_ms_per_sim_s = 1e3 * run.wall_seconds / run.simulated;
    row.model_share = run.model_seconds / run.wall_seconds;
  }
  if (run.failed) return row;
  const Real rest_volume = total_volume(problem.mesh.nodes, problem.mesh.tets);
  row.max_volume_change = 0;
  for (Real v : run.volume) {
    row.max_volume_change = std::max(row.max_volume_change, std::abs(v / rest_volume - 1));
  }

  // errors at the common sample times, t = 0 (where all agree) left out
  const std::size_t samples = std::min(run.samples.size(), ref.run.samples.size());
  Real sum = 0, centre_sum = 0, worst = 0;
  for (std::size_t s = 1; s < samples; ++s) {
    const std::vector<Vec3>& x = run.samples[s];
    const std::vector<Vec3>& r = ref.run.samples[s];
    const Real e = problem.is_cantilever() ? tip_deflection(problem, x) - tip_deflection(problem, r)
                                           : rms_distance(x, r);
    sum += e * e;
    worst = std::max(worst, std::abs(e));
    const Real c = centre_y(x) - centre_y(r);
    centre_sum += c * c;
  }
  const auto count = static_cast<Real>(samples - 1);
  row.rms_error = std::sqrt(sum / count);
  row.max_error = worst;

  if (problem.is_cantilever()) {
    const Oscillation o = tip_oscillation(problem, run, eq.tip);
    row.frequency_ratio = ref.period / o.period;
    row.decay = o.decay;
    row.static_error = eq.tip - ref.equilibrium.tip;
    row.static_shape_error = rms_distance(eq.x, ref.equilibrium.x);
    row.static_volume_change = total_volume(eq.x, problem.mesh.tets) / rest_volume - 1;
    row.relaxed = eq.converged;
  } else {
    row.centre_rms_error = std::sqrt(centre_sum / count);
    row.peak_compression = peak_compression(problem, run);
    row.static_error = tail_mean(run.t, run.centre, kRestWindow) - ref.resting_centre;
    row.static_volume_change = tail_mean(run.t, run.volume, kRestWindow) / rest_volume - 1;
  }
  return row;
}

// --- output
// ---------------------------------------------------------------------------------------

const char* bound_name(Bound b) {
  switch (b) {
    case Bound::kExact:
      return "exact";
    case Bound::kAtLeast:
      return "at_least";
    case Bound::kBelow:
      return "below";
  }
  return "";
}

struct Limit {
  std::string problem;
  Model model = Model::kFem;
  StableStep step;
};

const Limit* find_limit(const std::vector<Limit>& limits, std::string_view problem, Model model) {
  for (const Limit& l : limits) {
    if (l.problem == problem && l.model == model) return &l;
  }
  return nullptr;
}

void write_csv(const std::filesystem::path& path, const std::vector<Row>& rows,
               const std::vector<Limit>& limits) {
  std::ofstream out(path);
  out << "problem,model,h_s,substeps,failed,rescued_steps,cpu_ms_per_sim_s,wall_ms_per_sim_s,"
         "model_share,rms_error_m,max_error_m,centre_rms_error_m,frequency_ratio,"
         "decay_per_period,static_error_m,static_shape_error_m,relaxed,peak_compression,"
         "max_volume_change,static_volume_change,largest_stable_step_s,"
         "largest_stable_step_bound,stable_step_estimate_s\n";
  for (const Row& r : rows) {
    const Limit* l = find_limit(limits, r.problem, r.model);
    out << r.problem << ',' << model_name(r.model) << ',' << csv_number(r.h) << ',' << r.substeps
        << ',' << (r.failed ? 1 : 0) << ',' << r.rescued_steps << ','
        << csv_number(r.cpu_ms_per_sim_s) << ',' << csv_number(r.wall_ms_per_sim_s) << ','
        << csv_number(r.model_share) << ',' << csv_number(r.rms_error) << ','
        << csv_number(r.max_error) << ',' << csv_number(r.centre_rms_error) << ','
        << csv_number(r.frequency_ratio) << ',' << csv_number(r.decay) << ','
        << csv_number(r.static_error) << ',' << csv_number(r.static_shape_error) << ','
        << (r.relaxed ? 1 : 0) << ',' << csv_number(r.peak_compression) << ','
        << csv_number(r.max_volume_change) << ',' << csv_number(r.static_volume_change) << ','
        << (l ? csv_number(l->step.h) : "") << ',' << (l ? bound_name(l->step.bound) : "") << ','
        << (l ? csv_number(l->step.estimate) : "") << '\n';
  }
}

/// problem, model ("fem_reference" for the reference), h, t and the plotted signal: the
/// cantilever's tip deflection, the cube's mean node height.
class TrajectoryCsv {
 public:
  explicit TrajectoryCsv(const std::filesystem::path& path) : out_(path) {
    out_ << "problem,model,h_s,t_s,signal_m\n";
  }
  void add(const Problem& problem, std::string_view model, const Run& run) {
    const long every = steps_per(kPlotInterval, run.h);
    const Real rest_tip = mean_y(problem.mesh.nodes, problem.top);
    for (std::size_t i = 0; i < run.t.size(); i += static_cast<std::size_t>(every)) {
      const Real signal = problem.is_cantilever() ? run.top_y[i] - rest_tip : run.centre[i];
      out_ << problem.name << ',' << model << ',' << csv_number(run.h) << ','
           << csv_number(run.t[i]) << ',' << csv_number(signal) << '\n';
    }
  }

 private:
  std::ofstream out_;
};

std::string cell(Real value, const char* fmt = "%.3g") {
  return std::isfinite(value) ? format(fmt, value) : std::string("—");
}

std::string limit_cell(const StableStep& s) {
  switch (s.bound) {
    case Bound::kExact:
      return format("%.3g", s.h * 1e3);
    case Bound::kAtLeast:
      return "≥ " + ms(s.h);
    case Bound::kBelow:
      return "< " + format("%.3g", s.h * 1e3);
  }
  return "";
}

/// "model @ h ms: CPU ms/s" of the cheapest run of `problem` with rms_error ≤ target, or "none".
std::string cheapest(const std::vector<Row>& rows, std::string_view problem, Real target) {
  const Row* best = nullptr;
  for (const Row& r : rows) {
    if (r.problem != problem || r.failed || !(r.rms_error <= target)) continue;
    if (!best || r.cpu_ms_per_sim_s < best->cpu_ms_per_sim_s) best = &r;
  }
  if (!best) return "none";
  return model_name(best->model) + " @ " + ms(best->h) +
         " ms: " + format("%.3g", best->cpu_ms_per_sim_s);
}

struct Summary {
  Stiffness stiffness;
  int mass_spring_relaxations = 0, shape_matching_relaxations = 0;
  Real reference_tip = 0;     ///< m, the static tip deflection all models are calibrated to
  Real reference_period = 0;  ///< s
  Real reference_compression = 0, reference_resting_centre = 0;
  Real cantilever_check = 0, cube_check = 0;  ///< m, reference against twice its step
  Real cantilever_reference_cpu = 0, cube_reference_cpu = 0;  ///< s per simulated s
  Real cantilever_node_mass = 0, cube_node_mass = 0;
};

/// The cloth integrators on the force models: error against the FEM reference and cost.
void integrator_table(std::ostringstream& out, const std::vector<Row>& rows) {
  out << "### Cloth integrators on the force models\n\n"
      << "The mass-spring and FEM bodies above stepped by each cloth integrator that applies to "
         "them (docs/scenes.md) instead of the time-corrected Verlet of the main table, at three "
         "steps, through the same SolidSystem: the substeps are the Verlet stability bound's for "
         "every integrator. Error as in the main table (cantilever: tip deflection; cube: node "
         "positions; RMS over the samples) against the same FEM reference; \"failed\": an "
         "unrecoverable step.\n\n"
      << "| problem | model | integrator | h (ms) | substeps | CPU ms/s | RMS error (mm) | "
         "max error (mm) |\n|---|---|---|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows) {
    out << "| " << r.problem << " | " << model_name(r.model) << " | " << r.integrator << " | "
        << ms(r.h) << " | " << r.substeps << " | " << cell(r.cpu_ms_per_sim_s) << " | "
        << (r.failed ? std::string("failed") : cell(r.rms_error * 1e3)) << " | "
        << (r.failed ? std::string("—") : cell(r.max_error * 1e3)) << " |\n";
  }
  out << '\n';
}

std::string make_tables(const Plan& plan, const Summary& s, const std::vector<Row>& rows,
                        const std::vector<Limit>& limits, const std::vector<Row>& integrator_rows,
                        double total_seconds) {
  std::ostringstream out;
  out << study::generated_by("solid_model_study", total_seconds)
      << " Costs are CPU time of the study's thread in SolidSystem::step on a shared 2-core "
         "machine: compare ratios within this run.\n"
      << "Steps h in ms are the requested steps; SolidSystem splits each into `substeps` no "
         "longer than the body's stable step. \"—\": not measurable (see each table).\n\n";

  const Real sag = -s.reference_tip;
  out << "### Calibration\n\n"
      << "Static tip deflection of the cantilever at h = " << ms(plan.reference_step)
      << " ms, matched to " << kCalibrationTolerance * 100 << " %. Node masses "
      << format("%.4g", s.cantilever_node_mass) << " kg (cantilever), "
      << format("%.4g", s.cube_node_mass) << " kg (cube).\n\n"
      << "| model | parameters | static tip deflection (mm) | relaxations |\n"
      << "|---|---|---:|---:|\n"
      << "| fem | E = " << format("%g", kYoung) << " Pa, ν = " << format("%g", kPoisson)
      << ", β = " << ms(kRayleigh) << " ms | " << format("%.2f", sag * 1e3) << " | 1 |\n"
      << "| mass_spring | k_D = " << format("%.4g", s.stiffness.distance_stiffness) << ", k_V = "
      << format("%.4g", kVolumeRatio * s.stiffness.distance_stiffness / (kCell * kCell * kCell))
      << ", d_C = " << format("%.3g", kRayleigh * s.stiffness.distance_stiffness) << " | "
      << format("%.2f", sag * 1e3) << " (calibrated) | " << s.mass_spring_relaxations << " |\n"
      << "| shape_matching | τ = " << format("%.4g", s.stiffness.time_constant * 1e3)
      << " ms, linear, β = 0.5, a cluster per cell | " << format("%.2f", sag * 1e3)
      << " (calibrated) | " << s.shape_matching_relaxations << " |\n"
      << "| shape_matching_per_step | τ at each step h such that τ_eff = h / (1 − e^(−h/τ)) = "
      << format("%.4g", s.stiffness.effective_time_constant * 1e3)
      << " ms, its value at the calibration; τ = h / " << format("%g", kStiffestStepsPerTau)
      << " (the stiffest) at h ≥ that; otherwise as above | " << format("%.2f", sag * 1e3)
      << " where h < τ_eff | — |\n\n"
      << "Reference: FEM at h = " << ms(plan.reference_step) << " ms ("
      << format("%.2f", s.cantilever_reference_cpu) << " and "
      << format("%.2f", s.cube_reference_cpu)
      << " s of CPU time per simulated second). Its first bending period is "
      << format("%.3f", s.reference_period) << " s; the cube's peak compression "
      << format("%.2f", 100 * s.reference_compression) << " %, its resting centre "
      << format("%.1f", s.reference_resting_centre * 1e3)
      << " mm above the floor. Against FEM at twice its step the reference differs by "
      << format("%.2g", s.cantilever_check * 1e3) << " mm (cantilever tip, RMS) and "
      << format("%.2g", s.cube_check * 1e3)
      << " mm (cube nodes, RMS); Verlet is second order, so its own error is about a third of "
         "that where the motion is smooth.\n\n";

  auto by_model = [&](std::string_view problem, auto&& write) {
    for (Model model : kModels) {
      for (const Row& r : rows) {
        if (r.problem == problem && r.model == model) write(r);
      }
    }
  };
  auto costs = [&](const Row& r) {
    out << "| " << model_name(r.model) << " | " << ms(r.h) << " | " << r.substeps << " | "
        << cell(r.cpu_ms_per_sim_s) << " | " << cell(100 * r.model_share, "%.0f") << " | ";
  };

  out << "### Cantilever: " << format("%g", plan.cantilever_time)
      << " s from rest under gravity\n\n"
      << "Tip: the mean vertical displacement of the free end face. Errors against the reference "
         "every "
      << format("%g", kSampleInterval * 1e3)
      << " ms. f/f_FEM: the first bending frequency (from crossings of the model's own "
         "equilibrium) over the reference's. Lost: amplitude lost per period. Static: the "
         "equilibrium SolidSystem reaches at that step (kinetic damping), against the "
         "reference's, tip deflection (positive: the model sags more) and RMS over all nodes. "
         "ΔV: volume change, the largest during the run and at equilibrium.\n\n"
      << "| model | h | substeps | CPU ms/s | model (%) | tip RMS error (mm) | (% of sag) | tip "
         "max error (mm) | f/f_FEM | lost (%/period) | static tip error (%) | static shape "
         "error (mm) | max ΔV (%) | static ΔV (%) |\n"
      << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  by_model("cantilever", [&](const Row& r) {
    costs(r);
    if (r.failed) {
      out << "failed | | | | | | | | |\n";
      return;
    }
    out << cell(r.rms_error * 1e3) << " | " << cell(100 * r.rms_error / sag, "%.2g") << " | "
        << cell(r.max_error * 1e3) << " | " << cell(r.frequency_ratio, "%.3f") << " | "
        << cell(100 * r.decay, "%.2g") << " | " << cell(100 * r.static_error / -sag, "%+.3g")
        << (r.relaxed ? "" : " (not settled)") << " | " << cell(r.static_shape_error * 1e3) << " | "
        << cell(100 * r.max_volume_change, "%.2g") << " | "
        << cell(100 * r.static_volume_change, "%+.2g") << " |\n";
  });

  out << "\n### Cube: dropped flat from " << format("%g", kDropHeight * 1e2) << " cm, "
      << format("%g", plan.cube_time) << " s\n\n"
      << "Node error: RMS over all nodes, then RMS (and max) over the samples every "
      << format("%g", kSampleInterval * 1e3)
      << " ms. Centre: the mean height of the nodes. Peak compression: 1 − the smallest "
         "distance between the top and bottom faces / its rest value (reference: "
      << format("%.2f", 100 * s.reference_compression) << " %). Resting error: the centre's mean "
      << "over the last " << format("%g", kRestWindow)
      << " s against the reference's (negative: lower, squashed or sunk). ΔV: the largest "
         "|V/V₀ − 1| during the run and the mean over the last window.\n\n"
      << "| model | h | substeps | CPU ms/s | model (%) | node RMS error (mm) | node max error "
         "(mm) | centre RMS error (mm) | peak compression (%) | resting error (mm) | max ΔV (%) | "
         "resting ΔV (%) |\n"
      << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  by_model("cube", [&](const Row& r) {
    costs(r);
    if (r.failed) {
      out << "failed | | | | | | |\n";
      return;
    }
    out << cell(r.rms_error * 1e3) << " | " << cell(r.max_error * 1e3) << " | "
        << cell(r.centre_rms_error * 1e3) << " | " << cell(100 * r.peak_compression) << " | "
        << cell(r.static_error * 1e3, "%+.3g") << " | " << cell(100 * r.max_volume_change, "%.2g")
        << " | " << cell(100 * r.static_volume_change, "%+.2g") << " |\n";
  });

  out << "\n### The cheapest run under an error target\n\n"
      << "Over the requested steps of every model; CPU ms per simulated second.\n\n"
      << "| cantilever: tip RMS error ≤ | cheapest run |\n|---|---|\n";
  for (Real percent : {0.01, 0.1, 1.0, 10.0, 100.0}) {
    out << "| " << format("%g", percent) << " % of the sag | "
        << cheapest(rows, "cantilever", percent / 100 * sag) << " |\n";
  }
  out << "\n| cube: node RMS error ≤ | cheapest run |\n|---|---|\n";
  for (Real mm : {0.3, 1.0, 3.0, 10.0, 30.0, 100.0}) {
    out << "| " << format("%g", mm) << " mm | " << cheapest(rows, "cube", mm * 1e-3) << " |\n";
  }

  out << "\n### Largest fixed step survived, without substeps (ms)\n\n"
      << "The body stepped at one fixed step for the whole problem, no substeps, no rescue; "
         "survived: every node finite and slower than "
      << format("%g", kMaxSpeed) << " m/s. Bisection in log h to " << (kStableRatio - 1) * 100
      << " %. ≥ " << ms(kStepCap)
      << ": survived the cap. Estimate: `stable_time_step()`, the substep SolidSystem uses.\n\n"
      << "| model | cantilever | estimate | survived / estimate | cube | estimate | survived / "
         "estimate |\n"
      << "|---|---:|---:|---:|---:|---:|---:|\n";
  for (Model model : kModels) {
    if (model == Model::kShapeMatchingPerStep) continue;  // its material changes with the step
    out << "| " << model_name(model) << " |";
    for (std::string_view problem : {"cantilever", "cube"}) {
      const Limit* l = find_limit(limits, problem, model);
      if (!l) {
        out << " ? | ? | ? |";
        continue;
      }
      const Real ratio = l->step.h / l->step.estimate;
      out << ' ' << limit_cell(l->step) << " | " << cell(l->step.estimate * 1e3) << " | "
          << (l->step.bound == Bound::kExact ? cell(ratio, "%.2f") : std::string("—")) << " |";
    }
    out << '\n';
  }
  out << '\n';
  integrator_table(out, integrator_rows);
  return out.str();
}

// --- the study ----------------------------------------------------------------------------------

int run_study(const std::filesystem::path& dir, const Plan& plan) {
  std::filesystem::create_directories(dir);
  const Problem bar = cantilever(plan.cantilever_time);
  const Problem cube = dropped_cube(plan.cube_time);
  const int runs = static_cast<int>(kModels.size() * plan.steps.size()) + 1;  // with the check
  const int limited = static_cast<int>(kModels.size()) - 1;  // not the per-step shape matching
  int integrator_runs = 0;
  for (SolidModel model : kIntegratorModels) {
    integrator_runs += static_cast<int>(integrators_for(model).size() * kIntegratorSteps.size());
  }
  // calibration (3); per problem the reference, the runs, the stable steps and the
  // integrators; the cantilever's relaxation after each run
  study::Progress progress(3 + 2 * (1 + runs + limited + integrator_runs) + runs);
  Summary summary;
  summary.cantilever_node_mass = bar.node_mass;
  summary.cube_node_mass = cube.node_mass;
  const Real h_ref = plan.reference_step;

  // the reference's static sag, and the two models calibrated to it
  progress.begin(format("calibration: fem static sag at h=%sms", ms(h_ref).c_str()));
  const Equilibrium reference_eq =
      relax(bar, material(Model::kFem, {}, bar.node_mass, h_ref), h_ref);
  summary.reference_tip = reference_eq.tip;
  progress.end(
      format("%.2f mm%s", -reference_eq.tip * 1e3, reference_eq.converged ? "" : " (not settled)"));
  const Real target = std::abs(reference_eq.tip);

  progress.begin("calibration: mass_spring k_D");
  summary.stiffness.distance_stiffness = calibrate(
      [&](Real k_d) {
        return relax(bar, material(Model::kMassSpring, {k_d, 0}, bar.node_mass, h_ref), h_ref).tip;
      },
      kYoung * kCell * kCell * kCell, target, summary.mass_spring_relaxations);
  progress.end(format("k_D = %.4g (%d relaxations)", summary.stiffness.distance_stiffness,
                      summary.mass_spring_relaxations));

  progress.begin("calibration: shape_matching tau");
  summary.stiffness.time_constant = calibrate(
      [&](Real tau) {
        return relax(bar, material(Model::kShapeMatching, {0, tau}, bar.node_mass, h_ref), h_ref)
            .tip;
      },
      kCell * std::sqrt(kDensity / kYoung), target, summary.shape_matching_relaxations);
  summary.stiffness.effective_time_constant =
      effective_time_constant(summary.stiffness.time_constant, h_ref);
  progress.end(format("tau = %.4g ms (%d relaxations)", summary.stiffness.time_constant * 1e3,
                      summary.shape_matching_relaxations));

  std::vector<Row> rows, integrator_rows;
  std::vector<Limit> limits;
  TrajectoryCsv trajectories(dir / "solid_models_trajectories.csv");

  for (const Problem* problem : {&bar, &cube}) {
    auto material_of = [&](Model model, Real h) {
      return material(model, summary.stiffness, problem->node_mass, h);
    };

    Reference ref;
    progress.begin(format("%s reference fem h=%sms", problem->name.c_str(), ms(h_ref).c_str()));
    ref.run = simulate(*problem, material_of(Model::kFem, h_ref), h_ref);
    if (ref.run.failed) {
      std::fprintf(stderr, "\nthe reference failed; choose a smaller reference step\n");
      return 1;
    }
    const Real reference_cpu = ref.run.cpu_seconds / ref.run.simulated;
    if (problem->is_cantilever()) {
      ref.equilibrium = reference_eq;
      ref.period = tip_oscillation(bar, ref.run, reference_eq.tip).period;
      summary.reference_period = ref.period;
      summary.cantilever_reference_cpu = reference_cpu;
    } else {
      ref.resting_centre = tail_mean(ref.run.t, ref.run.centre, kRestWindow);
      summary.reference_resting_centre = ref.resting_centre;
      summary.reference_compression = peak_compression(cube, ref.run);
      summary.cube_reference_cpu = reference_cpu;
    }
    trajectories.add(*problem, "fem_reference", ref.run);
    progress.end(format("%.2f s CPU per simulated s", reference_cpu));

    // a run through SolidSystem, and for the cantilever the equilibrium at the same step
    auto measure = [&](Model model, Real h) {
      const SolidMaterial m = material_of(model, h);
      const Run run = simulate(*problem, m, h);
      Equilibrium eq;
      if (problem->is_cantilever()) {
        progress.end(format("%.3g ms/s", 1e3 * run.cpu_seconds / run.simulated));
        progress.begin(format("%s static %s h=%sms", problem->name.c_str(),
                              model_name(model).c_str(), ms(h).c_str()));
        eq = relax(*problem, m, h);
      }
      rows.push_back(make_row(*problem, model, run, ref, eq));
      const Row& row = rows.back();
      progress.end(row.failed ? std::string("failed")
                              : format("error %.3g mm (RMS), static %+.3g mm%s, %.3g ms/s",
                                       row.rms_error * 1e3, row.static_error * 1e3,
                                       row.relaxed ? "" : " (not settled)", row.cpu_ms_per_sim_s));
      return run;
    };
    // FEM at twice the reference step: the reference's own error, and one more FEM point
    progress.begin(
        format("%s fem h=%sms (reference check)", problem->name.c_str(), ms(2 * h_ref).c_str()));
    measure(Model::kFem, 2 * h_ref);
    (problem->is_cantilever() ? summary.cantilever_check : summary.cube_check) =
        rows.back().rms_error;

    for (Model model : kModels) {
      for (Real h : plan.steps) {
        progress.begin(format("%s %s h=%sms", problem->name.c_str(), model_name(model).c_str(),
                              ms(h).c_str()));
        const Run run = measure(model, h);
        if (std::ranges::find(kPlottedSteps, h) != kPlottedSteps.end()) {
          trajectories.add(*problem, model_name(model), run);
        }
      }
    }

    for (SolidModel solid_model : kIntegratorModels) {
      const Model model = solid_model == SolidModel::kMassSpring ? Model::kMassSpring : Model::kFem;
      for (std::string_view integrator : integrators_for(solid_model)) {
        for (Real h : kIntegratorSteps) {
          progress.begin(format("%s %s %s h=%sms", problem->name.c_str(), model_name(model).c_str(),
                                std::string(integrator).c_str(), ms(h).c_str()));
          const Run run = simulate(*problem, material_of(model, h), h, integrator);
          Row row = make_row(*problem, model, run, ref, ref.equilibrium);
          row.integrator = integrator;
          progress.end(row.failed ? std::string("failed")
                                  : format("error %.3g mm (RMS), %.3g ms/s", row.rms_error * 1e3,
                                           row.cpu_ms_per_sim_s));
          integrator_rows.push_back(std::move(row));
        }
      }
    }

    for (Model model : kModels) {
      if (model == Model::kShapeMatchingPerStep) continue;
      progress.begin(
          format("%s largest stable step %s", problem->name.c_str(), model_name(model).c_str()));
      const StableStep s = largest_stable_step(*problem, material_of(model, kStepCap));
      limits.push_back({problem->name, model, s});
      progress.end(format("%s ms (estimate %.3g ms, %d trials)", limit_cell(s).c_str(),
                          s.estimate * 1e3, s.trials));
    }
  }

  write_csv(dir / "solid_models.csv", rows, limits);
  study::write_tables(
      dir, "solid_models.md", "Soft-solid models: error against cost", "solid_models_tables.md",
      "solid_model_study",
      make_tables(plan, summary, rows, limits, integrator_rows, progress.elapsed()));
  std::fprintf(stderr, "done in %.0f s: %s\n", progress.elapsed(), dir.c_str());
  return 0;
}

}  // namespace
}  // namespace felt

int main(int argc, char** argv) {
  std::filesystem::path dir;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--quick") {
      quick = true;
    } else if (dir.empty() && !arg.starts_with("-")) {
      dir = arg;
    } else {
      dir.clear();
      break;
    }
  }
  if (dir.empty()) {
    std::fprintf(stderr, "usage: %s OUT_DIR [--quick]\n", argv[0]);
    return 2;
  }
  return felt::run_study(dir, quick ? felt::quick_plan() : felt::full_plan());
}
