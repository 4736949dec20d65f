#pragma once
// The picture of a sweep: error against cost on log axes, a line per integrator through its
// time steps, and the Pareto front, drawn by gnuplot from the sweep's CSV.

#include <expected>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace felt::feltd {

/// Draws `png` from `csv` (as sweep writes it) with gnuplot, with the Pareto front through
/// `front` (cost, error); an error when gnuplot is missing or fails.
std::expected<void, std::string> plot_sweep(const std::filesystem::path& csv,
                                            const std::filesystem::path& png,
                                            const std::string& title,
                                            const std::vector<std::string>& integrators,
                                            std::vector<std::pair<double, double>> front);

}  // namespace felt::feltd
