// The server's frame stream against the client's assembler: what one encodes the other decodes,
// in every encoding, with the triangles sent once, deltas only against acknowledged frames,
// 16-bit deltas well under float32's size on a moving cloth, and the bodies of one snapshot in
// one encoding encoded once for every subscriber.

#include "net/frame_stream.hpp"

#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "core/cloth/cloth_grid.hpp"
#include "felt/v1/envelope.pb.h"
#include "frame_assembler.hpp"
#include "net/shared_frame_bodies.hpp"
#include "wire/frame_codec.hpp"

namespace felt::net {
namespace {

/// A hanging 30 x 30 cloth falling from its top corners, one body (or two, the second still).
World swinging_world(bool second_body = false) {
  World world(WorldSettings{Vec3(0, -9.81, 0), 1e-3, 100, 6});
  for (int b = 0; b < (second_body ? 2 : 1); ++b) {
    GridClothSpec spec;
    spec.nx = spec.ny = 30;
    spec.center = Vec3(2.0 * b, 1.5, 0);
    ClothParams params;
    params.spring(SpringKind::kStructural) = {true, 200, 0.05};
    params.spring(SpringKind::kShear) = {true, 50, 0.02};
    params.spring(SpringKind::kBend) = {true, 5, 0.005};
    ClothBody cloth("c" + std::to_string(b),
                    std::make_shared<const ClothModel>(make_grid_cloth(spec)), params,
                    make_integrator("symplectic_euler"));
    for (std::uint32_t p : grid_pin_indices(spec, GridPinPreset::kTopCorners)) cloth.pin(p);
    world.add_body(std::move(cloth));
  }
  return world;
}

/// The stream's next frame from `world`, as the client decodes it.
struct Sent {
  v1::Frame frame;
  client::DecodedFrame decoded;
};

Sent send(FrameStream& stream, const World& world, client::FrameAssembler& assembler,
          bool written = true) {
  Sent sent;
  stream.build(make_snapshot(world), 7, 0, sent.frame);
  if (written) stream.written();
  auto decoded = assembler.assemble(sent.frame);
  EXPECT_TRUE(decoded) << decoded.error();
  if (decoded) sent.decoded = std::move(*decoded);
  return sent;
}

/// The largest coordinate error of body `b` of `decoded` against the world's positions rounded
/// to float (what a float32 frame carries).
double max_error(const client::DecodedFrame& decoded, std::size_t b, const World& world) {
  const std::vector<Vec3>& x = world.cloths()[b].state().x;
  EXPECT_EQ(decoded.bodies[b].positions.size(), 3 * x.size());
  double worst = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double sent = static_cast<float>(x[i][k]);
      worst = std::max(worst, std::abs(decoded.bodies[b].positions[3 * i + k] - sent));
    }
  }
  return worst;
}

/// Half a quantization step of body `b`'s bounds in `frame`, the error 16 bits may make,
/// plus float rounding of the dequantized value.
double half_step(const v1::Frame& frame, int b) {
  const v1::QuantizedVectors& q = frame.bodies(b).quantized_positions();
  double widest = 0;
  for (int k = 0; k < 3; ++k) widest = std::max<double>(widest, q.upper(k) - q.lower(k));
  return 0.5 * widest / 65535 + 1e-6;
}

TEST(FrameStream, Float32FramesCarryExactFloatsAndTrianglesOnce) {
  World world = swinging_world();
  FrameStream stream;
  stream.start({60, true, {}, false, false});
  client::FrameAssembler assembler;
  const Sent first = send(stream, world, assembler);
  EXPECT_EQ(first.frame.sequence(), 1u);
  EXPECT_EQ(first.frame.bodies(0).triangles_size(), 3 * 29 * 29 * 2);
  EXPECT_EQ(max_error(first.decoded, 0, world), 0.0);  // exactly the floats that were sent
  EXPECT_EQ(first.decoded.bodies[0].normals.size(), 3u * 900);
  world.step();
  const Sent second = send(stream, world, assembler);
  EXPECT_EQ(second.frame.bodies(0).triangles_size(), 0);
  ASSERT_NE(second.decoded.bodies[0].triangles, nullptr);  // the client kept them
  EXPECT_EQ(second.decoded.bodies[0].triangles->size(), 3u * 29 * 29 * 2);
}

