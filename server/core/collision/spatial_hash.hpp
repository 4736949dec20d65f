#pragma once
// Optimized spatial hashing (Teschner et al. 2003, thesis 2 §6.3.1–6.3.3): the nodes of all
// bodies sorted into a virtual uniform grid whose cells live in a one-dimensional hash table.

#include <array>
#include <cstdint>
#include <vector>

#include "core/math/types.hpp"

namespace felt {

class SpatialHash {
 public:
  /// Integer grid coordinates (⌊x/l⌋, ⌊y/l⌋, ⌊z/l⌋) of a cell.
  using Cell = std::array<std::int32_t, 3>;

  /// First prime greater than 4/3 × point_count: the table is at most 75% full (§6.3.3).
  static std::size_t table_size_for(std::size_t point_count);

  /// Starts a new step with cubic cells of edge `cell_size` for about `point_count` points.
  /// Entries of earlier steps become empty by a new timestamp, not by clearing the table; the
  /// table is reallocated only when `point_count` changes its size.
  void begin(Real cell_size, std::size_t point_count);

  /// Stores node `node` of body `body` at position x.
  void insert(std::uint32_t body, std::uint32_t node, const Vec3& x) {
    insert(body, node, cell_of(x));
  }
  /// Stores node `node` of body `body` in `cell`: an entry that spans several cells (a triangle
  /// hashed by its bounding box) is stored once per cell.
  void insert(std::uint32_t body, std::uint32_t node, const Cell& cell);

  /// Calls visit(body, node) once for every stored point whose cell the box [lo, hi] overlaps:
  /// a superset of the points inside the box.
  template <class Visit>
  void for_each_in_box(const Vec3& lo, const Vec3& hi, Visit&& visit) const;

  Cell cell_of(const Vec3& x) const;
  std::size_t table_size() const { return buckets_.size(); }
  std::size_t point_count() const { return entries_.size(); }

 private:
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};

  /// A slot of the table: the head of its chain, valid only while `stamp` is the current one.
  struct Bucket {
    std::uint32_t stamp = 0;
    std::uint32_t head = kNone;
  };
  struct Entry {
    Cell cell;  ///< kept so that a chain shared by two cells yields only the queried cell
    std::uint32_t body = 0;
    std::uint32_t node = 0;
    std::uint32_t next = kNone;
  };

  std::size_t slot_of(const Cell& cell) const;

  Real inverse_cell_size_ = 1;
  std::uint32_t stamp_ = 0;
  std::vector<Bucket> buckets_;
  std::vector<Entry> entries_;
};

template <class Visit>
void SpatialHash::for_each_in_box(const Vec3& lo, const Vec3& hi, Visit&& visit) const {
  const Cell first = cell_of(lo);
  const Cell last = cell_of(hi);
  std::uint64_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    if (last[a] < first[a]) return;
    cells *= static_cast<std::uint64_t>(last[a] - first[a] + 1);
  }
  // a box over more cells than there are points (a stretched or exploded tetrahedron) is
  // cheaper to answer by scanning the points, which bounds the work per query
  if (cells > entries_.size()) {
    for (const Entry& e : entries_) {
      bool overlapped = true;
      for (int a = 0; a < 3; ++a) overlapped &= e.cell[a] >= first[a] && e.cell[a] <= last[a];
      if (overlapped) visit(e.body, e.node);
    }
    return;
  }
  Cell cell;
  for (cell[2] = first[2]; cell[2] <= last[2]; ++cell[2]) {
    for (cell[1] = first[1]; cell[1] <= last[1]; ++cell[1]) {
      for (cell[0] = first[0]; cell[0] <= last[0]; ++cell[0]) {
        const Bucket& bucket = buckets_[slot_of(cell)];
        if (bucket.stamp != stamp_) continue;  // empty this step
        for (std::uint32_t i = bucket.head; i != kNone; i = entries_[i].next) {
          // three int compares: std::array's == became a memcmp call that dominated queries
          const Cell& c = entries_[i].cell;
          if (c[0] == cell[0] && c[1] == cell[1] && c[2] == cell[2]) {
            visit(entries_[i].body, entries_[i].node);
          }
        }
      }
    }
  }
}

}  // namespace felt
