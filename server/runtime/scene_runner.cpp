#include "runtime/scene_runner.hpp"

#include <algorithm>
#include <chrono>

namespace felt {
namespace {

using Clock = std::chrono::steady_clock;
using Seconds = std::chrono::duration<double>;

// Lagging further than this behind the wall clock re-synchronises instead of catching up, so a
// slow scene runs slower than real time rather than stepping in bursts.
constexpr double kMaxLagSeconds = 0.1;
// unrecoverable steps are reported at most this often, and this many events are kept
constexpr double kEventIntervalSeconds = 0.5;
constexpr std::size_t kKeptEvents = 16;
// real-time factor and step time are averaged over windows this long
constexpr double kStatsWindowSeconds = 0.5;
// haptic frames are made while some proxy was rendered this recently
constexpr auto kHapticIdle = std::chrono::seconds(1);
// retired haptic frames kept for reuse: the latest, one a reader may still hold, one free
constexpr std::size_t kHapticPoolSize = 3;

}  // namespace

SceneRunner::SceneRunner(Scene scene)
    : scene_(std::move(scene)),
      name_(scene_.name),
      haptics_(scene_.haptics),
      haptic_structure_(scene_.haptic_structure) {
  publish();
  for (const BodySnapshot& body : latest()->bodies) {
    const bool cloth = scene_.world.body_ref(body.body_id).kind == BodyRef::Kind::kCloth;
    bodies_.push_back({body.body_id, body.name, cloth ? "cloth" : "solid",
                       static_cast<std::uint32_t>(body.positions.size()),
                       static_cast<std::uint32_t>(body.triangles().size())});
  }
  if (!scene_.devices.empty()) {
    // sessions key their proxies by session id (from 1) in the high half: 0 is the servo's
    servo_ = std::make_unique<HapticServo>(
        ScriptedDevices(scene_.devices, haptics_, 0), scene_.servo_rate,
        [this] { return haptic_frame(); }, reactions_);
  }
}

SceneRunner::~SceneRunner() {
  stop();
}

void SceneRunner::start() {
  if (thread_.joinable()) return;
  thread_ = std::jthread([this](std::stop_token stop) { run(stop); });
  if (servo_) servo_->start();
}

void SceneRunner::stop() {
  if (servo_) servo_->stop();
  if (!thread_.joinable()) return;
  thread_.request_stop();
  wake_.notify_all();
  thread_.join();
}

std::vector<HapticRecord> SceneRunner::device_states() const {
  return servo_ ? servo_->latest() : std::vector<HapticRecord>{};
}

ProxyOutput SceneRunner::render(HapticProxy& proxy, const Vec3& device, std::uint32_t buttons) {
  const auto frame = haptic_frame();
  const SteadyClock::time_point now = SteadyClock::now();
  const ProxyOutput out =
      proxy.update(frame->surface(now), proxy.seconds_since_last(now), device, buttons, reactions_);
  haptic_updates_.fetch_add(1, std::memory_order_relaxed);
  return out;
}

std::shared_ptr<const HapticFrame> SceneRunner::haptic_frame() {
  const SteadyClock::time_point now = SteadyClock::now();
  const SteadyClock::time_point last(
      SteadyClock::duration(last_render_.exchange(now.time_since_epoch().count())));
  auto frame = haptic_.load();
  if (frame && now - last < kHapticIdle) return frame;
  // the physics thread may have stopped making frames: start from a still copy of the latest
  std::lock_guard lock(haptic_mutex_);
  frame = haptic_.load();
  const auto snapshot = latest();
  if (!frame || frame->to != snapshot) {
    frame = make_haptic_frame(snapshot, nullptr, nullptr, haptic_structure_, now);
    haptic_.store(frame);
  }
  return frame;
}

void SceneRunner::publish_haptics(SteadyClock::time_point now) {
  const SteadyClock::time_point last(SteadyClock::duration(last_render_.load()));
  if (now - last >= kHapticIdle) return;
  std::lock_guard lock(haptic_mutex_);
  std::shared_ptr<HapticFrame> recycled;
  for (const auto& retired : haptic_pool_) {
    if (retired.use_count() == 1) recycled = retired;
  }
  const auto previous = haptic_.load();
  auto frame = make_haptic_frame(latest(), previous.get(), recycled, haptic_structure_, now);
  if (!recycled) {
    if (haptic_pool_.size() == kHapticPoolSize) haptic_pool_.erase(haptic_pool_.begin());
    haptic_pool_.push_back(frame);
  }
  haptic_.store(std::move(frame));
}

RunnerStats SceneRunner::stats() const {
  std::lock_guard lock(stats_mutex_);
  RunnerStats stats = stats_;
  stats.haptic_updates = haptic_updates_.load(std::memory_order_relaxed);
  if (servo_) stats.servo = servo_->stats();
  return stats;
}

void SceneRunner::publish() {
  auto snapshot = make_snapshot(scene_.world, latest_.load().get());
  snapshot->events = events_;
  latest_.store(std::move(snapshot));
}

void SceneRunner::record_event(std::uint64_t unrecoverable_steps,
                               std::vector<std::uint32_t> bodies) {
  std::vector<SceneEvent> events = events_ ? *events_ : std::vector<SceneEvent>{};
  const std::uint64_t sequence = events.empty() ? 1 : events.back().sequence + 1;
  events.push_back({sequence, scene_.world.step_count(), scene_.world.time(), unrecoverable_steps,
                    std::move(bodies)});
  if (events.size() > kKeptEvents) events.erase(events.begin());
  events_ = std::make_shared<const std::vector<SceneEvent>>(std::move(events));
}

void SceneRunner::run(std::stop_token stop) {
  World& world = scene_.world;
  const double h = world.settings().time_step;
  // simulated time = wall time since `origin` (shifted forward whenever we re-synchronise)
  Clock::time_point origin =
      Clock::now() - std::chrono::duration_cast<Clock::duration>(Seconds(world.time()));
  Clock::time_point window_start = Clock::now();
  double window_sim_start = world.time();
  double window_step_seconds = 0;
  std::uint64_t window_steps = 0;
  // unrecoverable steps not reported yet, and the bodies of the last one
  std::uint64_t unreported = 0;
  std::vector<std::uint32_t> failed_bodies;
  Clock::time_point last_event = Clock::now() - std::chrono::hours(1);

  while (!stop.stop_requested()) {
    const Clock::time_point now = Clock::now();
    double lag = Seconds(now - origin).count() - world.time();
    if (lag > kMaxLagSeconds) {
      origin += std::chrono::duration_cast<Clock::duration>(Seconds(lag - h));
      lag = h;
    }
    bool stepped = false;
    std::uint64_t rescued = 0, unrecoverable = 0;
    while (lag >= h && !stop.stop_requested()) {
      const Clock::time_point step_start = Clock::now();
      commands_.apply_all(scene_);
      reactions_.apply_and_clear(world);
      const StepReport report = world.step();
      rescued += (report.flags & kStepRescued) ? 1 : 0;
      if (report.flags & kStepUnrecoverable) {
        ++unrecoverable;
        failed_bodies = report.unrecoverable_bodies;
      }
      window_step_seconds += Seconds(Clock::now() - step_start).count();
      ++window_steps;
      lag -= h;
      stepped = true;
    }
    unreported += unrecoverable;
    if (unreported > 0 && Seconds(Clock::now() - last_event).count() >= kEventIntervalSeconds) {
      record_event(unreported, std::move(failed_bodies));
      unreported = 0;
      failed_bodies.clear();
      last_event = Clock::now();
    }
    if (stepped) {
      publish();
      publish_haptics(SteadyClock::now());
    }

    const Clock::time_point after = Clock::now();
    {
      std::lock_guard lock(stats_mutex_);
      stats_.steps = world.step_count();
      stats_.sim_time = world.time();
      stats_.rescued_steps += rescued;
      stats_.unrecoverable_steps += unrecoverable;
      const double window = Seconds(after - window_start).count();
      if (window >= kStatsWindowSeconds) {
        stats_.real_time_factor = (world.time() - window_sim_start) / window;
        stats_.ms_per_step = window_steps ? 1e3 * window_step_seconds / window_steps : 0;
        window_start = after;
        window_sim_start = world.time();
        window_step_seconds = 0;
        window_steps = 0;
      }
    }

    // sleep until the next step is due, or until stop() wakes us
    const auto due =
        origin + std::chrono::duration_cast<Clock::duration>(Seconds(world.time() + h));
    std::unique_lock lock(wake_mutex_);
    wake_.wait_until(lock, stop, due, [] { return false; });
  }
}

}  // namespace felt
