#pragma once
// Decoded frames to mesh files any viewer opens (OBJ, binary PLY, a VTK series), in the formats
// of the shared mesh writers (common/mesh_files), which `feltd run --trace` writes too.

#include <filesystem>

#include "frame_assembler.hpp"
#include "mesh_files/mesh_writers.hpp"

namespace felt::client {

using felt::mesh_extension;
using felt::MeshFormat;
using felt::parse_mesh_format;
using felt::write_pvd;

/// Writes every body of `frame` into one file (OBJ objects, one PLY mesh with the bodies
/// appended, VTK pieces). False when the file cannot be written.
bool write_frame(const std::filesystem::path& file, const DecodedFrame& frame, MeshFormat format);

}  // namespace felt::client
