// The soft-solid results table (docs/results/solids.md): the second thesis's scenes run from
// their start, measured from the first contact between bodies on, beside the thesis's own
// Tables 7.2–7.4. Like the thesis, every scene runs 8 times, and the best and the worst run
// (by mean step time) are dropped before the timings are averaged.
//
//   solid_results OUTPUT.md [--runs N] [--steps N]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "thesis_scenes.hpp"

namespace felt {
namespace {

/// One run of a scene, over the steps from the first contact on.
struct Run {
  std::size_t steps = 0;
  double mean_ms = 0, max_ms = 0;
  /// process CPU time, which the time other work on the machine takes does not add to
  double mean_cpu_ms = 0, max_cpu_ms = 0;
  double fastest_run_ms = 0, slowest_run_ms = 0;  ///< the range of mean_ms over the runs
  StepProfile stage_mean_ms, stage_max_ms;
  double mean_substeps = 0;
  int max_substeps = 0;
  double mean_nodes = 0, mean_triangles = 0;  ///< colliding (Table 7.3 PKU, PKT)
  std::size_t max_nodes = 0, max_triangles = 0;
};

struct SceneResult {
  std::string name;
  std::size_t bodies = 0, nodes = 0, edges = 0, triangles = 0, tets = 0;
  Run run;  ///< over the runs (combine_runs); the counts are the same in every run
};

Run measure(std::string_view name, std::uint64_t steps) {
  Scene scene = bench::load_thesis_scene(name);
  Run run;
  for (std::uint64_t s = 0; s < steps; ++s) {
    const std::clock_t cpu_start = std::clock();
    const auto start = std::chrono::steady_clock::now();
    scene.world.step();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const double cpu_ms = 1e3 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    const SolidStepStats& stats = scene.world.solids().last_stats();
    if (run.steps == 0 && stats.colliding_nodes == 0) continue;  // not touching yet
    ++run.steps;
    run.mean_ms += ms;
    run.mean_cpu_ms += cpu_ms;
    run.max_cpu_ms = std::max(run.max_cpu_ms, cpu_ms);
    run.max_ms = std::max(run.max_ms, ms);
    for (StepStage stage : bench::kStages) {
      const double stage_ms = 1e3 * stats.profile[stage];
      run.stage_mean_ms[stage] += stage_ms;
      run.stage_max_ms[stage] = std::max(run.stage_max_ms[stage], stage_ms);
    }
    run.mean_substeps += stats.substeps;
    run.max_substeps = std::max(run.max_substeps, stats.substeps);
    run.mean_nodes += static_cast<double>(stats.colliding_nodes);
    run.mean_triangles += static_cast<double>(stats.colliding_triangles);
    run.max_nodes = std::max(run.max_nodes, stats.colliding_nodes);
    run.max_triangles = std::max(run.max_triangles, stats.colliding_triangles);
  }
  if (run.steps == 0) throw std::runtime_error(std::string(name) + ": the bodies never touched");
  const auto n = static_cast<double>(run.steps);
  run.mean_ms /= n;
  run.mean_cpu_ms /= n;
  for (StepStage stage : bench::kStages) run.stage_mean_ms[stage] /= n;
  run.mean_substeps /= n;
  run.mean_nodes /= n;
  run.mean_triangles /= n;
  return run;
}

/// Over the runs: the means as the thesis averaged them (§7.6: sorted by mean step time, the
/// best and the worst run dropped when there are three or more, the others averaged), and the
/// slowest steps as the median of each run's slowest, which one preemption by other work on
/// the machine does not move.
Run combine_runs(std::vector<Run> runs) {
  std::ranges::sort(runs, {}, &Run::mean_ms);
  const std::size_t drop = runs.size() >= 3 ? 1 : 0;
  const std::span<const Run> kept(runs.data() + drop, runs.size() - 2 * drop);
  const auto average = [&](auto field) {
    double sum = 0;
    for (const Run& run : kept) sum += field(run);
    return sum / static_cast<double>(kept.size());
  };
  const auto median = [&](auto field) {
    std::vector<double> values;
    for (const Run& run : runs) values.push_back(field(run));
    std::ranges::sort(values);
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  };
  Run combined = runs.front();  // the counts, which do not vary
  combined.fastest_run_ms = runs.front().mean_ms;
  combined.slowest_run_ms = runs.back().mean_ms;
  combined.mean_ms = average([](const Run& r) { return r.mean_ms; });
  combined.mean_cpu_ms = average([](const Run& r) { return r.mean_cpu_ms; });
  combined.max_ms = median([](const Run& r) { return r.max_ms; });
  combined.max_cpu_ms = median([](const Run& r) { return r.max_cpu_ms; });
  for (StepStage stage : bench::kStages) {
    combined.stage_mean_ms[stage] = average([&](const Run& r) { return r.stage_mean_ms[stage]; });
    combined.stage_max_ms[stage] = median([&](const Run& r) { return r.stage_max_ms[stage]; });
  }
  return combined;
}

SceneResult measure_scene(std::string_view name, int runs, std::uint64_t steps) {
  SceneResult result;
  result.name = name;
  const Scene scene = bench::load_thesis_scene(name);
  for (const SolidBody& body : scene.world.solids().bodies()) {
    ++result.bodies;
    result.nodes += body.node_count();
    result.edges += body.topology().edges.size();
    result.triangles += body.topology().surface.size();
    result.tets += body.rest().tets.size();
  }
  std::vector<Run> measured;
  for (int r = 0; r < runs; ++r) measured.push_back(measure(name, steps));
  result.run = combine_runs(std::move(measured));
  return result;
}

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.starts_with("model name")) return line.substr(line.find(':') + 2);
  }
  return "unknown CPU";
}

