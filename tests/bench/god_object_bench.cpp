// Latency of one god-object update (issue 5: p99 ≤ 20 µs) on a 100 × 100 grid cloth (19,602
// triangles) under a BVH, while the cloth waves (a new snapshot pair every 10 updates, as a
// 100 Hz physics step seen by a 1 kHz haptic loop) and the device strokes across it: pressed
// 1 cm into it, then lifted 5 cm clear, back and forth. Prints p50 / p99 / p99.9 / max in µs
// per update, for the default proxy and a few variants: of wall time (what the device waits)
// and of the thread's CPU time (the same without the time the scheduler gave to others, which
// on a shared machine is most of the tail).
//
//   god_object_bench [--updates N] [--query bvh_aabb_4|...]

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/collision/triangle_query.hpp"
#include "core/geometry/surface_normals.hpp"
#include "core/haptics/god_object.hpp"
#include "scheduling/thread_cpu_time.hpp"

namespace felt {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::uint32_t kSide = 100;  // particles per side: 2 · 99² = 19,602 triangles
constexpr int kUpdatesPerStep = 10;   // 1 kHz haptics over a 100 Hz physics step
constexpr Real kHapticDt = 1e-3;

/// The cloth's height at (x, y) and time t: a travelling wave, 2 cm high.
Real wave(Real x, Real y, Real t) {
  return 0.02 * std::sin(6 * x + 4 * y - 8 * t);
}

struct Cloth {
  /// One physics snapshot, shared and immutable as the runtime's are: a proxy keeps the one
  /// it rendered against until its next update.
  struct Snapshot {
    std::vector<Vec3> positions, normals;
  };

  std::vector<Triangle> triangles;
  std::shared_ptr<const Snapshot> older, newer;
  std::unique_ptr<TriangleQuery> query;
  SurfaceMotion motion{0, 0, 1};

  Cloth(TriangleQueryKind kind) {
    for (std::uint32_t j = 0; j + 1 < kSide; ++j) {
      for (std::uint32_t i = 0; i + 1 < kSide; ++i) {
        const std::uint32_t v = j * kSide + i;
        triangles.push_back({v, v + 1, v + kSide + 1});
        triangles.push_back({v, v + kSide + 1, v + kSide});
      }
    }
    newer = snapshot(0);
    older = newer;
    query = make_triangle_query(kind, triangles, newer->positions);
  }

  std::shared_ptr<const Snapshot> snapshot(Real t) const {
    auto s = std::make_shared<Snapshot>();
    for (std::uint32_t j = 0; j < kSide; ++j) {
      for (std::uint32_t i = 0; i < kSide; ++i) {
        const Real px = Real(i) / (kSide - 1);
        const Real py = Real(j) / (kSide - 1);
        s->positions.emplace_back(px, py, wave(px, py, t));
      }
    }
    compute_vertex_normals(s->positions, triangles, s->normals);
    return s;
  }

  /// The physics thread's part: a new snapshot, its normals and the refit (not timed).
  void advance(Real t) {
    older = std::exchange(newer, snapshot(t));
    query->refit(older->positions, newer->positions);
    motion = motion.then(older->positions, newer->positions);
  }

