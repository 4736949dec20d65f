#include "feltd/sweep_plot.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace felt::feltd {
namespace {

/// `text` as a gnuplot single-quoted string, where a quote is written twice.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::expected<void, std::string> plot_sweep(const std::filesystem::path& csv,
                                            const std::filesystem::path& png,
                                            const std::string& title,
                                            const std::vector<std::string>& integrators,
                                            std::vector<std::pair<double, double>> front) {
  std::string names;
  for (const std::string& name : integrators) names += (names.empty() ? "" : " ") + name;
  std::ranges::sort(front);
  std::ostringstream script;
  script.precision(17);
  // the front as an inline data block: gnuplot draws a line through points in the order given
  script << "$front << EOD\n";
  for (const auto& [cost, error] : front) script << cost << ',' << error << '\n';
  script << "EOD\n";
  // columns of sweep.csv: 1 integrator, 2 time_step, 3 max_error, 6 cpu_per_sim_second,
  // 12 stable
  script << "set datafile separator ','\n"
         << "set terminal pngcairo size 1000,700 font 'DejaVu Sans,11' noenhanced\n"
         << "set output " << quoted(png.string()) << "\n"
         << "set title " << quoted(title) << "\n"
         << "set logscale xy\nset grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
         << "set key outside right top\nset format y '%g'\n"
         << "set xlabel 'CPU seconds per simulated second'\n"
         << "set ylabel 'largest position error against the reference (m)'\n"
         << "names = " << quoted(names) << "\n"
         << "array colour[10] = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', "
            "'#8c564b', '#e377c2', '#7f7f7f', '#bcbd22', '#17becf']\n"
         << "do for [i = 1:10] { set linetype i lc rgb colour[i] lw 2 pt (i + 3) ps 1.4 }\n"
         << "set linetype 11 lc rgb 'black' lw 1 dt 2\n"
         << "plot for [i = 1:words(names)] " << quoted(csv.string())
         << " using ((strcol(1) eq word(names, i) && $12 == 1) ? $6 : NaN):3 "
            "with linespoints lt i title word(names, i), \\\n"
         << "  " << quoted(csv.string())
         << " using (($12 == 1) ? $6 : NaN):3:(sprintf('%g ms', 1e3 * $2)) with labels "
            "offset 0.6,0.6 left font ',8' textcolor rgb '#555555' notitle, \\\n"
         << "  $front using 1:2 with lines lt 11 title 'Pareto front'\n";
  FILE* gnuplot = popen("gnuplot 2>&1", "w");
  if (!gnuplot) return std::unexpected("cannot start gnuplot (scripts/install-deps installs it)");
  const std::string text = script.str();
  std::fwrite(text.data(), 1, text.size(), gnuplot);
  const int status = pclose(gnuplot);
  if (status != 0) {
    return std::unexpected("gnuplot failed (status " + std::to_string(status) +
                           "; scripts/install-deps installs it)");
  }
  return {};
}

}  // namespace felt::feltd
