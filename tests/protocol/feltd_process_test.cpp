// The feltd a test starts does not outlive the test process, however that process ends.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "feltd_fixture.hpp"

namespace felt::test {
namespace {

/// Whether process `pid` is gone or a zombie (killed, not yet reaped by its new parent).
bool ended(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string id, name, state;
  if (!(stat >> id >> name >> state)) return true;
  return state == "Z";
}

// A test process that a sanitizer stops runs no destructor. Its feltd, started with
// posix_spawn, ran on with the test's output open, and ctest waited for it.
TEST(FeltdProcess, DiesWithTheTestProcessThatStartedIt) {
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const pid_t test_process = fork();
  ASSERT_GE(test_process, 0);
  if (test_process == 0) {
    FeltdProcess server(default_args());
    const pid_t feltd = server.pid();
    if (write(fds[1], &feltd, sizeof feltd) != sizeof feltd) _exit(1);
    _exit(0);  // stopped at once, as a sanitizer stops a test
  }
  close(fds[1]);
  pid_t feltd = 0;
  const ssize_t got = read(fds[0], &feltd, sizeof feltd);
  close(fds[0]);
  int status = 0;
  waitpid(test_process, &status, 0);
  ASSERT_EQ(got, static_cast<ssize_t>(sizeof feltd));
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const bool killed = eventually([&] { return ended(feltd); }, 5s);
  if (!killed) kill(feltd, SIGKILL);  // leave nothing behind
  EXPECT_TRUE(killed);
}

}  // namespace
}  // namespace felt::test
