// A local model's pass-throughs, recorded (issue 26): what a LocalRenderer was given by real
// runs that went through the curtain of the default scene (tests/client/data/), replayed.
//
// local_model_crossing.json: the device comes up to the curtain from the front and stays in
// front of it: every model puts the curtain 3 to 6 cm behind the device. After 16 ms without a
// model (the server's physics thread stalled) the first model's vertices, crumpling at up to
// 2 m/s with opposite signs, had been moved on to a surface that touched the device; the next
// model put the curtain back where it was, and the proxy, carried with a triangle that had turned
// by 90° in one tick, came out on the curtain's far side, pulling the device into it at 7 N.
//
// local_model_swing.json: over a 50 ms round trip, the device 3 cm behind the curtain's rest is
// free: the curtain has swung 9-12 cm back. A model with nothing near comes, then one with the
// curtain swinging forward at 5 m/s: moved on by 28 ms its new triangles appeared in front of the
// proxy, which had not seen them pass, and pulled the device in at 2.3 N.

#include <algorithm>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "local_renderer.hpp"

namespace felt::client {
namespace {

template <class Message>
Message from_json(const nlohmann::json& json) {
  Message message;
  const auto status = google::protobuf::util::JsonStringToMessage(json.dump(), &message);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return message;
}

/// What a recording's renderer did at its ticks.
struct Replayed {
  int models = 0;
  std::vector<LocalForce> ticks;
};

Replayed replay(const char* path) {
  std::ifstream file(path);
  EXPECT_TRUE(file) << path;
  const nlohmann::json recording = nlohmann::json::parse(file);
  LocalRenderer renderer(from_json<v1::ProxySettings>(recording["settings"]),
                         {recording["device_damping"], recording["servo_period"]});
  Replayed out;
  for (const nlohmann::json& event : recording["events"]) {
    if (event.contains("model")) {
      const std::optional<LocalModel> model =
          local_model_from(from_json<v1::LocalModel>(event["model"]));
      EXPECT_TRUE(model);
      if (model) renderer.take(*model, event["shows"], event["round_trip"]);
      ++out.models;
      continue;
    }
    const Vec3 device(event["device"][0], event["device"][1], event["device"][2]);
    out.ticks.push_back(renderer.tick(device, event["time"]));
  }
  return out;
}

/// Checks that no tick of `replayed` pulls the device into the curtain (its normals are within
/// 30° of +z where these recordings touch it: a push out of its front has a positive z), that
/// `touching` ticks or more are in contact and the largest push is above `largest` N.
void expect_pushed_out_only(const Replayed& replayed, int touching, double largest) {
  int in_contact = 0;
  double largest_push = 0;
  for (std::size_t k = 0; k < replayed.ticks.size(); ++k) {
    const HapticContact& contact = replayed.ticks[k].contact;
    EXPECT_GE(contact.force.z(), 0) << "tick " << k << " of the recording";
    in_contact += contact.in_contact ? 1 : 0;
    largest_push = std::max(largest_push, contact.force.z());
  }
  // the replay renders real contact
  EXPECT_GE(in_contact, touching);
  EXPECT_GT(largest_push, largest);
}

TEST(RecordedLocalModel, TheProxyStaysOnTheCurtainsSideOfTheDeviceWhenAModelCorrectsAFarGuess) {
  const Replayed replayed = replay(LOCAL_MODEL_CROSSING);
  EXPECT_EQ(replayed.models, 2);
  EXPECT_EQ(replayed.ticks.size(), 19u);
  expect_pushed_out_only(replayed, 8, 3.0);
}

TEST(RecordedLocalModel, ACurtainSwingingInToAFreeProxyCarriesItAlong) {
  const Replayed replayed = replay(LOCAL_MODEL_SWING);
  EXPECT_EQ(replayed.models, 5);
  EXPECT_EQ(replayed.ticks.size(), 19u);
  expect_pushed_out_only(replayed, 5, 1.5);
}

}  // namespace
}  // namespace felt::client
