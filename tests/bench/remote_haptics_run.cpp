#include "remote_haptics_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <fstream>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <utility>

#include "felt/v1/haptics.pb.h"
#include "local_renderer.hpp"
#include "net/haptic_wire.hpp"
#include "net/wire_convert.hpp"
#include "runtime/haptic_frame.hpp"
#include "runtime/proxy_render.hpp"
#include "runtime/snapshot.hpp"
#include "scene/scene_loader.hpp"

namespace felt::study {
namespace {

using Nanoseconds = std::int64_t;

Nanoseconds nanoseconds(double seconds) {
  return static_cast<Nanoseconds>(std::llround(seconds * 1e9));
}

double seconds(Nanoseconds t) {
  return static_cast<double>(t) * 1e-9;
}

/// The steady-clock reading the runtime sees at simulated time `t`: one second after the clock's
/// epoch, which the runtime takes for "never".
SteadyClock::time_point at(Nanoseconds t) {
  return SteadyClock::time_point(std::chrono::seconds(1) + std::chrono::nanoseconds(t));
}

/// One direction of the simulated network (SimulatedNetwork), delivering in order.
template <class Message>
class DelayedChannel {
 public:
  DelayedChannel(const SimulatedNetwork& network, std::uint64_t seed)
      : delay_(nanoseconds(network.round_trip / 2)),
        jitter_(network.jitter / 2),
        loss_(network.loss),
        random_(seed) {}

  void send(Nanoseconds now, Message message) {
    Nanoseconds arrival = now + delay_;
    if (jitter_ > 0) arrival += nanoseconds(std::normal_distribution<double>(0, jitter_)(random_));
    if (loss_ > 0 && std::uniform_real_distribution<double>(0, 1)(random_) < loss_) {
      arrival += nanoseconds(kRetransmissionTimeout);
    }
    // never before it was sent, nor before the one ahead of it
    arrival = std::max({arrival, now, last_arrival_});
    last_arrival_ = arrival;
    queue_.emplace_back(arrival, std::move(message));
  }
  /// When the next message arrives (none: the largest time).
  Nanoseconds next_arrival() const {
    return queue_.empty() ? std::numeric_limits<Nanoseconds>::max() : queue_.front().first;
  }
  Message take() {
    Message message = std::move(queue_.front().second);
    queue_.pop_front();
    return message;
  }

 private:
  Nanoseconds delay_;
  double jitter_;  ///< s, standard deviation
  double loss_;
  std::mt19937_64 random_;
  Nanoseconds last_arrival_ = 0;
  std::deque<std::pair<Nanoseconds, Message>> queue_;
};

/// feltd's side: the scene stepped at its time step, a haptic frame published after each step,
/// and the proxy rendered for each ProxyUpdate as the request handler renders it.
class SimulatedServer {
 public:
  SimulatedServer(Scene scene, const RemoteCase& c)
      : scene_(std::move(scene)),
        step_(nanoseconds(scene_.world.settings().time_step)),
        proxy_(ProxyKey{0, 1}, scene_.haptics) {
    if (c.rendering == Rendering::kLocalModel) proxy_.enable_local_model({c.model_radius, 0});
    if (c.rendering == Rendering::kLocalModel) compliance_.emplace(ComplianceWorker::Mode::kInline);
    snapshot_ = make_snapshot(scene_.world, nullptr, compliance());
    frame_ = make_haptic_frame(snapshot_, nullptr, nullptr, scene_.haptic_structure, at(0));
  }

  const ProxySettings& settings() const { return proxy_.settings(); }
  /// When the step in progress ends.
  Nanoseconds next_step() const { return stepped_to_ + step_; }

  void step() {
    reactions_.apply_and_clear(scene_.world);
    scene_.world.step();
    stepped_to_ += step_;
    const std::uint64_t version = snapshot_->version + 1;
    snapshot_ = make_snapshot(scene_.world, snapshot_.get(), compliance());
    snapshot_->version = version;  // a new publication, as LiveScene::publish numbers them
    frame_ = make_haptic_frame(snapshot_, frame_.get(), nullptr, scene_.haptic_structure,
                               at(stepped_to_));
  }

