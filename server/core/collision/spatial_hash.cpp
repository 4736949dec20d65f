#include "core/collision/spatial_hash.hpp"

#include <cmath>

#include "core/math/check.hpp"

namespace felt {
namespace {

// The large primes of the hash function (Teschner et al. 2003, thesis 2 §6.3.2).
constexpr std::uint32_t kP1 = 73856093;
constexpr std::uint32_t kP2 = 19349663;
constexpr std::uint32_t kP3 = 83492791;

// Cell coordinates are clamped to ±2^20: points far away (or exploding) share the outermost
// cells instead of overflowing the conversion, and a box's cell count fits in 64 bits. The
// clamp is monotone, so a point inside a box still has its cell among the box's cells.
constexpr Real kMaxCell = 1 << 20;

bool is_prime(std::size_t n) {
  if (n < 2) return false;
  for (std::size_t d = 2; d * d <= n; ++d) {
    if (n % d == 0) return false;
  }
  return true;
}

}  // namespace

std::size_t SpatialHash::table_size_for(std::size_t point_count) {
  // the smallest integer greater than 4n/3 is ⌊4n/3⌋ + 1
  std::size_t n = point_count * 4 / 3 + 1;
  while (!is_prime(n)) ++n;
  return n;
}

void SpatialHash::begin(Real cell_size, std::size_t point_count) {
  FELT_CHECK(cell_size > 0 && std::isfinite(cell_size));
  FELT_CHECK(point_count < kNone);
  inverse_cell_size_ = 1 / cell_size;
  const std::size_t size = table_size_for(point_count);
  if (size != buckets_.size()) {
    buckets_.assign(size, Bucket{});
    stamp_ = 0;
  }
  if (++stamp_ == 0) {  // the stamp wrapped around: old stamps could look current again
    for (Bucket& bucket : buckets_) bucket.stamp = 0;
    stamp_ = 1;
  }
  entries_.clear();
  entries_.reserve(point_count);
}

void SpatialHash::insert(std::uint32_t body, std::uint32_t node, const Cell& cell) {
  FELT_CHECK(entries_.size() < kNone);
  Bucket& bucket = buckets_[slot_of(cell)];
  if (bucket.stamp != stamp_) {
    bucket.stamp = stamp_;
    bucket.head = kNone;
  }
  entries_.push_back(Entry{cell, body, node, bucket.head});
  bucket.head = static_cast<std::uint32_t>(entries_.size() - 1);
}

SpatialHash::Cell SpatialHash::cell_of(const Vec3& x) const {
  Cell cell;
  for (int a = 0; a < 3; ++a) {
    // written so that NaN, which compares false, lands in an outermost cell instead of in
    // undefined behaviour
    const Real c = std::floor(x[a] * inverse_cell_size_);
    cell[a] = static_cast<std::int32_t>(c > -kMaxCell ? (c < kMaxCell ? c : kMaxCell) : -kMaxCell);
  }
  return cell;
}

std::size_t SpatialHash::slot_of(const Cell& cell) const {
  // unsigned arithmetic: negative coordinates wrap to well-defined values (§6.3.2 leaves them
  // open), and the products may overflow by design
  const std::uint32_t h = (static_cast<std::uint32_t>(cell[0]) * kP1) ^
                          (static_cast<std::uint32_t>(cell[1]) * kP2) ^
                          (static_cast<std::uint32_t>(cell[2]) * kP3);
  return h % buckets_.size();
}

}  // namespace felt
