// The peer benchmark of issue 29: wall seconds per simulated second against the final max
// strain and sag error, for every Felt cloth integrator and Bullet's soft body, on the same
// n × n cloth (peer_cloth.hpp). Every configuration runs ROUNDS times; each round runs all of
// them in turn with the engines interleaved, so that a change in the machine's load falls on
// both. Reports medians.
//
// A Felt run counts (on the front, at equal strain) only if its cloth has come down at least
// kSettled of its material's static sag, that of implicit Euler at the same stiffness (the
// fixed point of backward Euler is the exact static equilibrium, whatever the step): a method
// that damps so much that the cloth is still creeping down at 2 s shows a small strain that is
// not a stiffer cloth. Bullet's links are inextensible (kLST = 1): its reference is 1 m.
//
// Usage: peer_bench OUT_DIR --size N [--rounds R | --tables-only]
// Writes OUT_DIR/peers_N.csv (one row per configuration, with whether it is on its engine's
// Pareto front) and the Markdown tables into OUT_DIR/peers.md between the markers of size N.
// Progress on stderr. scripts/bench-peers builds it, runs it into docs/results/ at 40 and 100
// and draws the plot; a size below 40 is a smoke test. --tables-only runs nothing: it reads
// OUT_DIR/peers_N.csv from an earlier run and writes the tables again. --only runs only the
// Felt configurations of the integrators listed and takes every other row from the earlier run's
// OUT_DIR/peers_N.csv (the stamp above the tables says so).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "../study_output.hpp"
#include "core/math/check.hpp"
#include "peer_configs.hpp"

namespace felt::peers {
namespace {

/// the share of its material's static sag a Felt run must have reached to count: accurate
/// integrators, still swinging a little at 2 s, are at 0.8-1.2 of implicit Euler's; kang, which
/// over-damps, at 0.1-0.2
constexpr double kSettled = 0.5;

struct Measured {
  PeerConfig config;
  std::vector<Outcome> runs;
  Outcome median;  ///< each number the median of the runs'; ok only if every run was
  std::size_t run_count = 0;
  /// Felt: sag error ÷ implicit Euler's at the same stiffness (NaN without one); Bullet: NaN
  double sag_reached = std::numeric_limits<double>::quiet_NaN();
  bool pareto = false;

