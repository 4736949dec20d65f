#include "wire/vector_quantizer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace felt::wire {
namespace {

/// Values per block: a whole number of vectors (3) and of SIMD lanes (up to 8), so that a lane
/// always holds the same axis and the loop over a block vectorizes. Blocks start at value 0, so
/// value i is in lane i % kBlock, the values past the last whole block included.
constexpr std::size_t kBlock = 24;

template <typename T>
using Lanes = std::array<T, kBlock>;

template <typename T, typename U>
Lanes<T> per_lane(const std::array<U, 3>& axes) {
  Lanes<T> lanes{};
  for (std::size_t j = 0; j < kBlock; ++j) lanes[j] = static_cast<T>(axes[j % 3]);
  return lanes;
}

/// Calls `each(i, j)` for every value i, in lane j, a block at a time.
template <typename Each>
void for_each_lane(std::size_t size, Each&& each) {
  std::size_t i = 0;
  for (; i + kBlock <= size; i += kBlock) {
    for (std::size_t j = 0; j < kBlock; ++j) each(i + j, j);
  }
  for (std::size_t j = 0; i < size; ++i, ++j) each(i, j);
}

}  // namespace

QuantizationBounds bounds_around(std::span<const float> xyz, float margin, float min_margin) {
  Lanes<float> lo, hi;
  lo.fill(std::numeric_limits<float>::max());
  hi.fill(std::numeric_limits<float>::lowest());
  const float* x = xyz.data();
  for_each_lane(xyz.size(), [&](std::size_t i, std::size_t j) {
    lo[j] = x[i] < lo[j] ? x[i] : lo[j];
    hi[j] = x[i] > hi[j] ? x[i] : hi[j];
  });
  QuantizationBounds bounds;
  for (std::size_t k = 0; k < 3; ++k) {
    float low = lo[k], high = hi[k];
    for (std::size_t j = k + 3; j < kBlock; j += 3) {
      low = std::min(low, lo[j]);
      high = std::max(high, hi[j]);
    }
    if (low > high) low = high = 0;  // no vectors
    const float grow = std::max(margin * (high - low), min_margin);
    bounds.lower[k] = low - grow;
    bounds.upper[k] = high + grow;
  }
  return bounds;
}

bool fits(std::span<const float> xyz, const QuantizationBounds& bounds) {
  const Lanes<float> lower = per_lane<float>(bounds.lower);
  const Lanes<float> upper = per_lane<float>(bounds.upper);
  const float* x = xyz.data();
  // gathered rather than tested, so that the loop has no exit to vectorize around; written so
  // that a NaN does not fit either
  unsigned outside = 0;
  for_each_lane(xyz.size(), [&](std::size_t i, std::size_t j) {
    const unsigned in = unsigned{x[i] >= lower[j]} & unsigned{x[i] <= upper[j]};
    outside |= in ^ 1u;
  });
  return outside == 0;
}

void quantize(std::span<const float> xyz, const QuantizationBounds& bounds,
              std::vector<std::uint16_t>& q) {
  q.resize(xyz.size());
  std::array<double, 3> scale{};
  for (int k = 0; k < 3; ++k) {
    const double extent = double{bounds.upper[k]} - bounds.lower[k];
    scale[k] = extent > 0 ? kQuantizedMax / extent : 0;
  }
  const Lanes<double> lower = per_lane<double>(bounds.lower);
  const Lanes<double> scales = per_lane<double>(scale);
  const float* x = xyz.data();
  std::uint16_t* out = q.data();
  for_each_lane(xyz.size(), [&](std::size_t i, std::size_t j) {
    const double steps = (double{x[i]} - lower[j]) * scales[j];
    // clamped, then rounded to the nearest step; std::max(0, NaN) is 0; through int32, which
    // has a vector conversion
    const double clamped = std::min(std::max(0.0, steps), double{kQuantizedMax});
    out[i] = static_cast<std::uint16_t>(static_cast<std::int32_t>(clamped + 0.5));
  });
}

void dequantize(std::span<const std::uint16_t> q, const QuantizationBounds& bounds,
                std::vector<float>& xyz) {
  xyz.resize(q.size());
  std::array<double, 3> step{};
  for (int k = 0; k < 3; ++k) step[k] = (double{bounds.upper[k]} - bounds.lower[k]) / kQuantizedMax;
  const Lanes<double> lower = per_lane<double>(bounds.lower);
  const Lanes<double> steps = per_lane<double>(step);
  const std::uint16_t* in = q.data();
  float* out = xyz.data();
  for_each_lane(q.size(), [&](std::size_t i, std::size_t j) {
    out[i] = static_cast<float>(lower[j] + in[i] * steps[j]);
  });
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
