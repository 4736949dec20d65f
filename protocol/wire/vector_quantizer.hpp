#pragma once
// Vertex buffers at 16 bits a coordinate, and as changes against an earlier buffer: the
// encodings of felt.v1.QuantizedVectors (frames.proto). Pure, shared by the server and the
// client, so both sides are tested against each other without sockets.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace felt::wire {

inline constexpr std::uint32_t kQuantizedMax = 65535;

/// Per-axis bounds the 16-bit values span: x = lower + q · (upper − lower) / 65535.
struct QuantizationBounds {
  std::array<float, 3> lower{0, 0, 0};
  std::array<float, 3> upper{0, 0, 0};
};

/// Bounds around `xyz` (x, y, z per vector) grown by `margin` of the extent on each side and by
/// at least `min_margin`, so that later frames of a moving body still fit for a while.
QuantizationBounds bounds_around(std::span<const float> xyz, float margin, float min_margin);
/// Whether every coordinate lies inside the bounds.
bool fits(std::span<const float> xyz, const QuantizationBounds& bounds);

/// Rounds each coordinate to the nearest 16-bit step of the bounds (clamped to them).
void quantize(std::span<const float> xyz, const QuantizationBounds& bounds,
              std::vector<std::uint16_t>& q);
void dequantize(std::span<const std::uint16_t> q, const QuantizationBounds& bounds,
                std::vector<float>& xyz);

/// Key frame bytes: each value as uint16 little endian.
void append_values(std::span<const std::uint16_t> q, std::string& bytes);
/// False when the byte count is not `count` values.
bool read_values(std::string_view bytes, std::size_t count, std::vector<std::uint16_t>& q);

/// Delta bytes: per value i, the zigzag varint of (q[i] − base[i]) − (q[i−3] − base[i−3]) (the
/// previous vertex's change of the same coordinate; 0 for the first vertex), so that a body
/// whose neighbouring vertices move alike costs about a byte a coordinate.
void append_deltas(std::span<const std::uint16_t> q, std::span<const std::uint16_t> base,
                   std::string& bytes);
/// False when the bytes are not exactly base.size() varints, or a value leaves 0 ... 65535.
bool read_deltas(std::string_view bytes, std::span<const std::uint16_t> base,
                 std::vector<std::uint16_t>& q);

}  // namespace felt::wire
