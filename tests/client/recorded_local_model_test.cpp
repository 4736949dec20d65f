// A local model's pass-through, recorded (issue 26): what a LocalRenderer was given by a real
// run that went through the curtain (tests/client/data/local_model_crossing.json), replayed. The
// device comes up to the curtain of the default scene from the front and stays in front of it:
// every model puts the curtain 3 to 6 cm behind the device. After 16 ms without a model (the
// server's physics thread stalled) the first model's vertices, crumpling at up to 2 m/s with
// opposite signs, had been moved on to a surface that touched the device; the next model put
// the curtain back where it was, and the proxy, carried with a triangle that had turned by 90°
// in one tick, came out on the curtain's far side, pulling the device into it at 7 N.

#include <algorithm>
#include <fstream>
#include <optional>
#include <string>

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

TEST(RecordedLocalModel, TheProxyStaysOnTheCurtainsSideOfTheDeviceWhenAModelCorrectsAFarGuess) {
  std::ifstream file(LOCAL_MODEL_CROSSING);
  ASSERT_TRUE(file) << LOCAL_MODEL_CROSSING;
  const nlohmann::json recording = nlohmann::json::parse(file);
  LocalRenderer renderer(from_json<v1::ProxySettings>(recording["settings"]),
                         {recording["device_damping"], recording["servo_period"]});
  int ticks = 0;
  int models = 0;
  int touching = 0;
  double largest_push = 0;
  for (const nlohmann::json& event : recording["events"]) {
    if (event.contains("model")) {
      const std::optional<LocalModel> model =
          local_model_from(from_json<v1::LocalModel>(event["model"]));
      ASSERT_TRUE(model);
      renderer.take(*model, event["shows"], event["round_trip"]);
      ++models;
      continue;
    }
    const Vec3 device(event["device"][0], event["device"][1], event["device"][2]);
    const LocalForce felt = renderer.tick(device, event["time"]);
    ++ticks;
    // the curtain's normals are within 30° of +z here: a push out of its front has a positive z
    EXPECT_GE(felt.contact.force.z(), 0)
        << "tick " << ticks << " of the recording, " << models << " models in";
    touching += felt.contact.in_contact ? 1 : 0;
    largest_push = std::max(largest_push, felt.contact.force.z());
  }
  EXPECT_EQ(models, 2);
  EXPECT_EQ(ticks, 19);
  // the guessed surface was touched, firmly: the replay renders real contact
  EXPECT_GE(touching, 8);
  EXPECT_GT(largest_push, 3.0);
}

}  // namespace
}  // namespace felt::client