TEST(FrameStream, NormalsASnapshotLeftOutAreFoundForAFrameThatAsksForThem) {
  // a served scene leaves them out of its snapshots while no haptics render (live_scene.hpp)
  World world = swinging_world();
  for (int s = 0; s < 20; ++s) world.step();  // swung out of its plane
  const auto with = make_snapshot(world);
  const auto without = make_snapshot(world, nullptr, nullptr, VertexNormals::kLeftOut);
  ASSERT_TRUE(without->bodies[0].normals.empty());
  for (const bool quantized : {false, true}) {
    const auto frame_of = [&](std::shared_ptr<const SceneSnapshot> snapshot) {
      FrameStream stream;
      stream.start({60, true, {}, quantized, false});
      v1::Frame frame;
      stream.build(std::move(snapshot), 7, 0, frame);
      return frame.bodies(0).SerializeAsString();
    };
    EXPECT_EQ(frame_of(without), frame_of(with)) << "quantized " << quantized;
  }
}

TEST(FrameStream, QuantizedFramesAreWithinHalfAStepAndHalfTheSize) {
  World world = swinging_world();
  FrameStream floats, quantized;
  floats.start({60, false, {}, false, false});
  quantized.start({60, false, {}, true, false});
  client::FrameAssembler a, b;
  send(floats, world, a);
  send(quantized, world, b);  // the first frames carry the triangles
  for (int i = 0; i < 200; ++i) world.step();
  const Sent f = send(floats, world, a);
  const Sent q = send(quantized, world, b);
  EXPECT_LT(max_error(q.decoded, 0, world), half_step(q.frame, 0));
  EXPECT_LT(half_step(q.frame, 0), 2e-5);  // a 1 m cloth: bounds of about 1.5 m
  EXPECT_LT(q.frame.ByteSizeLong(), 0.55 * f.frame.ByteSizeLong());
}

TEST(FrameStream, DeltasOfAMovingClothAreUnderFortyPercentOfFloat32) {
  World world = swinging_world();
  FrameStream floats, deltas;
  floats.start({60, true, {}, false, false});
  deltas.start({60, true, {}, true, true});
  client::FrameAssembler a, b;
  send(floats, world, a);
  const Sent key = send(deltas, world, b);
  ASSERT_TRUE(deltas.acknowledge(key.frame.sequence()));
  std::size_t float_bytes = 0, delta_bytes = 0, delta_frames = 0;
  for (int frame = 0; frame < 60; ++frame) {
    for (int s = 0; s < 16; ++s) world.step();  // 60 Hz frames of a 1 kHz scene
    float_bytes += send(floats, world, a).frame.ByteSizeLong();
    const Sent d = send(deltas, world, b);
    delta_bytes += d.frame.ByteSizeLong();
    delta_frames += d.frame.base_sequence() != 0 ? 1 : 0;
    EXPECT_LT(max_error(d.decoded, 0, world), half_step(d.frame, 0)) << frame;
    ASSERT_TRUE(deltas.acknowledge(d.frame.sequence()));  // the client takes every frame
  }
  EXPECT_GT(delta_frames, 50u);
  // with normals in both (a viewer's usual subscription)
  EXPECT_LT(delta_bytes, 0.4 * float_bytes) << delta_bytes << " vs " << float_bytes;
}

TEST(FrameStream, DeltasUseOnlyAcknowledgedFramesAndABodyLeavingItsBoundsGetsAKeyFrame) {
  World world = swinging_world();
  FrameStream stream;
  stream.start({60, false, {}, true, true});
  client::FrameAssembler assembler;
  const Sent key = send(stream, world, assembler);
  world.step();
  const Sent unacknowledged = send(stream, world, assembler);
  EXPECT_EQ(unacknowledged.frame.base_sequence(), 0u);  // nothing acknowledged yet
  EXPECT_FALSE(stream.acknowledge(99));                 // never sent
  ASSERT_TRUE(stream.acknowledge(key.frame.sequence()));
  world.step();
  const Sent delta = send(stream, world, assembler);
  EXPECT_EQ(delta.frame.base_sequence(), key.frame.sequence());
  EXPECT_FALSE(delta.frame.bodies(0).quantized_positions().deltas().empty());
  // the cloth moved far: outside the base's bounds, so its values come whole
  for (Vec3& x : world.cloths()[0].state().x) x += Vec3(5, 0, 0);
  const Sent moved = send(stream, world, assembler);
  EXPECT_FALSE(moved.frame.bodies(0).quantized_positions().values().empty());
  EXPECT_LT(max_error(moved.decoded, 0, world), half_step(moved.frame, 0));
  // a client that lost the base frame cannot decode, and says why
  client::FrameAssembler forgetful;
  const auto lost = forgetful.assemble(delta.frame);
  ASSERT_FALSE(lost);
  EXPECT_NE(lost.error().find("not kept"), std::string::npos);
}

