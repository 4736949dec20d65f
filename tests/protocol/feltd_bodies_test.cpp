// End to end: bodies added and removed at run time, pushed, pinned; per-proxy settings; frame
// encodings and subscriptions.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <thread>

#include "feltd_fixture.hpp"
#include "frame_assembler.hpp"

namespace felt::test {
namespace {

/// The next frame whose step is at least `step` (frames the client buffered before it are
/// skipped).
std::optional<v1::Frame> frame_from(Client& client, std::uint64_t step) {
  for (int i = 0; i < 200; ++i) {
    auto frame = client.next_frame(scaled(5s));
    if (!frame || frame->step() >= step) return frame;
  }
  return std::nullopt;
}

// A solid's integrator is chosen in its JSON and changed while it runs, among those that apply
// to its model; the others are refused with the reason.
TEST_F(FeltdTest, ASolidsIntegratorIsChosenAndChangedAmongThoseThatApply) {
  auto client = greeted("integrators");
  client->create_scene({});
  const v1::BodyInfo springs = client
                                   ->add_body(R"({"type": "solid", "integrator": "kang",
      "lattice": {"cells": [2, 2, 2], "size": [0.2, 0.2, 0.2]}})")
                                   .body();
  v1::SetBodyParameters set;
  set.set_body_id(springs.body_id());
  for (const char* name : {"rk4", "time_corrected_verlet", "imex"}) {
    set.set_integrator(name);
    EXPECT_EQ(client->set_body_parameters(set).body_id(), springs.body_id()) << name;
  }
  set.set_integrator("implicit_euler");
  try {
    client->set_body_parameters(set);
    ADD_FAILURE() << "implicit Euler was set on a solid";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), v1::ERROR_CODE_BAD_REQUEST);
    EXPECT_NE(std::string(e.what()).find("needs a force Jacobian"), std::string::npos) << e.what();
  }
  const v1::BodyInfo matching = client
                                    ->add_body(R"({"type": "solid", "model": "shape_matching",
      "lattice": {"cells": [2, 2, 2], "size": [0.2, 0.2, 0.2]}})")
                                    .body();
  set.set_body_id(matching.body_id());
  set.set_integrator("rk4");
  expect_error([&] { client->set_body_parameters(set); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error(
      [&] {
        client->add_body(R"({"type": "solid", "model": "corotated_fem", "integrator": "desbrun",
            "lattice": {"cells": [2, 2, 2], "size": [0.2, 0.2, 0.2]}})");
      },
      v1::ERROR_CODE_BAD_SCENE);
  // the scene steps on (its first step may still be coming)
  const auto deadline = std::chrono::steady_clock::now() + scaled(5s);
  while (client->stats().scene().steps() == 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_GT(client->stats().scene().steps(), 0u);
}

TEST_F(FeltdTest, ClothsSolidsAndCollidersComeAndGo) {
  auto client = greeted("builder");
  client->create_scene({});
  const v1::BodyInfo cloth = client->add_body(small_cloth_json(0)).body();
  EXPECT_EQ(cloth.kind(), "cloth");
  EXPECT_EQ(cloth.particles(), 36u);
  EXPECT_EQ(cloth.triangles(), 50u);
  const v1::BodyInfo solid = client
                                 ->add_body(R"({"type": "solid", "lattice": {"cells": [2, 2, 2],
      "size": [0.2, 0.2, 0.2]}, "transform": {"translate": [1, 0.5, 0]}})")
                                 .body();
  EXPECT_EQ(solid.kind(), "solid");
  EXPECT_EQ(solid.nodes(), 27u);
  const v1::BodyInfo floor =
      client->add_collider(R"({"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]})").body();
  EXPECT_EQ(floor.kind(), "collider");
  client->subscribe_frames(60);
  auto frame = client->next_frame(scaled(5s));
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->bodies_size(), 2);  // colliders have nothing to stream
  // the solid falls onto the floor and rests on it instead of falling through: in 1.5 s of
  // the scene's clock (a sanitized or loaded server steps it slower than the wall's)
  ASSERT_TRUE(eventually([&] { return client->stats().scene().sim_time() >= 1.5; }, 20s));
  frame = frame_from(*client, client->stats().scene().steps());
  ASSERT_TRUE(frame);
  double lowest = 1e9;
  const auto& y = frame->bodies(1).positions();
  for (int i = 1; i < y.size(); i += 3) lowest = std::min<double>(lowest, y[i]);
  EXPECT_GT(lowest, -0.02);
  EXPECT_LT(lowest, 0.1);
  EXPECT_EQ(client->remove_body(floor.body_id()).body_id(), floor.body_id());
  expect_error([&] { client->remove_body(floor.body_id()); }, v1::ERROR_CODE_UNKNOWN_ID);
  client->remove_body(cloth.body_id());
  frame = frame_from(*client, client->stats().scene().steps() + 1);
  ASSERT_TRUE(frame);
  ASSERT_EQ(frame->bodies_size(), 1);
  EXPECT_EQ(frame->bodies(0).body_id(), solid.body_id());
}

