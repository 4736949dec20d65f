#include "scene/scene_overrides.hpp"

#include <charconv>

#include <nlohmann/json.hpp>

namespace felt {

std::expected<void, std::string> apply_override(nlohmann::json& document, std::string_view key,
                                                std::string_view value) {
  using nlohmann::json;
  if (key.empty()) return std::unexpected("empty key");
  json* node = &document;
  std::string walked;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    const std::string_view part = key.substr(start, dot - start);
    if (part.empty()) return std::unexpected("empty part in key \"" + std::string(key) + "\"");
    walked += (walked.empty() ? "" : ".") + std::string(part);
    if (node->is_array()) {
      std::size_t index = 0;
      const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), index);
      if (ec != std::errc() || end != part.data() + part.size()) {
        return std::unexpected(walked + ": an array needs a numeric index");
      }
      if (index >= node->size()) {
        return std::unexpected(walked + ": index out of range (size " +
                               std::to_string(node->size()) + ")");
      }
      node = &(*node)[index];
    } else if (node->is_object() || node->is_null()) {
      node = &(*node)[std::string(part)];
    } else {
      return std::unexpected(walked + ": cannot descend into a " + std::string(node->type_name()));
    }
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  json parsed = json::parse(value, nullptr, /*allow_exceptions=*/false);
  *node = parsed.is_discarded() ? json(std::string(value)) : std::move(parsed);
  return {};
}

std::expected<void, std::string> apply_override(nlohmann::json& document,
                                                std::string_view assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string_view::npos) {
    return std::unexpected("\"" + std::string(assignment) + "\" is not KEY=VALUE");
  }
  return apply_override(document, assignment.substr(0, eq), assignment.substr(eq + 1));
}

}  // namespace felt
