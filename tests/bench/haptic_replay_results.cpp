// Thesis 1 Table 9.4 regenerated the way De Boeck et al. measure (thesis 1 §9): cloths are let
// fall and then frozen, a device strokes them, each path is recorded with the brute-force
// broad phase, and every structure replays the recorded device positions through a fresh
// god-object proxy. Per structure: the mean time of an update that found a contact (CD) and of
// one that did not (N-CD), and how many updates are collision-equivalent to the recording
// (same contact, body and triangle, proxy within 1 nm). Prints markdown tables (the "Haptic
// query and collision equivalence" section of docs/results/haptics.md).
//
//   haptic_replay_results [OUTPUT.md] [--recordings DIR] [--repeats N (5)] [--seconds S (10)]
//
// --recordings writes each brute-force recording as CSV (common/device/haptic_recording.hpp)
// to DIR.
//
// Over 500 lines: one benchmark read top to bottom (falling and freezing the cloths, recording,
// replaying per structure, the tables); its parts are used nowhere else.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <numeric>
#include <optional>
#include <random>
#include <ranges>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/collision/triangle_query.hpp"
#include "core/geometry/surface_normals.hpp"
#include "core/haptics/god_object.hpp"
#include "core/world/world.hpp"
#include "device/haptic_recording.hpp"
#include "falling_cloth.hpp"
#include "study_output.hpp"

namespace felt {
namespace {

using Clock = std::chrono::steady_clock;
using study::format;

constexpr Real kPhysicsStep = 1e-3;  // s: the server's default
constexpr int kFallSteps = 300;      // physics steps before the cloth is frozen
constexpr Real kHapticDt = 1e-3;     // s: a 1 kHz haptic loop
constexpr Real kTolerance = 1e-9;    // m: proxies this close are the same
constexpr std::uint32_t kSeed = 2005;

constexpr std::array kStructures{
    TriangleQueryKind::kBruteForce, TriangleQueryKind::kSpatialHash, TriangleQueryKind::kBvhSphere2,
    TriangleQueryKind::kBvhSphere4, TriangleQueryKind::kBvhAabb2,    TriangleQueryKind::kBvhAabb4,
};

/// Thesis 1 Table 9.4 (ms per haptic frame, AMD 1.2 GHz, 2005): CD and N-CD per structure in the
/// order of kStructures (AD, OSH, sphere-2, sphere-4, AABB-2, AABB-4).
const std::map<std::size_t, std::array<std::array<double, 2>, 6>> kThesisTable94{
    {162,
     {{{0.102874, 0.084212},
       {0.025004, 0.009021},
       {0.026063, 0.010382},
       {0.025858, 0.010057},
       {0.023502, 0.008524},
       {0.023779, 0.008153}}}},
    {576,
     {{{0.752296, 0.735026},
       {0.024336, 0.012568},
       {0.028830, 0.011875},
       {0.028204, 0.012390},
       {0.025501, 0.009450},
       {0.024892, 0.012568}}}},
    {3042,
     {{{2.781679, 2.745635},
       {0.025572, 0.009210},
       {0.031033, 0.013224},
       {0.029767, 0.012841},
       {0.027431, 0.010374},
       {0.026700, 0.011111}}}},
};

/// A cloth of side × side particles and the thesis's row it stands for. The thesis's 576
/// triangles is no 2 (N − 1)²: 18 × 18 particles (578) is the nearest square grid.
struct ClothSize {
  std::uint32_t side;
  std::size_t thesis_triangles;  ///< 0: not in the thesis
};
constexpr std::array<ClothSize, 4> kSizes{{{10, 162}, {18, 576}, {40, 3042}, {100, 0}}};

/// A 1 m cloth after kFallSteps of falling, frozen, and its surface looked up by grid
/// coordinates.
struct FrozenCloth {
  std::uint32_t side = 0;
  std::vector<Triangle> triangles;
  std::vector<Vec3> rest;  ///< flat: the structures are built here, as the server builds them
  std::vector<Vec3> frozen;
  std::vector<Vec3> normals;  ///< unit vertex normals of the frozen state

