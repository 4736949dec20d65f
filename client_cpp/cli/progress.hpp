#pragma once
// One-line progress displays on the terminal for anything long: a bar for what counts its way
// to an end (watch, touch, bench), a spinner with the time waited for a single long request (a
// load that builds a big scene). Neither shows anything unless standard error is a terminal, so
// output to pipes and files stays clean.

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

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

class Spinner {
 public:
  /// Shows `label`, a spinner and the seconds since, redrawn 10 times a second until destroyed.
  explicit Spinner(std::string label);
  /// Stops and clears the line.
  ~Spinner();
  Spinner(const Spinner&) = delete;
  Spinner& operator=(const Spinner&) = delete;

 private:
  void spin();

  std::string label_;
  std::mutex mutex_;
  std::condition_variable stop_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace felt::cli