  /// The reply to `update`, received at `now`.
  v1::ForceUpdate answer(const v1::ProxyUpdate& update, Nanoseconds now) {
    std::optional<LocalContact> local;
    if (update.has_local()) {
      auto felt = net::local_contact(update.local(), proxy_.settings());
      if (!felt) throw std::runtime_error("the local renderer sent " + felt.error());
      local = *felt;
    }
    // the scene keeps pace with the wall clock: time scale 1
    const ProxyOutput out =
        render_proxy(proxy_, *frame_, at(now), 1, net::to_vec3(update.position()), 0, reactions_,
                     local ? &*local : nullptr);
    v1::ForceUpdate force;
    force.set_proxy_id(1);
    net::fill_force_update(out, force);
    force.set_client_time_us(update.client_time_us());
    if (out.local_model) {
      net::put_local_model(*out.local_model, net::steady_ns(at(now)), *force.mutable_local_model());
    }
    return force;
  }

 private:
  ComplianceWorker* compliance() { return compliance_ ? &*compliance_ : nullptr; }

  Scene scene_;
  Nanoseconds step_;
  Nanoseconds stepped_to_ = 0;
  HapticProxy proxy_;
  /// snapshots carry point compliance, as feltd's do for local models: found inline, so that a
  /// run repeats bit for bit (feltd finds it on a thread of its own, a few steps later)
  std::optional<ComplianceWorker> compliance_;
  ReactionAccumulator reactions_;
  std::shared_ptr<SceneSnapshot> snapshot_;
  std::shared_ptr<HapticFrame> frame_;
};

std::uint64_t microseconds(Nanoseconds t) {
  return static_cast<std::uint64_t>(t / 1000);
}

/// The device's side: `felt touch --path`, with or without --local-model, on simulated time.
class SimulatedDevice {
 public:
  SimulatedDevice(const RemoteCase& c, const ProxySettings& settings)
      : case_(c),
        period_(nanoseconds(1 / c.device_rate)),
        every_(
            static_cast<std::size_t>(std::max(1.0, std::round(c.device_rate / c.upstream_rate)))) {
    v1::ProxySettings wire;
    net::fill_proxy_settings(settings, wire);
    renderer_.emplace(wire, client::LocalRendererOptions{c.device_damping, 1 / c.device_rate});
    const auto count = static_cast<std::size_t>(std::floor(c.duration * c.device_rate)) + 1;
    samples_.resize(count);
  }

  std::size_t ticks() const { return samples_.size(); }
  Nanoseconds tick_time(std::size_t k) const { return static_cast<Nanoseconds>(k) * period_; }

  /// Tick `k`: what goes upstream, if anything.
  std::optional<v1::ProxyUpdate> tick(std::size_t k) {
    const Nanoseconds now = tick_time(k);
    RemoteSample& s = samples_[k];
    s.time = seconds(now);
    s.device = case_.path.at(s.time).position;
    v1::ProxyUpdate update;
    update.set_proxy_id(1);
    net::put_vec3(s.device, *update.mutable_position());
    update.set_client_time_us(microseconds(now));
    if (case_.rendering == Rendering::kRoundTrip) return update;

    if (model_) {
      renderer_->take(model_->first, model_->second, round_trip_);
      model_.reset();
    }
    const client::LocalForce felt = renderer_->tick(s.device, s.time);
    s.answered = true;
    s.force = felt.contact.force;
    s.in_contact = felt.contact.in_contact;
    s.proxy = felt.contact.proxy;
    s.round_trip = round_trip_;
    if (k % every_ != 0) return std::nullopt;
    *update.mutable_local() = renderer_->upstream();
    return update;
  }

  /// `force` arrived at `now`.
  void receive(const v1::ForceUpdate& force, Nanoseconds now) {
    const double round_trip = seconds(now) - static_cast<double>(force.client_time_us()) * 1e-6;
    if (case_.rendering == Rendering::kLocalModel) {
      round_trip_ = round_trip;
      if (!force.has_local_model()) return;
      std::optional<LocalModel> model = client::local_model_from(force.local_model());
      if (!model) throw std::runtime_error("the server sent a malformed local model");
      model_.emplace(std::move(*model),
                     client::local_model_time(force.local_model(), seconds(now), round_trip));
      return;
    }
    RemoteSample& s = samples_[static_cast<std::size_t>(
        static_cast<Nanoseconds>(force.client_time_us()) * 1000 / period_)];
    s.answered = true;
    s.force = net::to_vec3(force.force());
    s.in_contact = force.in_contact();
    s.proxy = net::to_vec3(force.proxy());
    s.round_trip = round_trip;
  }