TEST_F(FeltdTest, BadBodiesAreRefusedWithTheirJsonPath) {
  auto client = greeted("careless");
  try {
    client->add_body(R"({"type": "cloth", "grid": {"nx": 1}})");
    ADD_FAILURE() << "a 1-particle-wide grid was accepted";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), v1::ERROR_CODE_BAD_SCENE);
    EXPECT_NE(std::string(e.what()).find("body.grid.nx"), std::string::npos) << e.what();
  }
  expect_error([&] { client->add_body("{not json"); }, v1::ERROR_CODE_BAD_SCENE);
  expect_error([&] { client->add_body(R"({"type": "jelly"})"); }, v1::ERROR_CODE_BAD_SCENE);
  expect_error([&] { client->add_collider(R"({"type": "sphere", "radius": -1})"); },
               v1::ERROR_CODE_BAD_SCENE);
  expect_error(
      [&] { client->add_body(R"({"type": "cloth", "mesh": {"file": "../../etc/passwd"}})"); },
      v1::ERROR_CODE_BAD_SCENE);
  v1::ClientMessage empty_add;
  empty_add.mutable_add_body();
  expect_error([&] { client->request(empty_add); }, v1::ERROR_CODE_BAD_REQUEST);
  // more particles than a client's scene may have
  expect_error([&] { client->add_body(R"({"type": "cloth", "grid": {"nx": 600, "ny": 600}})"); },
               v1::ERROR_CODE_LIMIT_EXCEEDED, "--max-particles");
  EXPECT_EQ(client->stats().scene().bodies(), 1u);  // nothing was added
}

TEST_F(FeltdTest, ABodyAddedAtRunTimeIsCheckedAgainstItsScenesHealthSettings) {
  // a cloth whose stable step under symplectic Euler is about 0.1 ms: some 100 substeps of a
  // 10 ms step, which the default budget of 1000 affords and a budget of 10 does not. It was
  // checked against the default settings, whatever its scene said
  const std::string stiff = R"({"type": "cloth", "grid": {"nx": 6, "ny": 6},
      "integrator": "symplectic_euler", "springs": {"structural": {"stiffness": 1e6}}})";
  auto client = greeted("adder");
  client->load_scene_json(R"({"time_step": 0.01, "health": {"step_budget": 10}, "bodies": []})");
  expect_error([&] { client->add_body(stiff); }, v1::ERROR_CODE_BAD_SCENE,
               "beyond the step budget of 10 (health.step_budget)");
  EXPECT_EQ(client->stats().scene().bodies(), 0u);
  client->load_scene_json(R"({"time_step": 0.01, "bodies": []})");
  EXPECT_EQ(client->add_body(stiff).body().kind(), "cloth");
}

TEST_F(FeltdTest, AForcePushesTheClothForItsDuration) {
  auto client = greeted("pusher");
  client->load_scene_by_name("default");
  client->pause();
  client->subscribe_frames(0);
  const auto before = frame_from(*client, 0);
  ASSERT_TRUE(before);
  // the curtain's bottom edge, pushed along +z for 0.2 s
  std::vector<std::uint32_t> bottom;
  for (std::uint32_t v = 0; v < 20; ++v) bottom.push_back(v);
  client->apply_force(0, bottom, {0, 0, 0.05}, 0.2);
  const v1::SceneStatus after = client->step(200);
  const auto pushed = frame_from(*client, after.step());
  ASSERT_TRUE(pushed);
  EXPECT_GT(vertex(pushed->bodies(0), 10)[2], vertex(before->bodies(0), 10)[2] + 0.01);
  expect_error([&] { client->apply_force(0, {400}, {0, 0, 1}, 0); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client->apply_force(0, {}, {0, 0, 1}, 0); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client->apply_force(0, {1}, {0, NAN, 1}, 0); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client->apply_force(0, {1}, {0, 1e30, 1}, 0); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client->apply_force(0, {1}, {0, 0, 1}, -1); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client->apply_force(9, {1}, {0, 0, 1}, 0); }, v1::ERROR_CODE_UNKNOWN_ID);
}

