#pragma once
// The god-object's sphere swept against the candidate triangles as they are rendered now,
// frozen (leg 2 of an update, god_object.hpp): where it first meets one, where it stops a skin
// short of it, and whether it rests within the skin of one.

#include <cstddef>
#include <optional>

#include "core/collision/sphere_sweep.hpp"
#include "core/haptics/candidate_triangles.hpp"

namespace felt {

struct CandidateHit {
  std::size_t candidate = 0;
  SweepHit sweep;
};

/// The first candidate the sphere of `radius` meets on its way from p0 to p1; of equal hits,
/// the lower triangle index.
std::optional<CandidateHit> first_hit(const CandidateTriangles& c, const Vec3& p0, const Vec3& p1,
                                      Real radius);

/// How far the sphere gets from p0 toward p1: all the way, or to where it meets a triangle,
/// backed off along the path until the skin is between them.
struct SweepStop {
  Vec3 position;
  std::optional<CandidateHit> hit;
};

SweepStop sweep_to(const CandidateTriangles& c, const Vec3& p0, const Vec3& p1, Real radius);

/// Whether the sphere at `centre` is within the skin of touching some candidate.
bool touches(const CandidateTriangles& c, const Vec3& centre, Real radius);

}  // namespace felt
