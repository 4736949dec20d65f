#pragma once
// TetGen .node and .ele files -> TetMesh: the volumetric meshes the thesis made with TetGen
// (thesis 2 §7.1). '#' starts a comment; attributes and boundary markers are read past;
// numbering starts at the first node's number (0 or 1); only 4-node tetrahedra are accepted.
// Tetrahedra come back positively oriented.

#include <expected>
#include <filesystem>
#include <istream>
#include <string>

#include "core/geometry/tet_mesh.hpp"

namespace felt {

/// Errors name the file and the line: "cube.ele:7: node index 12 out of range".
std::expected<TetMesh, std::string> read_tetgen(std::istream& node, const std::string& node_name,
                                                std::istream& ele, const std::string& ele_name);

/// Reads base.node and base.ele, where `path` is either file or their common base
/// ("meshes/cube", "meshes/cube.node" and "meshes/cube.ele" read the same mesh).
std::expected<TetMesh, std::string> read_tetgen_files(const std::filesystem::path& path);

}  // namespace felt
