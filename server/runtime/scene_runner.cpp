#include "runtime/scene_runner.hpp"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <optional>

#include <sched.h>

#include "scheduling/thread_latency.hpp"
#include "scheduling/thread_name.hpp"

namespace felt {
namespace {

// haptic frames are made while some proxy was rendered this recently
constexpr auto kHapticIdle = std::chrono::seconds(1);
// the most triangles a local model carries: a 10 cm radius holds a few hundred of a fine cloth;
// this many (about 600 KB) is a proxy asking for far more than it can reach
constexpr std::size_t kMaxLocalModelTriangles = 8192;
// retired haptic frames kept for reuse: the latest, one a reader may still hold, one free
constexpr std::size_t kHapticPoolSize = 3;
// while a paused scene takes requested steps as fast as it can, it publishes this often
constexpr auto kBurstPublishPeriod = std::chrono::milliseconds(16);
// a paused scene with nothing to do still wakes this often to keep its statistics fresh
constexpr auto kIdleWake = std::chrono::milliseconds(100);

// Lets a thread waiting for this core run now (returns at once when none is). A network thread
// woken onto the physics thread's core is often not yet due under the fair scheduler, and would
// otherwise wait for the physics thread to sleep: a whole step, 0.7 ms for a 100 x 100 cloth.
void yield_core() {
  sched_yield();
}

// What a job makes on another thread for a command that waits for it.
template <class T>
class MadeElsewhere {
 public:
  bool ready() const {
    std::lock_guard lock(mutex_);
    return made_.has_value();
  }
  void set(std::expected<T, RunnerError> made) {
    std::lock_guard lock(mutex_);
    made_ = std::move(made);
  }
  std::expected<T, RunnerError> take() {
    std::lock_guard lock(mutex_);
    return std::move(*made_);
  }