// Requests pipelined behind a body the loader builds wait for it; a change checked meanwhile
// against a body that a request before it removes is answered only once it is due: UNKNOWN_ID.
TEST_F(FeltdTest, AChangeToABodyRemovedBeforeItsTurnIsAnUnknownId) {
  auto client = greeted("racer");
  client->create_scene({});
  client->pause();
  const std::uint32_t cloth = client->add_body(small_cloth_json()).body().body_id();
  v1::ClientMessage message;
  message.mutable_add_body()->set_body_json(R"({"type": "cloth", "grid": {"nx": 400, "ny": 400}})");
  const std::uint64_t big = client->send(message);
  message.mutable_remove_body()->set_body_id(cloth);
  const std::uint64_t remove = client->send(message);
  message.mutable_set_body_parameters()->set_body_id(cloth);
  message.mutable_set_body_parameters()->set_drag(0.5);
  const std::uint64_t set = client->send(message);
  message.mutable_pin_particles()->set_body_id(cloth);
  message.mutable_pin_particles()->add_pin(0);
  const std::uint64_t pin = client->send(message);
  std::map<std::uint64_t, v1::ServerMessage> replies;
  while (replies.size() < 4) {
    const auto reply = client->receive(scaled(30s));
    ASSERT_TRUE(reply);
    if (reply->request_id() != 0) replies[reply->request_id()] = *reply;
  }
  EXPECT_TRUE(replies[big].has_body_added());
  EXPECT_EQ(replies[remove].body_removed().body_id(), cloth);
  for (const std::uint64_t id : {set, pin}) {
    EXPECT_EQ(replies[id].error().code(), v1::ERROR_CODE_UNKNOWN_ID) << id;
    EXPECT_EQ(replies[id].error().request_id(), id);
  }
}

/// The largest strain of a 6 x 6 grid's vertical structural springs (rest length 0.1 m) and its
/// lowest vertex's height.
struct Hang {
  double max_strain = 0;
  double lowest = 1e9;
};

Hang hang_of(const v1::BodyFrame& body) {
  Hang hang;
  for (int v = 0; v < 36; ++v) {
    const auto p = vertex(body, v);
    hang.lowest = std::min(hang.lowest, p[1]);
    if (v + 6 < 36) {
      const auto q = vertex(body, v + 6);
      const double length = std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);  // float32 positions
      hang.max_strain = std::max(hang.max_strain, length / 0.1 - 1);
    }
  }
  return hang;
}

// Three stiff cloths hang side by side from their top rows; two are made softer, one of those
// with a stretch limit. Stepped on a paused scene, so the physics alone decides.
TEST_F(FeltdTest, BodyParametersChangeHowAClothHangs) {
  auto client = greeted("tailor");
  std::string bodies;
  for (const char* x : {"-1", "0", "1"}) {
    if (!bodies.empty()) bodies += ", ";
    bodies += R"({"type": "cloth", "grid": {"nx": 6, "ny": 6, "width": 0.5, "height": 0.5,
        "center": [)" +
              std::string(x) + R"(, 1.5, 0]}, "mass": 0.5, "drag": 0.5,
        "springs": {"structural": {"stiffness": 2000, "damping": 1},
                    "shear": {"stiffness": 2}, "bend": {"stiffness": 0.2}},
        "integrator": "implicit_euler", "pin": "top_row"})";
  }
  client->load_scene_json(R"({"time_step": 0.01, "bodies": [)" + bodies + "]}");
  client->pause();
  v1::SetBodyParameters soft;
  soft.set_body_id(1);
  soft.set_structural_stiffness(20);
  EXPECT_EQ(client->set_body_parameters(soft).body_id(), 1u);
  soft.set_body_id(2);
  soft.set_max_strain(0.05);
  EXPECT_EQ(client->set_body_parameters(soft).body_id(), 2u);
  const v1::SceneStatus settled = client->step(1000);  // 10 s
  client->subscribe_frames(0);
  const auto frame = frame_from(*client, settled.step());
  ASSERT_TRUE(frame);
  ASSERT_EQ(frame->step(), settled.step());
  const Hang stiff = hang_of(frame->bodies(0));
  const Hang softer = hang_of(frame->bodies(1));
  const Hang limited = hang_of(frame->bodies(2));
  // 2000 N/m barely stretches under the cloth's weight (0.3 %); at 20 N/m the top springs
  // stretch by 31 % and the cloth hangs 9 cm lower
  EXPECT_LT(stiff.max_strain, 0.01);
  EXPECT_GT(softer.max_strain, 0.2);
  EXPECT_LT(softer.lowest, stiff.lowest - 0.05);
  // the stretch limit holds every spring to 5 %, within 1 % of it
  EXPECT_LE(limited.max_strain, 0.05 * 1.01);
  EXPECT_GT(limited.lowest, softer.lowest + 0.03);
}

