#pragma once
// A one-line progress display on the terminal for anything long (watch, touch, bench).

#include <chrono>
#include <string>

namespace felt::cli {

class Progress {
 public:
  /// Shows nothing unless standard error is a terminal.
  Progress(std::string label, double total);
  ~Progress();
  /// `done` of the total, with a note after the bar; redrawn at most 10 times a second.
  void update(double done, const std::string& note = "");
  void finish();

 private:
  std::string label_;
  double total_;
  bool enabled_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace felt::cli
