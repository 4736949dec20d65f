#include "cli/latency_table.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

namespace felt::cli {
namespace {

double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0;
  const auto at = static_cast<std::size_t>(std::ceil(p * static_cast<double>(sorted.size()))) - 1;
  return sorted[std::min(at, sorted.size() - 1)];
}

}  // namespace

void LatencySamples::add(double client_send_us, double server_receive_us, double server_send_us,
                         double client_read_us) {
  sent.push_back(client_send_us);
  round_trips.push_back(client_read_us - client_send_us);
  server.push_back(server_send_us - server_receive_us);
  inbound.push_back(server_receive_us - client_send_us);
  outbound.push_back(client_read_us - server_send_us);
}

void LatencySamples::append(const LatencySamples& other) {
  sent.insert(sent.end(), other.sent.begin(), other.sent.end());
  round_trips.insert(round_trips.end(), other.round_trips.begin(), other.round_trips.end());
  server.insert(server.end(), other.server.begin(), other.server.end());
  inbound.insert(inbound.end(), other.inbound.begin(), other.inbound.end());
  outbound.insert(outbound.end(), other.outbound.begin(), other.outbound.end());
}

void LatencySamples::write_csv(std::ostream& out, int client) const {
  for (std::size_t k = 0; k < round_trips.size(); ++k) {
    out << client << ',' << static_cast<std::uint64_t>(sent[k]) << ',' << round_trips[k] << ','
        << inbound[k] << ',' << outbound[k] << '\n';
  }
}

void print_latency_table(const LatencyRun& run, LatencySamples& samples) {
  for (auto* v : {&samples.round_trips, &samples.server, &samples.inbound, &samples.outbound}) {
    std::sort(v->begin(), v->end());
  }
  const std::vector<double>& all = samples.round_trips;
  std::printf(
      "| clients | slow readers | rate Hz | updates | answered | p50 us | p90 us | "
      "p99 us | p99.9 us | max us | server p50 us | server p99 us | frames/s per client | "
      "kB per frame | skipped | inbound p99 us | outbound p99 us |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::printf(
      "| %d | %d | %.0f | %llu | %zu | %.0f | %.0f | %.0f | %.0f | %.0f | %.1f | %.1f | "
      "%.1f | %.2f | %llu | %.0f | %.0f |\n",
      run.clients, run.slow_readers, run.rate, static_cast<unsigned long long>(run.sent),
      all.size(), percentile(all, 0.5), percentile(all, 0.9), percentile(all, 0.99),
      percentile(all, 0.999), percentile(all, 1.0), percentile(samples.server, 0.5),
      percentile(samples.server, 0.99), run.frames_per_client_per_second, run.kb_per_frame,
      static_cast<unsigned long long>(run.skipped), percentile(samples.inbound, 0.99),
      percentile(samples.outbound, 0.99));
}

std::chrono::steady_clock::time_point run_paced_devices(
    int devices, double rate, std::uint64_t ticks,
    const std::function<bool(int, std::uint64_t)>& tick) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now() + std::chrono::milliseconds(100);
  const auto period = std::chrono::duration<double>(1.0 / rate);
  std::vector<std::thread> loops;
  for (int c = 0; c < devices; ++c) {
    loops.emplace_back([&, c] {
      const double phase = static_cast<double>(c) / devices;
      for (std::uint64_t k = 0; k < ticks; ++k) {
        std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(
                                                  period * (static_cast<double>(k) + phase)));
        if (!tick(c, k)) return;
      }
    });
  }
  for (std::thread& loop : loops) loop.join();
  return start;
}

}  // namespace felt::cli