TEST_F(FeltdTest, AProxyOpensWithItsOwnSettings) {
  auto client = greeted("toucher");
  client->load_scene_by_name("default");
  client->pause();  // a still curtain: the force is exactly k times the depth
  v1::ProxySettings settings;
  settings.set_stiffness(1000);
  settings.set_max_force(50);
  settings.set_radius(0.03);
  const v1::ProxyOpened opened = client->open_proxy(settings);
  EXPECT_NE(opened.proxy_id(), 0u);
  EXPECT_DOUBLE_EQ(opened.settings().stiffness(), 1000);
  EXPECT_DOUBLE_EQ(opened.settings().damping(), 0);  // the scene's, as it was not given
  // the curtain hangs in z = 0: a sphere of 3 cm whose device is 1 cm in front is 2 cm deep
  const v1::ForceUpdate force = client->proxy_update(opened.proxy_id(), {0, 1.2, 0.01});
  ASSERT_TRUE(force.in_contact());
  EXPECT_NEAR(force.force().z(), 1000 * 0.02, 0.05);
  // the scene's default proxy is softer: 400 N/m and 2 cm
  EXPECT_NEAR(client->proxy_update(0, {0.3, 1.2, 0.01}).force().z(), 400 * 0.01, 0.02);
  EXPECT_EQ(client->close_proxy(opened.proxy_id()).proxy_id(), opened.proxy_id());
  expect_error([&] { client->close_proxy(opened.proxy_id()); }, v1::ERROR_CODE_UNKNOWN_ID);
  for (auto bad : {&v1::ProxySettings::set_radius, &v1::ProxySettings::set_stiffness,
                   &v1::ProxySettings::set_max_force, &v1::ProxySettings::set_damping}) {
    for (double value : {-1.0, std::nan(""), 1e12}) {
      v1::ProxySettings wrong;
      (wrong.*bad)(value);
      expect_error([&] { client->open_proxy(wrong); }, v1::ERROR_CODE_BAD_REQUEST);
    }
  }
  v1::ProxySettings slippery;
  slippery.set_static_friction(0.1);
  slippery.set_dynamic_friction(0.5);
  expect_error([&] { client->open_proxy(slippery); }, v1::ERROR_CODE_BAD_REQUEST);
}

TEST_F(FeltdTest, QuantizedDeltaFramesShowWhatFloatFramesShow) {
  auto floats = greeted("floats");
  const std::uint64_t scene = floats->load_scene_by_name("default").scene_id();
  auto deltas = greeted("deltas");
  deltas->join_scene(scene);
  floats->pause();
  floats->subscribe_frames(0);
  client::FrameSubscription subscription;
  subscription.quantized = true;
  subscription.deltas = true;
  subscription.normals = true;
  const v1::Subscribed granted = deltas->subscribe_frames(subscription);
  EXPECT_EQ(granted.encoding(), v1::FRAME_ENCODING_QUANTIZED16);
  EXPECT_TRUE(granted.deltas());
  client::FrameAssembler assembler;
  std::uint64_t step = floats->stats().scene().steps();
  std::size_t float_bytes = 0, delta_bytes = 0;
  bool any_delta = false;
  for (int round = 0; round < 10; ++round) {
    const auto f = frame_from(*floats, step);
    const auto d = frame_from(*deltas, step);
    ASSERT_TRUE(f && d);
    ASSERT_EQ(f->step(), d->step());
    const auto decoded = assembler.assemble(*d);
    ASSERT_TRUE(decoded) << decoded.error();
    deltas->ack_frame_async(d->sequence());
    any_delta |= d->base_sequence() != 0;
    if (round > 0) {  // after the frames that carry triangles
      float_bytes += f->ByteSizeLong();
      delta_bytes += d->ByteSizeLong() - d->bodies(0).quantized_normals().ByteSizeLong();
    }
    for (int i = 0; i < f->bodies(0).positions_size(); ++i) {
      ASSERT_NEAR(decoded->bodies[0].positions[i], f->bodies(0).positions(i), 3e-5);
    }
    step = floats->step(20).step();
  }
  EXPECT_TRUE(any_delta);
  EXPECT_LT(delta_bytes, 0.4 * float_bytes);
  expect_error([&] { deltas->ack_frame(100000); }, v1::ERROR_CODE_BAD_REQUEST);
}