// The delta history is bounded in bytes: a frame of this 30 x 30 cloth keeps 5.4 kB, so a
// budget of 12 kB keeps two frames (a base and one more, or two unacknowledged) and deltas
// still work against a recent acknowledgement; a budget below one frame keeps none, and every
// frame is a key frame the client decodes on its own.
TEST(FrameStream, TheDeltaHistoryStaysWithinItsBudget) {
  constexpr std::size_t kFrameBytes = 900 * 3 * sizeof(std::uint16_t);
  for (const std::size_t budget : {2 * kFrameBytes + 100, kFrameBytes / 2}) {
    World world = swinging_world();
    FrameStream stream(budget);
    stream.start({60, false, {}, true, true});
    client::FrameAssembler assembler;
    std::uint64_t last = 0;
    for (int f = 0; f < 12; ++f) {
      world.step();
      const Sent sent = send(stream, world, assembler);
      EXPECT_LE(stream.history_bytes(), budget) << "frame " << f;
      if (budget < kFrameBytes) {
        EXPECT_EQ(sent.frame.base_sequence(), 0u) << "frame " << f;
      } else if (f > 1) {
        EXPECT_EQ(sent.frame.base_sequence(), last) << "frame " << f;  // the one acknowledged
      }
      EXPECT_LT(max_error(sent.decoded, 0, world), half_step(sent.frame, 0));
      ASSERT_TRUE(stream.acknowledge(sent.frame.sequence()));
      last = sent.frame.sequence();
    }
  }
}

TEST(FrameStream, ADroppedFrameGivesItsTrianglesToTheNext) {
  World world = swinging_world();
  FrameStream stream;
  stream.start({60, false, {}, false, false});
  v1::Frame dropped;
  stream.build(make_snapshot(world), 7, 0, dropped);
  EXPECT_GT(dropped.bodies(0).triangles_size(), 0);
  stream.dropped();
  world.step();
  v1::Frame next;
  stream.build(make_snapshot(world), 7, 1, next);
  EXPECT_EQ(next.bodies(0).triangles_size(), dropped.bodies(0).triangles_size());
  EXPECT_EQ(next.skipped(), 1u);
}

// A window of unacknowledged frames (SubscribeFrames.max_unacknowledged) is full while that many
// frames were written and not acknowledged; an acknowledgement takes every frame up to the one it
// names out of it, and a frame dropped unsent never counts.
TEST(FrameStream, TheWindowCountsWrittenFramesUntilAnAcknowledgementCoversThem) {
  World world = swinging_world();
  FrameStream stream;
  FrameOptions options;
  options.max_unacknowledged = 2;
  stream.start(options);
  client::FrameAssembler assembler;
  const Sent first = send(stream, world, assembler);
  EXPECT_FALSE(stream.window_full());
  world.step();
  v1::Frame dropped;
  stream.build(make_snapshot(world), 7, 0, dropped);
  stream.dropped();
  EXPECT_FALSE(stream.window_full());
  world.step();
  send(stream, world, assembler);
  EXPECT_TRUE(stream.window_full());
  ASSERT_TRUE(stream.acknowledge(first.frame.sequence()));
  EXPECT_FALSE(stream.window_full());
  world.step();
  const Sent third = send(stream, world, assembler);
  EXPECT_TRUE(stream.window_full());
  ASSERT_TRUE(stream.acknowledge(third.frame.sequence()));  // the second with it
  EXPECT_FALSE(stream.window_full());
  // subscribing again starts an empty window; without one, nothing is counted
  send(stream, world, assembler);
  send(stream, world, assembler);
  ASSERT_TRUE(stream.window_full());
  stream.start(options);
  EXPECT_FALSE(stream.window_full());
  stream.start(FrameOptions{});
  for (int i = 0; i < 100; ++i) send(stream, world, assembler);
  EXPECT_FALSE(stream.window_full());
}

