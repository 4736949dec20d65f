#include "mesh_files/mesh_writers.hpp"

#include <cstdint>
#include <fstream>
#include <limits>
#include <span>

namespace felt {
namespace {

std::size_t vertex_count(const MeshPiece& body) {
  return body.positions.size() / 3;
}

std::size_t triangle_count(const MeshPiece& body) {
  return body.triangles.size() / 3;
}

bool has_normals(const MeshPiece& body) {
  return !body.normals.empty() && body.normals.size() == body.positions.size();
}

/// `text` as an XML attribute value (a body's name is the scene's free text).
std::string xml_escaped(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

bool write_obj(std::ofstream& out, const MeshFrame& frame) {
  out.precision(std::numeric_limits<float>::max_digits10);  // the frame's floats, exactly
  out << "# " << frame.comment << "\n";
  std::size_t first_vertex = 1;  // OBJ indices are 1-based and global across objects
  for (const MeshPiece& body : frame.pieces) {
    out << "o " << body.name << "\n";
    const std::span<const float> x = body.positions;
    for (std::size_t i = 0; i + 2 < x.size(); i += 3) {
      out << "v " << x[i] << " " << x[i + 1] << " " << x[i + 2] << "\n";
    }
    const bool normals = has_normals(body);
    for (std::size_t i = 0; normals && i + 2 < x.size(); i += 3) {
      out << "vn " << body.normals[i] << " " << body.normals[i + 1] << " " << body.normals[i + 2]
          << "\n";
    }
    for (std::size_t t = 0; t + 2 < body.triangles.size(); t += 3) {
      out << "f";
      for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t index = first_vertex + body.triangles[t + k];
        out << " " << index;
        if (normals) out << "//" << index;
      }
      out << "\n";
    }
    first_vertex += vertex_count(body);
  }
  return static_cast<bool>(out);
}

template <class T>
void put(std::ofstream& out, T value) {
  // PLY binary_little_endian; every machine Felt builds on is little endian
  out.write(reinterpret_cast<const char*>(&value), sizeof value);
}

bool write_ply(std::ofstream& out, const MeshFrame& frame) {
  std::size_t vertices = 0, faces = 0;
  bool normals = !frame.pieces.empty();
  for (const MeshPiece& body : frame.pieces) {
    vertices += vertex_count(body);
    faces += triangle_count(body);
    normals = normals && has_normals(body);
  }
  out << "ply\nformat binary_little_endian 1.0\n"
      << "comment " << frame.comment << "\n"
      << "element vertex " << vertices
      << "\nproperty float x\nproperty float y\nproperty float z\n";
  if (normals) out << "property float nx\nproperty float ny\nproperty float nz\n";
  out << "element face " << faces << "\nproperty list uchar uint vertex_indices\nend_header\n";
  for (const MeshPiece& body : frame.pieces) {
    for (std::size_t v = 0; v < vertex_count(body); ++v) {
      for (int k = 0; k < 3; ++k) put(out, body.positions[3 * v + k]);
      for (int k = 0; normals && k < 3; ++k) put(out, body.normals[3 * v + k]);
    }
  }
  std::uint32_t first_vertex = 0;
  for (const MeshPiece& body : frame.pieces) {
    for (std::size_t t = 0; t + 2 < body.triangles.size(); t += 3) {
      put(out, std::uint8_t{3});
      for (int k = 0; k < 3; ++k) put(out, first_vertex + body.triangles[t + k]);
    }
    first_vertex += static_cast<std::uint32_t>(vertex_count(body));
  }
  return static_cast<bool>(out);
}

bool write_vtp(std::ofstream& out, const MeshFrame& frame) {
  out.precision(std::numeric_limits<float>::max_digits10);  // the frame's floats, exactly
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<!-- " << frame.comment << " -->\n<PolyData>\n";
  for (const MeshPiece& body : frame.pieces) {
    const std::size_t triangles = triangle_count(body);
    out << "<Piece Name=\"" << xml_escaped(body.name) << "\" NumberOfPoints=\""
        << vertex_count(body) << "\" NumberOfPolys=\"" << triangles << "\">\n";
    const bool scalars = body.scalars.size() == vertex_count(body);
    if (has_normals(body) || scalars) {
      out << "<PointData" << (has_normals(body) ? " Normals=\"Normals\"" : "")
          << (scalars ? " Scalars=\"strain\"" : "") << ">\n";
      if (has_normals(body)) {
        out << "<DataArray type=\"Float32\" Name=\"Normals\" NumberOfComponents=\"3\" "
               "format=\"ascii\">\n";
        for (float n : body.normals) out << n << " ";
        out << "\n</DataArray>\n";
      }
      if (scalars) {
        out << "<DataArray type=\"Float32\" Name=\"strain\" format=\"ascii\">\n";
        for (float s : body.scalars) out << s << " ";
        out << "\n</DataArray>\n";
      }
      out << "</PointData>\n";
    }
    out << "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (float x : body.positions) out << x << " ";
    out << "\n</DataArray></Points>\n<Polys>\n"
        << "<DataArray type=\"UInt32\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < 3 * triangles; ++i) out << body.triangles[i] << " ";
    out << "\n</DataArray>\n<DataArray type=\"UInt32\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t t = 1; t <= triangles; ++t) out << 3 * t << " ";
    out << "\n</DataArray>\n</Polys>\n</Piece>\n";
  }
  out << "</PolyData>\n</VTKFile>\n";
  return static_cast<bool>(out);
}

}  // namespace

bool parse_mesh_format(const std::string& name, MeshFormat& format) {
  if (name == "obj")
    format = MeshFormat::kObj;
  else if (name == "ply")
    format = MeshFormat::kPly;
  else if (name == "vtk")
    format = MeshFormat::kVtk;
  else
    return false;
  return true;
}

const char* mesh_extension(MeshFormat format) {
  switch (format) {
    case MeshFormat::kObj:
      return ".obj";
    case MeshFormat::kPly:
      return ".ply";
    case MeshFormat::kVtk:
      return ".vtp";
  }
  return "";
}

bool write_mesh(const std::filesystem::path& file, const MeshFrame& frame, MeshFormat format) {
  std::ofstream out(file, std::ios::binary);
  if (!out) return false;
  switch (format) {
    case MeshFormat::kObj:
      return write_obj(out, frame);
    case MeshFormat::kPly:
      return write_ply(out, frame);
    case MeshFormat::kVtk:
      return write_vtp(out, frame);
  }
  return false;
}

bool write_pvd(const std::filesystem::path& file,
               const std::vector<std::pair<double, std::string>>& frames) {
  std::ofstream out(file);
  // every digit: a scene that has run for hours has frames 1/60 s apart at 5 significant digits
  out.precision(std::numeric_limits<double>::max_digits10);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [time, name] : frames) {
    out << "<DataSet timestep=\"" << time << "\" part=\"0\" file=\"" << xml_escaped(name)
        << "\"/>\n";
  }
  out << "</Collection>\n</VTKFile>\n";
  return static_cast<bool>(out);
}

}  // namespace felt
