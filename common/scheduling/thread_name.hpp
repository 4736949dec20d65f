#pragma once
// Names feltd's threads as top -H, perf and /proc/<pid>/task/<tid>/comm show them, so that a
// scheduler trace says which thread waited behind which (felt-physics, felt-net-1,
// felt-spin-0, felt-servo) instead of a column of "feltd".

#include <pthread.h>

#include <cstddef>
#include <string_view>

namespace felt {

/// The kernel keeps 15 characters of a thread's name.
constexpr std::size_t kMaxThreadName = 15;

/// Names `thread`, cut to kMaxThreadName characters; false if the system refused.
bool name_thread(pthread_t thread, std::string_view name);

}  // namespace felt
