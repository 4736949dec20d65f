#pragma once
// Haptic runtime types <-> felt.v1 messages (docs/protocol.md 7.4, 7.5): what a ProxyUpdate's
// `local` says a client felt, and the ForceUpdate (with its local model) a render answers with.
// Shared by the request handler and tests/bench/remote_haptics_study.

#include <chrono>
#include <cstdint>
#include <expected>
#include <string>

#include "felt/v1/haptics.pb.h"
#include "runtime/haptic_proxy.hpp"

namespace felt::net {

/// `t` in nanoseconds of the steady clock.
std::uint64_t steady_ns(std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now());

/// What a client's local renderer says it felt, or why that is no reading.
std::expected<LocalContact, std::string> local_contact(const v1::LocalContact& local,
                                                       const ProxySettings& settings);

/// `cut` as sent at `send_ns` (steady_ns): its age is from when its positions hold to then.
void put_local_model(const LocalModelCut& cut, std::uint64_t send_ns, v1::LocalModel& out);

/// What a render felt, into the ForceUpdate's contact and grab fields (not its ids, times or
/// local model).
void fill_force_update(const ProxyOutput& out, v1::ForceUpdate& force);

}  // namespace felt::net
