#include "mesh_files.hpp"

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace felt::test {
namespace {

std::string contents(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::runtime_error bad(const std::filesystem::path& file, const std::string& why) {
  return std::runtime_error(file.string() + ": " + why);
}

/// "a//b", "a/b/c" or "a": the vertex index (1-based in OBJ).
std::uint32_t obj_index(const std::string& corner) {
  return static_cast<std::uint32_t>(std::stoul(corner.substr(0, corner.find('/'))));
}

MeshFile read_obj(const std::filesystem::path& file) {
  MeshFile mesh;
  std::istringstream in(contents(file));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string kind;
    fields >> kind;
    if (kind == "o") {
      mesh.names.push_back(line.substr(2));
    } else if (kind == "v" || kind == "vn") {
      std::array<float, 3> v;
      if (!(fields >> v[0] >> v[1] >> v[2])) throw bad(file, "bad line: " + line);
      (kind == "v" ? mesh.vertices : mesh.normals).push_back(v);
    } else if (kind == "f") {
      std::array<std::string, 3> corners;
      if (!(fields >> corners[0] >> corners[1] >> corners[2])) throw bad(file, "bad " + line);
      std::array<std::uint32_t, 3> t;
      for (int k = 0; k < 3; ++k) t[k] = obj_index(corners[k]) - 1;
      mesh.triangles.push_back(t);
    }
  }
  return mesh;
}

template <class T>
T take(const std::string& bytes, std::size_t& at) {
  if (at + sizeof(T) > bytes.size()) throw std::runtime_error("the PLY data ends early");
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  at += sizeof(T);
  return value;
}

MeshFile read_ply(const std::filesystem::path& file) {
  const std::string bytes = contents(file);
  const std::size_t header_end = bytes.find("end_header\n");
  if (bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0) != 0 ||
      header_end == std::string::npos) {
    throw bad(file, "not a binary little-endian PLY");
  }
  std::istringstream header(bytes.substr(0, header_end));
  std::size_t vertices = 0, faces = 0;
  std::vector<std::string> vertex_properties;
  std::string line, element;
  while (std::getline(header, line)) {
    std::istringstream fields(line);
    std::string word, type, name;
    fields >> word;
    if (word == "element") {
      fields >> element >> (element == "vertex" ? vertices : faces);
    } else if (word == "property" && element == "vertex") {
      fields >> type >> name;
      if (type != "float") throw bad(file, "vertex property " + name + " is not a float");
      vertex_properties.push_back(name);
    } else if (word == "property" && line != "property list uchar uint vertex_indices") {
      throw bad(file, "unexpected " + line);
    }
  }
  const bool normals = vertex_properties.size() == 6;
  if (vertex_properties.size() != 3 && !normals) throw bad(file, "unexpected vertex properties");
  MeshFile mesh;
  std::size_t at = header_end + std::strlen("end_header\n");
  for (std::size_t v = 0; v < vertices; ++v) {
    std::array<float, 3> x, n;
    for (float& value : x) value = take<float>(bytes, at);
    mesh.vertices.push_back(x);
    if (!normals) continue;
    for (float& value : n) value = take<float>(bytes, at);
    mesh.normals.push_back(n);
  }
  for (std::size_t f = 0; f < faces; ++f) {
    if (take<std::uint8_t>(bytes, at) != 3) throw bad(file, "a face that is not a triangle");
    std::array<std::uint32_t, 3> t;
    for (std::uint32_t& index : t) index = take<std::uint32_t>(bytes, at);
    mesh.triangles.push_back(t);
  }
  if (at != bytes.size()) throw bad(file, "bytes after the last face");
  return mesh;
}

std::string xml_unescaped(std::string text) {
  const std::pair<const char*, char> entities[] = {
      {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}, {"&amp;", '&'}};
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    bool replaced = false;
    for (const auto& [entity, c] : entities) {
      if (text.compare(i, std::strlen(entity), entity) == 0) {
        out += c;
        i += std::strlen(entity) - 1;
        replaced = true;
        break;
      }
    }
    if (!replaced) out += text[i];
  }
  return out;
}

/// The value of attribute `name` in the start tag that begins at `tag` of `text`.
std::string attribute(const std::string& text, std::size_t tag, const std::string& name) {
  const std::size_t tag_end = text.find('>', tag);
  const std::size_t at = text.find(" " + name + "=\"", tag);
  if (at == std::string::npos || at > tag_end) return "";
  const std::size_t value = at + name.size() + 3;
  return xml_unescaped(text.substr(value, text.find('"', value) - value));
}

/// The numbers of the first DataArray of `piece` whose start tag contains `marker`.
template <class T>
std::vector<T> data_array(const std::string& piece, const std::string& marker) {
  const std::size_t at = piece.find(marker);
  if (at == std::string::npos) return {};
  const std::size_t begin = piece.find('>', at + marker.size()) + 1;
  std::istringstream in(piece.substr(begin, piece.find("</DataArray>", begin) - begin));
  std::vector<T> values;
  for (T value; in >> value;) values.push_back(value);
  return values;
}

MeshFile read_vtp(const std::filesystem::path& file) {
  const std::string text = contents(file);
  MeshFile mesh;
  for (std::size_t tag = text.find("<Piece "); tag != std::string::npos;
       tag = text.find("<Piece ", tag + 1)) {
    const std::string piece = text.substr(tag, text.find("</Piece>", tag) - tag);
    const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
    const auto points = data_array<float>(piece, "<Points><DataArray");
    const auto normals = data_array<float>(piece, "Name=\"Normals\" NumberOfComponents");
    const auto connectivity = data_array<std::uint32_t>(piece, "Name=\"connectivity\"");
    const auto offsets = data_array<std::uint32_t>(piece, "Name=\"offsets\"");
    if (points.size() != 3 * std::stoul(attribute(text, tag, "NumberOfPoints")) ||
        offsets.size() != std::stoul(attribute(text, tag, "NumberOfPolys"))) {
      throw bad(file, "a piece whose counts do not match its data");
    }
    mesh.names.push_back(attribute(text, tag, "Name"));
    for (std::size_t i = 0; i + 2 < points.size(); i += 3) {
      mesh.vertices.push_back({points[i], points[i + 1], points[i + 2]});
    }
    for (std::size_t i = 0; i + 2 < normals.size(); i += 3) {
      mesh.normals.push_back({normals[i], normals[i + 1], normals[i + 2]});
    }
    for (std::size_t t = 0; t < offsets.size(); ++t) {
      if (offsets[t] != 3 * (t + 1)) throw bad(file, "a polygon that is not a triangle");
      mesh.triangles.push_back({first + connectivity.at(3 * t), first + connectivity.at(3 * t + 1),
                                first + connectivity.at(3 * t + 2)});
    }
  }
  return mesh;
}

}  // namespace

MeshFile read_mesh_file(const std::filesystem::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".obj") return read_obj(file);
  if (extension == ".ply") return read_ply(file);
  if (extension == ".vtp") return read_vtp(file);
  throw bad(file, "not an .obj, .ply or .vtp file");
}

std::vector<std::pair<double, std::string>> read_pvd(const std::filesystem::path& file) {
  const std::string text = contents(file);
  std::vector<std::pair<double, std::string>> sets;
  for (std::size_t tag = text.find("<DataSet "); tag != std::string::npos;
       tag = text.find("<DataSet ", tag + 1)) {
    sets.emplace_back(std::stod(attribute(text, tag, "timestep")), attribute(text, tag, "file"));
  }
  return sets;
}

}  // namespace felt::test
