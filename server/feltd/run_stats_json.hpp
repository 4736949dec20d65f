#pragma once
// What `feltd run --stats-json` writes: a batch run's statistics as JSON.

#include <nlohmann/json.hpp>

#include "runtime/batch_run.hpp"

namespace felt::feltd {

/// The run's steps and timing, each body's size and state, the solids' and the cloth's
/// per-stage times and the scripted devices' haptics.
nlohmann::json stats_to_json(const BatchRunStats& stats);

}  // namespace felt::feltd
