#pragma once

#include <cstdint>

#include "core/math/types.hpp"

namespace felt {

/// The role of a spring in a cloth (thesis 1 §3): each kind has its own constants.
enum class SpringKind : std::uint8_t { kStructural, kShear, kBend };
inline constexpr int kSpringKindCount = 3;

/// A damped linear spring between particles i and j.
struct Spring {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
  Real rest_length = 0;
  SpringKind kind = SpringKind::kStructural;
};

/// Whether stretch limiting holds the spring and strain is measured on it: structural and shear
/// springs of positive rest length (bend springs span two edges and may fold).
inline bool is_limited(const Spring& s) {
  return s.kind != SpringKind::kBend && s.rest_length > 0;
}

/// Stiffness and damping of one spring kind.
struct SpringParams {
  bool enabled = true;
  Real stiffness = 0;  ///< k_s, N/m
  Real damping = 0;    ///< k_d, N·s/m, along the spring

  bool operator==(const SpringParams&) const = default;
};

}  // namespace felt
