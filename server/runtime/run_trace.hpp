#pragma once
// `feltd run --trace DIR --every N`: a run recorded from outside. Every step adds a row per body
// to DIR/trace.csv (energies and their drift, centre of mass, bounding box, largest speed,
// strain and compression, substeps, the world's state hash); every N-th step writes every
// body's positions into DIR/frame_NNNNN.vtp, listed by DIR/frames.pvd (the series `felt watch
// --format vtk` writes, for ParaView).

#include <cstdint>
#include <expected>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "core/world/world.hpp"

namespace felt {

class RunTrace {
 public:
  /// Creates `dir` (if missing) and the CSV's header; frames every `every` steps (>= 1).
  static std::expected<RunTrace, std::string> open(const std::filesystem::path& dir,
                                                   std::string scene_name, std::uint64_t every);

  /// Records `world` after a step (or, with an empty report, before the first). The first
  /// call fixes each body's energy the drift is measured from. False once a file could not
  /// be written; error() says which.
  bool record(const World& world, const StepReport& report);
  /// Writes the collection of the frames written so far.
  bool finish();

  const std::string& error() const { return error_; }
  std::size_t frames() const { return frames_.size(); }

 private:
  RunTrace(std::filesystem::path dir, std::string scene_name, std::uint64_t every);
  void write_rows(const World& world, const StepReport& report);
  bool write_frame(const World& world);
  bool fail(std::string why);

  std::filesystem::path dir_;
  std::string scene_name_;
  std::uint64_t every_ = 1;
  std::ofstream csv_;
  std::vector<Real> start_energy_;  ///< per body in id order, from the first record
  std::vector<std::pair<double, std::string>> frames_;
  std::string error_;
};

}  // namespace felt
