#include "core/cloth/long_range_attachments.hpp"

#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace felt {

std::vector<Attachment> long_range_attachments(const ClothModel& model,
                                               std::span<const Real> inv_mass) {
  const std::size_t n = model.particle_count();
  // adjacency of the limited springs, compressed: the neighbours of p are at [first[p], first[p+1])
  std::vector<std::uint32_t> first(n + 1, 0);
  for (const Spring& s : model.springs) {
    if (!is_limited(s)) continue;
    ++first[s.i + 1];
    ++first[s.j + 1];
  }
  for (std::size_t p = 0; p < n; ++p) first[p + 1] += first[p];
  std::vector<std::pair<std::uint32_t, Real>> neighbours(first[n]);
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (const Spring& s : model.springs) {
    if (!is_limited(s)) continue;
    neighbours[fill[s.i]++] = {s.j, s.rest_length};
    neighbours[fill[s.j]++] = {s.i, s.rest_length};
  }

  constexpr Real kUnreached = std::numeric_limits<Real>::infinity();
  std::vector<Real> distance(n, kUnreached);
  std::vector<std::uint32_t> nearest_pin(n, 0);
  using Entry = std::pair<Real, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (std::uint32_t p = 0; p < n; ++p) {
    if (inv_mass[p] != 0) continue;
    distance[p] = 0;
    nearest_pin[p] = p;
    queue.emplace(0, p);
  }
  while (!queue.empty()) {
    const auto [d, p] = queue.top();
    queue.pop();
    if (d > distance[p]) continue;
    for (std::uint32_t k = first[p]; k < first[p + 1]; ++k) {
      const auto [q, length] = neighbours[k];
      if (d + length < distance[q]) {
        distance[q] = d + length;
        nearest_pin[q] = nearest_pin[p];
        queue.emplace(distance[q], q);
      }
    }
  }

  std::vector<Attachment> attachments;
  for (std::uint32_t p = 0; p < n; ++p) {
    if (inv_mass[p] == 0 || distance[p] == kUnreached) continue;
    attachments.push_back({p, nearest_pin[p], distance[p]});
  }
  return attachments;
}

}  // namespace felt
