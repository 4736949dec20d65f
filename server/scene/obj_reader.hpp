#pragma once
// Wavefront OBJ -> TriangleMesh: positions, texture coordinates and faces (polygons are
// triangulated as fans). Everything else in the file (normals, groups, materials) is ignored.

#include <expected>
#include <filesystem>
#include <istream>
#include <string>

#include "core/geometry/triangle_mesh.hpp"

namespace felt {

/// Errors name the line: "bunny.obj:12: face index 2000 out of range".
std::expected<TriangleMesh, std::string> read_obj(std::istream& in, const std::string& name);
std::expected<TriangleMesh, std::string> read_obj_file(const std::filesystem::path& file);

}  // namespace felt
