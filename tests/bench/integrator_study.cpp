// The integrator study: every integrator × time step × stiffness, on two problems.
//
//  (a) A spring–mass oscillator: one cloth particle on one structural spring to a pinned
//      anchor, undamped, started 1 mm from rest; analytic solution x0 cos ωt.
//  (b) A 40 × 40 cloth (0.6 m, 0.2 kg) pinned at its two top corners and released from the
//      horizontal, so it swings down through large motions; reference solution RK4 at a much
//      smaller step.
//
// Per run it records the error at t = 0.5 s, the wall time per simulated second and the energy
// drift; per integrator × stiffness the largest stable step (bisection). Rescue by substeps is
// off, so every number is what the scheme does on its own. Not a unit test: machines are
// shared and noisy, so compare ratios within one run.
//
// Usage: integrator_study OUT_DIR [--quick]
// Writes OUT_DIR/integrators.csv (one row per run), OUT_DIR/integrators_stable_step.csv (one row
// per scene × integrator × stiffness) and the Markdown tables into OUT_DIR/integrators.md,
// between the markers below (the text around them is kept; a missing file is created).
// Progress goes to stderr. --quick runs a small subset (a smoke test, not for the results).
// scripts/bench-integrators builds it, runs it into docs/results/ and draws the plots.
//
// Over 500 lines: one study read top to bottom (the two problems, the runs, the bisection of
// the stable step, the tables); its parts are used nowhere else.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "core/cloth/cloth_grid.hpp"
#include "core/world/world.hpp"
#include "study_output.hpp"