// Issue 32: a body's own time step, chosen while it runs: the cloth takes the substeps its
// max_step asks for and GetStats tells both; 0 gives the scene's step back; a step outside
// [1e-6, 1] s is refused with the range, and the body keeps what it had.
TEST_F(FeltdTest, ABodysOwnTimeStepIsChosenWhileItRuns) {
  auto client = greeted("stepper");
  v1::CreateScene create;
  create.set_time_step(0.002);
  client->create_scene(create);
  const v1::BodyInfo cloth = client->add_body(small_cloth_json(0)).body();
  // the statistics come per window of steps: wait for one that shows the change
  const auto stats_of_cloth = [&](double max_step, std::uint32_t substeps) {
    v1::BodyStats last;
    const auto deadline = std::chrono::steady_clock::now() + scaled(10s);
    while (std::chrono::steady_clock::now() < deadline) {
      const v1::Stats stats = client->stats();
      for (const v1::BodyStats& body : stats.scene().body_stats()) {
        if (body.body_id() == cloth.body_id()) last = body;
      }
      if (last.max_step() == max_step && last.substeps() == substeps) break;
      std::this_thread::sleep_for(20ms);
    }
    return last;
  };
  EXPECT_EQ(stats_of_cloth(0, 1).substeps(), 1u);  // its stable step is longer than 2 ms
  v1::SetBodyParameters set;
  set.set_body_id(cloth.body_id());
  set.set_max_step(0.0005);
  EXPECT_EQ(client->set_body_parameters(set).body_id(), cloth.body_id());
  v1::BodyStats stepped = stats_of_cloth(0.0005, 4);
  EXPECT_EQ(stepped.max_step(), 0.0005);
  EXPECT_EQ(stepped.substeps(), 4u);  // 2 ms in steps of at most 0.5 ms
  for (const double bad : {-1.0, 1e-7, 2.0, std::nan("")}) {
    set.set_max_step(bad);
    expect_error([&] { client->set_body_parameters(set); }, v1::ERROR_CODE_BAD_REQUEST,
                 "max_step must be a finite number in [1e-06, 1]");
  }
  EXPECT_EQ(stats_of_cloth(0.0005, 4).substeps(), 4u);
  set.set_max_step(0);
  client->set_body_parameters(set);
  const v1::BodyStats back = stats_of_cloth(0, 1);
  EXPECT_EQ(back.max_step(), 0);
  EXPECT_EQ(back.substeps(), 1u);
}

TEST_F(FeltdTest, SubscriptionsChooseBodiesAndEndOnUnsubscribe) {
  auto client = greeted("picky");
  client->add_body(small_cloth_json());
  client::FrameSubscription only_flag;
  only_flag.body_ids = {1};
  client->subscribe_frames(only_flag);
  const auto frame = client->next_frame(scaled(5s));
  ASSERT_TRUE(frame);
  ASSERT_EQ(frame->bodies_size(), 1);
  EXPECT_EQ(frame->bodies(0).name(), "flag");
  EXPECT_EQ(client->ack_frame(frame->sequence()).sequence(), frame->sequence());
  only_flag.body_ids = {42};
  expect_error([&] { client->subscribe_frames(only_flag); }, v1::ERROR_CODE_UNKNOWN_ID);
  v1::ClientMessage bad;
  bad.mutable_subscribe_frames()->set_deltas(true);
  expect_error([&] { client->request(bad); }, v1::ERROR_CODE_BAD_REQUEST);
  bad.mutable_subscribe_frames()->set_deltas(false);
  bad.mutable_subscribe_frames()->set_encoding(static_cast<v1::FrameEncoding>(7));
  expect_error([&] { client->request(bad); }, v1::ERROR_CODE_BAD_REQUEST);
  client->unsubscribe_frames();
  while (client->next_frame(100ms)) {
  }
  EXPECT_FALSE(client->next_frame(300ms));
  expect_error([&] { client->ack_frame(1); }, v1::ERROR_CODE_WRONG_STATE);
}

}  // namespace
}  // namespace felt::test
