// 16-bit vertex buffers and their deltas: exact round trips, bounded error, compact deltas,
// and malformed bytes refused rather than read past.

#include "wire/vector_quantizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace felt::wire {
namespace {

std::vector<float> random_points(std::size_t n, float scale, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> uniform(-scale, scale);
  std::vector<float> xyz(3 * n);
  for (float& x : xyz) x = uniform(random);
  return xyz;
}

TEST(VectorQuantizer, ErrorIsAtMostHalfAStepOfTheBounds) {
  const std::vector<float> xyz = random_points(1000, 2, 1);
  const QuantizationBounds bounds = bounds_around(xyz, 0.25f, 0.01f);
  EXPECT_TRUE(fits(xyz, bounds));
  std::vector<std::uint16_t> q;
  quantize(xyz, bounds, q);
  std::vector<float> back;
  dequantize(q, bounds, back);
  ASSERT_EQ(back.size(), xyz.size());
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    const int axis = static_cast<int>(i % 3);
    const double step = (double{bounds.upper[axis]} - bounds.lower[axis]) / kQuantizedMax;
    EXPECT_LE(std::abs(back[i] - xyz[i]), 0.5 * step + 1e-6) << i;
  }
}

TEST(VectorQuantizer, BoundsGrowByTheMarginOrAtLeastTheMinimum) {
  const std::vector<float> flat = {0, 1, 0, 2, 1, 0};  // flat in y and z
  const QuantizationBounds b = bounds_around(flat, 0.25f, 0.01f);
  EXPECT_FLOAT_EQ(b.lower[0], -0.5f);
  EXPECT_FLOAT_EQ(b.upper[0], 2.5f);
  EXPECT_FLOAT_EQ(b.lower[1], 0.99f);
  EXPECT_FLOAT_EQ(b.upper[2], 0.01f);
  EXPECT_FALSE(fits(std::vector<float>{3, 1, 0}, b));
}

// The quantizer works a block of values at a time: every length, whole blocks or not, whole
// vectors or not, gets each value's own axis, checked against the formula one value at a time.
TEST(VectorQuantizer, EveryLengthMatchesTheFormulaValueByValue) {
  const QuantizationBounds bounds{{-1, 0, 10}, {1, 4, 10.5f}};
  for (std::size_t n = 0; n <= 75; ++n) {
    std::vector<float> xyz = random_points(n, 1, static_cast<unsigned>(n));
    xyz.resize(n);                         // any length, not only whole vectors
    for (std::size_t i = 0; i < n; ++i) {  // from [-1, 1] into the axis's bounds
      const std::size_t k = i % 3;
      xyz[i] = bounds.lower[k] + (bounds.upper[k] - bounds.lower[k]) * (xyz[i] + 1) / 2;
    }
    if (n > 30) xyz[30] = 100;                                      // above: the top step
    if (n > 40) xyz[40] = std::numeric_limits<float>::quiet_NaN();  // no value: step 0
    std::vector<std::uint16_t> q;
    quantize(xyz, bounds, q);
    ASSERT_EQ(q.size(), n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t k = i % 3;
      const double steps =
          (xyz[i] - double{bounds.lower[k]}) / (double{bounds.upper[k]} - bounds.lower[k]) * 65535;
      const double expected = std::isnan(steps) ? 0 : std::round(std::clamp(steps, 0.0, 65535.0));
      EXPECT_NEAR(q[i], expected, 0.5) << "length " << n << " value " << i;
    }
    std::vector<float> back;
    dequantize(q, bounds, back);
    ASSERT_EQ(back.size(), n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t k = i % 3;
      EXPECT_FLOAT_EQ(
          back[i], static_cast<float>(bounds.lower[k] +
                                      q[i] * (double{bounds.upper[k]} - bounds.lower[k]) / 65535))
          << "length " << n << " value " << i;
    }
    // a NaN or a value outside, in a whole block or past the last, does not fit
    EXPECT_EQ(fits(xyz, bounds), n <= 30) << "length " << n;
    if (n > 0 && n <= 30) {
      xyz[n - 1] = std::numeric_limits<float>::quiet_NaN();
      EXPECT_FALSE(fits(xyz, bounds)) << "length " << n;
    }
  }
}

