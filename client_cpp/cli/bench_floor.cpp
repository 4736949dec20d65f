// felt bench-floor: what the machine's own round trip costs, to set beside felt bench-latency.
// Each simulated device sends a message the size of a ProxyUpdate at the rate, at the same
// phases, and a reader thread takes the reply the size of a ForceUpdate, as the asynchronous
// client does; the other end is a process of blocking threads that answer at once. Nothing of
// Felt is in the way: no protobuf, no event loop, no scene. Busy threads at the kernel's time
// slice stand in for a physics thread, to show what felt's short slice does beside one.

#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>
#include <thread>

#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/latency_table.hpp"
#include "cli/progress.hpp"
#include "scheduling/thread_latency.hpp"

namespace felt::cli {
namespace {

// on the wire, a ProxyUpdate with its envelope and a ForceUpdate with its envelope are about
// this long (felt bench-latency's, measured)
constexpr std::size_t kRequestBytes = 48;
constexpr std::size_t kReplyBytes = 160;

std::uint64_t now_ns() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::steady_clock::now().time_since_epoch())
                                        .count());
}

bool read_exactly(int fd, std::uint8_t* bytes, std::size_t size) {
  for (std::size_t got = 0; got < size;) {
    const ssize_t n = ::recv(fd, bytes + got, size - got, 0);
    if (n <= 0) return false;
    got += static_cast<std::size_t>(n);
  }
  return true;
}

bool write_all(int fd, const std::uint8_t* bytes, std::size_t size) {
  for (std::size_t sent = 0; sent < size;) {
    const ssize_t n = ::send(fd, bytes + sent, size - sent, MSG_NOSIGNAL);
    if (n <= 0) return false;
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

void no_delay(int fd) {
  const int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
}

/// The answering process: a thread per connection copies the request's stamp into a reply
/// with its own receive and send times, until the connection closes.
[[noreturn]] void answer(int listener, int connections) {
  std::vector<std::thread> threads;
  for (int c = 0; c < connections; ++c) {
    const int fd = ::accept(listener, nullptr, nullptr);
    if (fd < 0) break;
    no_delay(fd);
    threads.emplace_back([fd] {
      std::array<std::uint8_t, kRequestBytes> request{};
      std::array<std::uint8_t, kReplyBytes> reply{};
      while (read_exactly(fd, request.data(), request.size())) {
        const std::uint64_t received = now_ns();
        std::memcpy(reply.data(), request.data(), sizeof(std::uint64_t));
        std::memcpy(reply.data() + 8, &received, sizeof received);
        const std::uint64_t sent = now_ns();
        std::memcpy(reply.data() + 16, &sent, sizeof sent);
        if (!write_all(fd, reply.data(), reply.size())) break;
      }
      ::close(fd);
    });
  }
  for (std::thread& t : threads) t.join();
  ::_exit(0);
}

struct Connection {
  int fd = -1;
  std::mutex mutex;
  LatencySamples samples;
  std::uint64_t sent = 0;
  std::thread reader;
};

}  // namespace

int bench_floor(const BenchOptions& o) {
  if (o.clients < 1 || o.clients > 64) {
    throw UsageError("--clients must be 1 to 64");
  }
  const int listener = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof address;
  if (listener < 0 || ::bind(listener, reinterpret_cast<sockaddr*>(&address), length) != 0 ||
      ::listen(listener, o.clients) != 0 ||
      ::getsockname(listener, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    throw LocalError(std::string("loopback listener: ") + std::strerror(errno));
  }
  const pid_t answerer = ::fork();
  if (answerer < 0) {
    throw LocalError(std::string("fork: ") + std::strerror(errno));
  }
  if (answerer == 0) answer(listener, o.clients);
  ::close(listener);

  std::vector<std::unique_ptr<Connection>> connections;
  for (int c = 0; c < o.clients; ++c) {
    auto connection = std::make_unique<Connection>();
    connection->fd = ::socket(AF_INET, SOCK_STREAM, 0);
    if (::connect(connection->fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
      ::kill(answerer, SIGKILL);
      ::waitpid(answerer, nullptr, 0);
      throw LocalError(std::string("connect: ") + std::strerror(errno));
    }
    no_delay(connection->fd);
    Connection* mine = connection.get();
    mine->reader = std::thread([mine] {
      std::array<std::uint8_t, kReplyBytes> reply{};
      while (read_exactly(mine->fd, reply.data(), reply.size())) {
        const std::uint64_t read_us = client::steady_microseconds();
        std::uint64_t stamps[3];
        std::memcpy(stamps, reply.data(), sizeof stamps);
        std::lock_guard lock(mine->mutex);
        mine->samples.add(static_cast<double>(stamps[0]), 1e-3 * static_cast<double>(stamps[1]),
                          1e-3 * static_cast<double>(stamps[2]), static_cast<double>(read_us));
      }
    });
    connections.push_back(std::move(connection));
  }

  std::atomic<bool> done{false};
  std::vector<std::thread> busy;
  for (int b = 0; b < o.busy_threads; ++b) {
    busy.emplace_back([&done] {
      (void)request_time_slice(std::chrono::microseconds{0});  // not felt's short one
      for (volatile std::uint64_t spins = 0; !done.load(std::memory_order_relaxed);) {
        spins = spins + 1;
      }
    });
  }
  Progress progress("floor", o.seconds);
  run_paced_devices(o.clients, o.rate, static_cast<std::uint64_t>(o.seconds * o.rate),
                    [&](int c, std::uint64_t k) {
                      Connection& connection = *connections[c];
                      std::array<std::uint8_t, kRequestBytes> request{};
                      const std::uint64_t sent_us = client::steady_microseconds();
                      std::memcpy(request.data(), &sent_us, sizeof sent_us);
                      if (!write_all(connection.fd, request.data(), request.size())) return false;
                      ++connection.sent;
                      if (c == 0)
                        progress.update(static_cast<double>(k + 1) / o.rate);  // ticks done
                      return true;
                    });
  progress.finish();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the last replies
  done = true;
  for (std::thread& thread : busy) thread.join();

  LatencySamples all;
  std::uint64_t sent = 0;
  for (auto& connection : connections) {
    ::shutdown(connection->fd, SHUT_RDWR);
    connection->reader.join();
    ::close(connection->fd);
    sent += connection->sent;
    all.append(connection->samples);
  }
  ::waitpid(answerer, nullptr, 0);
  const std::size_t answered = all.round_trips.size();
  print_latency_table({.clients = o.clients, .rate = o.rate, .sent = sent}, all);
  return answered == sent ? 0 : 1;
}

}  // namespace felt::cli