std::string fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

/// The thesis's rows (§7.6, Pentium 4 1.8 GHz) for the scenes it measured.
struct ThesisRow {
  std::string_view scene, name;
  int nodes, edges, triangles, tets;
  int fps_mean, fps_min, pku, mku, pkt, mkt;
  /// Table 7.4, worst case at first contact, ms, in the order of bench::kStages (NF + UI, CD,
  /// TC, PD, CR, no colliders, FI)
  std::array<std::string_view, 7> stages;
};
constexpr ThesisRow kThesis[] = {
    {"three_cubes",
     "3× cube 5×5×5",
     648,
     2970,
     900,
     1875,
     31,
     29,
     92,
     147,
     370,
     575,
     {"16 + 32", "32", "16", "16", "47", "—", "16"}},
    {"four_bunnies",
     "4× dog",
     452,
     1804,
     864,
     928,
     30,
     25,
     105,
     142,
     451,
     596,
     {"16 + 16", "16", "16", "16", "16", "—", "—"}},
};

/// ms per simulation step at `fps` frames per second, two steps a frame (thesis §4.5).
double thesis_step_ms(int fps) {
  return 1e3 / (2.0 * fps);
}

const ThesisRow* thesis_row(std::string_view scene) {
  for (const ThesisRow& row : kThesis) {
    if (row.scene == scene) return &row;
  }
  return nullptr;
}

