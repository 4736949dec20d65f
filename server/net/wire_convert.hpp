#pragma once
// Runtime types <-> felt.v1 messages: the conversions every request handler shares.

#include <cstdint>
#include <expected>
#include <memory>
#include <string>

#include "felt/v1/envelope.pb.h"
#include "runtime/scene_registry.hpp"

namespace felt::net {

void put_vec3(const Vec3& v, felt::v1::Vec3& out);
Vec3 to_vec3(const felt::v1::Vec3& v);

void fill_error(std::uint64_t request_id, felt::v1::ErrorCode code, const std::string& message,
                felt::v1::ServerMessage& out);
felt::v1::ErrorCode error_code(RunnerError::Code code);

void fill_body_info(const BodyInfo& body, felt::v1::BodyInfo& out);
void fill_collider(const Collider& collider, felt::v1::ColliderShape& out);
void fill_event(SceneId scene, const SceneEvent& event, felt::v1::SceneEvent& out);
void fill_status(SceneId scene, const SceneStatus& status, felt::v1::SceneStatus& out);
void fill_proxy_settings(const ProxySettings& settings, felt::v1::ProxySettings& out);

void fill_state(const WorldState& state, Real time_step, felt::v1::SceneState& out);
/// A state a client sent, or why it is not one (counts that do not come in threes).
std::expected<std::shared_ptr<const WorldState>, std::string> to_state(
    const felt::v1::SceneState& state);

}  // namespace felt::net