  bool counts() const { return median.ok && !(sag_reached < kSettled); }
};

double median_of(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t m = values.size() / 2;
  return values.size() % 2 ? values[m] : (values[m - 1] + values[m]) / 2;
}

Outcome median_outcome(const std::vector<Outcome>& runs) {
  std::vector<double> wall, strain, sag;
  Outcome out;
  for (const Outcome& r : runs) {
    wall.push_back(r.wall_per_sim_s);
    strain.push_back(r.max_strain);
    sag.push_back(r.sag_error);
    out.ok = out.ok && r.ok;
    if (!r.note.empty()) out.note = r.note;
  }
  out.wall_per_sim_s = median_of(wall);
  out.max_strain = median_of(strain);
  out.sag_error = median_of(sag);
  return out;
}

void set_sag_reached(std::vector<Measured>& all) {
  for (Measured& m : all) {
    if (m.config.bullet) continue;
    for (const Measured& r : all) {
      if (!r.config.bullet && r.config.felt.integrator == "implicit_euler" && r.median.ok &&
          r.config.felt.stiffness == m.config.felt.stiffness) {
        m.sag_reached = m.median.sag_error / r.median.sag_error;
      }
    }
  }
}

/// A configuration is on its engine's front when no other of the same engine is at most as
/// costly and at most as strained, and better in one.
void mark_pareto(std::vector<Measured>& all) {
  for (Measured& a : all) {
    if (!a.counts()) continue;
    a.pareto = std::none_of(all.begin(), all.end(), [&](const Measured& b) {
      return &a != &b && b.counts() && b.config.bullet == a.config.bullet &&
             b.median.wall_per_sim_s <= a.median.wall_per_sim_s &&
             b.median.max_strain <= a.median.max_strain &&
             (b.median.wall_per_sim_s < a.median.wall_per_sim_s ||
              b.median.max_strain < a.median.max_strain);
    });
  }
}

/// The cheapest healthy configuration of an engine on a cloth at or below a strain.
const Measured* cheapest(const std::vector<Measured>& all, bool bullet, double strain) {
  const Measured* best = nullptr;
  for (const Measured& m : all) {
    if (m.config.bullet != bullet || !m.counts()) continue;
    if (m.median.max_strain > strain) continue;
    if (!best || m.median.wall_per_sim_s < best->median.wall_per_sim_s) best = &m;
  }
  return best;
}

std::string status(const Outcome& o) {
  if (!o.ok) return "blew up";
  return o.note.empty() ? "ok" : o.note;
}

std::string status(const Measured& m) {
  if (m.median.ok && !m.counts()) return "still sagging";
  return status(m.median);
}

std::string tables(const std::vector<Measured>& all, std::uint32_t n, int rounds) {
  std::string out = study::format("\n### %u × %u: at equal final max strain\n\n", n, n);
  out +=
      "| max strain at most | Felt's cheapest (strain) | s/s | Bullet's cheapest (strain) | s/s | "
      "Bullet ÷ Felt |\n|---|---|---|---|---|---|\n";
  for (double strain : {0.10, 0.05, 0.025, 0.01}) {
    const Measured* f = cheapest(all, false, strain);
    const Measured* b = cheapest(all, true, strain);
    auto cell = [](const Measured* m) {
      return m ? study::format("%s (%.4f) | %.3f", m->config.label().c_str(), m->median.max_strain,
                               m->median.wall_per_sim_s)
               : std::string("none | –");
    };
    const std::string ratio =
        f && b ? study::format("%.2f", b->median.wall_per_sim_s / f->median.wall_per_sim_s) : "–";
    out += study::format("| %.1f %% | %s | %s | %s |\n", strain * 100, cell(f).c_str(),
                         cell(b).c_str(), ratio.c_str());
  }
  out += study::format(
      "\n### %u × %u: every configuration (medians of %d rounds)\n\n| engine | configuration | "
      "wall s per simulated s | final max strain | sag error | share of static sag | front | "
      "status |\n|---|---|---|---|---|---|---|---|\n",
      n, n, rounds);
  std::vector<const Measured*> rows;
  for (const Measured& m : all) rows.push_back(&m);
  std::stable_sort(rows.begin(), rows.end(), [](const Measured* a, const Measured* b) {
    return a->median.wall_per_sim_s < b->median.wall_per_sim_s;
  });
  for (const Measured* m : rows) {
    out += study::format(
        "| %s | %s | %.3f | %.4f | %.4f | %s | %s | %s |\n", m->config.engine().c_str(),
        m->config.label().c_str(), m->median.wall_per_sim_s, m->median.max_strain,
        m->median.sag_error,
        std::isnan(m->sag_reached) ? "" : study::format("%.2f", m->sag_reached).c_str(),
        m->pareto ? "yes" : "", status(*m).c_str());
  }
  return out;
}

void write_csv(const std::filesystem::path& path, const std::vector<Measured>& all) {
  std::ofstream csv(path);
  csv << "n,engine,configuration,integrator,stiffness_N_per_m,step_s,substeps,iterations,runs,"
         "wall_per_sim_s,max_strain,sag_error,share_of_static_sag,status,pareto,chebyshev_rho\n";
  for (const Measured& m : all) {
    const PeerConfig& c = m.config;
    csv << c.n << ',' << c.engine() << ',' << c.label() << ','
        << (c.bullet ? "bullet" : c.felt.integrator) << ','
        << (c.bullet ? "" : study::csv_number(c.felt.stiffness)) << ','
        << study::csv_number(c.bullet ? c.bullet_config.step : c.felt.step) << ','
        << (c.bullet ? 1 : c.felt.substeps) << ','
        << (c.bullet ? c.bullet_config.iterations : c.felt.iterations) << ',' << m.run_count << ','
        << study::csv_number(m.median.wall_per_sim_s) << ','
        << study::csv_number(m.median.max_strain) << ',' << study::csv_number(m.median.sag_error)
        << ',' << study::csv_number(m.sag_reached) << ',' << status(m) << ',' << (m.pareto ? 1 : 0)
        << ',' << (c.bullet ? "" : study::csv_number(c.felt.chebyshev_rho)) << '\n';
  }
}

/// The configurations and medians a run wrote with write_csv (for --tables-only).
std::vector<Measured> read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  FELT_CHECK(in.good());
  std::vector<Measured> all;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cell;
    std::stringstream row(line);
    for (std::string c; std::getline(row, c, ',');) cell.push_back(c);
    if (cell.size() < 14) continue;
    Measured m;
    PeerConfig& c = m.config;
    c.n = static_cast<std::uint32_t>(std::stoul(cell[0]));
    c.bullet = cell[1] == "bullet";
    if (c.bullet) {
      c.bullet_config = {std::stod(cell[5]), std::stoi(cell[7])};
    } else {
      c.felt = {cell[3],
                std::stod(cell[4]),
                std::stod(cell[5]),
                std::stoi(cell[6]),
                std::stoi(cell[7]),
                cell.size() > 15 && !cell[15].empty() ? std::stod(cell[15]) : 0};
    }
    m.run_count = std::stoul(cell[8]);
    m.median.wall_per_sim_s = std::stod(cell[9]);
    m.median.max_strain = std::stod(cell[10]);
    m.median.sag_error = std::stod(cell[11]);
    // the strain bound again: it decides, not what the file says
    m.median.ok = cell[13] != "blew up" && m.median.max_strain < kBlownUpStrain;
    if (cell[13] == "rescued") m.median.note = "rescued";
    all.push_back(std::move(m));
  }
  return all;
}

}  // namespace
}  // namespace felt::peers

