#include "scene/thesis_scene_reader.hpp"

#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <regex>
#include <vector>

#include <nlohmann/json.hpp>

namespace felt {
namespace {

using nlohmann::json;

struct Token {
  std::string text;
  int line = 0;
};

std::vector<Token> tokenize(std::string_view text) {
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '{' || c == '}') {
      tokens.push_back({std::string(1, c), line});
      ++i;
    } else {
      const std::size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) &&
             text[i] != '{' && text[i] != '}' && text[i] != '#') {
        ++i;
      }
      tokens.push_back({std::string(text.substr(start, i - start)), line});
    }
  }
  return tokens;
}

struct Failure {
  SceneError error;
};

class Parser {
 public:
  Parser(std::vector<Token> tokens, std::string source)
      : tokens_(std::move(tokens)), source_(std::move(source)) {}

  json scene() {
    expect("DeformableModels");
    json bodies = json::array();
    while (pos_ < tokens_.size()) bodies.push_back(model());
    if (bodies.empty()) fail_here("the file has no DeformableModel");
    return {{"name", "thesis scene"},
            {"time_step", 0.01},
            {"colliders", json::array({{{"type", "plane"}, {"point", {0, 0, 0}}}})},
            {"bodies", std::move(bodies)}};
  }

 private:
  [[noreturn]] void fail_at(int line, const std::string& message) const {
    throw Failure{{"", source_ + ":" + std::to_string(line) + ": " + message}};
  }
  [[noreturn]] void fail_here(const std::string& message) const {
    fail_at(pos_ < tokens_.size() ? tokens_[pos_].line : last_line(), message);
  }
  int last_line() const { return tokens_.empty() ? 1 : tokens_.back().line; }

  const Token& next(const char* what) {
    if (pos_ >= tokens_.size()) fail_at(last_line(), std::string("expected ") + what);
    return tokens_[pos_++];
  }
  void expect(const std::string& word) {
    const Token& t = next(word.c_str());
    if (t.text != word) fail_at(t.line, "expected " + word + ", found \"" + t.text + "\"");
  }
  double number(const std::string& key) {
    const Token& t = next(("a number after " + key).c_str());
    double value = 0;
    const auto [end, error] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), value);
    if (error != std::errc() || end != t.text.data() + t.text.size() || !std::isfinite(value)) {
      fail_at(t.line, key + ": \"" + t.text + "\" is not a finite number");
    }
    return value;
  }
  json vec3(const std::string& key) { return {number(key), number(key), number(key)}; }

  json model() {
    expect("DeformableModel");
    expect("{");
    const int start_line = tokens_[pos_ - 1].line;
    // Table B.1 defaults
    json body = {{"type", "solid"},
                 {"name", "N/A"},
                 {"node_mass", 1.0},
                 {"mass_spring",
                  {{"damping", 1.0}, {"distance_stiffness", 20.0}, {"volume_stiffness", 10.0}}}};
    json transform = {{"rotate", {0, 0, 0}}, {"scale", {1, 1, 1}}, {"translate", {0, 0, 0}}};
    std::optional<std::string> path, immersed;
    int path_line = start_line;
    for (;;) {
      const Token& key = next("a parameter or }");
      if (key.text == "}") break;
      const std::string& k = key.text;
      if (k == "Name") {
        body["name"] = next("a name after Name").text;
      } else if (k == "Path") {
        path = next("a file after Path").text;
        path_line = key.line;
      } else if (k == "Immersed") {
        immersed = next("a file after Immersed").text;
      } else if (k == "Color") {
        next("a colour after Color");  // rendering is the client's business
      } else if (k == "Mass") {
        body["node_mass"] = number(k);
      } else if (k == "Damping") {
        body["mass_spring"]["damping"] = number(k);
      } else if (k == "DistancePreservation") {
        body["mass_spring"]["distance_stiffness"] = number(k);
      } else if (k == "VolumePreservation") {
        body["mass_spring"]["volume_stiffness"] = number(k);
      } else if (k == "Scale") {
        transform["scale"] = vec3(k);
      } else if (k == "Translate") {
        transform["translate"] = vec3(k);
      } else if (k == "Rotate") {
        json degrees = vec3(k);
        for (auto& angle : degrees) angle = angle.get<double>() * 180 / std::numbers::pi;
        transform["rotate"] = degrees;
      } else {
        fail_at(key.line, "unknown parameter \"" + k + "\"");
      }
    }
    if (!path) fail_at(start_line, "a DeformableModel needs a Path");
    body["transform"] = transform;
    add_shape(body, *path, immersed, path_line);
    return body;
  }

  void add_shape(json& body, const std::string& path, const std::optional<std::string>& immersed,
                 int line) const {
    static const std::regex kLattice(R"(lattice:(\d+)x(\d+)x(\d+))");
    static const std::regex kBox(R"(box:(\d+))");
    std::smatch m;
    const auto ends_with = [&](std::string_view suffix) { return path.ends_with(suffix); };
    if (std::regex_match(path, m, kLattice)) {
      json lattice = {{"cells", {std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3])}},
                      {"size", {1, 1, 1}}};
      if (immersed) {
        std::smatch b;
        if (!std::regex_match(*immersed, b, kBox)) {
          fail_at(line, "a lattice carries Immersed box:N, not \"" + *immersed + "\"");
        }
        lattice["fine_divisions"] = std::stoi(b[1]);
      }
      body["lattice"] = lattice;
    } else if (ends_with(".obj")) {
      if (immersed && *immersed != path) {
        fail_at(line, "a voxelized .obj Path embeds itself; Immersed must be empty or the same");
      }
      body["mesh"] = {{"file", path}};
    } else if (ends_with(".node")) {
      if (immersed) fail_at(line, "Immersed is not supported with a TetGen Path");
      body["tetgen"] = {{"file", path}};
    } else {
      fail_at(line,
              "Path \"" + path +
                  "\" must be a TetGen .node file, a closed .obj surface or lattice:NXxNYxNZ");
    }
  }

  std::vector<Token> tokens_;
  std::string source_;
  std::size_t pos_ = 0;
};

}  // namespace

std::expected<json, SceneError> thesis_scene_to_json(std::string_view text,
                                                     const std::string& source) {
  try {
    return Parser(tokenize(text), source).scene();
  } catch (const Failure& failure) {
    return std::unexpected(failure.error);
  } catch (const std::out_of_range&) {
    return std::unexpected(SceneError{"", source + ": a count is too large"});
  }
}

}  // namespace felt
