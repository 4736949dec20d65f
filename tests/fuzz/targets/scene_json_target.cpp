// The scene loader (server/scene/scene_loader.*) on any text, as a client may send it in
// LoadScene or AddBody: it returns a scene or an error that names where, never anything else;
// a scene it returns keeps to a client's particle budget and steps without anything non-finite
// (loaded_scene_checks.hpp). Each body entry of a document is also loaded alone, as AddBody
// loads it.

#include <nlohmann/json.hpp>

#include "fuzz_target.hpp"
#include "loaded_scene_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace felt;
  using namespace felt::fuzz;
  const auto document = parse_json(as_text(data, size), "fuzz.json");
  if (!document) {
    check(!document.error().message.empty(), "a parse error says why");
    return 0;
  }
  const SceneLoadOptions options = client_load_options();
  auto scene = load_scene(*document, options);
  if (scene) {
    check_loaded_scene(*scene);
  } else {
    check(!scene.error().what().empty(), "a refused scene says why");
  }
  if (document->is_object() && document->contains("bodies") && (*document)["bodies"].is_array()) {
    const auto& bodies = (*document)["bodies"];
    for (std::size_t i = 0; i < bodies.size() && i < 4; ++i) {
      const auto body = load_body(bodies[i], "body", i, 1e-3, options);
      if (!body) check(!body.error().what().empty(), "a refused body says why");
    }
  }
  return 0;
}