int main(int argc, char** argv) {
  using namespace felt::peers;
  namespace study = felt::study;
  const char* usage =
      "usage: peer_bench OUT_DIR --size N [--rounds R [--only INTEGRATOR,...] | --tables-only]\n";
  if (argc < 2) {
    std::fprintf(stderr, "%s", usage);
    return 2;
  }
  const std::filesystem::path out_dir = argv[1];
  int rounds = 3;
  bool tables_only = false;
  std::string only_list;          // --only's argument
  std::vector<std::string> only;  // Felt integrators to run again; empty: everything
  std::uint32_t n = 0;
  for (int a = 2; a < argc; ++a) {
    if (std::strcmp(argv[a], "--size") == 0 && a + 1 < argc) {
      n = static_cast<std::uint32_t>(std::max(0, std::atoi(argv[++a])));
    } else if (std::strcmp(argv[a], "--rounds") == 0 && a + 1 < argc) {
      rounds = std::max(1, std::atoi(argv[++a]));
    } else if (std::strcmp(argv[a], "--tables-only") == 0) {
      tables_only = true;
    } else if (std::strcmp(argv[a], "--only") == 0 && a + 1 < argc) {
      only_list = argv[++a];
      std::stringstream list(only_list);
      for (std::string name; std::getline(list, name, ',');) only.push_back(name);
    } else {
      std::fprintf(stderr, "peer_bench: unknown argument %s\n%s", argv[a], usage);
      return 2;
    }
  }
  if (n < 3) {
    std::fprintf(stderr, "peer_bench: --size needs at least 3 particles per side\n%s", usage);
    return 2;
  }
  const std::filesystem::path csv = out_dir / study::format("peers_%u.csv", n);
  std::vector<Measured> all;
  std::string stamp;
  if (tables_only) {
    all = read_csv(csv);
    rounds = all.empty() ? 0 : static_cast<int>(all.front().run_count);
    stamp = study::format(
        "Measured by `peer_bench --size %u`; tables recomputed from peers_%u.csv.", n, n);
  } else {
    for (const PeerConfig& c : peer_configs(n)) {
      if (only.empty() || (!c.bullet && std::ranges::find(only, c.felt.integrator) != only.end())) {
        all.push_back({c, {}, {}});
      }
    }
    study::Progress progress(static_cast<int>(all.size()) * rounds);
    for (int r = 0; r < rounds; ++r) {
      for (Measured& m : all) {
        progress.begin(
            study::format("round %d: %u × %u %s", r + 1, n, n, m.config.label().c_str()));
        const Outcome o =
            m.config.bullet ? run_bullet(n, m.config.bullet_config) : run_felt(n, m.config.felt);
        m.runs.push_back(o);
        progress.end(study::format("%.3f s/s, strain %.4f, sag error %.4f, %s", o.wall_per_sim_s,
                                   o.max_strain, o.sag_error, status(o).c_str()));
      }
    }
    for (Measured& m : all) {
      m.median = median_outcome(m.runs);
      m.run_count = m.runs.size();
    }
    const std::string program =
        only.empty() ? study::format("peer_bench --size %u", n)
                     : study::format("peer_bench --size %u --only %s", n, only_list.c_str());
    stamp = study::generated_by(program, progress.elapsed());
    if (!only.empty()) {
      // the rows not run again come from the earlier run's CSV, measured under its load
      std::size_t kept = 0;
      for (Measured& earlier : read_csv(csv)) {
        const bool run_again = std::ranges::any_of(
            all, [&](const Measured& m) { return m.config.label() == earlier.config.label(); });
        if (!run_again) {
          all.push_back(std::move(earlier));
          ++kept;
        }
      }
      stamp += study::format(" The other %zu rows are an earlier run's, read from peers_%u.csv.",
                             kept, n);
    }
  }
  set_sag_reached(all);
  mark_pareto(all);
  std::filesystem::create_directories(out_dir);
  write_csv(csv, all);
  study::write_tables(out_dir, "peers.md", "Felt against Bullet's soft-body cloth",
                      study::format("peers_%u_tables.md", n), study::format("peer_bench %u", n),
                      stamp + "\n" + tables(all, n, rounds));
  return 0;
}
