#include "core/cloth/spring_colouring.hpp"

#include <algorithm>

#include "core/math/check.hpp"

namespace felt {

SpringColouring colour_springs(std::span<const Spring> springs, std::size_t particle_count) {
  // the classes each particle's springs already have, and a scratch mark per class
  std::vector<std::vector<std::uint32_t>> taken_at(particle_count);
  std::vector<std::uint32_t> colour(springs.size());
  std::vector<bool> taken;
  std::uint32_t class_count = 0;
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const Spring& spring = springs[s];
    FELT_CHECK(spring.i < particle_count && spring.j < particle_count && spring.i != spring.j);
    const std::vector<std::uint32_t>& at_i = taken_at[spring.i];
    const std::vector<std::uint32_t>& at_j = taken_at[spring.j];
    taken.assign(at_i.size() + at_j.size() + 1, false);
    for (const std::uint32_t c : at_i) {
      if (c < taken.size()) taken[c] = true;
    }
    for (const std::uint32_t c : at_j) {
      if (c < taken.size()) taken[c] = true;
    }
    const auto c =
        static_cast<std::uint32_t>(std::find(taken.begin(), taken.end(), false) - taken.begin());
    colour[s] = c;
    taken_at[spring.i].push_back(c);
    taken_at[spring.j].push_back(c);
    class_count = std::max(class_count, c + 1);
  }

  // the springs sorted by class, each class in the springs' order (a counting sort)
  SpringColouring colouring;
  colouring.class_ends.assign(class_count, 0);
  for (const std::uint32_t c : colour) ++colouring.class_ends[c];
  std::uint32_t end = 0;
  for (std::uint32_t& class_end : colouring.class_ends) {
    end += class_end;
    class_end = end;
  }
  colouring.order.resize(springs.size());
  std::vector<std::uint32_t> next(class_count, 0);
  for (std::uint32_t c = 1; c < class_count; ++c) next[c] = colouring.class_ends[c - 1];
  for (std::uint32_t s = 0; s < springs.size(); ++s) colouring.order[next[colour[s]]++] = s;
  return colouring;
}

}  // namespace felt