  /// The frozen surface at grid coordinates uv ∈ [0, 1]² (the ClothModel's uv), on the triangle
  /// of make_grid_cloth that holds it, and the vertex normals interpolated there.
  std::pair<Vec3, Vec3> at(const Vec2& uv) const {
    const Real last = side - 1;
    const auto cell = [&](Real coordinate, std::uint32_t& index) {
      const Real g = std::clamp(coordinate, Real{0}, Real{1}) * last;
      index = std::min(static_cast<std::uint32_t>(g), side - 2);
      return g - index;
    };
    std::uint32_t i = 0, j = 0;
    const Real s = cell(uv.x(), i);
    const Real t = cell(uv.y(), j);
    const std::uint32_t a = j * side + i, b = a + 1, c = a + side, d = c + 1;
    // make_grid_cloth cuts each cell along b–c: triangles (a, c, b) and (b, c, d)
    using Weights = std::array<std::pair<std::uint32_t, Real>, 3>;
    const Weights weights = s + t <= 1 ? Weights{{{a, 1 - s - t}, {b, s}, {c, t}}}
                                       : Weights{{{d, s + t - 1}, {b, 1 - t}, {c, 1 - s}}};
    Vec3 point = Vec3::Zero(), normal = Vec3::Zero();
    for (const auto& [v, weight] : weights) {
      point += weight * frozen[v];
      normal += weight * normals[v];
    }
    return {point, normal.normalized()};
  }
};

/// Pinned at the two corners of one edge, falling from horizontal (triangle_query_bench's
/// cloth, but for the drag): after 0.3 s it hangs curved and sheared, nowhere flat.
FrozenCloth fall_and_freeze(std::uint32_t side) {
  // drag per particle in proportion to its mass (0.005 N·s/m on the 10 × 10 cloth): a fixed
  // drag per particle would hold a fine cloth's light particles nearly still
  World world = bench::falling_cloth(side, 1.0 * 0.5 / (side * side), kPhysicsStep);
  const World& view = world;
  FrozenCloth out;
  out.side = side;
  out.triangles = view.cloths()[0].model().triangles;
  out.rest = view.cloths()[0].state().x;
  for (int s = 0; s < kFallSteps; ++s) world.step();
  out.frozen = view.cloths()[0].state().x;
  compute_vertex_normals(out.frozen, out.triangles, out.normals);
  return out;
}

/// A scripted device, as a PHANToM user strokes a cloth: keys in grid coordinates and height
/// above the surface along its normal (one side throughout), eased between keys.
struct DeviceScript {
  struct Key {
    Real time;
    Vec2 uv;
    Real height;
  };
  std::vector<Key> keys;

  Vec3 at(const FrozenCloth& cloth, Real t) const {
    std::size_t k = 0;
    while (k + 2 < keys.size() && keys[k + 1].time <= t) ++k;
    const Key& a = keys[k];
    const Key& b = keys[k + 1];
    const Real x = std::clamp((t - a.time) / (b.time - a.time), Real{0}, Real{1});
    const Real e = x * x * (3 - 2 * x);  // smoothstep: the hand slows into every key
    const auto [point, normal] = cloth.at((1 - e) * a.uv + e * b.uv);
    return point + ((1 - e) * a.height + e * b.height) * normal;
  }
};

/// Strokes until `seconds`: approach a point from 8–15 cm off, press in (the device 0.4–1.4 cm
/// inside the proxy's reach), slide through two more points at 0.15–0.3 m/s, leave, and wander
/// 8–15 cm off before the next stroke. The same seed for every cloth: the same strokes in the
/// cloth's own coordinates.
DeviceScript make_strokes(Real seconds, Real radius) {
  std::mt19937 rng(kSeed);
  const auto uniform = [&](Real lo, Real hi) {
    return std::uniform_real_distribution<Real>(lo, hi)(rng);
  };
  constexpr Real kLo = 0.15, kHi = 0.85;  // away from the pinned corners and the edges
  const auto somewhere = [&] { return Vec2(uniform(kLo, kHi), uniform(kLo, kHi)); };
  const auto far = [&] { return uniform(0.08, 0.15); };
  const auto pressed = [&] { return radius - uniform(0.004, 0.014); };
  DeviceScript script;
  Real t = 0;
  script.keys.push_back({t, somewhere(), far()});
  while (t < seconds) {
    Vec2 uv = somewhere();
    t += uniform(0.3, 0.5);
    script.keys.push_back({t, uv, pressed()});
    for (int waypoint = 0; waypoint < 2; ++waypoint) {
      const Real angle = uniform(0, 2 * std::numbers::pi);
      const Vec2 next = (uv + uniform(0.1, 0.25) * Vec2(std::cos(angle), std::sin(angle)))
                            .cwiseMax(kLo)
                            .cwiseMin(kHi);
      t += std::max((next - uv).norm() / uniform(0.15, 0.3), Real{0.2});
      uv = next;
      script.keys.push_back({t, uv, pressed()});
    }
    t += uniform(0.2, 0.35);
    script.keys.push_back({t, uv, far()});
    t += uniform(0.4, 0.8);
    script.keys.push_back({t, somewhere(), far()});
  }
  return script;
}

/// The structure of `kind` as the server makes it: built on the flat cloth, then refitted to
/// the frozen one (from = to).
std::unique_ptr<TriangleQuery> fitted_query(const FrozenCloth& cloth, TriangleQueryKind kind) {
  std::unique_ptr<TriangleQuery> query = make_triangle_query(kind, cloth.triangles, cloth.rest);
  query->refit(cloth.frozen, cloth.frozen);
  return query;
}

/// A structure whose collect() hands over its triangles in ascending index order, as brute
/// force does: what a replay through it still does differently from brute force, the
/// structure's choice of candidates does, not the order it finds them in.
class InIndexOrder final : public TriangleQuery {
 public:
  explicit InIndexOrder(std::unique_ptr<TriangleQuery> inner) : inner_(std::move(inner)) {}

