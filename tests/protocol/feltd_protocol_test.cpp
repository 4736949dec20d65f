// End to end: the real feltd on port 0, driven through felt_client over loopback.

#include <signal.h>
#include <sys/socket.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

#include "feltd_fixture.hpp"
#include "wire/frame_codec.hpp"
#include "wire/message_codec.hpp"

namespace felt::test {
namespace {

TEST_F(FeltdTest, HelloReportsVersionCapabilitiesAndTheDefaultScene) {
  Client client;
  connect(client);
  const v1::Welcome welcome = client.hello("test");
  EXPECT_EQ(welcome.protocol_version(), 1u);
  EXPECT_FALSE(welcome.server_version().empty());
  EXPECT_NE(welcome.scene_id(), 0u);
  EXPECT_NE(
      std::find(welcome.capabilities().begin(), welcome.capabilities().end(), "haptics.proxy"),
      welcome.capabilities().end());
}

TEST_F(FeltdTest, RequestsBeforeHelloAndWrongVersionsAreRefused) {
  Client client;
  connect(client);
  try {
    client.subscribe_frames();
    FAIL() << "subscribe before hello succeeded";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), v1::ERROR_CODE_HELLO_REQUIRED);
  }
  v1::ClientMessage hello;
  hello.mutable_hello()->set_protocol_version(99);
  try {
    client.request(hello);
    FAIL() << "protocol 99 accepted";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), v1::ERROR_CODE_UNSUPPORTED_VERSION);
  }
  // the connection is still usable
  EXPECT_EQ(client.hello("test").protocol_version(), 1u);
}

TEST_F(FeltdTest, LoadedSceneStreamsFramesThatMove) {
  Client client;
  connect(client);
  client.hello("test");
  const v1::SceneLoaded loaded = client.load_scene_by_name("default");
  ASSERT_EQ(loaded.bodies_size(), 1);
  EXPECT_EQ(loaded.bodies(0).particles(), 400u);
  EXPECT_EQ(loaded.bodies(0).triangles(), 722u);
  const v1::Subscribed subscribed = client.subscribe_frames(30, true);
  EXPECT_EQ(subscribed.scene_id(), loaded.scene_id());

  const auto first = client.next_frame(scaled(5s));
  ASSERT_TRUE(first);
  ASSERT_EQ(first->bodies_size(), 1);
  EXPECT_EQ(first->scene_id(), loaded.scene_id());
  EXPECT_EQ(first->bodies(0).positions_size(), 3 * 400);
  EXPECT_EQ(first->bodies(0).normals_size(), 3 * 400);
  EXPECT_EQ(first->bodies(0).triangles_size(), 3 * 722);  // topology in the first frame only

  // the free bottom corner falls while the cloth sags
  std::optional<v1::Frame> later;
  for (int i = 0; i < 10; ++i) later = client.next_frame(scaled(5s));
  ASSERT_TRUE(later);
  EXPECT_GT(later->step(), first->step());
  EXPECT_EQ(later->bodies(0).triangles_size(), 0);
  EXPECT_LT(vertex(later->bodies(0), 399)[1], vertex(first->bodies(0), 399)[1]);
  for (float x : later->bodies(0).positions()) ASSERT_TRUE(std::isfinite(x));
}

TEST_F(FeltdTest, ProxyPushedIntoTheClothIsPushedBackOut) {
  Client client;
  connect(client);
  client.hello("test");
  client.subscribe_frames(60, true);
  const auto frame = client.next_frame(scaled(5s));
  ASSERT_TRUE(frame);
  // put the proxy (radius 2 cm in the default scene) 1 cm in front of a middle vertex
  const v1::BodyFrame& body = frame->bodies(0);
  const int middle = 10 * 20 + 10;
  const auto p = vertex(body, middle);
  const std::array<double, 3> n = {body.normals(3 * middle), body.normals(3 * middle + 1),
                                   body.normals(3 * middle + 2)};
  const std::array<double, 3> at = {p[0] + 0.01 * n[0], p[1] + 0.01 * n[1], p[2] + 0.01 * n[2]};
  const v1::ForceUpdate force = client.proxy_update(0, at);
  ASSERT_TRUE(force.in_contact());
  const double along_normal =
      force.force().x() * n[0] + force.force().y() * n[1] + force.force().z() * n[2];
  EXPECT_GT(along_normal, 0.5 * 400 * 0.01);  // k · depth, depth ≈ 1 cm
  EXPECT_GE(force.triangle(), 0);
  EXPECT_GT(force.server_send_ns(), 0u);

  // far from the cloth: no force
  const v1::ForceUpdate free = client.proxy_update(0, {5, 5, 5});
  EXPECT_FALSE(free.in_contact());
  EXPECT_EQ(free.force().x(), 0);
  EXPECT_EQ(free.force().y(), 0);
  EXPECT_EQ(free.force().z(), 0);
}

