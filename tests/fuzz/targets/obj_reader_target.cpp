// The Wavefront OBJ reader (server/scene/obj_reader.*) on any text: a mesh or an error that
// names the file, never anything else. A mesh it reads has finite positions, one texture
// coordinate per position or none, and faces whose corners are positions of the mesh. The same
// bytes, as a scene's mesh file, then become a cloth and a voxelized solid through the scene
// loader (loaded_scene_checks.hpp checks what loads).

#include <sstream>

#include "asset_directory.hpp"
#include "fuzz_target.hpp"
#include "loaded_scene_checks.hpp"
#include "scene/obj_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace felt;
  using namespace felt::fuzz;
  std::istringstream in{std::string(as_text(data, size))};
  const auto mesh = read_obj(in, "fuzz.obj");
  if (!mesh) {
    check(mesh.error().starts_with("fuzz.obj"), "an error names the file");
    return 0;
  }
  check(all_finite(mesh->positions), "positions are finite");
  check(mesh->uv.empty() || mesh->uv.size() == mesh->positions.size(), "one uv per position");
  for (const Triangle& t : mesh->triangles) {
    for (const std::uint32_t corner : t) {
      check(corner < mesh->positions.size(), "a face's corners are positions of the mesh");
    }
  }

  static const AssetDirectory assets;
  assets.write("fuzz.obj", as_text(data, size));
  SceneLoadOptions options = client_load_options();
  options.asset_root = assets.path();
  for (const char* scene_text :
       {R"({"bodies": [{"type": "cloth", "mesh": {"file": "fuzz.obj"}}]})",
        R"({"bodies": [{"type": "solid", "mesh": {"file": "fuzz.obj", "resolution": 4}}]})"}) {
    auto scene = load_scene_text(scene_text, options);
    if (scene) check_loaded_scene(*scene);
  }
  return 0;
}
