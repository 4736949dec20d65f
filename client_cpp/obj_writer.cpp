#include "obj_writer.hpp"

#include <fstream>

namespace felt::client {

void TriangleCache::update(const felt::v1::Frame& frame) {
  for (const felt::v1::BodyFrame& body : frame.bodies()) {
    if (body.triangles_size() > 0) {
      triangles_[body.body_id()].assign(body.triangles().begin(), body.triangles().end());
    }
  }
}

const std::vector<std::uint32_t>* TriangleCache::find(std::uint32_t body_id) const {
  const auto it = triangles_.find(body_id);
  return it == triangles_.end() ? nullptr : &it->second;
}

bool write_obj(const std::filesystem::path& file, const felt::v1::Frame& frame,
               const TriangleCache& triangles) {
  std::ofstream out(file);
  out << "# felt frame: scene " << frame.scene_id() << ", step " << frame.step()
      << ", t = " << frame.sim_time() << " s\n";
  std::size_t first_vertex = 1;  // OBJ indices are 1-based and global across objects
  for (const felt::v1::BodyFrame& body : frame.bodies()) {
    out << "o " << body.name() << "\n";
    const int vertices = body.positions_size() / 3;
    for (int v = 0; v < vertices; ++v) {
      out << "v " << body.positions(3 * v) << " " << body.positions(3 * v + 1) << " "
          << body.positions(3 * v + 2) << "\n";
    }
    const bool normals = body.normals_size() == body.positions_size();
    if (normals) {
      for (int v = 0; v < vertices; ++v) {
        out << "vn " << body.normals(3 * v) << " " << body.normals(3 * v + 1) << " "
            << body.normals(3 * v + 2) << "\n";
      }
    }
    if (const auto* faces = triangles.find(body.body_id())) {
      for (std::size_t t = 0; t + 2 < faces->size(); t += 3) {
        out << "f";
        for (std::size_t k = 0; k < 3; ++k) {
          const std::size_t index = first_vertex + (*faces)[t + k];
          out << " " << index;
          if (normals) out << "//" << index;
        }
        out << "\n";
      }
    }
    first_vertex += static_cast<std::size_t>(vertices);
  }
  return static_cast<bool>(out);
}

}  // namespace felt::client
