#pragma once
// A scene directory of the fuzz target's own, for mesh files written from its input: the
// loader reads meshes only from files inside its asset root, so an input goes through the
// same path as a mesh a scene names.

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace felt::fuzz {

class AssetDirectory {
 public:
  AssetDirectory() {
    std::string pattern = (std::filesystem::temp_directory_path() / "felt-fuzz-XXXXXX").string();
    if (::mkdtemp(pattern.data()) != nullptr) path_ = pattern;
  }
  ~AssetDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  AssetDirectory(const AssetDirectory&) = delete;
  AssetDirectory& operator=(const AssetDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// Writes `bytes` as the file `name` in the directory.
  void write(const std::string& name, std::string_view bytes) const {
    std::ofstream(path_ / name, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }

 private:
  std::filesystem::path path_;
};

}  // namespace felt::fuzz