void write_table(std::ostream& out, const std::vector<SceneResult>& results, int runs,
                 std::uint64_t steps) {
  out << "# Soft solids: speed of the pipeline\n\n"
      << "Issue 4 item 9. Written by `tests/bench/solid_results docs/results/solids.md` (a "
         "Release build with `-DFELT_BENCH=ON`) on "
      << cpu_model() << ", one thread; the machine's 2 cores were shared with other work.\n\n"
      << "Each scene of `scenes/thesis/` runs " << steps << " steps of 10 ms from its start, "
      << runs << " times; the best and the worst run (by mean step time) are dropped and the "
      << "means of the others averaged, as the thesis did (§7.6: 8 runs, 6 averaged); the "
      << "slowest steps are the median over the runs of each run's slowest. "
      << "Everything is measured over the steps from the first contact between two bodies on "
      << "(the floor is a collider and does not count). A step is the whole pipeline of "
      << "`SolidSystem::step`: as many equal substeps as the stiffest body's stable step asks "
      << "for (`substeps`), each running integration, detection, triangle collection, "
      << "penetration vectors, the contact surface, the colliders (floor) and the velocity "
      << "update. The thesis's numbers are beside ours in *italics*; it ran on a Pentium 4 at "
      << "1.8 GHz and rendered every second step.\n\n";

  out << "## Scenes (thesis Table 7.2)\n\n"
      << "| scene | bodies | nodes | edges | surface triangles | tetrahedra |\n"
      << "|---|---:|---:|---:|---:|---:|\n";
  for (const SceneResult& r : results) {
    out << "| " << r.name << " | " << r.bodies << " | " << r.nodes << " | " << r.edges << " | "
        << r.triangles << " | " << r.tets << " |\n";
    if (const ThesisRow* t = thesis_row(r.name)) {
      out << "| *thesis: " << t->name << "* | | *" << t->nodes << "* | *" << t->edges << "* | *"
          << t->triangles << "* | *" << t->tets << "* |\n";
    }
  }

  out << "\n## Step time and colliding elements (thesis Table 7.3)\n\n"
      << "ms per step: the mean (in parentheses the fastest and the slowest run's mean: the "
         "shared virtual machine's speed varies from minute to minute) and the slowest step, "
         "by the wall clock and by the process's CPU time (the wall clock also counts the time "
         "other work took the core away). The "
         "thesis's step times are its frame times halved, a frame being two steps. PKU/MKU: "
         "mean and largest number of colliding nodes (a node inside two bodies counts twice); "
         "PKT/MKT: the same for the surface triangles collected for the contacts.\n\n"
      << "| scene | steps measured | ms/step mean | slowest | CPU ms/step mean | CPU slowest "
         "| steps/s | substeps mean (max) | PKU | MKU | PKT | MKT |\n"
      << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const SceneResult& r : results) {
    const Run& run = r.run;
    out << "| " << r.name << " | " << run.steps << " | " << fixed(run.mean_ms, 3) << " ("
        << fixed(run.fastest_run_ms, 2) << "–" << fixed(run.slowest_run_ms, 2) << ") | "
        << fixed(run.max_ms, 3) << " | " << fixed(run.mean_cpu_ms, 3) << " | "
        << fixed(run.max_cpu_ms, 3) << " | " << fixed(1e3 / run.mean_ms, 0) << " | "
        << fixed(run.mean_substeps, 2) << " (" << run.max_substeps << ") | "
        << fixed(run.mean_nodes, 1) << " | " << run.max_nodes << " | "
        << fixed(run.mean_triangles, 1) << " | " << run.max_triangles << " |\n";
    if (const ThesisRow* t = thesis_row(r.name)) {
      out << "| *thesis: " << t->name << ", " << t->fps_mean << " FPS mean, " << t->fps_min
          << " min* | | *≈" << fixed(thesis_step_ms(t->fps_mean), 1) << "* | *≈"
          << fixed(thesis_step_ms(t->fps_min), 1) << "* | | | *≈" << 2 * t->fps_mean << "* | | *"
          << t->pku << "* | *" << t->mku << "* | *" << t->pkt << "* | *" << t->mkt << "* |\n";
    }
  }

  out << "\n## Stages (thesis Table 7.4)\n\n"
      << "ms per step by the wall clock, mean (slowest step in parentheses, the median over "
         "the runs), summed over the substeps. "
         "Integration is the thesis's NF (internal forces) and UI (Verlet) together; "
         "colliders is the floor, which the thesis does not list; finish is its FI. The "
         "thesis's row is its worst case at first contact, in multiples of its 15.6 ms "
         "timer.\n\n"
      << "| scene |";
  for (StepStage stage : bench::kStages) out << " " << stage_name(stage) << " |";
  out << "\n|---|";
  for (std::size_t s = 0; s < bench::kStages.size(); ++s) out << "---:|";
  out << "\n";
  for (const SceneResult& r : results) {
    out << "| " << r.name << " |";
    for (StepStage stage : bench::kStages) {
      out << " " << fixed(r.run.stage_mean_ms[stage], 3) << " ("
          << fixed(r.run.stage_max_ms[stage], 2) << ") |";
    }
    out << "\n";
    if (const ThesisRow* t = thesis_row(r.name)) {
      out << "| *thesis: " << t->name << "* |";
      for (std::string_view ms : t->stages) out << " *" << ms << "* |";
      out << "\n";
    }
  }
}