  std::vector<RemoteSample> samples() && { return std::move(samples_); }

 private:
  const RemoteCase& case_;
  Nanoseconds period_;
  std::size_t every_;
  std::optional<client::LocalRenderer> renderer_;
  std::optional<std::pair<LocalModel, double>> model_;  ///< the latest, and the time it shows
  double round_trip_ = 0;
  std::vector<RemoteSample> samples_;
};

DevicePath through(const std::vector<std::pair<double, Vec3>>& keys) {
  DevicePath path;
  path.shape = DevicePath::Shape::kSamples;
  for (const auto& [time, position] : keys) path.samples.push_back(DeviceSample{time, position, 0});
  return path;
}

}  // namespace

DevicePath cube_press_path() {
  return through({{0, {-0.05, 0, 0.3}},
                  {0.5, {-0.05, 0, 0.23}},
                  {1.0, {-0.05, 0, 0.205}},
                  {2.0, {0.05, 0, 0.205}},
                  {2.5, {0.05, 0, 0.3}},
                  {3.0, {0.05, 0, 0.3}}});
}

DevicePath curtain_press_path() {
  return through({{0, {-0.1, 1.3, 0.08}},
                  {0.5, {-0.1, 1.3, 0.01}},
                  {1.0, {-0.1, 1.3, -0.03}},
                  {2.0, {0.1, 1.3, -0.03}},
                  {2.5, {0.1, 1.3, 0.08}},
                  {3.0, {0.1, 1.3, 0.08}}});
}

std::vector<RemoteSample> run_remote_case(const RemoteCase& c) {
  auto scene = load_scene_file(c.scene);
  if (!scene) throw std::runtime_error(c.scene.string() + ": " + scene.error().what());
  SimulatedServer server(std::move(*scene), c);
  SimulatedDevice device(c, server.settings());
  DelayedChannel<v1::ProxyUpdate> upstream(c.network, c.network.seed);
  DelayedChannel<v1::ForceUpdate> downstream(c.network, c.network.seed + 1);
  // events in time order; at the same time a step ends first, then what arrives, then the tick
  std::size_t k = 0;
  while (k < device.ticks()) {
    const Nanoseconds tick = device.tick_time(k);
    const Nanoseconds up = upstream.next_arrival();
    const Nanoseconds down = downstream.next_arrival();
    const Nanoseconds step = server.next_step();
    if (step <= std::min({tick, up, down})) {
      server.step();
    } else if (up <= std::min(tick, down)) {
      downstream.send(up, server.answer(upstream.take(), up));
    } else if (down <= tick) {
      device.receive(downstream.take(), down);
    } else if (auto update = device.tick(k++)) {
      upstream.send(tick, std::move(*update));
    }
  }
  // what is still on its way when the path ends arrives after it: the last replies of a round
  // trip of the path's length
  while (downstream.next_arrival() != std::numeric_limits<Nanoseconds>::max() ||
         upstream.next_arrival() != std::numeric_limits<Nanoseconds>::max()) {
    const Nanoseconds up = upstream.next_arrival();
    const Nanoseconds down = downstream.next_arrival();
    while (server.next_step() <= std::min(up, down)) server.step();
    if (up <= down) {
      downstream.send(up, server.answer(upstream.take(), up));
    } else {
      device.receive(downstream.take(), down);
    }
  }
  return std::move(device).samples();
}

void write_remote_log(const std::filesystem::path& file, const std::vector<RemoteSample>& samples) {
  std::ofstream out(file);
  out << "time,x,y,z,fx,fy,fz,in_contact,round_trip_us,proxy_x,proxy_y,proxy_z\n";
  out.precision(9);
  for (const RemoteSample& s : samples) {
    if (!s.answered) continue;
    out << s.time << "," << s.device.x() << "," << s.device.y() << "," << s.device.z() << ","
        << s.force.x() << "," << s.force.y() << "," << s.force.z() << "," << s.in_contact << ","
        << s.round_trip * 1e6 << "," << s.proxy.x() << "," << s.proxy.y() << "," << s.proxy.z()
        << "\n";
  }
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace felt::study
