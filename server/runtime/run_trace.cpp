#include "runtime/run_trace.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <limits>
#include <sstream>

#include "core/cloth/vertex_strain.hpp"
#include "core/world/state_hash.hpp"
#include "mesh_files/mesh_writers.hpp"
#include "runtime/body_measures.hpp"

namespace felt {
namespace {

constexpr const char* kHeader =
    "step,time,body_id,body,kinetic,elastic,gravitational,energy,drift,com_x,com_y,com_z,min_x,"
    "min_y,min_z,max_x,max_y,max_z,max_speed,max_strain,max_compression,substeps,rescued,"
    "unrecoverable,state_hash\n";

/// A body's name as one CSV field: quoted, with its quotes doubled (RFC 4180).
std::string csv_field(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::vector<float> to_floats(std::span<const Vec3> x) {
  std::vector<float> out;
  out.reserve(3 * x.size());
  for (const Vec3& p : x) {
    for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(p[k]));
  }
  return out;
}

std::vector<std::uint32_t> flatten(std::span<const Triangle> triangles) {
  std::vector<std::uint32_t> out;
  out.reserve(3 * triangles.size());
  for (const Triangle& t : triangles) out.insert(out.end(), t.begin(), t.end());
  return out;
}

/// What one body contributes to a frame; owns the data its MeshPiece views.
struct FramePiece {
  std::string name;
  std::vector<float> positions, strain;
  std::vector<std::uint32_t> triangles;
};

}  // namespace

RunTrace::RunTrace(std::filesystem::path dir, std::string scene_name, std::uint64_t every)
    : dir_(std::move(dir)),
      scene_name_(std::move(scene_name)),
      every_(std::max<std::uint64_t>(1, every)) {}

std::expected<RunTrace, std::string> RunTrace::open(const std::filesystem::path& dir,
                                                    std::string scene_name, std::uint64_t every) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return std::unexpected("cannot create " + dir.string() + ": " + ec.message());
  RunTrace trace(dir, std::move(scene_name), every);
  trace.csv_.open(dir / "trace.csv");
  trace.csv_ << kHeader;
  if (!trace.csv_) return std::unexpected("cannot write " + (dir / "trace.csv").string());
  // every digit: the drift of a long run is a small difference of large energies
  trace.csv_.precision(std::numeric_limits<Real>::max_digits10);
  return trace;
}

bool RunTrace::fail(std::string why) {
  if (error_.empty()) error_ = std::move(why);
  return false;
}

bool RunTrace::record(const World& world, const StepReport& report) {
  if (!error_.empty()) return false;
  write_rows(world, report);
  if (!csv_) return fail("cannot write " + (dir_ / "trace.csv").string());
  if (world.step_count() % every_ == 0) return write_frame(world);
  return true;
}

void RunTrace::write_rows(const World& world, const StepReport& report) {
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016" PRIx64, state_hash(world));
  std::size_t index = 0;
  for (BodyId id : world.body_ids()) {
    const BodyRef& ref = world.body_ref(id);
    if (ref.kind == BodyRef::Kind::kCollider) continue;
    const bool cloth = ref.kind == BodyRef::Kind::kCloth;
    const BodyMeasures m =
        cloth ? measure_body(world.cloths()[ref.index])
              : measure_body(world.solids().bodies()[ref.index], world.settings().gravity);
    const std::string& name =
        cloth ? world.cloths()[ref.index].name() : world.solids().bodies()[ref.index].name();
    if (start_energy_.size() <= index) start_energy_.push_back(m.energy());
    const bool unrecoverable =
        std::ranges::find(report.unrecoverable_bodies, id) != report.unrecoverable_bodies.end();
    csv_ << world.step_count() << ',' << world.time() << ',' << id << ',' << csv_field(name) << ','
         << m.kinetic << ',' << m.elastic << ',' << m.gravitational << ',' << m.energy() << ','
         << m.energy() - start_energy_[index];
    for (const Vec3* v : {&m.centre_of_mass, &m.lower, &m.upper}) {
      csv_ << ',' << v->x() << ',' << v->y() << ',' << v->z();
    }
    csv_ << ',' << m.max_speed << ',' << m.max_strain << ',' << m.max_compression << ','
         << world.step_counts(id).substeps << ',' << (report.flags.has(StepFlag::kRescued) ? 1 : 0)
         << ',' << (unrecoverable ? 1 : 0) << ',' << hash << '\n';
    ++index;
  }
}

bool RunTrace::write_frame(const World& world) {
  std::vector<FramePiece> pieces;
  for (BodyId id : world.body_ids()) {
    const BodyRef& ref = world.body_ref(id);
    if (ref.kind == BodyRef::Kind::kCloth) {
      const ClothBody& body = world.cloths()[ref.index];
      FramePiece& piece = pieces.emplace_back();
      piece.name = body.name();
      piece.positions = to_floats(body.state().x);
      piece.triangles = flatten(body.model().triangles);
      vertex_strain(body.model(), body.state().x, piece.strain);
    } else if (ref.kind == BodyRef::Kind::kSolid) {
      const SolidBody& body = world.solids().bodies()[ref.index];
      FramePiece& piece = pieces.emplace_back();
      piece.name = body.name();
      piece.positions = to_floats(body.positions());
      piece.triangles = flatten(body.topology().surface);
    }
  }
  std::ostringstream comment;
  comment << "felt trace: scene " << scene_name_ << ", step " << world.step_count()
          << ", t = " << world.time() << " s";
  MeshFrame frame{comment.str(), {}};
  for (const FramePiece& p : pieces) {
    frame.pieces.push_back({p.name, p.positions, {}, p.strain, p.triangles});
  }
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05zu.vtp", frames_.size());
  if (!write_mesh(dir_ / name, frame, MeshFormat::kVtk)) {
    return fail("cannot write " + (dir_ / name).string());
  }
  frames_.emplace_back(world.time(), name);
  return true;
}

bool RunTrace::finish() {
  if (!error_.empty()) return false;
  csv_.flush();
  if (!csv_) return fail("cannot write " + (dir_ / "trace.csv").string());
  if (!write_pvd(dir_ / "frames.pvd", frames_)) {
    return fail("cannot write " + (dir_ / "frames.pvd").string());
  }
  return true;
}

}  // namespace felt