/// Where we stand, with the ratios of this run, and what the pipeline does to get there.
void write_summary(std::ostream& out, const std::vector<SceneResult>& results) {
  out << "\n## Where we stand\n\n"
      << "Issue 4 asks for the three-cube and the four-bunny scenes to run the full pipeline in "
         "at most 1 ms per step. In this run:\n\n";
  for (const SceneResult& r : results) {
    const ThesisRow* t = thesis_row(r.name);
    if (t == nullptr) continue;
    const Run& run = r.run;
    StepStage largest = bench::kStages[0];
    for (StepStage stage : bench::kStages) {
      if (run.stage_mean_ms[stage] > run.stage_mean_ms[largest]) largest = stage;
    }
    const double thesis_ms = thesis_step_ms(t->fps_mean);
    out << "- **" << r.name << "**: " << fixed(run.mean_ms, 3) << " ms per step ("
        << fixed(run.mean_cpu_ms, 3) << " ms of CPU), " << fixed(100 * run.mean_ms, 0)
        << " % of the 1 ms target" << (run.mean_ms <= 1 ? "" : ", which is not reached")
        << "; the slowest step took " << fixed(run.max_ms, 2) << " ms (" << fixed(run.max_cpu_ms, 2)
        << " ms of CPU)" << (run.max_ms <= 1 ? "" : ", over the target") << ". The thesis took ≈"
        << fixed(thesis_ms, 1) << " ms per step (" << t->fps_mean
        << " frames/s, two steps a frame) on a 1.8 GHz Pentium 4: this is "
        << fixed(thesis_ms / run.mean_ms, 0) << "× faster ("
        << fixed(2 * thesis_ms / run.mean_ms, 0)
        << "× if a frame was one step, ≈30 steps/s). The largest stage is " << stage_name(largest)
        << ", " << fixed(100 * run.stage_mean_ms[largest] / run.mean_ms, 0) << " % of the step.\n";
  }
  out << "\nWhat keeps the step short: each body's stable step comes from the largest eigenvalue "
         "of its stiffness and damping matrices at rest (Lanczos, once per material) with a "
         "margin of 0.7, where a block row-sum bound had put it at 0.35 of the limit (in these "
         "scenes it went from 3.5 to 7.1 ms, from 3 substeps per 10 ms step to 2). Detection "
         "hashes and queries only where the bounding boxes of bodies that can touch overlap; "
         "the contact surface re-evaluates the internal forces of the elements at its region "
         "nodes only, in each of its three pressure comparisons; a ray scans only the colliding "
         "triangles whose box its own box meets. These three give bit for bit the states the "
         "plain loops give (the same state hashes after 300 steps of every thesis scene). What "
         "is left is spread over integration (one full force evaluation per substep), "
         "detection, penetration vectors and resolution in comparable parts. The margin to the "
         "target is real but not wide: this shared virtual machine runs some minutes a third "
         "slower than others, which takes the three cubes' slowest steps past 1 ms.\n";
}

}  // namespace
}  // namespace felt

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: solid_results OUTPUT.md [--runs N] [--steps N]\n";
    return 2;
  }
  int runs = 8;
  std::uint64_t steps = 500;
  for (int a = 2; a + 1 < argc; a += 2) {
    const std::string option = argv[a];
    if (option == "--runs") {
      runs = std::stoi(argv[a + 1]);
    } else if (option == "--steps") {
      steps = std::stoull(argv[a + 1]);
    } else {
      std::cerr << "unknown option " << option << "\n";
      return 2;
    }
  }
  std::vector<felt::SceneResult> results;
  for (std::string_view scene : felt::bench::kThesisScenes) {
    std::cerr << scene << "\n";
    results.push_back(felt::measure_scene(scene, runs, steps));
  }
  std::ostringstream text;
  felt::write_table(text, results, runs, steps);
  felt::write_summary(text, results);
  std::ofstream(argv[1]) << text.str();
  std::cout << text.str();
}
