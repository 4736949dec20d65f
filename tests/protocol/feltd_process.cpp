#include "feltd_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <regex>
#include <stdexcept>
#include <thread>

#include "support/time_scale.hpp"

extern char** environ;

namespace felt::test {

FeltdProcess::FeltdProcess(const std::vector<std::string>& args, bool default_listen) {
  std::vector<std::string> argv_storage = {FELTD_PATH, "serve"};
  if (!default_listen) argv_storage.insert(argv_storage.end(), {"--listen", "127.0.0.1:0"});
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& arg : argv_storage) argv.push_back(arg.data());
  argv.push_back(nullptr);

  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) throw std::runtime_error("pipe failed");
  // fork and exec rather than posix_spawn, to have feltd killed when the test process dies: a
  // test a sanitizer stopped left it running with the test's output open, and ctest waited on
  // it (16 minutes under AddressSanitizer, until it was killed by hand). Only async-signal-safe
  // calls between fork and exec.
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ == 0) {
    if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent) _exit(127);
    dup2(pipe_fds[1], STDOUT_FILENO);
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    execve(FELTD_PATH, argv.data(), environ);
    _exit(127);
  }
  close(pipe_fds[1]);
  stdout_fd_ = pipe_fds[0];
  if (pid_ < 0) throw std::runtime_error("cannot start " FELTD_PATH);

  const auto deadline = std::chrono::steady_clock::now() + scaled(std::chrono::seconds(10));
  first_line_ = read_line(deadline);
  std::smatch match;
  if (!std::regex_match(first_line_, match, std::regex(R"(listening on 127\.0\.0\.1:(\d+))"))) {
    throw std::runtime_error("unexpected first line: " + first_line_);
  }
  port_ = static_cast<std::uint16_t>(std::stoi(match[1]));
  // with --web, the web port is named on the next line
  if (std::find(args.begin(), args.end(), "--web") == args.end()) return;
  const std::string web_line = read_line(deadline);
  if (!std::regex_match(web_line, match, std::regex(R"(web on http://127\.0\.0\.1:(\d+)/)"))) {
    throw std::runtime_error("unexpected second line: " + web_line);
  }
  web_port_ = static_cast<std::uint16_t>(std::stoi(match[1]));
}

std::string FeltdProcess::read_line(std::chrono::steady_clock::time_point deadline) {
  std::string line;
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    pollfd pfd{stdout_fd_, POLLIN, 0};
    if (left.count() <= 0 || poll(&pfd, 1, static_cast<int>(left.count())) <= 0) {
      throw std::runtime_error("feltd printed no line in time");
    }
    char c;
    if (read(stdout_fd_, &c, 1) != 1) throw std::runtime_error("feltd exited: " + line);
    if (c == '\n') return line;
    line.push_back(c);
  }
}

FeltdProcess::~FeltdProcess() {
  if (pid_ > 0 && running()) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  if (stdout_fd_ >= 0) close(stdout_fd_);
}

bool FeltdProcess::running() {
  if (pid_ <= 0) return false;
  int status = 0;
  const pid_t result = waitpid(pid_, &status, WNOHANG);
  if (result == pid_) {
    pid_ = -1;
    return false;
  }
  return result == 0;
}

std::optional<int> FeltdProcess::stop(int signal, std::chrono::milliseconds timeout) {
  if (pid_ <= 0) return std::nullopt;
  kill(pid_, signal);
  const auto deadline = std::chrono::steady_clock::now() + scaled(timeout);
  while (std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return std::nullopt;
}

}  // namespace felt::test