TEST(VectorQuantizer, ValuesRoundTripExactly) {
  std::vector<std::uint16_t> q = {0, 1, 255, 256, 65535, 12345};
  std::string bytes;
  append_values(q, bytes);
  EXPECT_EQ(bytes.size(), 12u);
  std::vector<std::uint16_t> back;
  ASSERT_TRUE(read_values(bytes, q.size(), back));
  EXPECT_EQ(back, q);
  EXPECT_FALSE(read_values(bytes, q.size() + 1, back));
  EXPECT_FALSE(read_values(bytes.substr(1), q.size(), back));
}

TEST(VectorQuantizer, DeltasRoundTripExactlyForAnyChange) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> value(0, 65535);
  std::vector<std::uint16_t> base(3000), q(3000);
  for (std::size_t i = 0; i < base.size(); ++i) {
    base[i] = static_cast<std::uint16_t>(value(random));
    q[i] = static_cast<std::uint16_t>(value(random));
  }
  q[0] = 0;  // the extreme changes
  base[0] = 65535;
  q[1] = 65535;
  base[1] = 0;
  std::string bytes;
  append_deltas(q, base, bytes);
  std::vector<std::uint16_t> back;
  ASSERT_TRUE(read_deltas(bytes, base, back));
  EXPECT_EQ(back, q);
}

TEST(VectorQuantizer, SmallIndependentMotionCostsOneByteACoordinate) {
  const std::vector<float> before = random_points(500, 1, 3);
  std::vector<float> after = before;
  std::mt19937 random(4);
  std::uniform_real_distribution<float> jitter(-1e-4f, 1e-4f);  // 0.1 mm: ~2 steps of 3 m
  for (float& x : after) x += jitter(random);
  const QuantizationBounds bounds = bounds_around(before, 0.25f, 0.01f);
  std::vector<std::uint16_t> qb, qa;
  quantize(before, bounds, qb);
  quantize(after, bounds, qa);
  std::string deltas, values;
  append_deltas(qa, qb, deltas);
  append_values(qa, values);
  EXPECT_EQ(deltas.size(), qa.size());  // every |difference| < 64: one varint byte each
  EXPECT_EQ(values.size(), 2 * qa.size());
}

TEST(VectorQuantizer, AWholeBodyMovingTogetherCostsOneByteACoordinate) {
  const std::vector<float> before = random_points(500, 1, 5);
  std::vector<float> after = before;
  for (std::size_t i = 0; i < after.size(); ++i) after[i] += 0.05f * (1 + (i % 3));  // 5-15 cm
  const QuantizationBounds bounds = bounds_around(before, 0.25f, 0.01f);
  std::vector<std::uint16_t> qb, qa, back;
  quantize(before, bounds, qb);
  quantize(after, bounds, qa);
  std::string deltas;
  append_deltas(qa, qb, deltas);
  // thousands of steps each, but the same for every vertex up to rounding: only the first
  // vertex pays for the motion
  EXPECT_LE(deltas.size(), qa.size() + 6);
  ASSERT_TRUE(read_deltas(deltas, qb, back));
  EXPECT_EQ(back, qa);
}

TEST(VectorQuantizer, MalformedDeltasAreRefused) {
  const std::vector<std::uint16_t> base = {10, 20, 65530};
  std::vector<std::uint16_t> q;
  EXPECT_FALSE(read_deltas(std::string("\x02\x02", 2), base, q));                  // one missing
  EXPECT_FALSE(read_deltas(std::string("\x02\x02\x02\x02", 4), base, q));          // one too many
  EXPECT_FALSE(read_deltas(std::string("\x02\x02\x80", 3), base, q));              // cut inside
  EXPECT_FALSE(read_deltas(std::string("\x02\x02\x80\x80\x80\x01", 6), base, q));  // too long
  EXPECT_FALSE(read_deltas(std::string("\x02\x02\x20", 3), base, q));              // 65530 + 16
  EXPECT_FALSE(read_deltas(std::string("\x15\x02\x02", 3), base, q));              // 10 - 11 < 0
  ASSERT_TRUE(read_deltas(std::string("\x02\x03\x0a", 3), base, q));
  EXPECT_EQ(q, (std::vector<std::uint16_t>{11, 18, 65535}));
  // from the second vertex on, each change is sent less the previous vertex's
  const std::vector<std::uint16_t> two = {100, 200, 300, 1000, 2000, 3000};
  ASSERT_TRUE(read_deltas(std::string("\x0a\x0a\x0a\x00\x01\x02", 6), two, q));
  EXPECT_EQ(q, (std::vector<std::uint16_t>{105, 205, 305, 1005, 2004, 3006}));
}

}  // namespace
}  // namespace felt::wire
