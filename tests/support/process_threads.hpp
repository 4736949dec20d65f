#pragma once
// A process's threads as /proc shows them: each task's name, the CPU time it took, its nice and
// its policy (a task's stat: field 14 and 15 are its user and system time in clock ticks, 19 its
// nice, 41 its policy), and its threads under SCHED_IDLE.

#include <sched.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace felt::test {

struct ThreadStat {
  std::string name;
  long ticks = 0;  ///< user and system time, in sysconf(_SC_CLK_TCK) units
  int nice = 0;
  int policy = 0;
};

/// `process` is a pid or "self".
inline std::vector<ThreadStat> process_threads(const std::string& process) {
  std::vector<ThreadStat> threads;
  for (const auto& task : std::filesystem::directory_iterator("/proc/" + process + "/task")) {
    std::ifstream stat(task.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;  // the thread has just ended
    ThreadStat thread;
    // the command name is in parentheses and may hold spaces
    const std::size_t open = line.find('('), close = line.rfind(')');
    thread.name = line.substr(open + 1, close - open - 1);
    std::istringstream fields(line.substr(close + 2));
    std::string field;
    for (int i = 3; i <= 41 && fields >> field; ++i) {
      if (i == 14 || i == 15) thread.ticks += std::stol(field);
      if (i == 19) thread.nice = std::stoi(field);
      if (i == 41) thread.policy = std::stoi(field);
    }
    threads.push_back(std::move(thread));
  }
  return threads;
}

struct SchedIdleThreads {
  int count = 0;
  long ticks = 0;  ///< user and system time, in sysconf(_SC_CLK_TCK) units
};

inline SchedIdleThreads sched_idle_threads(const std::string& process) {
  SchedIdleThreads found;
  for (const ThreadStat& thread : process_threads(process)) {
    if (thread.policy != SCHED_IDLE) continue;
    ++found.count;
    found.ticks += thread.ticks;
  }
  return found;
}

}  // namespace felt::test