  void refit(std::span<const Vec3> from, std::span<const Vec3> to) override {
    inner_->refit(from, to);
  }
  void collect(const Aabb& region, std::vector<std::uint32_t>& out) const override {
    const auto first = static_cast<std::ptrdiff_t>(out.size());
    inner_->collect(region, out);
    std::sort(out.begin() + first, out.end());
  }
  std::unique_ptr<TriangleQuery> clone() const override {
    return std::make_unique<InIndexOrder>(inner_->clone());
  }
  TriangleQueryKind kind() const override { return inner_->kind(); }

 private:
  std::unique_ptr<TriangleQuery> inner_;
};

/// One pass of device positions through a fresh proxy.
struct Run {
  std::vector<HapticRecord> records;
  std::vector<double> micros;  ///< wall time of each update()
};

Run run_proxy(const FrozenCloth& cloth, const TriangleQuery& query,
              const std::vector<HapticRecord>& input) {
  HapticSurface surface;
  surface.bodies.push_back(HapticBody{0, cloth.triangles, cloth.frozen, cloth.frozen, cloth.normals,
                                      cloth.normals, &query, SurfaceMotion{}});
  surface.step = 1;
  surface.alpha = 1;
  GodObject proxy(ProxySettings{}, input.front().position);
  Run out;
  out.records.reserve(input.size());
  out.micros.reserve(input.size());
  for (const HapticRecord& in : input) {
    const Clock::time_point start = Clock::now();
    const HapticContact contact = proxy.update(surface, in.position, kHapticDt);
    const Clock::time_point end = Clock::now();
    out.micros.push_back(std::chrono::duration<double, std::micro>(end - start).count());
    HapticRecord& r = out.records.emplace_back(in);
    r.in_contact = contact.in_contact;
    r.body = contact.body_id;
    r.triangle = contact.triangle;
    r.proxy = contact.proxy;
    r.force = contact.force;
  }
  return out;
}

/// The device positions of the script at 1 kHz, as records still to be filled.
std::vector<HapticRecord> sample(const FrozenCloth& cloth, const DeviceScript& script,
                                 int updates) {
  std::vector<HapticRecord> out(static_cast<std::size_t>(updates));
  for (int k = 0; k < updates; ++k) {
    out[k].time = k * kHapticDt;
    out[k].position = script.at(cloth, out[k].time);
  }
  return out;
}

/// How a replay differs from the recording, update by update.
struct Divergence {
  std::size_t equivalent = 0;
  std::size_t contact_differs = 0;  ///< a contact found by one only
  /// both touching, proxies within the tolerance, another triangle sharing a corner
  std::size_t neighbour = 0;
  std::size_t apart = 0;  ///< both touching, proxies farther apart than the tolerance
  std::size_t other = 0;
  double largest_apart = 0;  ///< m
  double largest_force = 0;  ///< N: the largest difference in force, over every update
};

Divergence compare(const FrozenCloth& cloth, const std::vector<HapticRecord>& recorded,
                   const std::vector<HapticRecord>& replayed) {
  const auto neighbours = [&](std::int32_t a, std::int32_t b) {
    if (a < 0 || b < 0) return false;
    const Triangle& ta = cloth.triangles[static_cast<std::size_t>(a)];
    const Triangle& tb = cloth.triangles[static_cast<std::size_t>(b)];
    return std::ranges::any_of(ta, [&](std::uint32_t v) { return std::ranges::count(tb, v) > 0; });
  };
  Divergence out;
  for (std::size_t k = 0; k < recorded.size(); ++k) {
    const HapticRecord& a = recorded[k];
    const HapticRecord& b = replayed[k];
    out.largest_force = std::max(out.largest_force, (a.force - b.force).norm());
    if (collision_equivalent(a, b, kTolerance)) {
      ++out.equivalent;
    } else if (a.in_contact != b.in_contact) {
      ++out.contact_differs;
    } else if (const Real apart = (a.proxy - b.proxy).norm(); apart > kTolerance) {
      ++out.apart;
      out.largest_apart = std::max(out.largest_apart, apart);
    } else if (neighbours(a.triangle, b.triangle)) {
      ++out.neighbour;
    } else {
      ++out.other;
    }
  }
  return out;
}

/// Triangles the structure missed along the path: in a box about each device position and
/// proxy as large as an update looks (the proxy's reach), those whose box meets it that
/// collect() did not return. A broad phase must miss none.
std::size_t missed_candidates(const FrozenCloth& cloth, const TriangleQuery& query,
                              const std::vector<HapticRecord>& path) {
  std::vector<Aabb> boxes(cloth.triangles.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (const std::uint32_t v : cloth.triangles[i]) boxes[i].grow(cloth.frozen[v]);
  }
  std::size_t missed = 0;
  std::vector<std::uint32_t> found;
  for (const HapticRecord& r : path) {
    Aabb region;
    region.grow(r.position);
    region.grow(r.proxy);
    region = region.inflated(ProxySettings{}.radius + 1e-3);
    found.clear();
    query.collect(region, found);
    std::sort(found.begin(), found.end());
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
      if (boxes[i].overlaps(region) && !std::binary_search(found.begin(), found.end(), i)) {
        ++missed;
      }
    }
  }
  return missed;
}

/// One structure replaying one recording.
struct Replay {
  std::vector<double> micros;  ///< per update, the least of the repeats
  double cd_us = 0, ncd_us = 0;
  Divergence divergence;
  std::size_t equivalent_in_index_order = 0;
  std::size_t missed = 0;
  bool repeatable = true;  ///< every repeat found the same contacts and proxies
};

/// Every structure of kStructures replaying the recording, the repeats taken in turn (structure
/// after structure, then again), so that a busy spell of the shared machine falls on all of them.
std::vector<Replay> replay_all(const FrozenCloth& cloth, const std::vector<HapticRecord>& recording,
                               int repeats) {
  std::vector<std::unique_ptr<TriangleQuery>> queries;
  for (const TriangleQueryKind kind : kStructures) queries.push_back(fitted_query(cloth, kind));
  std::vector<Replay> out(queries.size());
  std::vector<std::vector<HapticRecord>> first(queries.size());
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t s = 0; s < queries.size(); ++s) {
      Run run = run_proxy(cloth, *queries[s], recording);
      if (r == 0) {
        out[s].micros = std::move(run.micros);
        first[s] = std::move(run.records);
        continue;
      }
      for (std::size_t k = 0; k < recording.size(); ++k) {
        const HapticRecord& a = first[s][k];
        const HapticRecord& b = run.records[k];
        out[s].micros[k] = std::min(out[s].micros[k], run.micros[k]);
        out[s].repeatable = out[s].repeatable && a.in_contact == b.in_contact &&
                            a.triangle == b.triangle && a.proxy == b.proxy;
      }
    }
  }
  for (std::size_t s = 0; s < queries.size(); ++s) {
    Replay& result = out[s];
    std::size_t cd = 0;
    for (std::size_t k = 0; k < recording.size(); ++k) {
      (first[s][k].in_contact ? result.cd_us : result.ncd_us) += result.micros[k];
      cd += first[s][k].in_contact ? 1 : 0;
    }
    result.cd_us /= static_cast<double>(std::max<std::size_t>(cd, 1));
    result.ncd_us /= static_cast<double>(std::max<std::size_t>(recording.size() - cd, 1));
    result.divergence = compare(cloth, recording, first[s]);
    const InIndexOrder sorted(queries[s]->clone());
    result.equivalent_in_index_order =
        compare(cloth, recording, run_proxy(cloth, sorted, recording).records).equivalent;
    result.missed = missed_candidates(cloth, *queries[s], recording);
  }
  return out;
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(p * static_cast<double>(values.size() - 1))];
}

