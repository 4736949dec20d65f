// felt bench-latency: the ProxyUpdate -> ForceUpdate round trip at haptic rate, for one or
// several clients at once, each also streaming frames (docs/results/service.md).

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <thread>

#include "cli/commands.hpp"
#include "cli/progress.hpp"

namespace felt::cli {

namespace v1 = felt::v1;

namespace {

using Clock = std::chrono::steady_clock;

/// One simulated device: its connection, its loop's results and the frames it took.
struct Device {
  client::AsyncClient client;
  std::mutex mutex;
  std::vector<double> round_trips_us;
  std::vector<double> server_us;  ///< of each round trip, the server's share (receive to send)
  // the legs before and after it; both ends read the same steady clock on one host
  std::vector<double> inbound_us;   ///< client send to server receive
  std::vector<double> outbound_us;  ///< server send to client read
  std::uint64_t sent = 0;
  std::atomic<std::uint64_t> frames{0};
  std::atomic<std::uint64_t> frame_bytes{0};
  std::atomic<std::uint64_t> skipped{0};
};

double percentile(std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0;
  const auto at = static_cast<std::size_t>(std::ceil(p * static_cast<double>(sorted.size()))) - 1;
  return sorted[std::min(at, sorted.size() - 1)];
}

}  // namespace

int bench_latency(const Common& common, const BenchOptions& o) {
  if (o.clients < 1 || o.clients > 64) {
    throw client::ClientError(v1::ERROR_CODE_BAD_REQUEST, "--clients must be 1 to 64");
  }
  std::vector<std::unique_ptr<Device>> devices;
  std::uint64_t scene = common.join;
  for (int c = 0; c < o.clients; ++c) {
    auto device = std::make_unique<Device>();
    Device* d = device.get();
    d->client.on_force([d](const v1::ForceUpdate& force, std::uint64_t received_us) {
      std::lock_guard lock(d->mutex);
      d->round_trips_us.push_back(static_cast<double>(received_us - force.client_time_us()));
      const double receive_us = 1e-3 * static_cast<double>(force.server_receive_ns());
      const double send_us = 1e-3 * static_cast<double>(force.server_send_ns());
      d->server_us.push_back(send_us - receive_us);
      d->inbound_us.push_back(receive_us - static_cast<double>(force.client_time_us()));
      d->outbound_us.push_back(static_cast<double>(received_us) - send_us);
    });
    d->client.on_frame([d, deltas = o.deltas](const v1::Frame& frame) {
      ++d->frames;
      d->frame_bytes += frame.ByteSizeLong();
      d->skipped += frame.skipped();
      if (deltas) {
        v1::ClientMessage ack;
        ack.mutable_ack_frame()->set_sequence(frame.sequence());
        d->client.send(std::move(ack));
      }
    });
    // the first client loads --scene (if given); the others join the scene it is in
    Common mine = common;
    if (c > 0) {
      mine.scene.clear();
      mine.join = scene;
    }
    const v1::Welcome welcome = connect(d->client, mine, "felt-bench-" + std::to_string(c));
    if (c == 0 && scene == 0) {
      v1::ClientMessage ask;
      ask.mutable_get_stats();
      scene = d->client.request(ask).stats().scene().scene_id();
      if (scene == 0) scene = welcome.scene_id();
    }
    if (o.frame_rate > 0) {
      v1::ClientMessage subscribe;
      v1::SubscribeFrames& s = *subscribe.mutable_subscribe_frames();
      s.set_max_rate_hz(o.frame_rate);
      s.set_encoding(o.quantized || o.deltas ? v1::FRAME_ENCODING_QUANTIZED16
                                             : v1::FRAME_ENCODING_FLOAT32);
      s.set_deltas(o.deltas);
      d->client.request(subscribe);
    }
    devices.push_back(std::move(device));
  }

  // clients that take frames at the highest rate and then read nothing: the server must skip
  // their frames, not queue them, and serve the others as before
  std::vector<std::unique_ptr<client::Client>> slow;
  for (int s = 0; s < o.slow_readers; ++s) {
    auto reader = std::make_unique<client::Client>();
    connect(*reader, Common{common.server, common.token, "", scene}, "felt-slow-reader");
    reader->subscribe_frames(1000);
    slow.push_back(std::move(reader));
  }

  // every device runs its own loop at the rate, each a little beside the others and at its own
  // phase (independent devices do not tick in the same microsecond)
  Progress progress("bench", o.seconds);
  const Clock::time_point start = Clock::now() + std::chrono::milliseconds(100);
  const auto period = std::chrono::duration<double>(1.0 / o.rate);
  const auto ticks = static_cast<std::uint64_t>(o.seconds * o.rate);
  std::vector<std::thread> loops;
  for (int c = 0; c < o.clients; ++c) {
    loops.emplace_back([&, c] {
      Device& d = *devices[c];
      const client::Point at{o.at[0] + 0.01 * c, o.at[1], o.at[2]};
      for (std::uint64_t k = 0; k < ticks && d.client.connected(); ++k) {
        const double phase = static_cast<double>(c) / o.clients;
        std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(
                                                  period * (static_cast<double>(k) + phase)));
        d.client.send_proxy_update(0, at);
        ++d.sent;
        if (c == 0) progress.update(static_cast<double>(k) / o.rate);
      }
    });
  }
  for (std::thread& loop : loops) loop.join();
  progress.finish();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the last replies
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();

