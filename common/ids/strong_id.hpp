#pragma once
// An integer id that knows what it names, so that ids of two kinds cannot be mixed up: a body id
// passed where a client id belongs fails to compile. Standard library only (felt_core uses it).

#include <compare>
#include <cstddef>
#include <functional>
#include <ostream>

namespace felt {

/// An id of the kind `Tag` held as a `Rep`. Made implicitly from its integer (the wire, an index,
/// a literal in a test) and read back only with `value()`: an integer becomes an id anywhere, an
/// id of one kind never becomes one of another, nor an integer unless asked.
template <class Tag, class Rep>
class StrongId {
 public:
  using rep = Rep;
  constexpr StrongId() = default;
  constexpr StrongId(Rep value) : value_(value) {}  // NOLINT(google-explicit-constructor)
  constexpr Rep value() const { return value_; }
  friend constexpr bool operator==(const StrongId&, const StrongId&) = default;
  friend constexpr auto operator<=>(const StrongId&, const StrongId&) = default;
  friend std::ostream& operator<<(std::ostream& out, StrongId id) { return out << id.value_; }

 private:
  Rep value_{};
};

}  // namespace felt

template <class Tag, class Rep>
struct std::hash<felt::StrongId<Tag, Rep>> {
  std::size_t operator()(felt::StrongId<Tag, Rep> id) const noexcept {
    return std::hash<Rep>{}(id.value());
  }
};
