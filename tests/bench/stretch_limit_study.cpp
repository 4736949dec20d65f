// Stretch limiting measured (issue 30; docs/results/cloth.md section 4): per integrator, a heavy
// cloth hung from its top row on soft springs, with the limiter on and off, for 5 s of simulated
// time at a step the integrator is stable at. Per run: the wall time of a step and of its
// stretch-limit stage, the largest strain after any step, the kinetic energy at the end, and
// the sag (the pins' height less the lowest particle's) against a converged stiff reference:
// the same cloth with springs 100 times stiffer, implicit Euler at 4 ms (at rest, implicit Euler
// stands at the static equilibrium whatever its step), whose sag is that of a cloth that hardly
// stretches. A cloth held to 10 % sags at most 1.1 times as far. Then the served scene
// (scenes/service_bench.json) the same way.
//
// Usage: stretch_limit_study [N] [TABLE]   (N particles per side of the per-integrator cloth, 40;
// TABLE one of top_row, served, corners, served_candidates, pressed: only that table)
// Prints Markdown tables. Not a unit test: machines are shared and noisy, so compare ratios
// within one run.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_scene.hpp"
#include "core/cloth/cloth_grid.hpp"
#include "core/cloth/hanging_cloth.hpp"
#include "core/collision/collider.hpp"
#include "core/integrate/xpbd_integrator.hpp"
#include "core/world/world.hpp"