int run(int argc, char** argv) {
  std::optional<std::string> output;
  std::optional<std::filesystem::path> recordings;
  int repeats = 5;
  Real seconds = 10;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--repeats" && a + 1 < argc) {
      repeats = std::max(1, std::stoi(argv[++a]));
    } else if (arg == "--seconds" && a + 1 < argc) {
      seconds = std::stod(argv[++a]);
    } else if (arg == "--recordings" && a + 1 < argc) {
      recordings = argv[++a];
    } else {
      output = arg;
    }
  }
  const Clock::time_point program_start = Clock::now();
  const int updates = static_cast<int>(std::lround(seconds / kHapticDt));
  const DeviceScript script = make_strokes(seconds, ProxySettings{}.radius);

  std::ostringstream paths, t94, largest, causes;
  paths << "| cloth | triangles | thesis row | updates | in contact | triangles touched | "
           "changes of triangle in contact | cloth's drop (m) |\n"
           "|---|---|---|---|---|---|---|---|\n";
  t94 << "| triangles thesis / Felt | structure | CD thesis µs | N-CD thesis µs | CD Felt µs | "
         "N-CD Felt µs | collision-equivalent | the same, candidates in index order | "
         "candidates missed |\n"
         "|---|---|---|---|---|---|---|---|---|\n";
  largest << "| structure | mean µs | p50 µs | p99 µs | max µs |\n|---|---|---|---|---|\n";
  causes << "| triangles | structure | not equivalent | same proxy, neighbouring triangle | "
            "proxies apart (largest) | contact differs | other | largest force difference (N) "
            "|\n|---|---|---|---|---|---|---|---|\n";
  bool any_divergence = false;

  study::Progress progress(static_cast<int>(kSizes.size()));
  for (const ClothSize& size : kSizes) {
    progress.begin(format("%u x %u cloth", size.side, size.side));
    const FrozenCloth cloth = fall_and_freeze(size.side);
    const std::size_t triangles = cloth.triangles.size();
    const std::string thesis_row =
        size.thesis_triangles ? std::to_string(size.thesis_triangles) : std::string("—");

    // the recording: brute force, De Boeck et al.'s reference
    const std::vector<HapticRecord> recording =
        run_proxy(cloth, *fitted_query(cloth, TriangleQueryKind::kBruteForce),
                  sample(cloth, script, updates))
            .records;
    if (recordings) {
      std::filesystem::create_directories(*recordings);
      std::ofstream csv(*recordings / format("haptic_recording_%zu.csv", triangles));
      write_recording_header(csv);
      for (const HapticRecord& r : recording) write_record(csv, r);
    }
    std::size_t contacts = 0, changes = 0;
    std::set<std::int32_t> touched;
    for (std::size_t k = 0; k < recording.size(); ++k) {
      if (!recording[k].in_contact) continue;
      ++contacts;
      touched.insert(recording[k].triangle);
      if (k > 0 && recording[k - 1].in_contact &&
          recording[k - 1].triangle != recording[k].triangle) {
        ++changes;
      }
    }
    const auto [low, high] = std::ranges::minmax(
        cloth.frozen | std::views::transform([](const Vec3& x) { return x.y(); }));
    const double contact_share = 100.0 * static_cast<double>(contacts) / recording.size();
    paths << "| " << format("%u × %u", size.side, size.side) << " | " << triangles << " | "
          << thesis_row << " | " << updates << " | " << format("%.0f %%", contact_share) << " | "
          << touched.size() << " | " << changes << " | " << format("%.2f", high - low) << " |\n";

    const std::vector<Replay> results = replay_all(cloth, recording, repeats);
    for (std::size_t column = 0; column < kStructures.size(); ++column) {
      const TriangleQueryKind kind = kStructures[column];
      const Replay& result = results[column];
      const auto thesis = kThesisTable94.find(size.thesis_triangles);
      const auto thesis_us = [&](int which) {
        return thesis == kThesisTable94.end() ? std::string("—")
                                              : format("%.1f", 1e3 * thesis->second[column][which]);
      };
      const Divergence& d = result.divergence;
      t94 << "| " << thesis_row << " / " << triangles << " | " << to_string(kind) << " | "
          << thesis_us(0) << " | " << thesis_us(1) << " | " << format("%.2f", result.cd_us) << " | "
          << format("%.2f", result.ncd_us) << " | " << d.equivalent << " of " << updates
          << (result.repeatable ? "" : " (repeats differ)") << " | "
          << result.equivalent_in_index_order << " of " << updates << " | " << result.missed
          << " |\n";
      if (d.equivalent < recording.size()) {
        any_divergence = true;
        causes << "| " << triangles << " | " << to_string(kind) << " | "
               << recording.size() - d.equivalent << " | " << d.neighbour << " | " << d.apart
               << (d.apart ? format(" (%.1e m)", d.largest_apart) : "") << " | "
               << d.contact_differs << " | " << d.other << " | " << format("%.1e", d.largest_force)
               << " |\n";
      }
      if (size.thesis_triangles == 0) {
        const double mean = std::accumulate(result.micros.begin(), result.micros.end(), 0.0) /
                            static_cast<double>(result.micros.size());
        largest << "| " << to_string(kind) << " | " << format("%.2f", mean) << " | "
                << format("%.2f", percentile(result.micros, 0.5)) << " | "
                << format("%.2f", percentile(result.micros, 0.99)) << " | "
                << format("%.1f", percentile(result.micros, 1.0)) << " |\n";
      }
    }
    progress.end(format("%zu triangles, %.0f %% in contact", triangles, contact_share));
  }

  std::ostringstream text;
  text << study::generated_by("haptic_replay_results", study::seconds_since(program_start))
       << "\n\nCloths: 1 m × 1 m, 0.5 kg, pinned at the two corners of one edge, let fall from "
          "horizontal for "
       << kFallSteps << " steps of " << kPhysicsStep * 1e3
       << " ms (implicit Euler; the default scene's springs, drag in proportion to the particles' "
          "mass) and frozen. Device: "
       << seconds << " s at 1 kHz of scripted strokes (seed " << kSeed
       << ", the same in every cloth's own coordinates): approach from 8–15 cm, press in, slide "
          "through two more points at 0.15–0.3 m/s, leave, move about 8–15 cm off. Proxy: the "
          "default god-object (radius 2 cm, 400 N/m, force shading, no friction). Recorded with "
          "brute force; each structure built on the flat cloth, refitted once to the frozen one "
          "(from = to, alpha 1) and replayed through a fresh proxy on the recorded positions. "
          "Times: wall time of each update(), the least of "
       << repeats
       << " replays per update (the structures replayed in turn, so that other work on the "
          "machine spreads over all of them); CD = mean over updates that found a contact, N-CD = "
          "over the others. The thesis's times are its ms × 1000.\n\n"
       << "**The recorded paths:**\n\n"
       << paths.str()
       << "\n**Table 9.4 — haptic query time per update, and collision equivalence** (against "
          "the brute-force recording: same contact, body and triangle, proxies within "
       << kTolerance * 1e9
       << " nm; \"in index order\": the structure's candidates handed to the proxy sorted, as "
          "brute force hands them; candidates missed: triangles whose box meets a proxy-sized "
          "box about the recorded device and proxy that collect() did not return):\n\n"
       << t94.str() << "\n**19,602 triangles (100 × 100), per update:**\n\n"
       << largest.str();
  if (any_divergence) {
    text << "\n**Updates that are not collision-equivalent, by kind:**\n\n" << causes.str();
  }
  if (output) std::ofstream(*output) << text.str();
  std::cout << text.str();
  return 0;
}

}  // namespace
}  // namespace felt

int main(int argc, char** argv) {
  return felt::run(argc, argv);
}
