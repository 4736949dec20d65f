#pragma once
// A process's threads under SCHED_IDLE and the CPU time they took, from /proc (a task's stat:
// field 14 and 15 are its user and system time in clock ticks, field 41 its policy).

#include <sched.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace felt::test {

struct SchedIdleThreads {
  int count = 0;
  long ticks = 0;  ///< user and system time, in sysconf(_SC_CLK_TCK) units
};

/// `process` is a pid or "self".
inline SchedIdleThreads sched_idle_threads(const std::string& process) {
  SchedIdleThreads found;
  for (const auto& task : std::filesystem::directory_iterator("/proc/" + process + "/task")) {
    std::ifstream stat(task.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;  // the thread has just ended
    // the fields after the command name, which is in parentheses and may hold spaces
    std::istringstream fields(line.substr(line.rfind(')') + 2));
    long ticks = 0;
    std::string field;
    for (int i = 3; i <= 41 && fields >> field; ++i) {
      if (i == 14 || i == 15) ticks += std::stol(field);
      if (i == 41 && std::stoi(field) == SCHED_IDLE) {
        ++found.count;
        found.ticks += ticks;
      }
    }
  }
  return found;
}

}  // namespace felt::test
