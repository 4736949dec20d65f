#include "ids/strong_id.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <type_traits>
#include <unordered_set>

namespace felt {
namespace {

using AppleId = StrongId<struct AppleTag, std::uint32_t>;
using PearId = StrongId<struct PearTag, std::uint32_t>;
using BigId = StrongId<struct BigTag, std::uint64_t>;

// an integer becomes an id; an id becomes neither an integer nor an id of another kind
static_assert(std::is_convertible_v<std::uint32_t, AppleId>);
static_assert(!std::is_convertible_v<AppleId, std::uint32_t>);
static_assert(!std::is_convertible_v<AppleId, PearId>);
static_assert(!std::is_constructible_v<PearId, AppleId>);
static_assert(!std::is_assignable_v<PearId&, AppleId>);
static_assert(!std::is_convertible_v<BigId, AppleId>);
// as cheap to pass as its integer
static_assert(sizeof(AppleId) == sizeof(std::uint32_t));
static_assert(sizeof(BigId) == sizeof(std::uint64_t));
static_assert(std::is_trivially_copyable_v<AppleId>);

template <class A, class B>
concept Comparable = requires(A a, B b) {
  a == b;
};
static_assert(Comparable<AppleId, AppleId>);
static_assert(Comparable<AppleId, int>);  // a literal in a test
static_assert(!Comparable<AppleId, PearId>);

TEST(StrongId, KeepsItsValueAndOrdersAsItsInteger) {
  EXPECT_EQ(AppleId{}.value(), 0u);
  const AppleId seven = 7;
  EXPECT_EQ(seven.value(), 7u);
  EXPECT_EQ(seven, 7u);
  EXPECT_LT(AppleId{3}, seven);
  EXPECT_GT(BigId{std::uint64_t{1} << 40}, BigId{1});
}

TEST(StrongId, HashesAndPrintsAsItsInteger) {
  std::unordered_set<AppleId> ids{1, 2, 2, 3};
  EXPECT_EQ(ids.size(), 3u);
  EXPECT_TRUE(ids.contains(2));
  EXPECT_EQ(std::hash<AppleId>{}(5), std::hash<std::uint32_t>{}(5));
  std::ostringstream text;
  text << AppleId{42};
  EXPECT_EQ(text.str(), "42");
}

}  // namespace
}  // namespace felt
