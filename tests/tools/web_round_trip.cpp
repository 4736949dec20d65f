// The haptic round trip (ProxyUpdate -> ForceUpdate) over TCP and over a WebSocket, one device
// each in turn, paced at a rate, in alternating rounds so that both see the same machine. Run by
// scripts/bench-web (docs/results/web.md); a benchmark, not a test.
//   web_round_trip HOST TCP_PORT WEB_PORT [ROUNDS] [UPDATES_PER_ROUND] [RATE_HZ]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "felt_client.hpp"
#include "support/websocket_client.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<std::size_t>(p * values.size()))];
}

/// `updates` round trips of `device` paced at `rate_hz`, in microseconds.
template <class Device>
std::vector<double> round_trips(Device& device, int updates, double rate_hz) {
  std::vector<double> out;
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
  auto next = Clock::now();
  for (int i = 0; i < updates; ++i) {
    std::this_thread::sleep_until(next);
    next += period;
    // a small circle just in front of the curtain: in and out of contact, as a hand moves
    const double angle = 0.01 * i;
    const auto sent = Clock::now();
    device.proxy_update(0, {0.1 * std::cos(angle), 1.2 + 0.1 * std::sin(angle), 0.01});
    out.push_back(std::chrono::duration<double, std::micro>(Clock::now() - sent).count());
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: web_round_trip HOST TCP_PORT WEB_PORT [ROUNDS] [UPDATES] [RATE_HZ]\n");
    return 2;
  }
  const std::string host = argv[1];
  const auto tcp_port = static_cast<std::uint16_t>(std::stoi(argv[2]));
  const auto web_port = static_cast<std::uint16_t>(std::stoi(argv[3]));
  const int rounds = argc > 4 ? std::stoi(argv[4]) : 5;
  const int updates = argc > 5 ? std::stoi(argv[5]) : 2000;
  const double rate = argc > 6 ? std::stod(argv[6]) : 1000;

  felt::client::Client tcp;
  tcp.connect(host, tcp_port);
  tcp.hello("bench-tcp");
  felt::test::WebSocketClient web;
  web.connect(host, web_port);
  web.hello("bench-websocket");
  std::vector<double> all_tcp, all_web;
  std::printf("| round | TCP p50 us | TCP p99 us | WebSocket p50 us | WebSocket p99 us |\n");
  std::printf("|---|---|---|---|---|\n");
  for (int round = 1; round <= rounds; ++round) {
    const auto a = round_trips(tcp, updates, rate);
    const auto b = round_trips(web, updates, rate);
    std::printf("| %d | %.0f | %.0f | %.0f | %.0f |\n", round, percentile(a, 0.5),
                percentile(a, 0.99), percentile(b, 0.5), percentile(b, 0.99));
    all_tcp.insert(all_tcp.end(), a.begin(), a.end());
    all_web.insert(all_web.end(), b.begin(), b.end());
  }
  std::printf("| all | %.0f | %.0f | %.0f | %.0f |\n", percentile(all_tcp, 0.5),
              percentile(all_tcp, 0.99), percentile(all_web, 0.5), percentile(all_web, 0.99));
  return 0;
}
