// End to end: scenes listed, loaded, created, joined, left, destroyed and controlled, with the
// other clients told, and ownership enforced.

#include <algorithm>
#include <cmath>
#include <thread>

#include "feltd_fixture.hpp"

namespace felt::test {
namespace {

bool has(const google::protobuf::RepeatedPtrField<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::vector<std::uint32_t> body_ids(const v1::SceneEvent& event) {
  return {event.body_ids().begin(), event.body_ids().end()};
}

TEST_F(FeltdTest, ScenesListTheirFilesAndTheRunningScenes) {
  auto client = greeted("lister");
  const v1::SceneList list = client->list_scenes();
  EXPECT_TRUE(has(list.files(), "default"));
  EXPECT_TRUE(has(list.files(), "thesis/three_cubes"));
  EXPECT_TRUE(std::is_sorted(list.files().begin(), list.files().end()));
  ASSERT_EQ(list.running_size(), 1);
  const v1::RunningScene& scene = list.running(0);
  EXPECT_EQ(scene.name(), "default");
  EXPECT_EQ(scene.clients(), 1u);  // this client, since its Hello
  EXPECT_TRUE(scene.shared());
  EXPECT_TRUE(scene.persistent());
}

TEST_F(FeltdTest, AClientIsInTheDefaultSceneOnlyAfterItsHello) {
  Client early;
  connect(early);
  auto watcher = greeted("watcher");
  EXPECT_EQ(watcher->stats().scene().clients(), 1u);  // the early one has not said hello
  early.hello("late");
  const auto joined = watcher->wait_event(v1::EVENT_KIND_CLIENT_JOINED, 5s);
  ASSERT_TRUE(joined);
  EXPECT_EQ(joined->client_name(), "late");
  // a long name is cut between characters, never inside one: the others still parse the event
  Client long_name;
  connect(long_name);
  long_name.hello(std::string(99, 'a') + "\u00e9t\u00e9");
  const auto named = watcher->wait_event(v1::EVENT_KIND_CLIENT_JOINED, 5s);
  ASSERT_TRUE(named);
  EXPECT_EQ(named->client_name(), std::string(99, 'a'));
}

TEST_F(FeltdTest, ACreatedSceneIsEmptyAndBelongsToItsCreator) {
  auto owner = greeted("owner");
  v1::CreateScene create;
  create.set_name("workbench");
  create.set_time_step(0.002);
  create.mutable_gravity()->set_y(-1.62);  // the moon
  const v1::SceneLoaded scene = owner->create_scene(create);
  EXPECT_EQ(scene.name(), "workbench");
  EXPECT_EQ(scene.bodies_size(), 0);
  EXPECT_DOUBLE_EQ(scene.time_step(), 0.002);
  EXPECT_FALSE(scene.shared());
  const std::uint32_t cloth = owner->add_body(small_cloth_json(0)).body().body_id();

  auto guest = greeted("guest");
  const v1::SceneLoaded joined = guest->join_scene(scene.scene_id());
  ASSERT_EQ(joined.bodies_size(), 1);
  EXPECT_EQ(joined.bodies(0).owner(), joined.owner());
  // the guest may look and touch, not change or control
  v1::SetBodyParameters set;
  set.set_body_id(cloth);
  set.set_drag(0.5);
  expect_error([&] { guest->set_body_parameters(set); }, v1::ERROR_CODE_PERMISSION_DENIED);
  expect_error([&] { guest->remove_body(cloth); }, v1::ERROR_CODE_PERMISSION_DENIED);
  expect_error([&] { guest->pause(); }, v1::ERROR_CODE_PERMISSION_DENIED);
  expect_error([&] { guest->destroy_scene(); }, v1::ERROR_CODE_PERMISSION_DENIED);
  EXPECT_FALSE(guest->proxy_update(0, {5, 5, 5}).in_contact());
  // the guest's own body is its own
  const std::uint32_t mine = guest->add_body(small_cloth_json(3)).body().body_id();
  set.set_body_id(mine);
  EXPECT_EQ(guest->set_body_parameters(set).body_id(), mine);
  set.set_body_id(mine);
  expect_error([&] { owner->remove_body(mine); }, v1::ERROR_CODE_PERMISSION_DENIED);

  // the owner destroys it: the guest hears so and is in no scene any more
  EXPECT_EQ(owner->destroy_scene().scene_id(), scene.scene_id());
  const auto destroyed = guest->wait_event(v1::EVENT_KIND_SCENE_DESTROYED, 5s);
  ASSERT_TRUE(destroyed);
  EXPECT_EQ(destroyed->scene_id(), scene.scene_id());
  expect_error([&] { guest->proxy_update(0, {5, 5, 5}); }, v1::ERROR_CODE_NO_SCENE);
  expect_error([&] { guest->join_scene(scene.scene_id()); }, v1::ERROR_CODE_UNKNOWN_ID);
  expect_error(
      [&] {
        owner->create_scene([] {
          v1::CreateScene bad;
          bad.set_time_step(5);
          return bad;
        }());
      },
      v1::ERROR_CODE_BAD_SCENE);
}

TEST_F(FeltdTest, InASharedSceneAnyoneChangesAnythingAndTheOthersHear) {
  auto first = greeted("first");
  const v1::SceneLoaded scene = first->load_scene_by_name("default", true);
  EXPECT_TRUE(scene.shared());
  auto second = greeted("second");
  second->join_scene(scene.scene_id());
  EXPECT_EQ(second->remove_body(0).body_id(), 0u);
  const auto removed = first->wait_event(v1::EVENT_KIND_BODY_REMOVED, 5s);
  ASSERT_TRUE(removed);
  EXPECT_EQ(removed->body_ids(0), 0u);
  EXPECT_EQ(removed->client_name(), "second");
  const v1::BodyInfo added = second->add_body(small_cloth_json()).body();
  EXPECT_NE(added.body_id(), 0u);  // a fresh id, never the removed one
  const auto event = first->wait_event(v1::EVENT_KIND_BODY_ADDED, 5s);
  ASSERT_TRUE(event);
  ASSERT_EQ(event->bodies_size(), 1);
  EXPECT_EQ(event->bodies(0).body_id(), added.body_id());
  EXPECT_EQ(event->bodies(0).particles(), 36u);
  first->pause();
  EXPECT_TRUE(second->wait_event(v1::EVENT_KIND_SCENE_PAUSED, 5s));
}

// What one client does, the others in the scene hear with its details, while the client
// itself gets its reply instead.
TEST_F(FeltdTest, TheOthersHearOfChangesControlAndRestoresWithTheirDetails) {
  Client actor;
  connect(actor);
  const std::uint32_t actor_id = actor.hello("actor").client_id();
  const v1::SceneLoaded scene = actor.load_scene_by_name("default", true);
  auto observer = greeted("observer");
  observer->join_scene(scene.scene_id());
  actor.pause();
  ASSERT_TRUE(observer->wait_event(v1::EVENT_KIND_SCENE_PAUSED, 5s));
  std::uint64_t sequence = 0;
  const auto heard = [&](v1::EventKind kind) {
    const auto event = observer->wait_event(kind, 5s);
    EXPECT_TRUE(event) << kind;
    if (!event) return v1::SceneEvent();
    EXPECT_EQ(event->scene_id(), scene.scene_id());
    EXPECT_EQ(event->client_id(), actor_id);
    EXPECT_EQ(event->client_name(), "actor");
    EXPECT_GT(event->sequence(), sequence);
    sequence = event->sequence();
    return *event;
  };

  v1::SetBodyParameters set;
  set.set_body_id(0);
  set.set_drag(0.01);
  EXPECT_EQ(actor.set_body_parameters(set).body_id(), 0u);
  EXPECT_EQ(body_ids(heard(v1::EVENT_KIND_BODY_CHANGED)), std::vector<std::uint32_t>{0});
  EXPECT_EQ(actor.pin_particles(0, {399}, {}).body_id(), 0u);
  EXPECT_EQ(body_ids(heard(v1::EVENT_KIND_BODY_CHANGED)), std::vector<std::uint32_t>{0});

  const v1::StateSaved saved = actor.save_state();
  EXPECT_EQ(actor.step(50).step(), saved.step() + 50);
  EXPECT_EQ(actor.restore_state(saved.state_id()).step(), saved.step());
  const v1::SceneEvent restored = heard(v1::EVENT_KIND_STATE_RESTORED);
  EXPECT_EQ(restored.step(), saved.step());
  EXPECT_DOUBLE_EQ(restored.sim_time(), saved.sim_time());

  EXPECT_DOUBLE_EQ(actor.set_time_scale(2.5).time_scale(), 2.5);
  EXPECT_DOUBLE_EQ(heard(v1::EVENT_KIND_TIME_SCALE).time_scale(), 2.5);

  const v1::SceneStatus resumed = actor.resume();
  EXPECT_FALSE(resumed.paused());
  const v1::SceneEvent running = heard(v1::EVENT_KIND_SCENE_RESUMED);
  EXPECT_EQ(running.step(), resumed.step());
  EXPECT_DOUBLE_EQ(running.time_scale(), 2.5);

  // an event is posted to a session before the reply of the request that raised it: had the
  // actor been sent its own, it would be here by now
  for (const v1::SceneEvent& event : actor.take_events()) {
    EXPECT_NE(event.client_id(), actor_id) << event.ShortDebugString();
  }
}

TEST_F(FeltdTest, APausedSceneStepsOnRequestAndScalesItsTime) {
  auto client = greeted("controller");
  client->load_scene_by_name("default");
  expect_error([&] { client->step(10); }, v1::ERROR_CODE_WRONG_STATE);  // running
  const v1::SceneStatus paused = client->pause();
  EXPECT_TRUE(paused.paused());
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(client->stats().scene().steps(), paused.step());
  const v1::SceneStatus stepped = client->step(500);
  EXPECT_EQ(stepped.step(), paused.step() + 500);
  EXPECT_NEAR(stepped.sim_time(), 0.001 * static_cast<double>(stepped.step()), 1e-9);
  expect_error([&] { client->step(0); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client->step(200'000); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client->set_time_scale(0); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client->set_time_scale(NAN); }, v1::ERROR_CODE_BAD_REQUEST);
  EXPECT_DOUBLE_EQ(client->set_time_scale(0.5).time_scale(), 0.5);
  const v1::SceneStatus resumed = client->resume();
  EXPECT_FALSE(resumed.paused());
  std::this_thread::sleep_for(400ms);
  const v1::SceneStats stats = client->stats().scene();
  EXPECT_GT(stats.steps(), resumed.step());
  EXPECT_LT(stats.sim_time() - resumed.sim_time(), 0.35);  // half of 0.4 s of wall time
  EXPECT_DOUBLE_EQ(stats.time_scale(), 0.5);
}

TEST_F(FeltdTest, ASavedStateComesBackExactlyAndCanTravelThroughTheClient) {
  auto client = greeted("saver");
  client->load_scene_by_name("default");
  client->pause();
  const v1::StateSaved saved = client->save_state(true);
  ASSERT_EQ(saved.data().bodies_size(), 1);
  const v1::BodyState& body = saved.data().bodies(0);
  EXPECT_EQ(body.positions_size(), 3 * 400);
  EXPECT_EQ(body.velocities_size(), 3 * 400);
  EXPECT_EQ(body.pinned_size(), 2);  // the curtain's top corners
  client->step(300);
  EXPECT_EQ(client->restore_state(saved.state_id()).step(), saved.step());
  client->subscribe_frames(0);
  const auto frame = client->next_frame(scaled(5s));
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->step(), saved.step());
  for (int v = 0; v < 400; v += 37) {
    EXPECT_EQ(frame->bodies(0).positions(3 * v + 1), static_cast<float>(body.positions(3 * v + 1)));
  }
  // a state edited by the client: the whole curtain a metre to the side
  v1::SceneState moved = saved.data();
  for (int i = 0; i < moved.bodies(0).positions_size(); i += 3) {
    moved.mutable_bodies(0)->set_positions(i, moved.bodies(0).positions(i) + 1);
  }
  client->restore_state(moved);
  client->step(1);
  std::optional<v1::Frame> later;
  while ((later = client->next_frame(scaled(5s))) && later->step() != saved.step() + 1) {
  }
  ASSERT_TRUE(later);
  EXPECT_NEAR(later->bodies(0).positions(0), body.positions(0) + 1, 1e-3);
  // states that do not fit are refused and change nothing
  v1::SceneState broken = saved.data();
  broken.mutable_bodies(0)->set_positions(5, NAN);
  expect_error([&] { client->restore_state(broken); }, v1::ERROR_CODE_BAD_REQUEST);
  broken = saved.data();
  broken.mutable_bodies(0)->mutable_velocities()->RemoveLast();
  expect_error([&] { client->restore_state(broken); }, v1::ERROR_CODE_BAD_REQUEST);
  broken = saved.data();
  broken.mutable_bodies(0)->set_body_id(77);
  expect_error([&] { client->restore_state(broken); }, v1::ERROR_CODE_BAD_REQUEST);
  expect_error([&] { client->restore_state(12345); }, v1::ERROR_CODE_UNKNOWN_ID);
}

TEST_F(FeltdTest, ResetTakesTheSceneBackToItsFile) {
  auto client = greeted("resetter");
  const v1::SceneLoaded scene = client->load_scene_by_name("default");
  client->add_body(small_cloth_json());
  auto other = greeted("other");
  other->join_scene(scene.scene_id());
  std::this_thread::sleep_for(100ms);
  const v1::SceneStatus reset = client->reset();
  EXPECT_LT(reset.sim_time(), 0.05);
  const auto event = other->wait_event(v1::EVENT_KIND_SCENE_RESET, 5s);
  ASSERT_TRUE(event);
  ASSERT_EQ(event->bodies_size(), 1);
  EXPECT_EQ(event->bodies(0).name(), "curtain");
}

TEST_F(FeltdTest, TheServersOwnScenesCannotBeDestroyedButKeptOnesOutliveTheirClient) {
  auto client = greeted("keeper");
  expect_error([&] { client->destroy_scene(); }, v1::ERROR_CODE_PERMISSION_DENIED);
  v1::ClientMessage load;
  load.mutable_load_scene()->set_name("default");
  load.mutable_load_scene()->set_keep(true);
  const std::uint64_t kept = client->request(load).scene_loaded().scene_id();
  client->close();
  auto later = greeted("later");
  const v1::SceneLoaded joined = later->join_scene(kept);  // still there
  EXPECT_EQ(joined.name(), "default");
  // its creator is gone, so it is anyone's to destroy
  EXPECT_EQ(later->destroy_scene(kept).scene_id(), kept);
  expect_error([&] { later->join_scene(kept); }, v1::ERROR_CODE_UNKNOWN_ID);
  // a scene that is not kept goes with its last client
  auto brief = greeted("brief");
  const std::uint64_t gone = brief->load_scene_by_name("default").scene_id();
  brief->close();
  std::this_thread::sleep_for(100ms);
  expect_error([&] { later->join_scene(gone); }, v1::ERROR_CODE_UNKNOWN_ID);
}

class FeltdKeptScenesTest : public FeltdTest {
 protected:
  std::vector<std::string> extra_args() const override { return {"--max-kept-scenes", "2"}; }
};

// Kept scenes outlive their client: one client may keep only so many, and others still load.
TEST_F(FeltdKeptScenesTest, OneClientKeepsAtMostTheLimitAndOthersStillLoad) {
  auto client = std::make_unique<Client>();
  connect(*client);
  EXPECT_EQ(client->hello("hoarder").limits().max_kept_scenes(), 2u);
  v1::ClientMessage load;
  load.mutable_load_scene()->set_name("default");
  load.mutable_load_scene()->set_keep(true);
  const std::uint64_t first = client->request(load).scene_loaded().scene_id();
  client->request(load);
  try {
    client->request(load);
    ADD_FAILURE() << "a third kept scene was loaded";
  } catch (const ClientError& e) {
    EXPECT_EQ(e.code(), v1::ERROR_CODE_LIMIT_EXCEEDED);
    EXPECT_NE(std::string(e.what()).find("keeps 2 scenes running (--max-kept-scenes)"),
              std::string::npos)
        << e.what();
  }
  // scenes that go with their client are not limited by it, and another client keeps its own
  EXPECT_NE(client->load_scene_by_name("default").scene_id(), 0u);
  auto other = greeted("other");
  EXPECT_NE(other->request(load).scene_loaded().scene_id(), 0u);
  // destroying one makes room again
  EXPECT_EQ(client->destroy_scene(first).scene_id(), first);
  EXPECT_NE(client->request(load).scene_loaded().scene_id(), 0u);
}

class ServerScenesControlledByNone : public FeltdTest {
  std::vector<std::string> extra_args() const override {
    return {"--server-scenes-control", "none"};
  }
};

// Issue 31, found 5: anyone could control the server's own scenes (and a scale of 1e-300 made
// their physics thread spin); the operator now says whether clients may.
TEST_F(ServerScenesControlledByNone, ClientsWatchTouchAndChangeBodiesButDoNotControl) {
  auto client = greeted("visitor");
  const std::string says = "the server's own scenes are controlled by no client";
  expect_error([&] { client->pause(); }, v1::ERROR_CODE_PERMISSION_DENIED, says);
  expect_error([&] { client->set_time_scale(1e-300); }, v1::ERROR_CODE_PERMISSION_DENIED, says);
  expect_error([&] { client->reset(); }, v1::ERROR_CODE_PERMISSION_DENIED, says);
  expect_error([&] { client->save_state(); }, v1::ERROR_CODE_PERMISSION_DENIED, says);
  EXPECT_FALSE(client->stats().scene().paused());
  client->subscribe_frames(60);
  EXPECT_TRUE(client->next_frame(scaled(5s)));
  // a scene a client creates is its own to control
  v1::CreateScene create;
  create.set_name("mine");
  client->create_scene(create);
  EXPECT_TRUE(client->pause().paused());
}

TEST_F(FeltdTest, LeavingASceneEndsItsFramesAndProxies) {
  auto client = greeted("leaver");
  const std::uint64_t scene = client->stats().scene().scene_id();
  client->subscribe_frames(60);
  ASSERT_TRUE(client->next_frame(scaled(5s)));
  EXPECT_EQ(client->leave_scene().scene_id(), scene);
  expect_error([&] { client->proxy_update(0, {0, 1, 0}); }, v1::ERROR_CODE_NO_SCENE);
  expect_error([&] { client->pause(); }, v1::ERROR_CODE_NO_SCENE);
  // frames already on their way may still come; then none
  while (client->next_frame(200ms)) {
  }
  EXPECT_FALSE(client->next_frame(300ms));
  EXPECT_EQ(client->join_scene(scene).scene_id(), scene);
  // in no scene, joining "scene 0" is an unknown id, not a crash
  client->leave_scene();
  expect_error([&] { client->join_scene(0); }, v1::ERROR_CODE_UNKNOWN_ID);
  EXPECT_TRUE(server_->running());
}

TEST_F(FeltdTest, APausedSceneStillShowsBodiesComingAndGoing) {
  auto client = greeted("still");
  client->load_scene_by_name("default");
  client->pause();
  client->subscribe_frames(60);
  ASSERT_TRUE(client->next_frame(scaled(5s)));
  const std::uint32_t added = client->add_body(small_cloth_json()).body().body_id();
  std::optional<v1::Frame> frame;
  while ((frame = client->next_frame(scaled(5s))) && frame->bodies_size() < 2) {
  }
  ASSERT_TRUE(frame);  // without a step
  EXPECT_EQ(frame->bodies(1).body_id(), added);
  EXPECT_GT(frame->bodies(1).triangles_size(), 0);
}

TEST_F(FeltdTest, RescuedStepsAreToldAsSuch) {
  auto client = greeted("stiff");
  // symplectic Euler at 1 ms cannot hold these springs in one step, but can in substeps (a
  // rescue's: automatic substeps would take them before the step fails)
  client->load_scene_json(R"({"health": {"auto_substeps": false},
      "bodies": [{"type": "cloth", "grid": {"nx": 6, "ny": 6},
      "springs": {"structural": {"stiffness": 1e6}}}]})");
  const auto rescued = client->wait_event(v1::EVENT_KIND_STEP_RESCUED, 5s);
  ASSERT_TRUE(rescued);
  EXPECT_GT(rescued->count(), 0u);
}

TEST_F(FeltdTest, StatsSayWhereTheStepsSpendTheirTime) {
  // the default scene's curtain: the cloth stages, and none of the solids' (it has none)
  auto client = greeted("profiler");
  const auto deadline = std::chrono::steady_clock::now() + scaled(5s);
  v1::SceneStats stats = client->stats().scene();
  while (stats.stages().empty() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(50ms);
    stats = client->stats().scene();
  }
  std::vector<std::string> stages;
  for (const v1::StageTime& stage : stats.stages()) {
    EXPECT_EQ(stage.system(), "cloth");
    EXPECT_GE(stage.ms_per_step(), 0);
    EXPECT_LT(stage.ms_per_step(), stats.ms_per_step()) << stage.stage();
    if (stage.stage() == "integration") {
      EXPECT_GT(stage.ms_per_step(), 0);
    }
    stages.push_back(stage.stage());
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"integration", "stretch_limit", "colliders",
                                              "self_collision", "constraints", "health"}));
}

}  // namespace
}  // namespace felt::test
