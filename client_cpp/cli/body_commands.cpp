// felt add-cloth, add-solid, remove, set, pin.

#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/progress.hpp"

namespace felt::cli {

namespace v1 = felt::v1;

namespace {

/// `json` itself, or the contents of the file it names when it starts with '@'.
std::string json_text(const std::string& json) {
  if (json.empty() || json.front() != '@') return json;
  std::ifstream in(json.substr(1));
  if (!in) throw UsageError("cannot read " + json.substr(1));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The scene-file entry of a body of `type`, named `name` when one is given.
nlohmann::json body_entry(const char* type, const std::string& name) {
  nlohmann::json body = {{"type", type}};
  if (!name.empty()) body["name"] = name;
  return body;
}

int add(const Common& common, const std::string& body_json) {
  client::Client client;
  connect(client, common);
  v1::BodyInfo body;
  {
    Spinner waiting("adding the body");  // a big mesh is voxelized first
    body = client.add_body(body_json).body();
  }
  std::printf("body %u: %s \"%s\", %u vertices, %u triangles\n", body.body_id(),
              body.kind().c_str(), body.name().c_str(), body.particles(), body.triangles());
  return 0;
}

}  // namespace

int add_cloth(const Common& common, const ClothOptions& o, const std::string& json) {
  if (!json.empty()) return add(common, json_text(json));
  nlohmann::json body = body_entry("cloth", o.name);
  body["grid"] = {{"nx", o.grid[0]},     {"ny", o.grid[1]},    {"width", o.size[0]},
                  {"height", o.size[1]}, {"center", o.center}, {"plane", o.plane}};
  body["mass"] = o.mass;
  body["integrator"] = o.integrator;
  if (!o.pin.empty() && o.pin != "none") body["pin"] = o.pin;
  return add(common, body.dump());
}

int add_solid(const Common& common, const SolidOptions& o, const std::string& json) {
  if (!json.empty()) return add(common, json_text(json));
  nlohmann::json body = body_entry("solid", o.name);
  body["lattice"] = {{"cells", o.cells}, {"size", o.size}};
  body["transform"] = {{"translate", o.center}};
  body["model"] = o.model;
  body["node_mass"] = o.node_mass;
  return add(common, body.dump());
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
