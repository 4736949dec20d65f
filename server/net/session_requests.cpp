// Hello and GetStats.

#include <algorithm>
#include <span>
#include <string_view>

#include "net/requests.hpp"

namespace felt::net {
namespace {

// what the server does, for clients that check before they ask
constexpr const char* kCapabilities[] = {
    "scenes.list",   "scenes.load",   "scenes.create", "scenes.join",    "scenes.control",
    "scenes.state",  "bodies.add",    "bodies.remove", "bodies.set",     "bodies.pin",
    "bodies.force",  "haptics.proxy", "haptics.grab",  "frames.float32", "frames.quantized16",
    "frames.deltas", "events",        "stats"};
constexpr std::size_t kMaxClientName = 100;

// Compares without an early exit, so the time taken does not reveal how much of a guess was
// right.
bool tokens_equal(const std::string& expected, const std::string& given) {
  unsigned char diff = expected.size() == given.size() ? 0 : 1;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    diff |= static_cast<unsigned char>(expected[i] ^ (i < given.size() ? given[i] : 0));
  }
  return diff == 0;
}

/// At most `bytes` of `text`, cut between characters: a string field that is not UTF-8 would
/// make every client that parses the events carrying it drop them.
std::string truncated_utf8(const std::string& text, std::size_t bytes) {
  if (text.size() <= bytes) return text;
  std::size_t end = bytes;
  while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xc0) == 0x80) --end;
  return text.substr(0, end);
}

void fill_limits(const ServerOptions& options, v1::Limits& out) {
  out.set_max_frame_bytes(options.max_inbound_frame_bytes);
  out.set_max_requests_in_flight(static_cast<std::uint32_t>(options.max_requests_in_flight));
  out.set_max_proxies(static_cast<std::uint32_t>(options.max_proxies_per_session));
  out.set_max_frame_rate_hz(options.max_frame_rate_hz);
  out.set_max_bodies_per_scene(static_cast<std::uint32_t>(options.max_bodies_per_scene));
  out.set_max_particles_per_scene(options.max_particles_per_scene);
  out.set_max_scenes(static_cast<std::uint32_t>(options.max_scenes));
  out.set_max_clients(static_cast<std::uint32_t>(options.max_clients));
  out.set_max_kept_scenes(static_cast<std::uint32_t>(options.max_kept_scenes_per_client));
  out.set_max_request_rate(options.max_request_rate);
}

}  // namespace

void handle_hello(Session& session, std::uint64_t id, const v1::Hello& hello) {
  const ServerContext& context = session.context();
  if (hello.protocol_version() != kProtocolVersion) {
    session.send_error(id, v1::ERROR_CODE_UNSUPPORTED_VERSION,
                       "this server speaks protocol version " + std::to_string(kProtocolVersion) +
                           ", not " + std::to_string(hello.protocol_version()));
    return;
  }
  if (!context.options.token.empty() && !tokens_equal(context.options.token, hello.token())) {
    const bool last = session.refuse_hello();
    session.send_error(
        id, v1::ERROR_CODE_UNAUTHORIZED,
        last ? "wrong or missing token; the connection closes" : "wrong or missing token");
    if (last) {
      session.context().log.warning(session.who() + " from " + session.peer() + " closed after " +
                                    std::to_string(Session::kMaxRefusedHellos) + " wrong tokens");
      session.close_after_replies();
    }
    return;
  }
  session.set_greeted(truncated_utf8(hello.client_name(), kMaxClientName));
  reply(session, id, [&](v1::ServerMessage& message) {
    v1::Welcome* welcome = message.mutable_welcome();
    welcome->set_protocol_version(kProtocolVersion);
    welcome->set_server_version(context.server_version);
    for (const char* capability : kCapabilities) welcome->add_capabilities(capability);
    welcome->set_scene_id(session.scene_id().value());
    welcome->set_client_id(session.client_id().value());
    fill_limits(context.options, *welcome->mutable_limits());
  });
}

/// The stages of one system, unless it spent no time at all (it has no bodies).
void add_stage_times(std::string_view system, std::span<const StepStage> stages,
                     const StepProfile& profile, v1::SceneStats& out) {
  if (std::ranges::none_of(stages, [&](StepStage s) { return profile[s] > 0; })) return;
  for (StepStage stage : stages) {
    v1::StageTime& entry = *out.add_stages();
    entry.set_system(std::string(system));
    entry.set_stage(std::string(stage_name(stage)));
    entry.set_ms_per_step(1e3 * profile[stage]);
  }
}

void handle_get_stats(Session& session, std::uint64_t id) {
  const ServerContext& context = session.context();
  reply(session, id, [&](v1::ServerMessage& message) {
    v1::Stats& stats = *message.mutable_stats();
    if (const auto& scene = session.scene()) {
      const RunnerStats runner = scene->stats();
      const auto bodies = scene->bodies();
      v1::SceneStats& out = *stats.mutable_scene();
      out.set_scene_id(session.scene_id().value());
      out.set_steps(runner.steps);
      out.set_sim_time(runner.sim_time);
      out.set_real_time_factor(runner.real_time_factor);
      out.set_ms_per_step(runner.ms_per_step);
      out.set_paused(runner.paused);
      out.set_time_scale(runner.time_scale);
      out.set_haptic_updates(runner.haptic_updates);
      out.set_rescued_steps(runner.rescued_steps);
      out.set_unrecoverable_steps(runner.unrecoverable_steps);
      out.set_over_budget_steps(runner.over_budget_steps);
      out.set_clients(static_cast<std::uint32_t>(scene->members().count()));
      out.set_bodies(static_cast<std::uint32_t>(bodies->bodies.size()));
      out.set_particles(bodies->particles());
      out.set_servo_ticks(runner.servo.ticks);
      out.set_servo_mean_tick_us(runner.servo.mean_tick_us);
      for (const BodyStats& body : runner.bodies) {
        v1::BodyStats& entry = *out.add_body_stats();
        entry.set_body_id(body.body_id.value());
        entry.set_kind(body.kind);
        entry.set_integrator(body.integrator);
        entry.set_max_strain(body.max_strain);
        entry.set_volume_ratio(body.volume_ratio);
        entry.set_kinetic_energy(body.kinetic_energy);
        entry.set_substeps(static_cast<std::uint32_t>(body.substeps));
        entry.set_rescued_steps(body.rescued_steps);
        entry.set_max_compression(body.max_compression);
        entry.set_over_budget_steps(body.over_budget_steps);
        entry.set_max_step(body.max_step);
      }
      add_stage_times("cloth", ClothSystem::kStages, runner.cloth_profile, out);
      add_stage_times("solids", SolidSystem::kStages, runner.solid_profile, out);
    }
    v1::SessionStats& own = *stats.mutable_session();
    const Session::Counters counters = session.counters();
    own.set_client_id(session.client_id().value());
    own.set_requests(counters.requests);
    own.set_frames_sent(counters.frames_sent);
    own.set_frames_skipped(counters.frames_skipped);
    own.set_bytes_sent(counters.bytes_sent);
    own.set_bytes_received(counters.bytes_received);
    own.set_requests_in_flight(static_cast<std::uint32_t>(session.requests_in_flight()));
    own.set_open_proxies(static_cast<std::uint32_t>(session.open_proxies()));
    own.set_queued_reply_bytes(session.queued_reply_bytes());
    v1::ServerStats& server = *stats.mutable_server();
    server.set_clients(context.clients.load());
    server.set_scenes(static_cast<std::uint32_t>(context.scenes.size()));
    server.set_uptime_s(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - context.started).count());
  });
}

}  // namespace felt::net