  std::vector<double> all, server, inbound, outbound;
  std::uint64_t sent = 0, frames = 0, frame_bytes = 0, skipped = 0;
  std::ofstream csv;
  if (!o.csv.empty()) {
    csv.open(o.csv);
    csv << "client,round_trip_us\n";
  }
  for (int c = 0; c < o.clients; ++c) {
    Device& d = *devices[c];
    d.client.close();
    sent += d.sent;
    frames += d.frames;
    frame_bytes += d.frame_bytes;
    skipped += d.skipped;
    all.insert(all.end(), d.round_trips_us.begin(), d.round_trips_us.end());
    server.insert(server.end(), d.server_us.begin(), d.server_us.end());
    inbound.insert(inbound.end(), d.inbound_us.begin(), d.inbound_us.end());
    outbound.insert(outbound.end(), d.outbound_us.begin(), d.outbound_us.end());
    if (csv) {
      for (double rtt : d.round_trips_us) csv << c << "," << rtt << "\n";
    }
  }
  std::sort(all.begin(), all.end());
  std::sort(server.begin(), server.end());
  std::sort(inbound.begin(), inbound.end());
  std::sort(outbound.begin(), outbound.end());
  std::printf(
      "| clients | slow readers | rate Hz | updates | answered | p50 us | p90 us | "
      "p99 us | p99.9 us | max us | server p50 us | server p99 us | frames/s per client | "
      "kB per frame | skipped | inbound p99 us | outbound p99 us |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::printf(
      "| %d | %d | %.0f | %llu | %zu | %.0f | %.0f | %.0f | %.0f | %.0f | %.1f | %.1f | "
      "%.1f | %.2f | %llu | %.0f | %.0f |\n",
      o.clients, o.slow_readers, o.rate, static_cast<unsigned long long>(sent), all.size(),
      percentile(all, 0.5), percentile(all, 0.9), percentile(all, 0.99), percentile(all, 0.999),
      percentile(all, 1.0), percentile(server, 0.5), percentile(server, 0.99),
      static_cast<double>(frames) / o.clients / wall,
      frames ? static_cast<double>(frame_bytes) / frames / 1e3 : 0.0,
      static_cast<unsigned long long>(skipped), percentile(inbound, 0.99),
      percentile(outbound, 0.99));
  return all.size() == sent ? 0 : 1;
}

}  // namespace felt::cli