TEST_F(FeltdTest, AForceUpdateEchoesTheClientsTimeAndStampsTheServers) {
  auto device = greeted("device");
  v1::ClientMessage message;
  v1::ProxyUpdate& update = *message.mutable_proxy_update();
  update.set_proxy_id(3);
  update.mutable_position()->set_y(1.2);
  update.mutable_position()->set_z(0.01);
  update.set_client_time_us(0xfedcba9876543210ull);  // every one of the 64 bits
  const v1::ForceUpdate first = device->request(message).force_update();
  EXPECT_EQ(first.proxy_id(), 3u);
  EXPECT_EQ(first.client_time_us(), 0xfedcba9876543210ull);
  EXPECT_GT(first.server_receive_ns(), 0u);
  EXPECT_LE(first.server_receive_ns(), first.server_send_ns());
  update.set_client_time_us(1);
  const v1::ForceUpdate second = device->request(message).force_update();
  EXPECT_EQ(second.client_time_us(), 1u);
  EXPECT_GT(second.server_receive_ns(), first.server_send_ns());  // one steady clock
  EXPECT_LE(second.server_receive_ns(), second.server_send_ns());
}

using FeltdLiveClothTest = FeltdUnnicedTest;

TEST_F(FeltdLiveClothTest, AClientFeelsSlidesAlongAndGrabsAMovingCloth) {
  Client client;
  connect(client);
  client.hello("test");
  // a 1 m cloth held at its four corners, sagging and swaying under the finger
  client.load_scene_json(R"({ "time_step": 0.001, "gravity": [0, -9.81, 0],
    "haptics": { "proxy_radius": 0.02, "stiffness": 400, "max_force": 20 },
    "bodies": [ { "type": "cloth",
      "grid": { "nx": 20, "ny": 20, "center": [0, 1, 0], "plane": "xz" }, "mass": 0.5,
      "springs": { "structural": { "stiffness": 200, "damping": 0.05 },
                   "shear": { "stiffness": 50, "damping": 0.02 },
                   "bend": { "stiffness": 5, "damping": 0.005 } },
      "integrator": "symplectic_euler", "pin": "four_corners" } ] })");
  client.subscribe_frames(60, false);
  // one update a millisecond, as a device's servo loop sends them
  using Point = std::array<double, 3>;
  const auto move = [&](Point from, Point to, int updates, std::uint32_t buttons) {
    v1::ForceUpdate last;
    for (int i = 1; i <= updates; ++i) {
      const double s = static_cast<double>(i) / updates;
      last = client.proxy_update(0,
                                 {from[0] + s * (to[0] - from[0]), from[1] + s * (to[1] - from[1]),
                                  from[2] + s * (to[2] - from[2])},
                                 buttons);
      std::this_thread::sleep_for(1ms);
    }
    return last;
  };
  // press down into the sag: held on top of the cloth, pushed back up
  v1::ForceUpdate force = move({0, 1.2, 0}, {0, 0.55, 0}, 300, 0);
  // the light cloth bounces off a finger that hits it at 2 m/s (contact comes and goes for tens
  // of milliseconds of scene time): hold still until 200 updates in a row touch and the sheet
  // has sunk onto the finger. The physics thread keeps its own pace and falls behind on a
  // loaded machine, where the same updates see less of the scene's time.
  const auto settled = [&](Point at, int in_a_row, const auto& done) {
    int touching = 0;
    const auto deadline = std::chrono::steady_clock::now() + scaled(10s);
    do {
      force = move(at, at, 1, 0);
      touching = force.in_contact() ? touching + 1 : 0;
    } while ((touching < in_a_row || !done()) && std::chrono::steady_clock::now() < deadline);
  };
  settled({0, 0.55, 0}, 200, [&] { return force.proxy().y() < 0.6; });
  ASSERT_TRUE(force.in_contact()) << force.ShortDebugString();
  EXPECT_GT(force.force().y(), 1.0) << force.ShortDebugString();
  EXPECT_GT(force.proxy().y(), 0.55);
  // slide sideways, pressed in: the cloth never lets the proxy through (it is never pushed
  // down, its proxy never below the device). The sheet chatters against the finger, and more
  // when updates come late (a touch keeps pushing until the next one), so contact may come and
  // go on the way.
  for (int i = 1; i <= 200; ++i) {
    force = client.proxy_update(0, {0.2 * i / 200.0, 0.55, 0});
    ASSERT_GE(force.force().y(), 0) << "update " << i << ": " << force.ShortDebugString();
    ASSERT_GE(force.proxy().y(), 0.55) << "update " << i << ": " << force.ShortDebugString();
    std::this_thread::sleep_for(1ms);
  }
  // still on top where the slide ended, once the scene has caught up with the finger
  settled({0.2, 0.55, 0}, 20, [&] { return force.contact_point().x() > 0.1; });
  ASSERT_TRUE(force.in_contact()) << force.ShortDebugString();
  EXPECT_GT(force.force().y(), 0) << force.ShortDebugString();
  EXPECT_GT(force.contact_point().x(), 0.1);  // it slid along
  // grab where it touches, as a device's button held down does (the contact that came and
  // went on the way may be gone at the press), and lift the cloth
  for (int i = 0; i < 1000 && !force.grabbing(); ++i)
    force = move({0.2, 0.55, 0}, {0.2, 0.55, 0}, 1, 1);
  ASSERT_TRUE(force.grabbing()) << force.ShortDebugString();
  const std::uint32_t held = force.grabbed_vertex();
  force = move({0.2, 0.55, 0}, {0.2, 1.1, 0}, 300, 1);
  ASSERT_TRUE(force.grabbing()) << force.ShortDebugString();
  EXPECT_EQ(force.grabbed_vertex(), held);
  EXPECT_GT(std::abs(force.force().y()), 0.1);  // the grab spring (batch tests check its value)
  // lifted out of the sag: the frames kept while the updates went out come first, so look
  // through them to the live ones
  double height = 0;
  const auto until = std::chrono::steady_clock::now() + scaled(5s);
  while (height <= 0.9 && std::chrono::steady_clock::now() < until) {
    const std::optional<v1::Frame> frame = client.next_frame(scaled(1s));
    if (frame) height = vertex(frame->bodies(0), static_cast<int>(held))[1];
  }
  EXPECT_GT(height, 0.9);
  // let go
  EXPECT_FALSE(client.proxy_update(0, {0.2, 1.5, 0}, 0).grabbing());
}