TEST(FrameStream, ASubscriptionSeesOnlyItsBodies) {
  World world = swinging_world(true);
  FrameStream stream;
  stream.start({60, false, {1}, false, false});
  v1::Frame frame;
  stream.build(make_snapshot(world), 7, 0, frame);
  ASSERT_EQ(frame.bodies_size(), 1);
  EXPECT_EQ(frame.bodies(0).body_id(), 1u);
  EXPECT_EQ(frame.bodies(0).name(), "c1");
}

/// The stream's next frame of `snapshot` encoded against `shared`, its bytes (a length-delimited
/// ServerMessage) and the frame parsed from them.
struct Encoded {
  std::string bytes;
  v1::ServerMessage message;
};

Encoded encode_shared(FrameStream& stream, std::shared_ptr<const SceneSnapshot> snapshot,
                      SharedFrameBodies& shared) {
  const FrameStream::Plan plan = stream.plan(std::move(snapshot), 7, 0);
  Encoded out;
  FrameStream::FrameRecord record;
  FrameStream::encode(plan, shared, out.bytes, record);
  stream.encoded(std::move(record));
  stream.written();
  const std::optional<wire::FrameView> frame = wire::first_frame(out.bytes);
  EXPECT_TRUE(frame && frame->size == out.bytes.size());
  if (frame) {
    EXPECT_TRUE(out.message.ParseFromString(std::string(frame->payload)));
  }
  return out;
}

TEST(SharedFrameBodies, SubscribersOfOneSnapshotAndEncodingShareItsBodiesBytes) {
  World world = swinging_world(true);
  const std::shared_ptr<const SceneSnapshot> snapshot = make_snapshot(world);
  SharedFrameBodies shared;
  FrameStream first, second, quantized;
  first.start({60, true, {}, false, false});
  second.start({60, true, {}, false, false});
  quantized.start({60, true, {}, true, false});
  const Encoded a = encode_shared(first, snapshot, shared);
  EXPECT_EQ(shared.encoded(), 2u);  // two bodies
  const Encoded b = encode_shared(second, snapshot, shared);
  EXPECT_EQ(shared.encoded(), 2u);
  EXPECT_EQ(shared.shared(), 2u);
  EXPECT_EQ(a.bytes, b.bytes);  // the same frame: the same bytes, in protobuf's own order
  EXPECT_EQ(a.bytes.substr(a.bytes.size() - a.message.ByteSizeLong()),
            a.message.SerializeAsString());
  client::FrameAssembler assembler;
  const auto decoded = assembler.assemble(b.message.frame());
  ASSERT_TRUE(decoded) << decoded.error();
  EXPECT_EQ(max_error(*decoded, 1, world), 0);
  // another encoding is encoded for itself
  encode_shared(quantized, snapshot, shared);
  EXPECT_EQ(shared.encoded(), 4u);
}

TEST(SharedFrameBodies, DeltasAreEachClientsOwnAndKeyFramesAreShared) {
  World world = swinging_world();
  SharedFrameBodies shared;
  FrameStream acknowledging, not_acknowledging;
  acknowledging.start({60, false, {}, true, true});
  not_acknowledging.start({60, false, {}, true, true});
  client::FrameAssembler assembler;
  const auto first = make_snapshot(world);
  const Encoded key = encode_shared(acknowledging, first, shared);
  encode_shared(not_acknowledging, first, shared);
  EXPECT_EQ(shared.encoded(), 1u);  // one key frame for both
  ASSERT_TRUE(assembler.assemble(key.message.frame()));
  ASSERT_TRUE(acknowledging.acknowledge(key.message.frame().sequence()));
  for (int s = 0; s < 16; ++s) world.step();
  const auto next = make_snapshot(world);
  const Encoded delta = encode_shared(acknowledging, next, shared);
  EXPECT_EQ(delta.message.frame().base_sequence(), key.message.frame().sequence());
  EXPECT_EQ(shared.encoded(), 1u);  // a delta is not shared
  const auto decoded = assembler.assemble(delta.message.frame());
  ASSERT_TRUE(decoded) << decoded.error();
  EXPECT_LT(max_error(*decoded, 0, world), half_step(delta.message.frame(), 0));
  // the client without a base gets the snapshot's key frame, encoded for it
  const Encoded other = encode_shared(not_acknowledging, next, shared);
  EXPECT_EQ(other.message.frame().base_sequence(), 0u);
  EXPECT_EQ(shared.encoded(), 2u);
}

}  // namespace
}  // namespace felt::net
