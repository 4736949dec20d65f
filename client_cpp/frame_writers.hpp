#pragma once
// Decoded frames to mesh files any viewer opens: Wavefront OBJ, PLY (binary), or a VTK
// PolyData file per frame gathered by a ParaView collection (.pvd) into a time series.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "frame_assembler.hpp"

namespace felt::client {

enum class MeshFormat { kObj, kPly, kVtk };

/// "obj", "ply" or "vtk"; false for anything else.
bool parse_mesh_format(const std::string& name, MeshFormat& format);
/// The file extension of one frame: ".obj", ".ply", ".vtp".
const char* mesh_extension(MeshFormat format);

/// Writes every body of `frame` into one file (OBJ objects, one PLY mesh with the bodies
/// appended, VTK pieces). False when the file cannot be written.
bool write_frame(const std::filesystem::path& file, const DecodedFrame& frame, MeshFormat format);

/// The ParaView collection of a VTK series: each frame file at its simulated time.
bool write_pvd(const std::filesystem::path& file,
               const std::vector<std::pair<double, std::string>>& frames);

}  // namespace felt::client
