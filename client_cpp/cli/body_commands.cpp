// felt add-cloth, add-solid, remove, set, pin.

#include <cstdio>
#include <fstream>
#include <sstream>

#include "cli/commands.hpp"

namespace felt::cli {

namespace v1 = felt::v1;

namespace {

std::string json_array(const std::vector<double>& values) {
  std::ostringstream out;
  out.precision(17);
  out << "[";
  for (std::size_t i = 0; i < values.size(); ++i) out << (i ? ", " : "") << values[i];
  out << "]";
  return out.str();
}

/// `json` itself, or the contents of the file it names when it starts with '@'.
std::string json_text(const std::string& json) {
  if (json.empty() || json.front() != '@') return json;
  std::ifstream in(json.substr(1));
  if (!in) throw client::ClientError(v1::ERROR_CODE_BAD_REQUEST, "cannot read " + json.substr(1));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

int add(const Common& common, const std::string& body_json) {
  client::Client client;
  connect(client, common);
  const v1::BodyInfo body = client.add_body(body_json).body();
  std::printf("body %u: %s \"%s\", %u vertices, %u triangles\n", body.body_id(),
              body.kind().c_str(), body.name().c_str(), body.particles(), body.triangles());
  return 0;
}

}  // namespace

int add_cloth(const Common& common, const ClothOptions& o, const std::string& json) {
  if (!json.empty()) return add(common, json_text(json));
  std::ostringstream body;
  body.precision(17);
  body << R"({"type": "cloth")";
  if (!o.name.empty()) body << R"(, "name": ")" << o.name << '"';
  body << R"(, "grid": {"nx": )" << o.grid[0] << R"(, "ny": )" << o.grid[1] << R"(, "width": )"
       << o.size[0] << R"(, "height": )" << o.size[1] << R"(, "center": )" << json_array(o.center)
       << R"(, "plane": ")" << o.plane << R"("})"
       << R"(, "mass": )" << o.mass << R"(, "integrator": ")" << o.integrator << '"';
  if (!o.pin.empty() && o.pin != "none") body << R"(, "pin": ")" << o.pin << '"';
  body << "}";
  return add(common, body.str());
}

int add_solid(const Common& common, const SolidOptions& o, const std::string& json) {
  if (!json.empty()) return add(common, json_text(json));
  std::ostringstream body;
  body.precision(17);
  body << R"({"type": "solid")";
  if (!o.name.empty()) body << R"(, "name": ")" << o.name << '"';
  body << R"(, "lattice": {"cells": [)" << o.cells[0] << ", " << o.cells[1] << ", " << o.cells[2]
       << R"(], "size": )" << json_array(o.size) << "}"
       << R"(, "transform": {"translate": )" << json_array(o.center) << "}"
       << R"(, "model": ")" << o.model << R"(", "node_mass": )" << o.node_mass << "}";
  return add(common, body.str());
}

int remove_body(const Common& common, std::uint32_t body) {
  client::Client client;
  connect(client, common);
  client.remove_body(body);
  std::printf("body %u removed\n", body);
  return 0;
}

int set(const Common& common, const v1::SetBodyParameters& parameters) {
  client::Client client;
  connect(client, common);
  client.set_body_parameters(parameters);
  std::printf("body %u updated\n", parameters.body_id());
  return 0;
}

int pin(const Common& common, std::uint32_t body, const std::vector<std::uint32_t>& pins,
        const std::vector<std::uint32_t>& unpins) {
  client::Client client;
  connect(client, common);
  client.pin_particles(body, pins, unpins);
  std::printf("body %u: %zu pinned, %zu freed\n", body, pins.size(), unpins.size());
  return 0;
}

}  // namespace felt::cli
