// The second thesis's scene format (server/scene/thesis_scene_reader.*) on any text: it gives
// a JSON scene or an error that names the line, never anything else; a scene it gives is then
// loaded as a client's (meshes from scenes/) and checked as the scene target checks it.

#include <nlohmann/json.hpp>

#include "fuzz_target.hpp"
#include "loaded_scene_checks.hpp"
#include "scene/thesis_scene_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace felt;
  using namespace felt::fuzz;
  const auto document = thesis_scene_to_json(as_text(data, size), "fuzz.cfg");
  if (!document) {
    check(document.error().what().starts_with("fuzz.cfg"), "an error names the file");
    return 0;
  }
  auto scene = load_scene(*document, client_load_options());
  if (scene) check_loaded_scene(*scene);
  return 0;
}