// Issue 31: an update at 1e308 after a contact came back in contact with a NaN contact point, a
// proxy sent to DBL_MAX and back stayed there, in contact with zero force, and grabbing, then
// moving to 1e308 gave a NaN force while the scene's steps went unrecoverable until the
// release. Positions beyond ±1e6 m, as in scene files, are refused; the proxy and its grab
// carry on from where they were.
TEST_F(FeltdLiveClothTest, PositionsBeyondTheBoundAreRefusedAndTheProxyCarriesOn) {
  Client client;
  connect(client);
  client.hello("test");
  // a still curtain while the refusals come: the touch is the same before and after them (a
  // running one gives way under the push between them, by how much depends on the load)
  client.pause();
  using Point = std::array<double, 3>;
  const double huge = std::numeric_limits<double>::max();
  const std::vector<Point> beyond = {
      {1e308, 1.2, 0.01}, {huge, huge, huge}, {0, 1.2, -1e200}, {0, std::nextafter(1e6, 2e6), 0}};
  const Point touching = {0, 1.2, 0.01};  // 1 cm in front of the curtain, with a 2 cm proxy
  ASSERT_TRUE(client.proxy_update(0, touching).in_contact());
  for (const Point& far : beyond) {
    expect_error([&] { client.proxy_update(0, far); }, v1::ERROR_CODE_BAD_REQUEST,
                 "position must be three numbers within ±1e6 m");
  }
  const v1::ForceUpdate back = client.proxy_update(0, touching);
  ASSERT_TRUE(back.in_contact());
  EXPECT_GT(back.force().z(), 1);
  // the bound itself is a position: free space, and back in contact from there
  EXPECT_FALSE(client.proxy_update(0, {0, 0, 1e6}).in_contact());
  EXPECT_TRUE(client.proxy_update(0, touching).in_contact());

  client.resume();  // the grab below pulls the running curtain
  v1::ForceUpdate grab = client.proxy_update(0, touching, 1);
  ASSERT_TRUE(grab.grabbing());
  const std::uint32_t held = grab.grabbed_vertex();
  for (const Point& far : beyond) {
    expect_error([&] { client.proxy_update(0, far, 1); }, v1::ERROR_CODE_BAD_REQUEST);
  }
  for (int i = 0; i < 100; ++i) {  // a tenth of a second of steps, held 4 cm in front
    grab = client.proxy_update(0, {0, 1.2, 0.04}, 1);
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_TRUE(grab.grabbing());
  EXPECT_EQ(grab.grabbed_vertex(), held);
  for (const double f : {grab.force().x(), grab.force().y(), grab.force().z()}) {
    EXPECT_TRUE(std::isfinite(f));
  }
  EXPECT_LE(std::hypot(grab.force().x(), grab.force().y(), grab.force().z()),
            8 + 1e-9);  // the scene's max_force
  for (const v1::SceneEvent& event : client.take_events()) {
    EXPECT_NE(event.kind(), v1::EVENT_KIND_UNRECOVERABLE_STEP);
  }
  EXPECT_FALSE(client.proxy_update(0, touching, 0).grabbing());
}

TEST_F(FeltdTest, SoftSolidsStreamTheirFineSurfaceAndCanBeTouched) {
  Client client;
  connect(client);
  client.hello("test");
  const v1::SceneLoaded loaded = client.load_scene_by_name("thesis/three_cubes");
  // three cubes, then the floor: colliders take the ids after the bodies
  ASSERT_EQ(loaded.bodies_size(), 4);
  EXPECT_EQ(loaded.bodies(3).kind(), "collider");
  EXPECT_EQ(loaded.bodies(3).body_id(), 3u);
  for (const v1::BodyInfo& body : loaded.bodies()) {
    if (body.kind() == "collider") continue;
    EXPECT_EQ(body.kind(), "solid");
    EXPECT_EQ(body.particles(), 2402u);  // the fine 20 x 20 x 20 box surface (Table 7.1)
    EXPECT_EQ(body.triangles(), 4800u);
  }
  client.subscribe_frames(30, true);
  const auto first = client.next_frame(scaled(5s));
  ASSERT_TRUE(first);
  ASSERT_EQ(first->bodies_size(), 3);
  EXPECT_EQ(first->bodies(2).positions_size(), 3 * 2402);
  EXPECT_EQ(first->bodies(2).triangles_size(), 3 * 4800);

  // the top cube's highest fine vertex: press the proxy 1 cm into it from above
  const v1::BodyFrame& top = first->bodies(2);
  int highest = 0;
  for (int v = 1; v < 2402; ++v) {
    if (vertex(top, v)[1] > vertex(top, highest)[1]) highest = v;
  }
  auto at = vertex(top, highest);
  at[1] += 0.02 - 0.01;  // proxy radius 2 cm
  const v1::ForceUpdate force = client.proxy_update(0, at);
  ASSERT_TRUE(force.in_contact());
  EXPECT_GT(force.force().y(), 0);
  // and grab it: the cube is far too heavy to lift, so it pulls the device down
  EXPECT_TRUE(client.proxy_update(0, at, 1).grabbing());
  const v1::ForceUpdate grab = client.proxy_update(0, {at[0], at[1] + 0.05, at[2]}, 1);
  EXPECT_TRUE(grab.grabbing());
  EXPECT_EQ(grab.body_id(), 2u);
  EXPECT_LT(grab.force().y(), 0);
  // let go, and stay away for a few steps: a proxy that stops sending keeps pushing with the
  // mean of its last step's updates (protocol.md, the reaction)
  for (int i = 0; i < 20; ++i) {
    EXPECT_FALSE(client.proxy_update(0, {at[0], at[1] + 5, at[2]}, 0).grabbing());
    std::this_thread::sleep_for(1ms);
  }

  // the cubes fall and settle onto each other; their surfaces stay finite
  std::optional<v1::Frame> later;
  for (int i = 0; i < 10; ++i) later = client.next_frame(scaled(5s));
  ASSERT_TRUE(later);
  EXPECT_LT(vertex(later->bodies(2), highest)[1], vertex(top, highest)[1]);
  for (const auto& body : later->bodies()) {
    for (float x : body.positions()) ASSERT_TRUE(std::isfinite(x));
  }

  // cloth-only parameters name the body's kind; pins index a solid's lattice nodes
  v1::SetBodyParameters set;
  set.set_body_id(0);
  set.set_drag(0.1);
  expect_error([&] { client.set_body_parameters(set); }, v1::ERROR_CODE_BAD_REQUEST);
  set.clear_drag();
  set.set_friction(0.2);
  EXPECT_EQ(client.set_body_parameters(set).body_id(), 0u);
  EXPECT_EQ(client.pin_particles(0, {1}, {}).body_id(), 0u);
  expect_error([&] { client.pin_particles(0, {216}, {}); }, v1::ERROR_CODE_BAD_REQUEST);
}

TEST_F(FeltdTest, UnrecoverableStepsReachSubscribersAsEvents) {
  Client client;
  connect(client);
  client.hello("test");
  // explicit Euler cannot integrate springs this stiff at any substep the budget affords (with
  // automatic substeps the loader refuses the scene for it)
  const v1::SceneLoaded loaded = client.load_scene_json(R"({ "health": { "auto_substeps": false },
    "bodies": [{ "type": "cloth", "grid": { "nx": 6, "ny": 6 }, "integrator": "explicit_euler",
                 "springs": { "structural": { "stiffness": 1e8 } } }] })");
  client.subscribe_frames(30);
  std::vector<v1::SceneEvent> events;
  const auto deadline = std::chrono::steady_clock::now() + scaled(5s);
  while (events.empty() && std::chrono::steady_clock::now() < deadline) {
    ASSERT_TRUE(client.next_frame(scaled(5s)));
    events = client.take_events();
  }
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events[0].kind(), v1::EVENT_KIND_UNRECOVERABLE_STEP);
  EXPECT_EQ(events[0].scene_id(), loaded.scene_id());
  EXPECT_GE(events[0].count(), 1u);
  ASSERT_EQ(events[0].body_ids_size(), 1);
  EXPECT_EQ(events[0].body_ids(0), 0u);
}

