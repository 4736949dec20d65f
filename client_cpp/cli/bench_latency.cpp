// felt bench-latency: the ProxyUpdate -> ForceUpdate round trip at haptic rate, for one or
// several clients at once, each also streaming frames (docs/results/service.md). Every force
// that comes back is checked: finite, and within its proxy's max_force.

#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <thread>

#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/first_error.hpp"
#include "cli/latency_table.hpp"
#include "cli/progress.hpp"

namespace felt::cli {

namespace v1 = felt::v1;

namespace {

using Clock = std::chrono::steady_clock;

/// One simulated device: its connection, its proxy, its loop's results and the frames it took.
struct Device {
  client::AsyncClient client;
  std::uint32_t proxy = 0;
  double max_force = 0;  ///< N: what the server clamps the proxy's force to
  std::mutex mutex;
  LatencySamples samples;
  std::uint64_t bad_forces = 0;  ///< not finite, or above max_force
  std::uint64_t sent = 0;
  std::atomic<std::uint64_t> frames{0};
  std::atomic<std::uint64_t> frame_bytes{0};
  std::atomic<std::uint64_t> skipped{0};
};

}  // namespace

int bench_latency(const Common& common, const BenchOptions& o) {
  if (o.clients < 1 || o.clients > 64) {
    throw UsageError("--clients must be 1 to 64");
  }
  FirstError error;  // any device's: every device stops (it outlives their handlers)
  std::vector<std::unique_ptr<Device>> devices;
  std::uint64_t scene = common.join;
  for (int c = 0; c < o.clients; ++c) {
    auto device = std::make_unique<Device>();
    Device* d = device.get();
    d->client.on_error([&error](const v1::Error& e) { error.keep(e); });
    d->client.on_force([d](const v1::ForceUpdate& force, std::uint64_t received_us) {
      const v1::Vec3& f = force.force();
      const double magnitude = std::hypot(std::hypot(f.x(), f.y()), f.z());
      std::lock_guard lock(d->mutex);
      if (!std::isfinite(magnitude) || magnitude > d->max_force * (1 + 1e-9)) ++d->bad_forces;
      d->samples.add(static_cast<double>(force.client_time_us()),
                     1e-3 * static_cast<double>(force.server_receive_ns()),
                     1e-3 * static_cast<double>(force.server_send_ns()),
                     static_cast<double>(received_us));
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
      const v1::ServerMessage reply = d->client.request(ask);
      client::check_reply(reply, v1::ServerMessage::kStats);
      scene = reply.stats().scene().scene_id();
      if (scene == 0) scene = welcome.scene_id();
    }
    // the device's own proxy, with the scene's settings: its reply says the force's limit
    v1::ClientMessage open;
    open.mutable_open_proxy();
    const v1::ServerMessage opened = d->client.request(open);
    client::check_reply(opened, v1::ServerMessage::kProxyOpened);
    d->proxy = opened.proxy_opened().proxy_id();
    d->max_force = opened.proxy_opened().settings().max_force();
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
    const v1::Welcome welcome =
        connect(*reader, Common{common.server, common.token, "", scene}, "felt-slow-reader");
    reader->subscribe_frames(welcome.limits().max_frame_rate_hz());
    slow.push_back(std::move(reader));
  }

  Progress progress("bench", o.seconds);
  const Clock::time_point start = run_paced_devices(
      o.clients, o.rate, static_cast<std::uint64_t>(o.seconds * o.rate),
      [&](int c, std::uint64_t k) {
        Device& d = *devices[c];
        if (error.any()) return false;
        d.client.send_proxy_update(d.proxy, {o.at[0] + 0.01 * c, o.at[1], o.at[2]});
        ++d.sent;
        if (c == 0) progress.update(static_cast<double>(k + 1) / o.rate);  // ticks done
        return true;
      });
  progress.finish();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the last replies
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();

  LatencySamples all;
  std::uint64_t sent = 0, frames = 0, frame_bytes = 0, skipped = 0, bad_forces = 0;
  std::ofstream csv;
  if (!o.csv.empty()) {
    csv.open(o.csv);
    csv << "client,sent_us,round_trip_us,inbound_us,outbound_us\n";
  }
  for (int c = 0; c < o.clients; ++c) {
    Device& d = *devices[c];
    d.client.close();
    sent += d.sent;
    frames += d.frames;
    frame_bytes += d.frame_bytes;
    skipped += d.skipped;
    bad_forces += d.bad_forces;
    all.append(d.samples);
    if (csv) d.samples.write_csv(csv, c);
  }
  error.throw_if_any();
  const std::size_t answered = all.round_trips.size();
  print_latency_table(
      {.clients = o.clients,
       .slow_readers = o.slow_readers,
       .rate = o.rate,
       .sent = sent,
       .frames_per_client_per_second = static_cast<double>(frames) / o.clients / wall,
       .kb_per_frame = frames ? static_cast<double>(frame_bytes) / frames / 1e3 : 0.0,
       .skipped = skipped},
      all);
  std::printf("forces: %zu answered, %llu not finite or above the proxy's max_force (%g N)\n",
              answered, static_cast<unsigned long long>(bad_forces), devices[0]->max_force);
  return answered == sent && bad_forces == 0 ? 0 : 1;
}

}  // namespace felt::cli
