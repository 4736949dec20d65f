#pragma once
// Meshes to files any viewer opens: Wavefront OBJ, PLY (binary), or a VTK PolyData file per
// frame gathered by a ParaView collection (.pvd) into a time series. Shared by `felt watch`
// (streamed frames) and `feltd run --trace` (the server's own bodies), so both write one format.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace felt {

enum class MeshFormat { kObj, kPly, kVtk };

/// "obj", "ply" or "vtk"; false for anything else.
bool parse_mesh_format(const std::string& name, MeshFormat& format);
/// The file extension of one frame: ".obj", ".ply", ".vtp".
const char* mesh_extension(MeshFormat format);

/// One body of a frame, viewed (the caller owns the data).
struct MeshPiece {
  std::string_view name;
  std::span<const float> positions;          ///< x, y, z per vertex
  std::span<const float> normals;            ///< empty, or x, y, z per vertex
  std::span<const float> scalars;            ///< empty, or one per vertex (written as "strain")
  std::span<const std::uint32_t> triangles;  ///< three per triangle; empty: none known
};

/// What one file holds: every body, and a one-line comment saying where it comes from.
struct MeshFrame {
  std::string comment;  ///< e.g. "felt frame: scene 1, step 20, t = 0.02 s"
  std::vector<MeshPiece> pieces;
};

/// Writes every piece of `frame` into one file (OBJ objects, one PLY mesh with the pieces
/// appended, VTK pieces). False when the file cannot be written.
bool write_mesh(const std::filesystem::path& file, const MeshFrame& frame, MeshFormat format);

/// The ParaView collection of a VTK series: each frame file at its simulated time.
bool write_pvd(const std::filesystem::path& file,
               const std::vector<std::pair<double, std::string>>& frames);

}  // namespace felt