  HapticSurface surface(std::uint64_t step) const {
    HapticSurface surface;
    surface.bodies = {HapticBody{0, triangles, older->positions, newer->positions, older->normals,
                                 newer->normals, query.get(), motion}};
    surface.step = step;
    surface.storage = std::make_shared<const std::array<std::shared_ptr<const Snapshot>, 2>>(
        std::array{older, newer});
    return surface;
  }
};

/// The device: 0.5 m/s along x across the cloth, y drifting slowly; pressed 1 cm into the
/// wave (the spring 1 cm long, 4 N) for 0.8 s, then 5 cm clear of it for 0.2 s.
Vec3 device_at(Real t, Real radius) {
  const Real phase = std::fmod(0.5 * t, 2.0);
  const Real x = 0.1 + 0.8 * (phase < 1 ? phase : 2 - phase);
  const Real y = 0.5 + 0.3 * std::sin(0.7 * t);
  const bool pressed = std::fmod(t, 1.0) < 0.8;
  return {x, y, wave(x, y, t) + radius + (pressed ? -0.01 : 0.05)};
}

/// The calling thread's CPU time, µs.
double cpu_micros() {
  return 1e6 * thread_cpu_seconds();
}

struct Result {
  std::vector<double> micros;      ///< wall time per update
  std::vector<double> cpu_micros;  ///< thread CPU time per update
  double contact_fraction = 0;
};

Result run(TriangleQueryKind kind, const ProxySettings& settings, int updates) {
  Cloth cloth(kind);
  GodObject proxy(settings, device_at(0, settings.radius) + Vec3(0, 0, 0.1));
  Result result;
  result.micros.reserve(static_cast<std::size_t>(updates));
  result.cpu_micros.reserve(static_cast<std::size_t>(updates));
  int in_contact = 0;
  std::uint64_t step = 0;
  HapticSurface surface;
  for (int u = 0; u < updates; ++u) {
    if (u % kUpdatesPerStep == 0) {
      ++step;
      cloth.advance(static_cast<Real>(step) * kUpdatesPerStep * kHapticDt);
      surface = cloth.surface(step);
    }
    surface.alpha = static_cast<Real>(u % kUpdatesPerStep + 1) / kUpdatesPerStep;
    // the device lags the cloth by one physics step, as the interpolated surface does
    const Vec3 device =
        device_at((static_cast<Real>(step - 1) + surface.alpha) * kUpdatesPerStep * kHapticDt,
                  settings.radius);
    const double cpu_start = cpu_micros();
    const Clock::time_point start = Clock::now();
    const HapticContact contact = proxy.update(surface, device, kHapticDt);
    const Clock::time_point end = Clock::now();
    result.cpu_micros.push_back(cpu_micros() - cpu_start);
    result.micros.push_back(std::chrono::duration<double, std::micro>(end - start).count());
    in_contact += contact.in_contact ? 1 : 0;
  }
  result.contact_fraction = static_cast<double>(in_contact) / updates;
  return result;
}

double percentile(std::vector<double> sorted, double p) {
  std::sort(sorted.begin(), sorted.end());
  const auto i = static_cast<std::size_t>(p * static_cast<double>(sorted.size() - 1));
  return sorted[i];
}

}  // namespace
}  // namespace felt

int main(int argc, char** argv) {
  using namespace felt;
  int updates = 100000;
  TriangleQueryKind kind = TriangleQueryKind::kBvhAabb4;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--updates") == 0) {
      updates = std::max(1000, std::atoi(argv[i + 1]));
    } else if (std::strcmp(argv[i], "--query") == 0) {
      const auto parsed = triangle_query_kind(argv[i + 1]);
      if (!parsed) {
        std::fprintf(stderr, "unknown query kind %s\n", argv[i + 1]);
        return 2;
      }
      kind = *parsed;
    }
  }

  struct Variant {
    const char* name;
    ProxySettings settings;
  };
  ProxySettings defaults;
  ProxySettings point = defaults;
  point.radius = 0;
  ProxySettings friction = defaults;
  friction.static_friction = 0.4;
  friction.dynamic_friction = 0.3;
  ProxySettings flat = defaults;
  flat.force_shading = false;
  const Variant variants[] = {{"default (r 2 cm, shading)", defaults},
                              {"point proxy (r 0)", point},
                              {"friction 0.4 / 0.3", friction},
                              {"no force shading", flat}};

  std::printf("god-object update, %u x %u cloth (%u triangles), %s, %d updates each\n\n", kSide,
              kSide, 2 * (kSide - 1) * (kSide - 1), std::string(to_string(kind)).c_str(), updates);
  std::printf("| proxy | in contact | time | p50 µs | p99 µs | p99.9 µs | max µs |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const Variant& v : variants) {
    const Result r = run(kind, v.settings, updates);
    for (const auto& [name, times] : {std::pair{"wall", &r.micros}, {"cpu", &r.cpu_micros}}) {
      std::printf("| %s | %.0f%% | %s | %.2f | %.2f | %.2f | %.1f |\n", v.name,
                  100 * r.contact_fraction, name, percentile(*times, 0.5), percentile(*times, 0.99),
                  percentile(*times, 0.999), percentile(*times, 1.0));
    }
  }
  return 0;
}
