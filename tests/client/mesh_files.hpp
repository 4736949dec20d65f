#pragma once
// Reads back what felt's frame writers wrote (OBJ, binary PLY, VTK PolyData .vtp and the .pvd
// collection), independently of them, for tests to compare with what was written.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace felt::test {

/// Every body of a file, their vertices one after the other.
struct MeshFile {
  std::vector<std::string> names;  ///< OBJ objects, VTK pieces (none in PLY)
  std::vector<std::array<float, 3>> vertices;
  std::vector<std::array<float, 3>> normals;            ///< empty when the file has none
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< 0-based indices into vertices
};

/// By the extension: .obj, .ply or .vtp. Throws std::runtime_error on what it cannot read.
MeshFile read_mesh_file(const std::filesystem::path& file);

/// A .pvd collection's data sets: (timestep, file) in order.
std::vector<std::pair<double, std::string>> read_pvd(const std::filesystem::path& file);

}  // namespace felt::test
