#pragma once
// Which file of the page's build folder a URL names. Only files inside that folder are ever
// served: a path with a "." or ".." part, or one that leads (through links) outside it, names
// nothing.

#include <filesystem>
#include <optional>
#include <string_view>

namespace felt::net {

struct PageFile {
  std::filesystem::path path;
  std::string_view content_type;
};

/// The file of `root` that the request target `target` names ("/" is index.html; a query or
/// fragment is ignored), with its content type; nothing for any other target.
std::optional<PageFile> page_file(const std::filesystem::path& root, std::string_view target);

}  // namespace felt::net
