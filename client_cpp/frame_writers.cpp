#include "frame_writers.hpp"

#include <sstream>

namespace felt::client {

bool write_frame(const std::filesystem::path& file, const DecodedFrame& frame, MeshFormat format) {
  std::ostringstream comment;
  comment << "felt frame: scene " << frame.scene_id << ", step " << frame.step
          << ", t = " << frame.sim_time << " s";
  MeshFrame mesh{comment.str(), {}};
  for (const DecodedBody& body : frame.bodies) {
    mesh.pieces.push_back({body.name, body.positions, body.normals, body.scalars,
                           body.triangles ? std::span<const std::uint32_t>(*body.triangles)
                                          : std::span<const std::uint32_t>()});
  }
  return write_mesh(file, mesh, format);
}

}  // namespace felt::client