 private:
  mutable std::mutex mutex_;
  std::optional<std::expected<T, RunnerError>> made_;
};

RunnerError error(RunnerError::Code code, std::string message) {
  return RunnerError{code, std::move(message)};
}

}  // namespace

SceneRunner::SceneRunner(Scene scene, SceneAccess access, SceneReloader reload, SceneLimits limits,
                         Clock& clock)
    : clock_(clock),
      scene_(std::move(scene)),
      name_(scene_.name),
      access_(access),
      reload_(std::move(reload)),
      limits_(limits),
      haptics_(scene_.haptics),
      time_step_(scene_.world.settings().time_step),
      pacer_(clock_, time_step_),
      haptic_structure_(scene_.haptic_structure) {
  own_scene_bodies();
  publish();
  publish_catalog();
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

void SceneRunner::start(int physics_nice) {
  if (thread_.joinable()) return;
  thread_ = std::jthread([this, physics_nice](std::stop_token stop) {
    // a nice out of range leaves the thread as it was (feltd checks its flag)
    if (physics_nice != 0) (void)set_this_thread_nice(physics_nice);
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
    thread_.request_stop();
    wake_.notify_all();
    thread_.join();
  }
  commands_.close();
  for (StepRequest& request : step_requests_) {
    request.done(std::unexpected(error(RunnerError::Code::kCancelled, "the scene was stopped")));
  }
  step_requests_.clear();
}

bool SceneRunner::may_change(ClientId client, const BodyInfo& body) const {
  return access_.shared || body.owner == client || !members_.contains(body.owner);
}

bool SceneRunner::may_control(ClientId client) const {
  return access_.shared || access_.owner == client || !members_.contains(access_.owner);
}

void SceneRunner::post(SceneCommand command, std::function<void()> cancel,
                       std::function<bool()> ready) {
  commands_.push(std::move(command), std::move(cancel), std::move(ready));
  wake();
}

void SceneRunner::wake() {
  // taking the lock orders what changed before the physics thread's check of the queue
  { std::lock_guard lock(wake_mutex_); }
  wake_.notify_all();
}

template <class T>
void SceneRunner::request(Completion<T> done, std::function<void(Scene&, Completion<T>&)> run,
                          std::function<bool()> ready) {
  auto shared = std::make_shared<Completion<T>>(std::move(done));
  post([shared, run = std::move(run)](Scene& scene) { run(scene, *shared); },
       [shared] {
         (*shared)(std::unexpected(error(RunnerError::Code::kCancelled, "the scene was stopped")));
       },
       std::move(ready));
}

template <class Made, class T>
void SceneRunner::request_made_elsewhere(Completion<T> done, const Offload& build_on,
                                         std::function<std::expected<Made, RunnerError>()> make,
                                         std::function<void(Scene&, Made&, Completion<T>&)> apply) {
  auto made = std::make_shared<MadeElsewhere<Made>>();
  request<T>(
      std::move(done),
      [made, apply = std::move(apply)](Scene& scene, Completion<T>& done) {
        auto value = made->take();
        if (!value) return done(std::unexpected(value.error()));
        apply(scene, *value, done);
      },
      [made] { return made->ready(); });
  build_on([this, made, make = std::move(make)] {
    made->set(make());
    wake();
  });
}

SceneEvent SceneRunner::event(SceneEvent::Kind kind, ClientId by) const {
  SceneEvent e;
  e.kind = kind;
  e.client = by;
  e.step = scene_.world.step_count();
  e.sim_time = scene_.world.time();
  e.time_scale = pacer_.scale();
  return e;
}

SceneStatus SceneRunner::status() const {
  return {scene_.world.step_count(), scene_.world.time(), pacer_.paused(), pacer_.scale()};
}

void SceneRunner::pause(ClientId by, Completion<SceneStatus> done) {
  request<SceneStatus>(std::move(done), [this, by](Scene&, Completion<SceneStatus>& done) {
    if (!pacer_.paused()) {
      pacer_.pause();
      members_.broadcast(event(SceneEvent::Kind::kPaused, by));
    }
    done(status());
  });
}

void SceneRunner::resume(ClientId by, Completion<SceneStatus> done) {
  request<SceneStatus>(std::move(done), [this, by](Scene&, Completion<SceneStatus>& done) {
    if (pacer_.paused()) {
      pacer_.resume();
      members_.broadcast(event(SceneEvent::Kind::kResumed, by));
    }
    done(status());
  });
}

void SceneRunner::step(ClientId, std::uint32_t steps, Completion<SceneStatus> done) {
  request<SceneStatus>(std::move(done), [this, steps](Scene& scene, Completion<SceneStatus>& done) {
    if (!pacer_.paused()) {
      done(std::unexpected(
          error(RunnerError::Code::kWrongState, "the scene is running; pause it first")));
      return;
    }
    if (steps == 0 || steps > kMaxStepsPerRequest) {
      done(std::unexpected(error(RunnerError::Code::kBadRequest,
                                 "steps must be 1 to " + std::to_string(kMaxStepsPerRequest))));
      return;
    }
    // requests queue up: each starts where the one before it ends
    const std::uint64_t from =
        step_requests_.empty() ? scene.world.step_count() : step_requests_.back().target;
    step_requests_.push_back({from + steps, std::move(done)});
  });
}

void SceneRunner::set_time_scale(ClientId by, double scale, Completion<SceneStatus> done) {
  request<SceneStatus>(std::move(done), [this, by, scale](Scene&, Completion<SceneStatus>& done) {
    if (!(scale > 0 && scale <= 100)) {
      done(std::unexpected(error(RunnerError::Code::kBadRequest, "scale must be in (0, 100]")));
      return;
    }
    pacer_.set_scale(scale);
    members_.broadcast(event(SceneEvent::Kind::kTimeScale, by));
    done(status());
  });
}

std::expected<Scene, RunnerError> SceneRunner::rebuild() const {
  if (!reload_) {
    return std::unexpected(error(RunnerError::Code::kWrongState,
                                 "this scene was built by requests and has no source to reset to"));
  }
  auto fresh = reload_();
  if (!fresh) return std::unexpected(error(RunnerError::Code::kBadScene, fresh.error().what()));
  return std::move(*fresh);
}

void SceneRunner::reset(ClientId by, const Offload& build_on, Completion<SceneStatus> done) {
  request_made_elsewhere<Scene, SceneStatus>(
      std::move(done), build_on, [this] { return rebuild(); },
      [this, by](Scene& scene, Scene& fresh, Completion<SceneStatus>& done) {
        for (StepRequest& pending : step_requests_) {
          pending.done(
              std::unexpected(error(RunnerError::Code::kCancelled, "the scene was reset")));
        }
        step_requests_.clear();
        fresh.world.continue_ids_from(scene.world);
        scene.world = std::move(fresh.world);
        own_scene_bodies();
        timed_forces_.clear();
        pacer_.restart();
        publish_bodies();
        SceneEvent e = event(SceneEvent::Kind::kReset, by);
        e.bodies = bodies()->bodies;
        members_.broadcast(std::move(e));
        done(status());
      });
}

void SceneRunner::save_state(ClientId, Completion<SavedState> done) {
  request<SavedState>(std::move(done), [this](Scene& scene, Completion<SavedState>& done) {
    SavedState saved{next_state_id_++,
                     std::make_shared<const WorldState>(capture_state(scene.world)),
                     scene.world.time()};
    saved_.push_back(saved);
    if (saved_.size() > kMaxSavedStates) saved_.pop_front();
    done(std::move(saved));
  });
}

void SceneRunner::restore(ClientId by, const WorldState& state, Completion<SceneStatus>& done) {
  if (!(static_cast<double>(state.step) * time_step_ < kMaxSimTime)) {
    done(std::unexpected(error(RunnerError::Code::kBadRequest,
                               "step is too large: the clock must stay below 1e9 s")));
    return;
  }
  if (auto restored = felt::restore_state(scene_.world, state); !restored) {
    done(std::unexpected(error(RunnerError::Code::kBadRequest, restored.error())));
    return;
  }
  pacer_.restart();
  publish();
  members_.broadcast(event(SceneEvent::Kind::kStateRestored, by));
  done(status());
}

void SceneRunner::restore_state(ClientId by, std::uint32_t state_id, Completion<SceneStatus> done) {
  request<SceneStatus>(
      std::move(done), [this, by, state_id](Scene&, Completion<SceneStatus>& done) {
        const auto it = std::find_if(saved_.begin(), saved_.end(),
                                     [state_id](const SavedState& s) { return s.id == state_id; });
        if (it == saved_.end()) {
          done(std::unexpected(
              error(RunnerError::Code::kUnknownId, "no saved state " + std::to_string(state_id) +
                                                       " (a scene keeps its latest " +
                                                       std::to_string(kMaxSavedStates) + ")")));
          return;
        }
        const auto state = it->state;
        restore(by, *state, done);
      });
}

void SceneRunner::restore_state(ClientId by, std::shared_ptr<const WorldState> state,
                                Completion<SceneStatus> done) {
  request<SceneStatus>(std::move(done),
                       [this, by, state = std::move(state)](Scene&, Completion<SceneStatus>& done) {
                         restore(by, *state, done);
                       });
}

bool SceneRunner::room_for_body(Completion<BodyInfo>& done) {
  if (bodies()->bodies.size() < limits_.max_bodies) return true;
  done(std::unexpected(
      RunnerError{RunnerError::Code::kLimitExceeded,
                  "the scene already has " + std::to_string(limits_.max_bodies) + " bodies",
                  SceneLimit::kBodies}));
  return false;
}

void SceneRunner::added(ClientId by, BodyId id, Completion<BodyInfo>& done) {
  owners_.emplace_back(id, by);
  publish_bodies();
  const BodyInfo info = *bodies()->find(id);
  SceneEvent e = event(SceneEvent::Kind::kBodyAdded, by);
  e.body_ids = {id};
  e.bodies = {info};
  members_.broadcast(std::move(e));
  done(info);
}

void SceneRunner::add_body(ClientId by, const Offload& build_on,
                           std::function<std::expected<BuiltBody, RunnerError>()> build,
                           Completion<BodyInfo> done) {
  request_made_elsewhere<BuiltBody, BodyInfo>(
      std::move(done), build_on, std::move(build),
      [this, by](Scene& scene, BuiltBody& built, Completion<BodyInfo>& done) {
        if (!room_for_body(done)) return;
        if (const Collider* collider = std::get_if<Collider>(&built)) {
          return added(by, scene.world.add_collider(*collider), done);
        }
        SceneBody& body = std::get<SceneBody>(built);
        const std::uint64_t used = bodies()->particles();
        const std::uint64_t particles =
            std::visit([](const auto& b) { return b.surface_vertex_count(); }, body);
        if (used + particles > limits_.max_particles) {
          done(std::unexpected(RunnerError{RunnerError::Code::kLimitExceeded,
                                           std::to_string(particles) + " particles exceed the " +
                                               std::to_string(limits_.max_particles - used) +
                                               " the scene's particle limit leaves",
                                           SceneLimit::kParticles}));
          return;
        }
        added(by,
              std::visit([&](auto&& b) { return scene.world.add_body(std::move(b)); },
                         std::move(body)),
              done);
      });
}

void SceneRunner::remove_body(ClientId by, BodyId body, Completion<BodyId> done) {
  request<BodyId>(std::move(done), [this, by, body](Scene& scene, Completion<BodyId>& done) {
    if (!scene.world.contains(body)) {
      done(
          std::unexpected(error(RunnerError::Code::kUnknownId, "no body " + std::to_string(body))));
      return;
    }
    scene.world.remove_body(body);
    std::erase_if(owners_, [body](const auto& owner) { return owner.first == body; });
    publish_bodies();
    SceneEvent e = event(SceneEvent::Kind::kBodyRemoved, by);
    e.body_ids = {body};
    members_.broadcast(std::move(e));
    done(body);
  });
}

void SceneRunner::change_body(ClientId by, BodyId body, std::function<void(World&)> change,
                              Completion<BodyId> done) {
  request<BodyId>(std::move(done), [this, by, body, change = std::move(change)](
                                       Scene& scene, Completion<BodyId>& done) {
    // removed by a request queued before this one, after this one was checked
    if (!scene.world.contains(body)) {
      done(std::unexpected(
          error(RunnerError::Code::kUnknownId, "no body " + std::to_string(body) + " any more")));
      return;
    }
    change(scene.world);
    SceneEvent e = event(SceneEvent::Kind::kBodyChanged, by);
    e.body_ids = {body};
    members_.broadcast(std::move(e));
    done(body);
  });
}

void SceneRunner::apply_force(ClientId, BodyId body, std::vector<std::uint32_t> vertices,
                              const Vec3& force, Real duration, Completion<BodyId> done) {
  auto shared_vertices = std::make_shared<std::vector<std::uint32_t>>(std::move(vertices));
  request<BodyId>(std::move(done), [this, body, shared_vertices, force, duration](
                                       Scene& scene, Completion<BodyId>& done) {
    if (timed_forces_.size() >= kMaxTimedForces) {
      done(std::unexpected(error(RunnerError::Code::kLimitExceeded,
                                 "the scene already holds " + std::to_string(kMaxTimedForces) +
                                     " forces; wait for some to end")));
      return;
    }
    timed_forces_.add(body, std::move(*shared_vertices), force, scene.world.time() + duration);
    done(body);
  });
}

std::vector<HapticRecord> SceneRunner::device_states() const {
  return servo_ ? servo_->latest() : std::vector<HapticRecord>{};
}

ProxyOutput SceneRunner::render(HapticProxy& proxy, const Vec3& device, std::uint32_t buttons,
                                const LocalContact* local) {
  const auto frame = haptic_frame();
  const SteadyClock::time_point now = SteadyClock::now();
  ProxyOutput out = proxy.update(frame->surface(now), proxy.seconds_since_last(now), device,
                                 buttons, reactions_, local);
  LocalModelFeed* feed = proxy.local_model();
  if (feed && feed->due(frame->to->version, now)) {
    // the newer snapshot, which the render reaches one interval after it was published
    // (HapticFrame), moving at the velocities of the simulation at the scene's pace: not over
    // the wall time between the two publications, which a loaded machine makes in bursts
    // (velocities 50 times too large, and a client's extrapolation far off)
    Real scale = 0;
    {
      std::lock_guard lock(stats_mutex_);
      scale = stats_.time_scale;
    }
    const Real stepped = frame->to->sim_time - frame->from->sim_time;
    const Vec3& centre = local ? local->proxy : out.contact.proxy;
    out.local_model =
        LocalModelCut{cut_local_model(frame->surface_at(1), scale > 0 ? stepped / scale : 0, centre,
                                      feed->request().radius, kMaxLocalModelTriangles),
                      frame->to->step, frame->published + frame->interval};
    feed->sent(frame->to->version, now);
  }
  haptic_updates_.fetch_add(1, std::memory_order_relaxed);
  const HapticContact& contact = out.contact;
  presence_.update({proxy.key(), contact.proxy, proxy.settings().radius, contact.in_contact,
                    contact.force, contact.contact_point, out.grabbing, now});
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
  // unless another thread made one while this one waited for the lock
  if (!frame || (frame->to != latest() && frame->published < now)) {
    frame = make_pooled_haptic_frame(nullptr, now);
  }
  return frame;
}

void SceneRunner::prepare_haptics() {
  // what a render does first, between two steps: a still frame of the latest snapshot if the
  // proxies were idle (none stale to interpolate from), and frames from the steps after it for
  // kHapticIdle, which fill the pool with frames to refit
  post([this](Scene&) { haptic_frame(); });
}

void SceneRunner::publish_haptics(SteadyClock::time_point now) {
  const SteadyClock::time_point last(SteadyClock::duration(last_render_.load()));
  if (now - last >= kHapticIdle) return;
  std::lock_guard lock(haptic_mutex_);
  make_pooled_haptic_frame(haptic_.load().get(), now);
}

std::shared_ptr<HapticFrame> SceneRunner::make_pooled_haptic_frame(const HapticFrame* previous,
                                                                   SteadyClock::time_point now) {
  std::shared_ptr<HapticFrame> recycled;
  for (const auto& retired : haptic_pool_) {
    if (retired.use_count() == 1) recycled = retired;
  }
  auto frame = make_haptic_frame(latest(), previous, recycled, haptic_structure_, now);
  if (!recycled) {
    if (haptic_pool_.size() == kHapticPoolSize) haptic_pool_.erase(haptic_pool_.begin());
    haptic_pool_.push_back(frame);
  }
  haptic_.store(frame);
  return frame;
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
  snapshot->version = ++published_;
  latest_.store(std::move(snapshot));
}

void SceneRunner::own_scene_bodies() {
  owners_.clear();
  for (BodyId id : scene_.world.body_ids()) owners_.emplace_back(id, access_.owner);
}

void SceneRunner::publish_bodies() {
  // the snapshot first: a client told of a body finds it in the next frame
  publish();
  publish_catalog();
}

void SceneRunner::publish_catalog() {
  auto catalog = std::make_shared<BodyCatalog>();
  for (BodyId id : scene_.world.body_ids()) {
    const auto owner = std::find_if(owners_.begin(), owners_.end(),
                                    [id](const auto& entry) { return entry.first == id; });
    catalog->bodies.push_back(
        describe_body(scene_.world, id, owner == owners_.end() ? 0 : owner->second));
  }
  catalog_.store(std::move(catalog));
}

void SceneRunner::step_once() {
  World& world = scene_.world;
  timed_forces_.apply(world);
  reactions_.apply_and_clear(world);
  health_.count(world.step(yield_core));
}

void SceneRunner::report_health(bool at_once) {
  health_.report(clock_.now(), at_once, event(SceneEvent::Kind::kUnrecoverableStep, 0));
}

void SceneRunner::run(std::stop_token stop) {
  World& world = scene_.world;
  const double h = time_step_;
  StatsWindow window(clock_.now(), world.time());

  const auto timed_step = [&] {
    const Clock::time_point start = clock_.now();
    step_once();
    window.add_step(clock_.now() - start);
  };

  while (!stop.stop_requested()) {
    const std::uint64_t published_before = published_;
    commands_.apply_all(scene_);
    bool stepped = false;
    if (!step_requests_.empty()) {
      // requested steps of a paused scene, as fast as they go; other requests still get in
      // between steps, and clients still see the scene move
      Clock::time_point last_publish = clock_.now();
      while (!step_requests_.empty() && !stop.stop_requested()) {
        timed_step();
        stepped = true;
        while (!step_requests_.empty() && step_requests_.front().target <= world.step_count()) {
          step_requests_.front().done(status());
          step_requests_.erase(step_requests_.begin());
        }
        commands_.apply_all(scene_);
        if (clock_.now() - last_publish >= kBurstPublishPeriod) {
          publish();
          publish_haptics(SteadyClock::now());
          last_publish = clock_.now();
        }
      }
      pacer_.restart();
    } else if (!pacer_.paused()) {
      double lag = pacer_.lag(world.time());
      while (lag >= h && !stop.stop_requested()) {
        if (stepped) commands_.apply_all(scene_);
        // a pause or a StepScene just applied ends the run: its reply named this step
        if (pacer_.paused() || !step_requests_.empty()) break;
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
      publish();
    }
    if (stepped || published_ != published_before) {
      yield_core();
      publish_haptics(SteadyClock::now());
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
      stats_.paused = pacer_.paused();
      stats_.time_scale = pacer_.scale();
      if (const auto rates = window.close_if_full(after, world.time())) {
        stats_.real_time_factor = rates->real_time_factor;
        stats_.ms_per_step = rates->ms_per_step;
        stats_.bodies = std::move(bodies);
      }
    }

    // sleep until the next step is due, a request arrives, or stop() wakes us
    if (!step_requests_.empty() || (!pacer_.paused() && pacer_.restarting())) continue;
    const auto due = pacer_.paused() ? after + kIdleWake : pacer_.next_due(world.time());
    std::unique_lock lock(wake_mutex_);
    clock_.wait_until(lock, wake_, stop, due, [this] { return !commands_.idle(); });
  }
  report_health(true);
}

}  // namespace felt
