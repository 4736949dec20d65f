#pragma once
// Frames to Wavefront OBJ files, one file per frame with every body as an object.

#include <cstdint>
#include <filesystem>
#include <map>
#include <vector>

#include "felt/v1/frames.pb.h"

namespace felt::client {

/// Remembers each body's triangles: the server sends them only in the first frame of a
/// subscription (and when they change).
class TriangleCache {
 public:
  void update(const felt::v1::Frame& frame);
  const std::vector<std::uint32_t>* find(std::uint32_t body_id) const;

 private:
  std::map<std::uint32_t, std::vector<std::uint32_t>> triangles_;
};

/// Writes `frame` as OBJ (vertices, vertex normals when present, faces). Returns false when the
/// file cannot be written.
bool write_obj(const std::filesystem::path& file, const felt::v1::Frame& frame,
               const TriangleCache& triangles);

}  // namespace felt::client
