#pragma once
// `--set KEY=VALUE` for scene JSON: KEY is a dotted path with array indices as numbers
// (bodies.0.integrator), VALUE is JSON, or a string when it does not parse as JSON.

#include <expected>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace felt {

/// Sets the value at `key` in `document`, creating missing object keys on the way.
std::expected<void, std::string> apply_override(nlohmann::json& document, std::string_view key,
                                                std::string_view value);

/// Splits "KEY=VALUE" and applies it.
std::expected<void, std::string> apply_override(nlohmann::json& document,
                                                std::string_view assignment);

}  // namespace felt
