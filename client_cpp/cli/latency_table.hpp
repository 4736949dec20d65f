#pragma once
// What felt bench-latency and felt bench-floor share: devices ticking at a rate, each at its own
// phase, and the table row their round trips make (docs/results/service.md).

#include <chrono>
#include <cstdint>
#include <functional>
#include <ostream>
#include <vector>

namespace felt::cli {

/// Round trips and the legs they split into, µs. Both ends read the steady clock of one host.
struct LatencySamples {
  std::vector<double> sent;  ///< when each was sent (the steady clock), in arrival order
  std::vector<double> round_trips;
  std::vector<double> server;    ///< the server's share: receive to send
  std::vector<double> inbound;   ///< client send to server receive
  std::vector<double> outbound;  ///< server send to client read

  void add(double client_send_us, double server_receive_us, double server_send_us,
           double client_read_us);
  void append(const LatencySamples& other);
  /// One line per round trip, in arrival order, as `client,sent_us,round_trip_us,inbound_us,
  /// outbound_us`: when a tail happened and whether all clients had it at once.
  void write_csv(std::ostream& out, int client) const;
};

/// The rest of a table row: how many were sent and what streamed beside them.
struct LatencyRun {
  int clients = 1;
  int slow_readers = 0;
  double rate = 1000;
  std::uint64_t sent = 0;
  double frames_per_client_per_second = 0;
  double kb_per_frame = 0;
  std::uint64_t skipped = 0;
};

/// Prints the header and the one row of `samples` (sorting them).
void print_latency_table(const LatencyRun& run, LatencySamples& samples);

/// Runs `devices` loops of `ticks` ticks at `rate` Hz, device c a fraction c/devices of a
/// period after device 0 (independent devices do not tick in the same microsecond), from
/// 100 ms from now. `tick(c, k)` is device c's k-th tick; it returns false to stop that device.
/// Returns when device 0's first tick was due.
std::chrono::steady_clock::time_point run_paced_devices(
    int devices, double rate, std::uint64_t ticks,
    const std::function<bool(int, std::uint64_t)>& tick);

}  // namespace felt::cli