namespace felt {
namespace {

using Clock = std::chrono::steady_clock;
using namespace study;
constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();

// --- the problems ------------------------------------------------------------------------------

constexpr Real kSimTime = 0.5;  ///< s: errors are measured here, and cloth runs last this long
constexpr Real kGravity = 9.81;
constexpr std::uint32_t kClothN = 40;  ///< particles per side
constexpr Real kClothSize = 0.6;       ///< m, width and height
constexpr Real kClothMass = 0.2;       ///< kg
constexpr Real kParticleMass = kClothMass / (kClothN * kClothN);
constexpr Real kRestLength = kClothSize / (kClothN - 1);  ///< of a structural spring
/// Structural stiffness of the tables that show one stiffness (the cloth of docs/results/
/// cloth.md table 1). Shear and bend scale with it in the same ratios as there (40 and 2 : 150).
constexpr Real kDefaultStiffness = 150;
/// The scale cloth energy errors are given in: the potential energy the cloth's centre of mass
/// loses when it swings from the horizontal to hanging straight down, M g W / 2.
constexpr Real kClothEnergyScale = kClothMass * kGravity * kClothSize / 2;

constexpr Real kAmplitude = 1e-3;        ///< m: oscillator start, a 6.5 % stretch of a cloth spring
constexpr Real kDriftPeriods = 1e4;      ///< the oscillator's long run, in periods ...
constexpr long kMaxDriftSteps = 200000;  ///< ... but at most this many steps
/// Stable: the amplitude |(x, v/ω)| stays within 10 x0. Not 2: near their limit the stable
/// schemes' invariant ellipse is stretched (symplectic Euler's already by 2 at ωh = 1.5), and
/// that is not a blow-up. Explicit Euler and midpoint gain energy at every h, so their "limit"
/// depends on this bound and on the number of steps: ωh < √(2 ln 10 / N), resp. (4 ln 100 / N)^¼.
constexpr Real kMaxAmplitude = 10;
constexpr long kStabilitySteps = 10000;  ///< steps of an oscillator stability trial

// --- the largest stable step --------------------------------------------------------------------

constexpr Real kStepCap = 16e-3;         ///< s: steps larger than this are not tried
constexpr Real kOscillatorFloor = 1e-7;  ///< s: the oscillator bisection's lower end
constexpr Real kOscillatorRatio = 1.01;  ///< bisection stops when hi/lo is below this
constexpr Real kClothRatio = 1.05;
constexpr int kClothFloorHalvings = 3;  ///< below the smallest swept step, try h/2, h/4, h/8

struct Plan {
  std::vector<Real> steps;      ///< s, descending
  std::vector<Real> stiffness;  ///< structural k, N/m; must include kDefaultStiffness
  Real reference_step = 0;      ///< s
};

Plan full_plan() {
  // reference: a tenth of the smallest swept step (the tables show its estimated error)
  return {{4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4}, {50, 150, 500, 1500, 5000}, 1.25e-5};
}
Plan quick_plan() {
  return {{2e-3, 1e-3, 5e-4}, {150, 1500}, 5e-5};
}

// --- (a) the oscillator
// ----------------------------------------------------------------------------

/// Particle 1 on a structural spring of rest length kRestLength to particle 0, which is pinned.
/// It moves along x only, where the spring force is exactly −k (|l| − r).
ClothBody make_oscillator(std::string_view integrator, Real k) {
  auto model = std::make_shared<ClothModel>();
  model->rest_positions = {Vec3::Zero(), Vec3(kRestLength, 0, 0)};
  model->uv = {Vec2(0, 0), Vec2(1, 0)};
  model->mass = {kParticleMass, kParticleMass};
  model->springs = {Spring{0, 1, kRestLength, SpringKind::kStructural}};
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, k, 0};
  params.spring(SpringKind::kShear).enabled = false;
  params.spring(SpringKind::kBend).enabled = false;
  params.drag = 0;
  ClothBody body("oscillator", std::move(model), params, make_integrator(integrator));
  body.pin(0);
  body.state().x[1].x() += kAmplitude;
  return body;
}

Real omega_of(Real k) {
  return std::sqrt(k / kParticleMass);
}

/// (x² + (v/ω)²) / x0²: the squared amplitude relative to the start; 1 for the exact solution.
Real amplitude_sq(const ClothBody& body, Real omega) {
  const Real x = body.state().x[1].x() - kRestLength;
  const Real v = body.state().v[1].x() / omega;
  return (x * x + v * v) / (kAmplitude * kAmplitude);
}

/// |(x, v/ω) − (x_exact, v_exact/ω)| / x0 at time t.
Real oscillator_error(const ClothBody& body, Real t, Real omega) {
  const Real x = body.state().x[1].x() - kRestLength;
  const Real v = body.state().v[1].x();
  return std::hypot(x - kAmplitude * std::cos(omega * t),
                    (v + kAmplitude * omega * std::sin(omega * t)) / omega) /
         kAmplitude;
}

Real energy(const ClothBody& body) {
  return body.kinetic_energy() + body.elastic_energy();
}

struct OscillatorRun {
  Real error = kNaN;  ///< at kSimTime; NaN when it left the bound before
  Real drift = kNaN;  ///< relative energy change over the long run; NaN when not stable
  Real wall_ms_per_sim_s = kNaN;
  long steps = 0;       ///< the long run's length
  long steps_done = 0;  ///< less when the amplitude left the bound
  bool stable = false;
};

/// One long run: min(kDriftPeriods periods, kMaxDriftSteps steps), at least to kSimTime. The
/// error is taken at kSimTime on the way, the wall time and the drift over the whole run.
OscillatorRun run_oscillator(std::string_view integrator, Real k, Real h) {
  ClothBody body = make_oscillator(integrator, k);
  const Real omega = omega_of(k);
  const long error_step = std::lround(kSimTime / h);
  const long drift_steps = std::lround(kDriftPeriods * 2 * std::numbers::pi / omega / h);
  OscillatorRun run;
  run.steps = std::max(error_step, std::min(drift_steps, kMaxDriftSteps));
  const Real start_energy = energy(body);
  const Real bound = kMaxAmplitude * kMaxAmplitude;
  run.stable = true;
  run.steps_done = run.steps;
  const auto start = Clock::now();
  for (long n = 0; n < run.steps; ++n) {
    body.integrator().step(body, body.state(), static_cast<Real>(n) * h, h);
    if (!(amplitude_sq(body, omega) <= bound)) {
      run.stable = false;
      run.steps_done = n + 1;
      break;
    }
    if (n + 1 == error_step)
      run.error = oscillator_error(body, static_cast<Real>(n + 1) * h, omega);
  }
  run.wall_ms_per_sim_s = 1e3 * seconds_since(start) / (static_cast<Real>(run.steps_done) * h);
  if (run.stable) run.drift = (energy(body) - start_energy) / start_energy;
  return run;
}

/// Stable: the amplitude stays within kMaxAmplitude x0 for kStabilitySteps steps of h.
bool oscillator_stable(std::string_view integrator, Real k, Real h) {
  ClothBody body = make_oscillator(integrator, k);
  const Real omega = omega_of(k);
  for (long n = 0; n < kStabilitySteps; ++n) {
    body.integrator().step(body, body.state(), static_cast<Real>(n) * h, h);
    if (!(amplitude_sq(body, omega) <= kMaxAmplitude * kMaxAmplitude)) return false;
  }
  return true;
}

// --- (b) the cloth
// ----------------------------------------------------------------------------------

ClothParams cloth_params(Real k) {
  ClothParams params;
  params.spring(SpringKind::kStructural) = {true, k, 0.02};
  params.spring(SpringKind::kShear) = {true, k * 40 / 150, 0.01};
  params.spring(SpringKind::kBend) = {true, k * 2 / 150, 0.002};
  // the same drag per unit mass as the 15 × 15 cloth of cloth.md (0.002 N·s/m on 0.2/225 kg)
  params.drag = 2.25 * kParticleMass;
  return params;
}

GridClothSpec cloth_spec() {
  GridClothSpec spec;
  spec.nx = spec.ny = kClothN;
  spec.width = spec.height = kClothSize;
  spec.total_mass = kClothMass;
  spec.plane = GridClothSpec::Plane::kXZ;  // horizontal; it falls and swings from the pins
  return spec;
}

World swinging_cloth(std::string_view integrator, Real k, Real h) {
  static const auto model = std::make_shared<const ClothModel>(make_grid_cloth(cloth_spec()));
  ClothBody body("cloth", model, cloth_params(k), make_integrator(integrator));
  for (std::uint32_t p : grid_pin_indices(cloth_spec(), GridPinPreset::kTopCorners)) body.pin(p);
  // No rescue: a step that leaves a non-finite state or a particle faster than 1000 m/s is
  // unrecoverable. The energy-growth check is off (a scheme that gains energy slowly is not
  // stopped for it; its energy error shows it). Off takes an infinite factor: a finite one,
  // however large, still fails explicit Euler's first step from rest, where the positions do not
  // move, so gravity did no work, and any kinetic energy exceeds "factor × 0". The health
  // checks added since (the energy balance over a window, the scaled speed limit) are off too,
  // and so are automatic substeps: the study measures each scheme at the step it is given.
  HealthSettings health;
  health.energy_tolerance = std::numeric_limits<Real>::infinity();
  health.speed_growth = std::numeric_limits<Real>::infinity();
  health.auto_substeps = false;
  World world(WorldSettings{.gravity = Vec3(0, -kGravity, 0),
                            .time_step = h,
                            .max_speed = 1e3,
                            .max_substep_doublings = 0,
                            .max_energy_growth = std::numeric_limits<Real>::infinity(),
                            .health = health});
  world.add_body(std::move(body));
  return world;
}

/// Kinetic + elastic + gravitational energy (zero at the start: at rest, unstretched, y = 0).
Real cloth_energy(const ClothBody& body) {
  Real e = body.kinetic_energy() + body.elastic_energy();
  for (std::size_t p = 0; p < body.state().size(); ++p) {
    e += body.model().mass[p] * kGravity * body.state().x[p].y();
  }
  return e;
}

struct ClothRun {
  std::vector<Vec3> x;
  Real energy = kNaN;
  double wall_seconds = 0;
  long steps = 0;
  long steps_done = 0;
  bool failed = false;  ///< an unrecoverable step; the run stops there
};

ClothRun run_cloth(std::string_view integrator, Real k, Real h) {
  World world = swinging_cloth(integrator, k, h);
  ClothRun run;
  run.steps = std::lround(kSimTime / h);
  const auto start = Clock::now();
  for (; run.steps_done < run.steps; ++run.steps_done) {
    if (world.step().flags.has(StepFlag::kUnrecoverable)) {
      run.failed = true;
      break;
    }
  }
  run.wall_seconds = seconds_since(start);
  const ClothBody& body = std::as_const(world).cloths()[0];
  run.x = body.state().x;
  run.energy = cloth_energy(body);
  return run;
}

Real max_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  Real d = 0;
  for (std::size_t p = 0; p < a.size(); ++p) d = std::max(d, (a[p] - b[p]).norm());
  return d;
}

