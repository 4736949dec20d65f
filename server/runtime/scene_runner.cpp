#include "runtime/scene_runner.hpp"

#include <algorithm>
#include <chrono>
#include <mutex>

#include <sched.h>

#include "runtime/proxy_render.hpp"
#include "scheduling/thread_latency.hpp"
#include "scheduling/thread_name.hpp"

namespace felt {
namespace {

// a pass of the physics thread takes steps for at most this long of its clock before it
// publishes, reports and answers requests: the cadence clients see a scene at however short its
// steps, and however many are due
constexpr auto kPassLength = std::chrono::milliseconds(16);
// a scene with nothing due (paused, or a tiny time scale) still wakes this often to keep its
// statistics fresh
constexpr auto kIdleWake = std::chrono::milliseconds(100);

// Lets a thread waiting for this core run now (returns at once when none is). A network thread
// woken onto the physics thread's core is often not yet due under the fair scheduler, and would
// otherwise wait for the physics thread to sleep: a whole step, 0.7 ms for a 100 x 100 cloth.
void yield_core() {
  sched_yield();
}

}  // namespace

SceneRunner::SceneRunner(Scene scene, SceneAccess access, SceneReloader reload, SceneLimits limits,
                         Clock& clock)
    : clock_(clock),
      name_(scene.name),
      access_(access),
      haptics_(scene.haptics),
      time_step_(scene.world.settings().time_step),
      health_settings_(scene.world.settings().health),
      live_(std::move(scene), access.owner, clock),
      requests_(live_, commands_, members_, std::move(reload), limits),
      haptic_frames_(live_, live_.scene.haptic_structure) {
  const Scene& built = live_.scene;
  if (!built.devices.empty()) {
    // sessions key their proxies by session id (from 1) in the high half: 0 is the servo's
    servo_ = std::make_unique<HapticServo>(
        ScriptedDevices(built.devices, haptics_), built.servo_rate,
        [this] { return haptic_frames_.current(); }, reactions_);
  }
}

SceneRunner::~SceneRunner() {
  stop();
}

void SceneRunner::start(int physics_nice) {
  if (thread_.joinable()) return;
  thread_ = std::jthread([this, physics_nice](std::stop_token stop) {
    // a nice out of range leaves the thread as it was (feltd checks its flag)
    if (physics_nice != 0) (void)step_this_thread_aside(physics_nice);
    run(stop);
  });
  name_thread(thread_.native_handle(), "felt-physics");
  if (servo_) servo_->start();
}

void SceneRunner::stop() {
  // the last member leaving and the server's shutdown may stop a scene at the same time
  std::lock_guard lock(stop_mutex_);
  if (servo_) servo_->stop();
  if (thread_.joinable()) {
    thread_.request_stop();  // wakes the thread where it waits for commands
    thread_.join();
  }
  commands_.close();
  live_.step_requests.cancel_all("the scene was stopped");
}

bool SceneRunner::may_change(ClientId client, const BodyInfo& body) const {
  return access_.shared || body.owner == client || !members_.contains(body.owner);
}

bool SceneRunner::may_control(ClientId client) const {
  if (!access_.controllable) return false;
  return access_.shared || access_.owner == client || !members_.contains(access_.owner);
}

void SceneRunner::post(SceneCommand command, std::function<void()> cancel,
                       std::function<bool()> ready) {
  commands_.push(std::move(command), std::move(cancel), std::move(ready));
}

std::vector<HapticRecord> SceneRunner::device_states() const {
  return servo_ ? servo_->latest() : std::vector<HapticRecord>{};
}

ProxyOutput SceneRunner::render(HapticProxy& proxy, const Vec3& device, std::uint32_t buttons,
                                const LocalContact* local) {
  const auto frame = haptic_frames_.current();
  const SteadyClock::time_point now = SteadyClock::now();
  Real scale = 0;
  if (proxy.local_model()) {  // only a local model needs the scene's pace and point compliance
    live_.serve_local_models();
    std::lock_guard lock(stats_mutex_);
    scale = stats_.time_scale;
  }
  ProxyOutput out = render_proxy(proxy, *frame, now, scale, device, buttons, reactions_, local);
  haptic_updates_.fetch_add(1, std::memory_order_relaxed);
  const HapticContact& contact = out.contact;
  presence_.update({proxy.key(), contact.proxy, proxy.settings().radius, contact.in_contact,
                    contact.force, contact.contact_point, out.grabbing, now});
  return out;
}

void SceneRunner::prepare_haptics() {
  // what a render does first, between two steps: a still frame of the latest snapshot if the
  // proxies were idle (none stale to interpolate from), and frames from the steps after it for
  // a while, which fill the pool with frames to refit
  post([this](Scene&) { haptic_frames_.current(); });
}

void SceneRunner::prepare_frames() {
  if (catching_up_.exchange(true)) return;  // asked already: one command does it
  post([this](Scene&) {
    catching_up_ = false;
    live_.latest();  // a read: the steps from now on are published too
    live_.catch_up();
  });
}

RunnerStats SceneRunner::stats() const {
  std::lock_guard lock(stats_mutex_);
  RunnerStats stats = stats_;
  stats.haptic_updates = haptic_updates_.load(std::memory_order_relaxed);
  if (servo_) stats.servo = servo_->stats();
  return stats;
}

StepReport SceneRunner::step_once() {
  World& world = live_.scene.world;
  live_.timed_forces.apply(world);
  reactions_.apply_and_clear(world);
  StepReport report = world.step(yield_core);
  health_.count(report);
  return report;
}

void SceneRunner::report_health(bool at_once) {
  health_.report(clock_.now(), at_once, live_.event(SceneEvent::Kind::kUnrecoverableStep, 0));
}

void SceneRunner::run(std::stop_token stop) {
  Scene& scene = live_.scene;
  World& world = scene.world;
  Pacer& pacer = live_.pacer;
  StepRequests& step_requests = live_.step_requests;
  const double h = time_step_;
  StatsWindow window(clock_.now(), world.time());

  const auto timed_step = [&] {
    const Clock::time_point start = clock_.now();
    const StepReport report = step_once();
    window.add_step(clock_.now() - start, report.cloth_profile, report.solid_profile);
  };

  while (!stop.stop_requested()) {
    const std::uint64_t published_before = live_.published();
    commands_.apply_all(scene);
    bool stepped = false;
    if (!step_requests.empty()) {
      // requested steps of a paused scene, as fast as they go; other requests still get in
      // between steps, and clients still see the scene move
      Clock::time_point last_publish = clock_.now();
      while (!step_requests.empty() && !stop.stop_requested()) {
        timed_step();
        stepped = true;
        step_requests.answer_reached(live_.status());
        commands_.apply_all(scene);
        if (clock_.now() - last_publish >= kPassLength) {
          const std::uint64_t before = live_.published();
          live_.publish_steps();
          if (live_.published() != before) haptic_frames_.publish(SteadyClock::now());
          last_publish = clock_.now();
        }
      }
      pacer.restart();
    } else if (!pacer.paused()) {
      // the steps due, for one pass at most: a scene that cannot keep up falls behind (and the
      // Pacer re-synchronises) instead of taking a burst of steps before its clients see any
      const Clock::time_point pass_start = clock_.now();
      double lag = pacer.lag(world.time());
      while (lag >= h && !stop.stop_requested() && clock_.now() - pass_start < kPassLength) {
        if (stepped) commands_.apply_all(scene);
        // a pause or a StepScene just applied ends the run: its reply named this step
        if (pacer.paused() || !step_requests.empty()) break;
        timed_step();
        lag -= h;
        stepped = true;
      }
    }
    report_health(false);
    // a command that changes what clients see (bodies added, removed, reset, restored)
    // publishes it itself; the others (pause, time scale, pins, parameters, forces) leave a
    // paused scene as it was, and its subscribers get no frame for them
    if (stepped) {
      yield_core();
      live_.publish_steps();
    } else {
      live_.catch_up();  // someone came to read a scene whose steps nobody watched
    }
    if (live_.published() != published_before) {
      yield_core();
      haptic_frames_.publish(SteadyClock::now());
    }

    const Clock::time_point after = clock_.now();
    {
      // measured before the lock, which GetStats on a network thread waits for
      std::vector<BodyStats> bodies =
          window.full(after) ? body_stats(world) : std::vector<BodyStats>();
      std::lock_guard lock(stats_mutex_);
      stats_.steps = world.step_count();
      stats_.sim_time = world.time();
      stats_.rescued_steps = health_.rescued();
      stats_.unrecoverable_steps = health_.unrecoverable();
      stats_.over_budget_steps = health_.over_budget();
      stats_.paused = pacer.paused();
      stats_.time_scale = pacer.scale();
      if (const auto rates = window.close_if_full(after, world.time())) {
        stats_.real_time_factor = rates->real_time_factor;
        stats_.ms_per_step = rates->ms_per_step;
        stats_.cloth_profile = rates->cloth_profile;
        stats_.solid_profile = rates->solid_profile;
        stats_.bodies = std::move(bodies);
      }
    }

    // sleep until the next step is due, a request arrives, or stop() wakes us
    if (!step_requests.empty() || (!pacer.paused() && pacer.restarting())) continue;
    const Clock::time_point idle_wake = after + kIdleWake;
    commands_.wait(clock_, stop,
                   pacer.paused() ? idle_wake : std::min(idle_wake, pacer.next_due(world.time())));
  }
  report_health(true);
}

}  // namespace felt