namespace felt {
namespace {

using Clock = std::chrono::steady_clock;
constexpr Real kSimTime = 5;  ///< s

struct Run {
  double ms_per_step = 0;
  double limit_ms_per_step = 0;
  Real max_strain = 0;
  Real final_kinetic_energy = 0;
  Real sag = 0;
  std::uint64_t rescued = 0, unrecoverable = 0;
};

Run run(World world) {
  Run r;
  const ClothBody& body = world.cloths()[0];
  double seconds = 0, limit_seconds = 0;
  std::uint64_t steps = 0;
  while (world.time() < kSimTime - 1e-9) {
    const auto start = Clock::now();
    const StepReport report = world.step();
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
    limit_seconds += report.cloth_profile[StepStage::kStretchLimit];
    ++steps;
    if (report.flags.has(StepFlag::kRescued)) ++r.rescued;
    if (report.flags.has(StepFlag::kUnrecoverable)) ++r.unrecoverable;
    r.max_strain = std::max(r.max_strain, body.max_strain());
  }
  r.ms_per_step = 1e3 * seconds / static_cast<double>(steps);
  r.limit_ms_per_step = 1e3 * limit_seconds / static_cast<double>(steps);
  r.final_kinetic_energy = body.kinetic_energy();
  r.sag = test::sag_of(body);
  return r;
}

void print_row(const std::string& name, Real h, const Run& off, const Run& on, Real reference) {
  std::printf(
      "| %s | %.4g | %.3f | %.3f | %.3f | %.4f | %.4f | %.2g | %.3f | %.3f | %.2g | %llu/%llu |\n",
      name.c_str(), 1e3 * h, off.ms_per_step, on.ms_per_step, on.limit_ms_per_step, off.max_strain,
      on.max_strain, off.final_kinetic_energy, off.sag / reference, on.sag / reference,
      on.final_kinetic_energy, static_cast<unsigned long long>(on.rescued),
      static_cast<unsigned long long>(on.unrecoverable));
  std::fflush(stdout);
}

void header() {
  std::printf(
      "| integrator | h (ms) | ms/step off | ms/step on | limiter ms/step | strain off | "
      "strain on | KE at 5 s off (J) | sag off / ref | sag on / ref | KE at 5 s on (J) | "
      "rescued/unrecoverable on |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
}

struct Case {
  const char* integrator;
  Real h;
};

void top_row_table(std::uint32_t n) {
  const Run reference = run(test::hanging_cloth(n, "implicit_euler", 4e-3, false, 100));
  std::printf(
      "%u x %u, 2 m, 4 kg, top row pinned; stiff reference (k x 100, implicit Euler, "
      "4 ms): sag %.4f m, largest strain %.4f, KE at 5 s %.2g J\n\n",
      n, n, reference.sag, reference.max_strain, reference.final_kinetic_energy);
  header();
  for (const Case& c :
       {Case{"symplectic_euler", 2e-3}, Case{"explicit_euler", 2.5e-4}, Case{"midpoint", 1e-3},
        Case{"rk4", 2e-3}, Case{"verlet", 2e-3}, Case{"velocity_verlet", 2e-3},
        Case{"leapfrog", 2e-3}, Case{"implicit_euler", 1.0 / 240}, Case{"imex", 1.0 / 240},
        Case{"desbrun", 1.0 / 240}, Case{"kang", 1.0 / 240}, Case{"xpbd", 2e-3},
        Case{"projective_dynamics", 1.0 / 240}}) {
    const Run off = run(test::hanging_cloth(n, c.integrator, c.h, false));
    const Run on = run(test::hanging_cloth(n, c.integrator, c.h, true));
    print_row(c.integrator, c.h, off, on, reference.sag);
  }
}

void served_table() {
  const Run served_reference = run(test::hanging_cloth(100, "implicit_euler", 4e-3, false, 100));
  std::printf(
      "\nscenes/service_bench.json (100 x 100, 2 ms); stiff reference "
      "at 100 x 100: sag %.4f m\n\n",
      served_reference.sag);
  header();
  // as the file has it, and with the integrator it had before (symplectic Euler, beyond its
  // stability limit at 2 ms on this cloth)
  for (const char* integrator : {"", "symplectic_euler"}) {
    auto served = [&](bool limited) {
      World world = bench::load_bench_scene("service_bench.json").world;
      ClothBody& sheet = world.cloths()[0];
      ClothParams params = sheet.params();
      params.stretch.enabled = limited;
      sheet.set_params(params);
      if (*integrator != 0) sheet.set_integrator(make_integrator(integrator));
      return run(std::move(world));
    };
    const Run off = served(false);
    const Run on = served(true);
    print_row(
        *integrator != 0 ? std::string("served scene, ") + integrator : std::string("served scene"),
        2e-3, off, on, served_reference.sag);
  }
}

/// An integrator (and stretch-limit cap) for the served scene, against the one it has.
struct Candidate {
  std::string label;
  std::unique_ptr<Integrator> (*make)();
  int iterations;  ///< the limiter's sweep cap; 0 keeps the scene's
};

struct CandidateRun {
  World world;
  double seconds = 0, integration_seconds = 0, limit_seconds = 0;
  std::uint64_t steps = 0, rescued = 0, unrecoverable = 0;
  Real max_strain = 0;
  Real largest_rise = 0;  ///< the largest rise of the mechanical energy in one step, J
  Real kinetic_at_3s = 0;
};

Real mechanical_energy(const ClothBody& body) {
  return body.kinetic_energy() + body.elastic_energy() + body.gravitational_energy();
}

void served_candidates_table() {
  // A/B in one run: every candidate's world steps once in turn, the order rotating every step,
  // so that a change of the machine's load falls on all of them alike
  const Candidate candidates[] = {
      {"kang (the scene's)", [] { return make_integrator("kang"); }, 0},
      {"xpbd, 1 substep",
       []() -> std::unique_ptr<Integrator> { return std::make_unique<XpbdIntegrator>(1); }, 0},
      {"xpbd, 2 substeps",
       []() -> std::unique_ptr<Integrator> { return std::make_unique<XpbdIntegrator>(2); }, 0},
      {"kang, at most 3 sweeps", [] { return make_integrator("kang"); }, 3},
      {"imex", [] { return make_integrator("imex"); }, 0},
      {"desbrun", [] { return make_integrator("desbrun"); }, 0},
  };
  std::vector<CandidateRun> runs;
  for (const Candidate& c : candidates) {
    World world = bench::load_bench_scene("service_bench.json").world;
    ClothBody& sheet = world.cloths()[0];
    sheet.set_integrator(c.make());
    if (c.iterations > 0) {
      ClothParams params = sheet.params();
      params.stretch.iterations = c.iterations;
      sheet.set_params(params);
    }
    runs.push_back({std::move(world)});
  }
  std::vector<Real> energy(runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k)
    energy[k] = mechanical_energy(runs[k].world.cloths()[0]);
  for (std::uint64_t n = 0; runs[0].world.time() < kSimTime - 1e-9; ++n) {
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const std::size_t k = (n + i) % runs.size();
      CandidateRun& r = runs[k];
      const auto start = Clock::now();
      const StepReport report = r.world.step();
      r.seconds += std::chrono::duration<double>(Clock::now() - start).count();
      r.integration_seconds += report.cloth_profile[StepStage::kIntegration];
      r.limit_seconds += report.cloth_profile[StepStage::kStretchLimit];
      ++r.steps;
      if (report.flags.has(StepFlag::kRescued)) ++r.rescued;
      if (report.flags.has(StepFlag::kUnrecoverable)) ++r.unrecoverable;
      const ClothBody& body = r.world.cloths()[0];
      r.max_strain = std::max(r.max_strain, body.max_strain());
      const Real e = mechanical_energy(body);
      r.largest_rise = std::max(r.largest_rise, e - energy[k]);
      energy[k] = e;
      if (std::abs(r.world.time() - 3) < 1e-9) r.kinetic_at_3s = body.kinetic_energy();
    }
  }
  std::printf(
      "\nscenes/service_bench.json (100 x 100, 2 ms, limit 10 %%): candidates stepped in turn\n\n"
      "| integrator | ms/step | ÷ the scene's | integrator ms/step | limiter ms/step | largest "
      "strain | KE at 3 s (J) | KE at 5 s (J) | "
      "largest energy rise in a step (J) | rescued/unrecoverable "
      "|\n|---|---|---|---|---|---|---|---|---|---|\n");
  const double base = runs[0].seconds / static_cast<double>(runs[0].steps);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const CandidateRun& r = runs[k];
    const double ms = r.seconds / static_cast<double>(r.steps);
    std::printf("| %s | %.3f | %.2f | %.3f | %.3f | %.4f | %.2g | %.2g | %.2g | %llu/%llu |\n",
                candidates[k].label.c_str(), 1e3 * ms, ms / base,
                1e3 * r.integration_seconds / static_cast<double>(r.steps),
                1e3 * r.limit_seconds / static_cast<double>(r.steps), r.max_strain, r.kinetic_at_3s,
                r.world.cloths()[0].kinetic_energy(), r.largest_rise,
                static_cast<unsigned long long>(r.rescued),
                static_cast<unsigned long long>(r.unrecoverable));
  }
  std::fflush(stdout);
}

void corners_table(std::uint32_t n) {
  // most of the weight carried by the limit through the few springs at two corners
  const Run corner_reference =
      run(test::hanging_cloth(n, "implicit_euler", 4e-3, false, 100, GridPinPreset::kTopCorners));
  std::printf("\n%u x %u hung from its two top corners; stiff reference: sag %.4f m\n\n", n, n,
              corner_reference.sag);
  header();
  for (const Case& c :
       {Case{"symplectic_euler", 2e-3}, Case{"implicit_euler", 1.0 / 240}, Case{"kang", 1.0 / 240},
        Case{"xpbd", 2e-3}, Case{"projective_dynamics", 1.0 / 240}}) {
    const Run off =
        run(test::hanging_cloth(n, c.integrator, c.h, false, 1, GridPinPreset::kTopCorners));
    const Run on =
        run(test::hanging_cloth(n, c.integrator, c.h, true, 1, GridPinPreset::kTopCorners));
    print_row(c.integrator, c.h, off, on, corner_reference.sag);
  }
}

void pressed_table() {
  // the served scene as its benchmark's eight clients touch it: 2 cm proxies held 1 cm into the
  // cloth (docs/results/service.md), here from 1 s after the start for 2 s
  World world = bench::load_bench_scene("service_bench.json").world;
  while (world.time() < 1 - 1e-9) world.step();
  const std::vector<Collider> proxies = test::balls_in_a_row(8, Vec3(0, 1.5, 0.01), 0.01, 0.02);
  const ClothBody& cloth = world.cloths()[0];
  double seconds = 0, limit_seconds = 0;
  std::uint64_t steps = 0, flagged = 0;
  Real largest_strain = 0;
  while (world.time() < 3 - 1e-9) {
    world.set_moving_colliders(proxies);
    const auto start = Clock::now();
    const StepReport report = world.step();
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
    limit_seconds += report.cloth_profile[StepStage::kStretchLimit];
    ++steps;
    if (report.flags != StepFlags{}) ++flagged;
    // the first steps meet proxies that appeared inside the cloth
    if (world.time() > 1.5) largest_strain = std::max(largest_strain, cloth.max_strain());
  }
  std::printf(
      "\nscenes/service_bench.json pressed by eight 2 cm proxies 1 cm into the cloth, 1 s to 3 "
      "s\n\n"
      "| ms/step | limiter ms/step | largest strain from 1.5 s | KE at 3 s (J) | flagged steps |\n"
      "|---|---|---|---|---|\n"
      "| %.3f | %.3f | %.4f | %.2g | %llu |\n",
      1e3 * seconds / static_cast<double>(steps), 1e3 * limit_seconds / static_cast<double>(steps),
      largest_strain, cloth.kinetic_energy(), static_cast<unsigned long long>(flagged));
  std::fflush(stdout);
}

}  // namespace
}  // namespace felt

int main(int argc, char** argv) {
  using namespace felt;
  const auto n = static_cast<std::uint32_t>(argc > 1 ? std::atoi(argv[1]) : 40);
  const std::string only = argc > 2 ? argv[2] : "";
  const auto wanted = [&](const char* table) { return only.empty() || only == table; };
  if (wanted("top_row")) top_row_table(n);
  if (wanted("served")) served_table();
  if (wanted("corners")) corners_table(n);
  if (wanted("served_candidates")) served_candidates_table();
  if (wanted("pressed")) pressed_table();
  return 0;
}