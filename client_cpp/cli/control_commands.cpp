// felt pause, resume, step, reset, save, restore, destroy: the scene control requests of
// docs/protocol.md sections 4.3 to 4.5, one connection each.

#include <cstdio>
#include <fstream>
#include <sstream>

#include <google/protobuf/util/json_util.h>

#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/progress.hpp"

namespace felt::cli {

namespace v1 = felt::v1;

namespace {

int print_status(const v1::SceneStatus& status) {
  std::printf("scene %llu: step %llu, t %.3f s, %s, time scale %g\n",
              static_cast<unsigned long long>(status.scene_id()),
              static_cast<unsigned long long>(status.step()), status.sim_time(),
              status.paused() ? "paused" : "running", status.time_scale());
  return 0;
}

}  // namespace

int pause(const Common& common) {
  client::Client client;
  connect(client, common);
  return print_status(client.pause());
}

int resume(const Common& common) {
  client::Client client;
  connect(client, common);
  return print_status(client.resume());
}

int step(const Common& common, std::uint32_t steps) {
  client::Client client;
  connect(client, common);
  v1::SceneStatus status;
  {
    Spinner waiting("stepping");
    status = client.step(steps);
  }
  return print_status(status);
}

int reset(const Common& common) {
  client::Client client;
  connect(client, common);
  v1::SceneStatus status;
  {
    Spinner waiting("resetting");  // the scene is built again from its source
    status = client.reset();
  }
  return print_status(status);
}

int save(const Common& common, const std::string& file) {
  client::Client client;
  connect(client, common);
  const v1::StateSaved saved = client.save_state(true);
  // protobuf's JSON mapping: readable, and its doubles read back exactly
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.preserve_proto_field_names = true;
  std::string json;
  if (const auto status = google::protobuf::util::MessageToJsonString(saved.data(), &json, options);
      !status.ok()) {
    throw LocalError("cannot write the state as JSON: " + status.ToString());
  }
  std::ofstream out(file);
  out << json;
  if (!out.flush()) throw LocalError("cannot write " + file);
  std::printf("state %u saved to %s: step %llu, t %.3f s, %d bodies\n", saved.state_id(),
              file.c_str(), static_cast<unsigned long long>(saved.step()), saved.sim_time(),
              saved.data().bodies_size());
  return 0;
}

int restore(const Common& common, const std::string& file) {
  std::ifstream in(file);
  if (!in) throw UsageError("cannot read " + file);
  std::ostringstream text;
  text << in.rdbuf();
  v1::SceneState state;
  if (const auto status = google::protobuf::util::JsonStringToMessage(text.str(), &state);
      !status.ok()) {
    throw UsageError(file + " is no state 'felt save' wrote: " + std::string(status.message()));
  }
  client::Client client;
  connect(client, common);
  return print_status(client.restore_state(state));
}

int destroy(const Common& common, std::uint64_t scene) {
  client::Client client;
  connect(client, common);
  std::printf("scene %llu destroyed\n",
              static_cast<unsigned long long>(client.destroy_scene(scene).scene_id()));
  return 0;
}

}  // namespace felt::cli
