// The TetGen reader (server/scene/tetgen_reader.*) on any pair of texts: the input up to its
// first NUL byte is the .node file, the rest the .ele file. It gives a mesh or an error that
// names a file, never anything else; a mesh it reads has finite nodes and tetrahedra whose
// corners are nodes of the mesh, positively oriented. The same files, named by a scene, then
// become a solid through the scene loader (loaded_scene_checks.hpp checks what loads).

#include <sstream>

#include "asset_directory.hpp"
#include "fuzz_target.hpp"
#include "loaded_scene_checks.hpp"
#include "scene/tetgen_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace felt;
  using namespace felt::fuzz;
  const std::string_view input = as_text(data, size);
  const std::size_t split = std::min(input.find('\0'), input.size());
  const std::string_view node_text = input.substr(0, split);
  const std::string_view ele_text = input.substr(std::min(split + 1, input.size()));
  std::istringstream node{std::string(node_text)}, ele{std::string(ele_text)};
  const auto mesh = read_tetgen(node, "fuzz.node", ele, "fuzz.ele");
  if (!mesh) {
    check(mesh.error().starts_with("fuzz.node") || mesh.error().starts_with("fuzz.ele"),
          "an error names the file");
    return 0;
  }
  check(all_finite(mesh->nodes), "nodes are finite");
  for (const Tetrahedron& t : mesh->tets) {
    for (const std::uint32_t corner : t) {
      check(corner < mesh->nodes.size(), "a tetrahedron's corners are nodes of the mesh");
    }
    check(signed_volume(mesh->nodes, t) >= 0, "tetrahedra are positively oriented");
  }

  static const AssetDirectory assets;
  assets.write("fuzz.node", node_text);
  assets.write("fuzz.ele", ele_text);
  SceneLoadOptions options = client_load_options();
  options.asset_root = assets.path();
  auto scene = load_scene_text(
      R"({"bodies": [{"type": "solid", "tetgen": {"file": "fuzz.node"}}]})", options);
  if (scene) check_loaded_scene(*scene);
  return 0;
}
