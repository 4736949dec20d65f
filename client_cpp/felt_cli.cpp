// felt: the command-line client of feltd.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "felt_client.hpp"
#include "obj_writer.hpp"
#include "wire/host_port.hpp"

namespace {

namespace v1 = felt::v1;
using felt::client::Client;

struct Common {
  std::string server = "127.0.0.1:7450";
  std::string token;
  std::string scene;  ///< load this scene by name before the command
};

/// Connects, says hello and loads --scene if one was given.
v1::Welcome connect(Client& client, const Common& common) {
  const auto address = felt::wire::parse_host_port(common.server);
  if (!address) {
    throw felt::client::ClientError(v1::ERROR_CODE_BAD_REQUEST, "--server: " + address.error());
  }
  client.connect(address->host, address->port);
  v1::Welcome welcome = client.hello("felt-cli", common.token);
  if (!common.scene.empty()) client.load_scene_by_name(common.scene);
  return welcome;
}

int hello(const Common& common) {
  Client client;
  const v1::Welcome welcome = connect(client, common);
  std::printf("feltd %s, protocol %u, scene %llu\ncapabilities:", welcome.server_version().c_str(),
              welcome.protocol_version(), static_cast<unsigned long long>(welcome.scene_id()));
  for (const std::string& capability : welcome.capabilities())
    std::printf(" %s", capability.c_str());
  std::printf("\n");
  return 0;
}

int watch(const Common& common, int frames, const std::string& out_dir, double rate, bool normals) {
  Client client;
  connect(client, common);
  std::filesystem::create_directories(out_dir);
  client.subscribe_frames(rate, normals);
  felt::client::TriangleCache triangles;
  for (int i = 0; i < frames; ++i) {
    const auto frame = client.next_frame(std::chrono::seconds(5));
    if (!frame) {
      std::cerr << "felt: no frame within 5 s\n";
      return 1;
    }
    triangles.update(*frame);
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.obj", i);
    const auto file = std::filesystem::path(out_dir) / name;
    if (!felt::client::write_obj(file, *frame, triangles)) {
      std::cerr << "felt: cannot write " << file << "\n";
      return 1;
    }
    std::printf("%s  step %llu  t %.3f s%s\n", file.c_str(),
                static_cast<unsigned long long>(frame->step()), frame->sim_time(),
                frame->skipped() ? "  (skipped some)" : "");
  }
  return 0;
}

int touch(const Common& common, const std::vector<double>& at, std::uint32_t proxy) {
  Client client;
  connect(client, common);
  const v1::ForceUpdate force = client.proxy_update(proxy, {at[0], at[1], at[2]});
  std::printf(
      "force %.6g %.6g %.6g N  |F| %.6g N\n", force.force().x(), force.force().y(),
      force.force().z(),
      std::sqrt(force.force().x() * force.force().x() + force.force().y() * force.force().y() +
                force.force().z() * force.force().z()));
  if (force.in_contact()) {
    std::printf("contact at %.6g %.6g %.6g on body %u, triangle %d\n", force.contact_point().x(),
                force.contact_point().y(), force.contact_point().z(), force.body_id(),
                force.triangle());
  } else {
    std::printf("no contact\n");
  }
  return 0;
}

int set(const Common& common, const v1::SetBodyParameters& parameters) {
  Client client;
  connect(client, common);
  client.set_body_parameters(parameters);
  std::printf("body %u updated\n", parameters.body_id());
  return 0;
}

int pin(const Common& common, std::uint32_t body, const std::vector<std::uint32_t>& pins,
        const std::vector<std::uint32_t>& unpins) {
  Client client;
  connect(client, common);
  client.pin_particles(body, pins, unpins);
  std::printf("body %u: %zu pinned, %zu freed\n", body, pins.size(), unpins.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"felt - command-line client of the Felt simulation service"};
  app.require_subcommand(1);
  Common common;
  if (const char* token = std::getenv("FELT_TOKEN")) common.token = token;
  app.add_option("--server", common.server, "feltd address HOST:PORT")->capture_default_str();
  app.add_option("--token", common.token, "Token the server requires (default: $FELT_TOKEN)");

  app.add_subcommand("hello", "Connect, say hello and print what the server reports");

  int frames = 10;
  std::string out_dir = "frames";
  double rate = 0;
  bool normals = false;
  CLI::App* watch_cmd =
      app.add_subcommand("watch", "Save streamed frames as OBJ files, one per frame");
  watch_cmd->add_option("--frames", frames, "How many frames")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  watch_cmd->add_option("--out", out_dir, "Directory for the OBJ files")->capture_default_str();
  watch_cmd->add_option("--rate", rate, "Frames per second to ask for (0: the server's default)");
  watch_cmd->add_flag("--normals", normals, "Ask for vertex normals too");
  watch_cmd->add_option("--scene", common.scene, "Load this scene (by name) first");

  std::vector<double> at;
  std::uint32_t proxy = 0;
  CLI::App* touch_cmd =
      app.add_subcommand("touch", "Put a haptic proxy at a point and print the force");
  touch_cmd->add_option("--at", at, "Proxy position X,Y,Z in metres")
      ->required()
      ->delimiter(',')
      ->expected(3);
  touch_cmd->add_option("--proxy", proxy, "Proxy id")->capture_default_str();
  touch_cmd->add_option("--scene", common.scene, "Load this scene (by name) first");

  v1::SetBodyParameters parameters;
  std::uint32_t body = 0;
  std::string integrator;
  double drag = 0, structural = 0, shear = 0, bend = 0, max_strain = 0;
  CLI::App* set_cmd = app.add_subcommand("set", "Change a body's integrator or parameters");
  set_cmd->add_option("--body", body, "Body id")->capture_default_str();
  auto* integrator_opt = set_cmd->add_option("--integrator", integrator, "Integrator name");
  auto* drag_opt = set_cmd->add_option("--drag", drag, "Viscous drag, N s/m");
  auto* structural_opt =
      set_cmd->add_option("--structural", structural, "Structural stiffness, N/m");
  auto* shear_opt = set_cmd->add_option("--shear", shear, "Shear stiffness, N/m");
  auto* bend_opt = set_cmd->add_option("--bend", bend, "Bend stiffness, N/m");
  auto* strain_opt =
      set_cmd->add_option("--max-strain", max_strain, "Stretch limit (0 switches it off)");
  set_cmd->add_option("--scene", common.scene, "Load this scene (by name) first");

  std::vector<std::uint32_t> pins, unpins;
  CLI::App* pin_cmd = app.add_subcommand("pin", "Pin particles where they are, or free them");
  pin_cmd->add_option("--body", body, "Body id")->capture_default_str();
  pin_cmd->add_option("--pin", pins, "Particles to pin, e.g. 0,19")->delimiter(',');
  pin_cmd->add_option("--unpin", unpins, "Particles to free")->delimiter(',');

  CLI11_PARSE(app, argc, argv);
  try {
    if (app.got_subcommand("hello")) return hello(common);
    if (watch_cmd->parsed()) return watch(common, frames, out_dir, rate, normals);
    if (set_cmd->parsed()) {
      parameters.set_body_id(body);
      if (*integrator_opt) parameters.set_integrator(integrator);
      if (*drag_opt) parameters.set_drag(drag);
      if (*structural_opt) parameters.set_structural_stiffness(structural);
      if (*shear_opt) parameters.set_shear_stiffness(shear);
      if (*bend_opt) parameters.set_bend_stiffness(bend);
      if (*strain_opt) parameters.set_max_strain(max_strain);
      return set(common, parameters);
    }
    if (pin_cmd->parsed()) return pin(common, body, pins, unpins);
    return touch(common, at, proxy);
  } catch (const felt::client::ClientError& e) {
    std::cerr << "felt: " << e.what() << "\n";
    return 1;
  }
}