// --- results -------------------------------------------------------------------------------------

enum class Bound { kExact, kAtLeast, kBelow };

struct StableStep {
  Real h = kNaN;
  Bound bound = Bound::kExact;
  int trials = 0;
};

struct Row {
  std::string scene;
  std::string integrator;
  Real stiffness = 0;
  Real h = 0;
  long steps = 0;
  long steps_done = 0;
  bool stable = false;
  Real error = kNaN;  ///< oscillator: relative state error; cloth: max particle distance, m
  Real wall_ms_per_sim_s = kNaN;
  /// oscillator: (E_end − E_0)/E_0 over the long run; cloth: (E − E_ref)/(M g W/2) at kSimTime
  Real energy_drift = kNaN;
};

struct Limit {
  std::string scene;
  std::string integrator;
  Real stiffness = 0;
  StableStep step;
};

struct ReferenceInfo {
  Real stiffness = 0;
  Real self_error = 0;  ///< m, estimated from RK4 at h_ref against RK4 at 2 h_ref
  double wall_seconds = 0;
};

/// Log-bisection between a stable lo and an unstable hi until hi/lo <= ratio; returns lo.
template <typename Stable>
Real bisect(Stable stable, Real lo, Real hi, Real ratio, int& trials) {
  while (hi / lo > ratio) {
    const Real mid = std::sqrt(lo * hi);
    ++trials;
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

StableStep oscillator_stable_step(std::string_view integrator, Real k) {
  StableStep s;
  auto stable = [&](Real h) { return oscillator_stable(integrator, k, h); };
  s.trials = 2;
  if (stable(kStepCap)) return {kStepCap, Bound::kAtLeast, 1};
  if (!stable(kOscillatorFloor)) return {kOscillatorFloor, Bound::kBelow, 2};
  s.h = bisect(stable, kOscillatorFloor, kStepCap, kOscillatorRatio, s.trials);
  return s;
}

/// Starts from the sweep's outcomes at the swept steps (the same runs: 0.5 s without an
/// unrecoverable step), then bisects between the largest stable and the next larger step.
StableStep cloth_stable_step(std::string_view integrator, Real k, const std::vector<Real>& steps,
                             const std::vector<bool>& stable_at) {
  auto stable = [&](Real h) { return !run_cloth(integrator, k, h).failed; };
  StableStep s;
  std::size_t largest = steps.size();  // index of the largest stable swept step
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (stable_at[i]) {
      largest = i;
      break;
    }
  }
  if (largest == 0) {
    ++s.trials;
    if (stable(kStepCap)) return {kStepCap, Bound::kAtLeast, s.trials};
    s.h = bisect(stable, steps[0], kStepCap, kClothRatio, s.trials);
    return s;
  }
  if (largest < steps.size()) {
    s.h = bisect(stable, steps[largest], steps[largest - 1], kClothRatio, s.trials);
    return s;
  }
  Real hi = steps.back();
  for (int i = 0; i < kClothFloorHalvings; ++i) {
    ++s.trials;
    if (stable(hi / 2)) {
      s.h = bisect(stable, hi / 2, hi, kClothRatio, s.trials);
      return s;
    }
    hi /= 2;
  }
  return {hi, Bound::kBelow, s.trials};
}

// --- output
// ----------------------------------------------------------------------------------------

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

const Limit* find_limit(const std::vector<Limit>& limits, std::string_view scene,
                        std::string_view integrator, Real k) {
  for (const Limit& l : limits) {
    if (l.scene == scene && l.integrator == integrator && l.stiffness == k) return &l;
  }
  return nullptr;
}

const Row* find_row(const std::vector<Row>& rows, std::string_view scene,
                    std::string_view integrator, Real k, Real h) {
  for (const Row& r : rows) {
    if (r.scene == scene && r.integrator == integrator && r.stiffness == k && r.h == h) return &r;
  }
  return nullptr;
}

void write_csv(const std::filesystem::path& path, const std::vector<Row>& rows,
               const std::vector<Limit>& limits) {
  std::ofstream out(path);
  out << "scene,integrator,stiffness_N_per_m,h_s,steps,steps_done,stable,error,wall_ms_per_sim_s,"
         "energy_drift,largest_stable_step_s,largest_stable_step_bound\n";
  for (const Row& r : rows) {
    const Limit* l = find_limit(limits, r.scene, r.integrator, r.stiffness);
    out << r.scene << ',' << r.integrator << ',' << csv_number(r.stiffness) << ','
        << csv_number(r.h) << ',' << r.steps << ',' << r.steps_done << ',' << (r.stable ? 1 : 0)
        << ',' << csv_number(r.error) << ',' << csv_number(r.wall_ms_per_sim_s) << ','
        << csv_number(r.energy_drift) << ',' << (l ? csv_number(l->step.h) : "") << ','
        << (l ? bound_name(l->step.bound) : "") << '\n';
  }
}

/// Sorted by scene, integrator and stiffness, so that each line of the plot is contiguous.
void write_limits_csv(const std::filesystem::path& path, std::vector<Limit> limits,
                      const std::vector<std::string_view>& integrators) {
  auto rank = [&](const Limit& l) {
    const auto i = std::ranges::find(integrators, l.integrator) - integrators.begin();
    return std::tuple(l.scene != "oscillator", i, l.stiffness);
  };
  std::ranges::stable_sort(limits, {}, rank);
  std::ofstream out(path);
  out << "scene,integrator,stiffness_N_per_m,largest_stable_step_s,bound,trials\n";
  for (const Limit& l : limits) {
    out << l.scene << ',' << l.integrator << ',' << csv_number(l.stiffness) << ','
        << csv_number(l.step.h) << ',' << bound_name(l.step.bound) << ',' << l.step.trials << '\n';
  }
}

std::string ms(Real seconds) {
  return format("%g", seconds * 1e3);
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

struct Tables {
  const Plan& plan;
  const std::vector<std::string_view>& integrators;
  const std::vector<Row>& rows;
  const std::vector<Limit>& limits;
  std::ostringstream out;

  /// With `omega`, each column also gives ω·h.
  void header_steps(Real omega) {
    out << "| integrator |";
    for (Real h : plan.steps) {
      out << ' ' << ms(h);
      if (omega > 0) out << " (ωh " << format("%.2g", omega * h) << ")";
      out << " |";
    }
    out << "\n|---|";
    for (std::size_t i = 0; i < plan.steps.size(); ++i) out << "---:|";
    out << '\n';
  }

  /// Rows integrators, columns the swept steps, at the default stiffness.
  template <typename Cell>
  void pivot(std::string_view scene, Cell cell) {
    header_steps(scene == "oscillator" ? omega_of(kDefaultStiffness) : 0);
    for (std::string_view name : integrators) {
      out << "| " << name << " |";
      for (Real h : plan.steps) {
        const Row* r = find_row(rows, scene, name, kDefaultStiffness, h);
        out << ' ' << (r ? cell(*r) : std::string("?")) << " |";
      }
      out << '\n';
    }
    out << '\n';
  }

  void limit_table(std::string_view scene, bool with_omega_h) {
    out << "| integrator |";
    for (Real k : plan.stiffness) out << " k = " << format("%g", k) << " |";
    if (with_omega_h) out << " ω·h at k = " << format("%g", kDefaultStiffness) << " |";
    out << "\n|---|";
    for (std::size_t i = 0; i < plan.stiffness.size(); ++i) out << "---:|";
    if (with_omega_h) out << "---:|";
    out << '\n';
    for (std::string_view name : integrators) {
      out << "| " << name << " |";
      for (Real k : plan.stiffness) {
        const Limit* l = find_limit(limits, scene, name, k);
        out << ' ' << (l ? limit_cell(l->step) : std::string("?")) << " |";
      }
      if (with_omega_h) {
        const Limit* l = find_limit(limits, scene, name, kDefaultStiffness);
        std::string cell = "?";
        if (l) {
          const Real w = omega_of(kDefaultStiffness) * l->step.h;
          cell = l->step.bound == Bound::kExact     ? format("%.3g", w)
                 : l->step.bound == Bound::kAtLeast ? format("≥ %.3g", w)
                                                    : format("< %.3g", w);
        }
        out << ' ' << cell << " |";
      }
      out << '\n';
    }
    out << '\n';
  }

  /// For each error target and stiffness, the cheapest swept cloth run that meets it.
  void cheapest_table() {
    out << "| max error ≤ |";
    for (Real k : plan.stiffness) out << " k = " << format("%g", k) << " |";
    out << "\n|---|";
    for (std::size_t i = 0; i < plan.stiffness.size(); ++i) out << "---|";
    out << '\n';
    for (Real target_mm : {10.0, 1.0, 0.1, 0.01, 0.001}) {
      out << "| " << format("%g", target_mm) << " mm |";
      for (Real k : plan.stiffness) {
        const Row* best = nullptr;
        for (const Row& r : rows) {
          if (r.scene != "cloth" || r.stiffness != k || !r.stable) continue;
          if (!(r.error * 1e3 <= target_mm)) continue;
          if (!best || r.wall_ms_per_sim_s < best->wall_ms_per_sim_s) best = &r;
        }
        if (best) {
          out << ' ' << best->integrator << " @ " << ms(best->h)
              << " ms: " << format("%.3g", best->wall_ms_per_sim_s) << " |";
        } else {
          out << " none |";
        }
      }
      out << '\n';
    }
    out << '\n';
  }
};

std::string today() {
  const std::time_t now = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d", std::localtime(&now));
  return buffer;
}

std::string compiler() {
#if defined(__clang__)
  return std::string("Clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("GCC ") + __VERSION__;
#else
  return "unknown compiler";
#endif
}

std::string make_tables(const Plan& plan, const std::vector<std::string_view>& integrators,
                        const std::vector<Row>& rows, const std::vector<Limit>& limits,
                        const std::vector<ReferenceInfo>& references, double total_seconds) {
  Tables t{plan, integrators, rows, limits, {}};
  std::ostringstream& out = t.out;
  const std::string k0 = format("%g", kDefaultStiffness);
  out << "Generated by `integrator_study` on " << today() << " in " << format("%.0f", total_seconds)
      << " s (" << compiler()
#ifdef NDEBUG
      << ", NDEBUG"
#endif
      << "). Wall times are from a shared 2-core machine: compare ratios within this run.\n"
      << "Step sizes h in ms; \"—\" means the run blew up (see each table); k is the structural "
         "stiffness in N/m.\n\n";

  out << "Cloth references (RK4 at h = " << ms(plan.reference_step)
      << " ms; error estimated against RK4 at twice that step, divided by 15):\n\n"
      << "| k | reference error estimate (mm) | reference wall time (s) |\n|---:|---:|---:|\n";
  for (const ReferenceInfo& r : references) {
    out << "| " << format("%g", r.stiffness) << " | " << format("%.2g", r.self_error * 1e3) << " | "
        << format("%.1f", r.wall_seconds) << " |\n";
  }
  out << '\n';

  auto cloth_stable = [](const Row& r) { return r.stable && std::isfinite(r.error); };
  out << "### Cloth, k = " << k0 << ": max particle error at t = 0.5 s (mm)\n\n"
      << "\"—\": an unrecoverable step (non-finite, or a particle faster than 1000 m/s) before "
         "t = 0.5 s.\n\n";
  t.pivot("cloth", [&](const Row& r) {
    return cloth_stable(r) ? format("%.3g", r.error * 1e3) : std::string("—");
  });
  out << "### Cloth, k = " << k0 << ": wall ms per simulated second\n\n"
      << "For a run that blew up, the cost of the steps it made (in parentheses).\n\n";
  t.pivot("cloth", [&](const Row& r) {
    const std::string cost = format("%.3g", r.wall_ms_per_sim_s);
    return r.stable ? cost : "(" + cost + ")";
  });
  out << "### Cloth, k = " << k0 << ": energy error at t = 0.5 s, % of M g W/2\n\n"
      << "(E − E_ref)/(M g W/2), E = kinetic + elastic + gravitational, M g W/2 = "
      << format("%.3g", kClothEnergyScale)
      << " J (what the swing can release). Negative: the scheme lost energy the reference "
         "kept.\n\n";
  t.pivot("cloth", [&](const Row& r) {
    return cloth_stable(r) ? format("%+.2g", 100 * r.energy_drift) : std::string("—");
  });
  out << "### Cloth: the cheapest swept run under an error target (wall ms per simulated s)\n\n"
      << "Only the swept steps count, so this is coarse (a factor 2 in h).\n\n";
  t.cheapest_table();

  out << "### Oscillator, k = " << k0 << " (ω = " << format("%.0f", omega_of(kDefaultStiffness))
      << " rad/s): relative error at t = 0.5 s\n\n"
      << "|(x, v/ω) − exact| / x0. \"—\": the amplitude passed 10 x0 before t = 0.5 s.\n\n";
  t.pivot("oscillator", [](const Row& r) {
    return std::isfinite(r.error) ? format("%.2g", r.error) : std::string("—");
  });
  out << "### Oscillator, k = " << k0
      << ": energy drift over the long run (min(10⁴ periods, 2·10⁵ steps))\n\n"
      << "(E_end − E_0)/E_0. \"—\": the amplitude passed 10 x0 before the end.\n\n";
  t.pivot("oscillator", [](const Row& r) {
    return r.stable ? format("%+.2g", r.energy_drift) : std::string("—");
  });

  out << "### Largest stable step (ms), oscillator\n\n"
      << "Bisection: the amplitude |(x, v/ω)| stays within 10 x0 for 10⁴ steps. ≥ " << ms(kStepCap)
      << ": stable at the largest step tried. The last column is ω·h at the limit, the same "
         "at every k for a linear spring.\n\n";
  t.limit_table("oscillator", true);
  out << "### Largest stable step (ms), cloth\n\n"
      << "Bisection: no unrecoverable step in the 0.5 s swing, rescue off. ≥ " << ms(kStepCap)
      << ": stable at the largest step tried; < h: unstable at every step tried.\n\n";
  t.limit_table("cloth", false);
  return out.str();
}

int run_study(const std::filesystem::path& dir, const Plan& plan) {
  std::filesystem::create_directories(dir);
  const std::vector<std::string_view> integrators = integrator_names();
  const int n_integrators = static_cast<int>(integrators.size());
  const int n_k = static_cast<int>(plan.stiffness.size());
  const int n_h = static_cast<int>(plan.steps.size());
  Progress progress(2 * n_integrators * n_k * n_h + 2 * n_integrators * n_k + 2 * n_k);

  std::vector<Row> rows;
  std::vector<Limit> limits;
  std::vector<ReferenceInfo> references;

  // (a) the oscillator
  for (Real k : plan.stiffness) {
    for (std::string_view name : integrators) {
      for (Real h : plan.steps) {
        progress.begin(
            format("oscillator %s h=%sms k=%g", std::string(name).c_str(), ms(h).c_str(), k));
        const OscillatorRun run = run_oscillator(name, k, h);
        rows.push_back({"oscillator", std::string(name), k, h, run.steps, run.steps_done,
                        run.stable, run.error, run.wall_ms_per_sim_s, run.drift});
        progress.end(format("error %.2g, drift %.2g, %.3g ms/s%s", run.error, run.drift,
                            run.wall_ms_per_sim_s, run.stable ? "" : ", unstable"));
      }
      progress.begin(format("oscillator stable step %s k=%g", std::string(name).c_str(), k));
      const StableStep s = oscillator_stable_step(name, k);
      limits.push_back({"oscillator", std::string(name), k, s});
      progress.end(limit_cell(s) + " ms");
    }
  }

  // (b) the cloth
  for (Real k : plan.stiffness) {
    progress.begin(format("cloth reference rk4 h=%sms k=%g", ms(plan.reference_step).c_str(), k));
    const ClothRun reference = run_cloth("rk4", k, plan.reference_step);
    if (reference.failed) {
      std::fprintf(stderr, "\nthe reference blew up; choose a smaller reference step\n");
      return 1;
    }
    progress.end(format("%.1f s wall", reference.wall_seconds));
    progress.begin(
        format("cloth reference check rk4 h=%sms k=%g", ms(2 * plan.reference_step).c_str(), k));
    const ClothRun check = run_cloth("rk4", k, 2 * plan.reference_step);
    const Real self_error = max_distance(reference.x, check.x) / 15;
    references.push_back({k, self_error, reference.wall_seconds});
    progress.end(format("reference error ≈ %.2g mm", self_error * 1e3));

    for (std::string_view name : integrators) {
      std::vector<bool> stable_at;
      for (Real h : plan.steps) {
        progress.begin(format("cloth %s h=%sms k=%g", std::string(name).c_str(), ms(h).c_str(), k));
        const ClothRun run = run_cloth(name, k, h);
        Row row{"cloth", std::string(name), k, h, run.steps, run.steps_done, !run.failed};
        if (!run.failed) {
          row.error = max_distance(run.x, reference.x);
          row.energy_drift = (run.energy - reference.energy) / kClothEnergyScale;
        }
        if (run.steps_done > 0) {
          row.wall_ms_per_sim_s = 1e3 * run.wall_seconds / (static_cast<Real>(run.steps_done) * h);
        }
        rows.push_back(row);
        stable_at.push_back(!run.failed);
        progress.end(
            run.failed
                ? format("blew up at step %ld of %ld", run.steps_done + 1, run.steps)
                : format("error %.3g mm, %.3g ms/s", row.error * 1e3, row.wall_ms_per_sim_s));
      }
      progress.begin(format("cloth stable step %s k=%g", std::string(name).c_str(), k));
      const StableStep s = cloth_stable_step(name, k, plan.steps, stable_at);
      limits.push_back({"cloth", std::string(name), k, s});
      progress.end(limit_cell(s) + format(" ms (%d trials)", s.trials));
    }
  }

  write_csv(dir / "integrators.csv", rows, limits);
  write_limits_csv(dir / "integrators_stable_step.csv", limits, integrators);
  write_tables(dir, "integrators.md", "Integrators: measured trade-offs", "integrators_tables.md",
               "integrator_study",
               make_tables(plan, integrators, rows, limits, references, progress.elapsed()));
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
