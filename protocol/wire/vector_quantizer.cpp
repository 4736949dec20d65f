#include "wire/vector_quantizer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace felt::wire {
namespace {

/// The axis after `k` (x, y, z, x, ...), without a division per value.
std::size_t next_axis(std::size_t k) {
  return k == 2 ? 0 : k + 1;
}

}  // namespace

QuantizationBounds bounds_around(std::span<const float> xyz, float margin, float min_margin) {
  std::array<float, 3> lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                          std::numeric_limits<float>::max()};
  std::array<float, 3> hi{std::numeric_limits<float>::lowest(),
                          std::numeric_limits<float>::lowest(),
                          std::numeric_limits<float>::lowest()};
  // a vector at a time, the three axes in registers; the values past the last whole vector
  // (none for vertex buffers) after
  const std::size_t whole = xyz.size() - xyz.size() % 3;
  for (std::size_t i = 0; i < whole; i += 3) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = xyz[i + k] < lo[k] ? xyz[i + k] : lo[k];
      hi[k] = xyz[i + k] > hi[k] ? xyz[i + k] : hi[k];
    }
  }
  for (std::size_t i = whole, k = 0; i < xyz.size(); ++i, ++k) {
    lo[k] = std::min(lo[k], xyz[i]);
    hi[k] = std::max(hi[k], xyz[i]);
  }
  QuantizationBounds bounds;
  for (int k = 0; k < 3; ++k) {
    if (lo[k] > hi[k]) lo[k] = hi[k] = 0;  // no vectors
    const float grow = std::max(margin * (hi[k] - lo[k]), min_margin);
    bounds.lower[k] = lo[k] - grow;
    bounds.upper[k] = hi[k] + grow;
  }
  return bounds;
}

bool fits(std::span<const float> xyz, const QuantizationBounds& bounds) {
  bool inside = true;
  // written so that a NaN does not fit either
  const auto in = [&](std::size_t i, int k) {
    return xyz[i] >= bounds.lower[k] && xyz[i] <= bounds.upper[k];
  };
  const std::size_t whole = xyz.size() - xyz.size() % 3;
  for (std::size_t i = 0; i < whole; i += 3) inside &= in(i, 0) & in(i + 1, 1) & in(i + 2, 2);
  for (std::size_t i = whole; i < xyz.size(); ++i) inside &= in(i, static_cast<int>(i - whole));
  return inside;
}

void quantize(std::span<const float> xyz, const QuantizationBounds& bounds,
              std::vector<std::uint16_t>& q) {
  q.resize(xyz.size());
  std::array<double, 3> scale{};
  for (int k = 0; k < 3; ++k) {
    const double extent = double{bounds.upper[k]} - bounds.lower[k];
    scale[k] = extent > 0 ? kQuantizedMax / extent : 0;
  }
  const auto one = [&](std::size_t i, int k) {
    const double steps = (double{xyz[i]} - bounds.lower[k]) * scale[k];
    // clamped, then rounded to the nearest step (the NaN-safe way round: NaN becomes 0)
    const double clamped = steps > 0 ? (steps < kQuantizedMax ? steps : kQuantizedMax) : 0.0;
    q[i] = static_cast<std::uint16_t>(clamped + 0.5);
  };
  const std::size_t whole = xyz.size() - xyz.size() % 3;
  for (std::size_t i = 0; i < whole; i += 3) {
    one(i, 0);
    one(i + 1, 1);
    one(i + 2, 2);
  }
  for (std::size_t i = whole; i < xyz.size(); ++i) one(i, static_cast<int>(i - whole));
}

void dequantize(std::span<const std::uint16_t> q, const QuantizationBounds& bounds,
                std::vector<float>& xyz) {
  xyz.resize(q.size());
  std::array<double, 3> step{};
  for (int k = 0; k < 3; ++k) step[k] = (double{bounds.upper[k]} - bounds.lower[k]) / kQuantizedMax;
  for (std::size_t i = 0, k = 0; i < q.size(); ++i, k = next_axis(k)) {
    xyz[i] = static_cast<float>(bounds.lower[k] + q[i] * step[k]);
  }
}

void append_values(std::span<const std::uint16_t> q, std::string& bytes) {
  const std::size_t start = bytes.size();
  bytes.resize(start + 2 * q.size());
  char* out = bytes.data() + start;
  for (std::uint16_t v : q) {
    *out++ = static_cast<char>(v & 0xff);
    *out++ = static_cast<char>(v >> 8);
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

namespace {

/// Appends `d` as a zigzag varint at `out` (room for three bytes) and returns the end. |d| <
/// 2^17, so one to three bytes, written without a branch: the lengths for moving vertices vary
/// too much to predict.
char* put_zigzag(char* out, std::int32_t d) {
  const std::uint32_t z =
      (static_cast<std::uint32_t>(d) << 1) ^ static_cast<std::uint32_t>(d >> 31);
  const std::uint32_t two = z >= 0x80 ? 1 : 0;
  const std::uint32_t three = z >= 0x4000 ? 1 : 0;
  const std::uint32_t word =
      (z & 0x7f) | (two << 7) | (((z >> 7) & 0x7f) << 8) | (three << 15) | ((z >> 14) << 16);
  // one store of the little-endian word; the bytes past the varint are overwritten next
  std::memcpy(out, &word, 3);
  return out + 1 + two + three;
}

}  // namespace

void append_deltas(std::span<const std::uint16_t> q, std::span<const std::uint16_t> base,
                   std::string& bytes) {
  const std::size_t start = bytes.size();
  bytes.resize(start + 3 * q.size());
  char* out = bytes.data() + start;
  // plain locals, so that the byte stores (which may alias anything) do not force reloads
  const std::uint16_t* now = q.data();
  const std::uint16_t* before = base.data();
  // neighbouring vertices (in index order) move alike: each coordinate's change is sent less
  // the previous vertex's change of the same coordinate
  std::int32_t px = 0, py = 0, pz = 0;
  const std::size_t whole = q.size() - q.size() % 3;
  for (std::size_t i = 0; i < whole; i += 3) {
    const std::int32_t cx = std::int32_t{now[i]} - before[i];
    const std::int32_t cy = std::int32_t{now[i + 1]} - before[i + 1];
    const std::int32_t cz = std::int32_t{now[i + 2]} - before[i + 2];
    out = put_zigzag(out, cx - px);
    out = put_zigzag(out, cy - py);
    out = put_zigzag(out, cz - pz);
    px = cx;
    py = cy;
    pz = cz;
  }
  const std::int32_t previous[3] = {px, py, pz};
  for (std::size_t i = whole; i < q.size(); ++i) {
    out = put_zigzag(out, std::int32_t{now[i]} - before[i] - previous[i - whole]);
  }
  bytes.resize(static_cast<std::size_t>(out - bytes.data()));
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
