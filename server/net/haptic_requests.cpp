// Haptics: open and close proxies, and the proxy update answered at once.

#include <chrono>
#include <cmath>
#include <sstream>

#include "core/math/bounds.hpp"
#include "net/haptic_wire.hpp"
#include "net/requests.hpp"

namespace felt::net {
namespace {

/// `settings` over the scene's `defaults`, or why they are not usable.
std::expected<ProxySettings, std::string> merge(const v1::ProxySettings& settings,
                                                const ProxySettings& defaults) {
  ProxySettings out = defaults;
  struct Field {
    bool given;
    double value;
    double lo, hi;
    bool open_below;  // (lo, hi] instead of [lo, hi]
    const char* name;
    Real& target;
  };
  const Field fields[] = {
      {settings.has_radius(), settings.radius(), 0, 0.5, false, "radius", out.radius},
      {settings.has_stiffness(), settings.stiffness(), 0, 1e5, true, "stiffness", out.stiffness},
      {settings.has_max_force(), settings.max_force(), 0, 1000, true, "max_force", out.max_force},
      {settings.has_damping(), settings.damping(), 0, 1000, false, "damping", out.damping},
      {settings.has_max_force_change(), settings.max_force_change(), 0, 1000, false,
       "max_force_change", out.max_force_change},
      {settings.has_static_friction(), settings.static_friction(), 0, 10, false, "static_friction",
       out.static_friction},
      {settings.has_dynamic_friction(), settings.dynamic_friction(), 0, 10, false,
       "dynamic_friction", out.dynamic_friction},
  };
  for (const Field& f : fields) {
    if (!f.given) continue;
    const bool ok = std::isfinite(f.value) && f.value <= f.hi &&
                    (f.open_below ? f.value > f.lo : f.value >= f.lo);
    if (!ok) {
      std::ostringstream why;
      why << f.name << " must be a finite number in " << (f.open_below ? "(" : "[") << f.lo << ", "
          << f.hi << "]";
      return std::unexpected(why.str());
    }
    f.target = f.value;
  }
  if (settings.has_force_shading()) out.force_shading = settings.force_shading();
  if (out.dynamic_friction > out.static_friction) {
    return std::unexpected("dynamic_friction must not exceed static_friction");
  }
  return out;
}

// what the scene files' vectors are held to (core/math/bounds.hpp)
constexpr const char* kPositionOutOfBound = "position must be three numbers within ±1e6 m";
static_assert(kMaxVectorComponent == 1e6, "the message names the bound");

/// What a client asked of a local model, or why it cannot have it.
std::expected<LocalModelRequest, std::string> local_model_request(
    const v1::LocalModelRequest& asked) {
  if (!(std::isfinite(asked.radius()) && asked.radius() > 0 && asked.radius() <= 1)) {
    return std::unexpected("local_model.radius must be a finite number in (0, 1] m");
  }
  if (!(std::isfinite(asked.rate_hz()) && asked.rate_hz() >= 0 && asked.rate_hz() <= 1000)) {
    return std::unexpected("local_model.rate_hz must be a finite number in [0, 1000]");
  }
  return LocalModelRequest{asked.radius(), asked.rate_hz()};
}

std::string too_many_proxies(Session& session) {
  return "at most " + std::to_string(session.context().options.max_proxies_per_session) +
         " proxies per client (--max-proxies)";
}

}  // namespace

void handle_open_proxy(Session& session, std::uint64_t id, const v1::OpenProxy& open) {
  const auto settings = merge(open.settings(), session.scene()->haptics());
  if (!settings) {
    session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, settings.error());
    return;
  }
  std::optional<LocalModelRequest> local_model;
  if (open.has_local_model()) {
    const auto asked = local_model_request(open.local_model());
    if (!asked) {
      session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, asked.error());
      return;
    }
    local_model = *asked;
  }
  const ProxyId proxy = session.open_proxy(*settings);
  if (proxy == 0) {
    session.send_error(id, v1::ERROR_CODE_LIMIT_EXCEEDED, too_many_proxies(session));
    return;
  }
  if (local_model) session.proxy(proxy)->enable_local_model(*local_model);
  reply(session, id, [&](v1::ServerMessage& message) {
    v1::ProxyOpened& opened = *message.mutable_proxy_opened();
    opened.set_proxy_id(proxy.value());
    fill_proxy_settings(*settings, *opened.mutable_settings());
    if (local_model) {
      opened.mutable_local_model()->set_radius(local_model->radius);
      opened.mutable_local_model()->set_rate_hz(local_model->rate_hz);
    }
  });
}

void handle_close_proxy(Session& session, std::uint64_t id, const v1::CloseProxy& close) {
  if (!session.close_proxy(close.proxy_id())) {
    session.send_error(id, v1::ERROR_CODE_UNKNOWN_ID,
                       "no open proxy " + std::to_string(close.proxy_id()));
    return;
  }
  reply(session, id, [&](v1::ServerMessage& message) {
    message.mutable_proxy_closed()->set_proxy_id(close.proxy_id());
  });
}

void handle_proxy_update(Session& session, std::uint64_t id, const v1::ProxyUpdate& update) {
  const auto now = std::chrono::steady_clock::now();
  const std::uint64_t received = steady_ns(now);
  // the cores stay awake while a device streams, so that its next update wakes no halted core
  if (IdleCoreSpinners* spinners = session.context().idle_core_spinners) spinners->touch(now);
  const Vec3 position = to_vec3(update.position());
  if (!update.has_position() || !within_bounds(position)) {
    session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, kPositionOutOfBound);
    return;
  }
  ProxyHandle* proxy = session.proxy(update.proxy_id());
  if (!proxy) {
    session.send_error(id, v1::ERROR_CODE_LIMIT_EXCEEDED, too_many_proxies(session));
    return;
  }
  std::optional<LocalContact> local;
  if (update.has_local()) {
    if (!proxy->has_local_model()) {
      session.send_error(id, v1::ERROR_CODE_BAD_REQUEST,
                         "proxy " + std::to_string(update.proxy_id()) +
                             " has no local model (OpenProxy.local_model)");
      return;
    }
    auto felt = local_contact(update.local(), proxy->settings());
    if (!felt) {
      session.send_error(id, v1::ERROR_CODE_BAD_REQUEST, felt.error());
      return;
    }
    local = *felt;
  }
  const ProxyOutput out = proxy->update(position, update.buttons(), local ? &*local : nullptr);
  // an idle proxy beside this one lets its snapshots go (no clock read: the update's time)
  session.forget_idle_proxy_surfaces(proxy->last_update());
  reply(session, id, [&](v1::ServerMessage& message) {
    v1::ForceUpdate* force = message.mutable_force_update();
    force->set_proxy_id(update.proxy_id());
    fill_force_update(out, *force);
    force->set_client_time_us(update.client_time_us());
    force->set_server_receive_ns(received);
    const std::uint64_t send_ns = steady_ns();
    if (out.local_model) put_local_model(*out.local_model, send_ns, *force->mutable_local_model());
    force->set_server_send_ns(send_ns);
  });
}

}  // namespace felt::net