TEST_F(FeltdTest, BadRequestsGetErrorsAndTheConnectionStaysUsable) {
  Client client;
  connect(client);
  client.hello("test");
  expect_error([&] { client.proxy_update(0, {NAN, 0, 0}); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client.proxy_update(0, {INFINITY, 0, 0}); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client.load_scene_by_name("../../etc/passwd"); }, v1::ERROR_CODE_NOT_FOUND);
  expect_error([&] { client.load_scene_by_name("no_such_scene"); }, v1::ERROR_CODE_NOT_FOUND);
  expect_error([&] { client.load_scene_json("{\"bodies\": 3}"); }, v1::ERROR_CODE_BAD_SCENE);
  expect_error([&] { client.load_scene_json("not json"); }, v1::ERROR_CODE_BAD_SCENE);
  expect_error([&] { client.subscribe_frames(-1); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client.subscribe_frames(1e-12); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client.load_scene_json(R"({"time_step": 1e400})"); },
               v1::ERROR_CODE_BAD_SCENE);
  v1::ClientMessage empty;
  expect_error([&] { client.request(empty); }, v1::ERROR_CODE_UNKNOWN_MESSAGE);
  for (std::uint32_t proxy = 0; proxy < 16; ++proxy) client.proxy_update(proxy, {5, 5, 5});
  expect_error([&] { client.proxy_update(16, {5, 5, 5}); }, v1::ERROR_CODE_LIMIT_EXCEEDED);
  EXPECT_FALSE(client.proxy_update(0, {5, 5, 5}).in_contact());
}

