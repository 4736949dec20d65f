#include "wire/vector_quantizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace felt::wire {

QuantizationBounds bounds_around(std::span<const float> xyz, float margin, float min_margin) {
  QuantizationBounds bounds;
  for (int axis = 0; axis < 3; ++axis) {
    float lo = std::numeric_limits<float>::max();
    float hi = std::numeric_limits<float>::lowest();
    for (std::size_t i = static_cast<std::size_t>(axis); i < xyz.size(); i += 3) {
      lo = std::min(lo, xyz[i]);
      hi = std::max(hi, xyz[i]);
    }
    if (lo > hi) lo = hi = 0;  // no vectors
    const float grow = std::max(margin * (hi - lo), min_margin);
    bounds.lower[axis] = lo - grow;
    bounds.upper[axis] = hi + grow;
  }
  return bounds;
}

bool fits(std::span<const float> xyz, const QuantizationBounds& bounds) {
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    const int axis = static_cast<int>(i % 3);
    if (!(xyz[i] >= bounds.lower[axis] && xyz[i] <= bounds.upper[axis])) return false;
  }
  return true;
}

void quantize(std::span<const float> xyz, const QuantizationBounds& bounds,
              std::vector<std::uint16_t>& q) {
  q.resize(xyz.size());
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    const int axis = static_cast<int>(i % 3);
    const double extent = double{bounds.upper[axis]} - bounds.lower[axis];
    const double t = extent > 0 ? (double{xyz[i]} - bounds.lower[axis]) / extent : 0;
    const double steps = std::round(std::clamp(t, 0.0, 1.0) * kQuantizedMax);
    q[i] = static_cast<std::uint16_t>(steps);
  }
}

void dequantize(std::span<const std::uint16_t> q, const QuantizationBounds& bounds,
                std::vector<float>& xyz) {
  xyz.resize(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    const int axis = static_cast<int>(i % 3);
    const double extent = double{bounds.upper[axis]} - bounds.lower[axis];
    xyz[i] = static_cast<float>(bounds.lower[axis] + q[i] * extent / kQuantizedMax);
  }
}

void append_values(std::span<const std::uint16_t> q, std::string& bytes) {
  bytes.reserve(bytes.size() + 2 * q.size());
  for (std::uint16_t v : q) {
    bytes.push_back(static_cast<char>(v & 0xff));
    bytes.push_back(static_cast<char>(v >> 8));
  }
}

bool read_values(std::string_view bytes, std::size_t count, std::vector<std::uint16_t>& q) {
  if (bytes.size() != 2 * count) return false;
  q.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    q[i] = static_cast<std::uint16_t>(static_cast<unsigned char>(bytes[2 * i]) |
                                      (static_cast<unsigned char>(bytes[2 * i + 1]) << 8));
  }
  return true;
}

void append_deltas(std::span<const std::uint16_t> q, std::span<const std::uint16_t> base,
                   std::string& bytes) {
  for (std::size_t i = 0; i < q.size(); ++i) {
    // neighbouring vertices (in index order) move alike: send the change of this coordinate
    // less the change of the previous vertex's same coordinate
    const std::int32_t d = std::int32_t{q[i]} - std::int32_t{base[i]} -
                           (i >= 3 ? std::int32_t{q[i - 3]} - std::int32_t{base[i - 3]} : 0);
    // zigzag: small magnitudes of either sign become small unsigned numbers
    std::uint32_t z = (static_cast<std::uint32_t>(d) << 1) ^ static_cast<std::uint32_t>(d >> 31);
    while (z >= 0x80) {
      bytes.push_back(static_cast<char>((z & 0x7f) | 0x80));
      z >>= 7;
    }
    bytes.push_back(static_cast<char>(z));
  }
}

bool read_deltas(std::string_view bytes, std::span<const std::uint16_t> base,
                 std::vector<std::uint16_t>& q) {
  q.resize(base.size());
  std::size_t at = 0;
  for (std::size_t i = 0; i < base.size(); ++i) {
    std::uint32_t z = 0;
    // a difference of two 16-bit changes needs at most 18 bits: three varint bytes
    for (int shift = 0;; shift += 7) {
      if (at == bytes.size() || shift > 14) return false;
      const auto byte = static_cast<unsigned char>(bytes[at++]);
      z |= std::uint32_t{byte & 0x7fu} << shift;
      if ((byte & 0x80) == 0) break;
    }
    const std::int32_t d = static_cast<std::int32_t>(z >> 1) ^ -static_cast<std::int32_t>(z & 1);
    const std::int32_t previous = i >= 3 ? std::int32_t{q[i - 3]} - std::int32_t{base[i - 3]} : 0;
    const std::int32_t v = std::int32_t{base[i]} + previous + d;
    if (v < 0 || v > static_cast<std::int32_t>(kQuantizedMax)) return false;
    q[i] = static_cast<std::uint16_t>(v);
  }
  return at == bytes.size();
}

}  // namespace felt::wire
