#include "feltd/run_stats_json.hpp"

#include <span>
#include <utility>

namespace felt::feltd {
namespace {

/// `profile`'s stages of `stages`, in milliseconds, by name.
nlohmann::json stage_ms_to_json(const felt::StepProfile& profile,
                                std::span<const felt::StepStage> stages) {
  nlohmann::json json = nlohmann::json::object();
  for (felt::StepStage stage : stages) json[felt::stage_name(stage)] = 1e3 * profile[stage];
  return json;
}

}  // namespace

nlohmann::json stats_to_json(const felt::BatchRunStats& stats) {
  nlohmann::json bodies = nlohmann::json::array();
  // the scene's size the way the second thesis's Table 7.2 counts it: all solids together
  nlohmann::json solid_totals = {{"nodes", 0}, {"edges", 0},         {"triangles", 0},
                                 {"tets", 0},  {"fine_vertices", 0}, {"fine_triangles", 0}};
  for (const felt::BodyRunStats& body : stats.bodies) {
    nlohmann::json entry = {{"name", body.name},
                            {"kind", body.kind},
                            {"particles", body.particles},
                            {"edges", body.edges},
                            {"triangles", body.triangles},
                            {"tets", body.tets},
                            {"kinetic_energy", body.kinetic_energy},
                            {"substeps", body.substeps},
                            {"rescued_steps", body.rescued_steps},
                            {"over_budget_steps", body.over_budget_steps}};
    if (body.kind == "cloth") {
      entry["max_strain"] = body.max_strain;
    } else {
      entry["fine_vertices"] = body.fine_vertices;
      entry["fine_triangles"] = body.fine_triangles;
      entry["volume_ratio"] = body.volume_ratio;
      for (const auto& [key, count] :
           {std::pair{"nodes", body.particles}, std::pair{"edges", body.edges},
            std::pair{"triangles", body.triangles}, std::pair{"tets", body.tets},
            std::pair{"fine_vertices", body.fine_vertices},
            std::pair{"fine_triangles", body.fine_triangles}}) {
        solid_totals[key] = solid_totals[key].get<std::size_t>() + count;
      }
    }
    bodies.push_back(std::move(entry));
  }
  const felt::SolidRunStats& solids = stats.solids;
  const felt::HapticRunStats& haptics = stats.haptics;
  return {{"steps", stats.steps},
          {"sim_time", stats.sim_time},
          {"wall_seconds", stats.wall_seconds},
          {"cpu_seconds", stats.cpu_seconds},
          {"ms_per_step", stats.ms_per_step},
          {"nonfinite", stats.nonfinite},
          {"rescued_steps", stats.rescued_steps},
          {"unrecoverable_steps", stats.unrecoverable_steps},
          {"over_budget_steps", stats.over_budget_steps},
          {"bodies", bodies},
          {"solids",
           {{"totals", solid_totals},
            {"mean_colliding_nodes", solids.mean_colliding_nodes},
            {"max_colliding_nodes", solids.max_colliding_nodes},
            {"mean_colliding_triangles", solids.mean_colliding_triangles},
            {"max_colliding_triangles", solids.max_colliding_triangles},
            {"max_substeps", solids.max_substeps},
            {"mean_stage_ms", stage_ms_to_json(solids.mean, felt::SolidSystem::kStages)},
            {"max_stage_ms", stage_ms_to_json(solids.max, felt::SolidSystem::kStages)}}},
          {"cloth",
           {{"max_substeps", stats.cloth.max_substeps},
            {"mean_stage_ms", stage_ms_to_json(stats.cloth.mean, felt::ClothSystem::kStages)},
            {"max_stage_ms", stage_ms_to_json(stats.cloth.max, felt::ClothSystem::kStages)}}},
          {"haptics",
           {{"ticks", haptics.ticks},
            {"contact_ticks", haptics.contact_ticks},
            {"mean_contact_us", haptics.mean_contact_us},
            {"mean_free_us", haptics.mean_free_us},
            {"max_force", haptics.max_force},
            {"max_force_step", haptics.max_force_step},
            {"mean_force_step", haptics.mean_force_step},
            {"compared", haptics.compared},
            {"equivalent", haptics.equivalent}}}};
}

}  // namespace felt::feltd
