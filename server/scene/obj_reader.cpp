#include "scene/obj_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/math/bounds.hpp"

namespace felt {
namespace {

/// A face corner "v", "v/vt", "v//vn" or "v/vt/vn"; 1-based, negative counts from the end.
bool parse_corner(const std::string& token, long& v, long& vt) {
  vt = 0;
  std::size_t slash = token.find('/');
  try {
    std::size_t used = 0;
    v = std::stol(token.substr(0, slash), &used);
    if (used != (slash == std::string::npos ? token.size() : slash)) return false;
    if (slash != std::string::npos && slash + 1 < token.size() && token[slash + 1] != '/') {
      const std::size_t next = token.find('/', slash + 1);
      vt = std::stol(token.substr(slash + 1, next - slash - 1));
    }
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

/// Resolves a 1-based or negative OBJ index against `count` elements; -1 when out of range.
long resolve(long index, std::size_t count) {
  const long n = static_cast<long>(count);
  const long zero_based = index > 0 ? index - 1 : n + index;
  return index != 0 && zero_based >= 0 && zero_based < n ? zero_based : -1;
}

}  // namespace

std::expected<TriangleMesh, std::string> read_obj(std::istream& in, const std::string& name) {
  TriangleMesh mesh;
  std::vector<Vec2> texcoords;
  std::vector<long> uv_of_vertex;  // the texcoord a vertex was first used with
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    const auto error = [&](const std::string& what) {
      return std::unexpected(name + ":" + std::to_string(number) + ": " + what);
    };
    std::istringstream fields(line);
    std::string tag;
    if (!(fields >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      Vec3 p;
      if (!(fields >> p.x() >> p.y() >> p.z()) || !p.allFinite()) return error("bad vertex");
      // as a scene's coordinates: 1e300 loaded, and its masses and energies became NaN
      if (!within_bounds(p)) return error("vertex coordinate outside ±1e6 m");
      mesh.positions.push_back(p);
      uv_of_vertex.push_back(-1);
    } else if (tag == "vt") {
      Vec2 t;
      if (!(fields >> t.x() >> t.y()) || !t.allFinite()) return error("bad texture coordinate");
      texcoords.push_back(t);
    } else if (tag == "f") {
      std::vector<std::uint32_t> corners;
      std::string token;
      while (fields >> token) {
        long v = 0, vt = 0;
        if (!parse_corner(token, v, vt)) return error("bad face corner \"" + token + "\"");
        const long vertex = resolve(v, mesh.positions.size());
        if (vertex < 0) return error("face index " + std::to_string(v) + " out of range");
        if (vt != 0) {
          const long texcoord = resolve(vt, texcoords.size());
          if (texcoord < 0) return error("texture index " + std::to_string(vt) + " out of range");
          if (uv_of_vertex[vertex] < 0) uv_of_vertex[vertex] = texcoord;
        }
        corners.push_back(static_cast<std::uint32_t>(vertex));
      }
      if (corners.size() < 3) return error("a face needs at least 3 corners");
      for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
        mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
      }
    }
  }
  if (mesh.triangles.empty()) return std::unexpected(name + ": no faces");
  if (!texcoords.empty()) {
    mesh.uv.resize(mesh.positions.size(), Vec2::Zero());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      if (uv_of_vertex[v] >= 0) mesh.uv[v] = texcoords[uv_of_vertex[v]];
    }
  }
  return mesh;
}

std::expected<TriangleMesh, std::string> read_obj_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return std::unexpected("cannot open " + file.filename().string());
  return read_obj(in, file.filename().string());
}

}  // namespace felt