TEST_F(FeltdTest, GarbageClosesOnlyThatConnection) {
  Client good;
  connect(good);
  good.hello("good");

  Client bad;
  connect(bad);
  // a 5-byte frame ("garba": field 12 with wire type 7) that is not a ClientMessage
  bad.send_raw("\x05garbage-that-is-not-protobuf\xff\xff");
  const auto reply = bad.receive(scaled(5s));
  ASSERT_TRUE(reply);
  ASSERT_TRUE(reply->has_error());
  EXPECT_EQ(reply->error().code(), v1::ERROR_CODE_MALFORMED_FRAME);
  EXPECT_THROW(bad.receive(scaled(5s)), ClientError);  // then the server hangs up

  Client huge;
  connect(huge);
  std::string prefix;
  wire::append_varint(prefix, 1ull << 40);
  huge.send_raw(prefix);
  const auto too_large = huge.receive(scaled(5s));
  ASSERT_TRUE(too_large);
  EXPECT_EQ(too_large->error().code(), v1::ERROR_CODE_FRAME_TOO_LARGE);

  EXPECT_FALSE(good.proxy_update(0, {5, 5, 5}).in_contact());
  EXPECT_TRUE(server_->running());
}

TEST_F(FeltdTest, BodiesChangeIntegratorAndPinsAtRunTime) {
  Client client;
  connect(client);
  client.hello("test");
  client.load_scene_by_name("default");
  v1::SetBodyParameters set;
  set.set_body_id(0);
  set.set_integrator("implicit_euler");
  set.set_max_strain(0.1);
  EXPECT_EQ(client.set_body_parameters(set).body_id(), 0u);

  // pin the free bottom corner where it is: it stops moving
  client.pin_particles(0, {399}, {});
  client.subscribe_frames(60);
  std::optional<v1::Frame> first;
  for (int i = 0; i < 3; ++i) first = client.next_frame(scaled(5s));  // past the pin's step
  ASSERT_TRUE(first);
  std::optional<v1::Frame> later;
  for (int i = 0; i < 10; ++i) later = client.next_frame(scaled(5s));
  ASSERT_TRUE(later);
  EXPECT_GT(later->step(), first->step());
  EXPECT_EQ(vertex(later->bodies(0), 399), vertex(first->bodies(0), 399));
  EXPECT_NE(vertex(later->bodies(0), 210), vertex(first->bodies(0), 210));  // the rest moves

  set.set_integrator("warp_drive");
  expect_error([&] { client.set_body_parameters(set); }, v1::ERROR_CODE_BAD_REQUEST);
  set.clear_integrator();
  set.set_structural_stiffness(-5);
  expect_error([&] { client.set_body_parameters(set); }, v1::ERROR_CODE_BAD_REQUEST);
  set.set_body_id(7);
  expect_error([&] { client.set_body_parameters(set); }, v1::ERROR_CODE_UNKNOWN_ID);
  expect_error([&] { client.pin_particles(0, {400}, {}); }, v1::ERROR_CODE_BAD_REQUEST);
}

TEST_F(FeltdTest, ExitsCleanlyOnSigterm) {
  Client client;
  connect(client);
  client.hello("test");
  client.subscribe_frames();
  ASSERT_TRUE(client.next_frame(scaled(5s)));
  EXPECT_EQ(server_->stop(SIGTERM, 5s), 0);
  EXPECT_FALSE(server_->running());
}

}  // namespace
}  // namespace felt::test
