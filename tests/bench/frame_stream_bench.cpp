// What a frame costs: building one from a snapshot of the 100 x 100 cloth of
// scenes/service_bench.json and serializing it, per encoding, for one subscriber
// (docs/results/service.md). Every client's frames are encoded on the server's one frame encoder
// thread (net/server_context.hpp); subscribers of one snapshot in one encoding share its bodies,
// so this is what each snapshot and encoding costs that thread (eight subscribers:
// scripts/bench-frame-sharing).

#include <benchmark/benchmark.h>

#include "bench_scene.hpp"
#include "net/frame_stream.hpp"
#include "net/shared_frame_bodies.hpp"

namespace felt::net {
namespace {

void frame(benchmark::State& state, bool quantized, bool deltas, bool normals) {
  World world = bench::load_bench_scene("service_bench.json").world;
  std::vector<std::shared_ptr<SceneSnapshot>> snapshots;
  for (int i = 0; i < 64; ++i) {
    for (int s = 0; s < 8; ++s) world.step();  // 60 Hz frames of a 500 Hz scene
    snapshots.push_back(make_snapshot(world));
  }
  FrameStream stream;
  stream.start({60, normals, {}, quantized, deltas});
  std::size_t i = 0, bytes = 0;
  std::string out;
  for (auto _ : state) {
    // one subscriber: nobody shares its bodies (shared_frame_bodies.hpp)
    SharedFrameBodies shared;
    const FrameStream::Plan plan = stream.plan(snapshots[i++ % snapshots.size()], 1, 0);
    FrameStream::FrameRecord record;
    out.clear();
    FrameStream::encode(plan, shared, out, record);
    stream.encoded(std::move(record));
    stream.written();
    if (deltas) stream.acknowledge(plan.sequence);
    bytes += out.size();
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["kB"] = benchmark::Counter(static_cast<double>(bytes) / 1e3 /
                                            static_cast<double>(state.iterations()));
}

BENCHMARK_CAPTURE(frame, float32, false, false, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(frame, float32_normals, false, false, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(frame, quantized16, true, false, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(frame, quantized16_deltas, true, true, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(frame, quantized16_deltas_normals, true, true, true)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace felt::net
