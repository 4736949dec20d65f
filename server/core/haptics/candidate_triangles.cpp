#include "core/haptics/candidate_triangles.hpp"

#include <algorithm>
#include <cmath>

#include "core/haptics/triangle_placement.hpp"

namespace felt {

Aabb segment_box(const Vec3& p0, const Vec3& p1, Real margin) {
  Aabb box;
  box.grow(p0);
  box.grow(p1);
  return box.inflated(margin);
}

void CandidateTriangles::forget() {
  if (++epoch_ == 0) {  // the stamps wrapped: none may look gathered
    for (std::vector<std::uint32_t>& stamps : stamps_) std::fill(stamps.begin(), stamps.end(), 0);
    epoch_ = 1;
  }
  gathered_.clear();
  gathered_.reserve(kGatheredBoxes);
  body_.clear();
  triangle_.clear();
  now_.clear();
  normal_.clear();
  centre_.clear();
  extent_.clear();
  bounds_.clear();
}

void CandidateTriangles::gather(const HapticSurface& surface, const Aabb& region) {
  for (const Aabb& box : gathered_) {
    if (box.contains(region)) return;
  }
  if (gathered_.size() < gathered_.capacity()) gathered_.push_back(region);  // else: look again
  if (stamps_.size() < surface.bodies.size()) stamps_.resize(surface.bodies.size());
  for (std::uint32_t b = 0; b < surface.bodies.size(); ++b) {
    const HapticBody& body = surface.bodies[b];
    if (body.query == nullptr) continue;
    std::vector<std::uint32_t>& stamps = stamps_[b];
    if (stamps.size() != body.triangles.size()) stamps.assign(body.triangles.size(), 0);
    collected_.clear();
    body.query->collect(region, collected_);
    std::sort(collected_.begin(), collected_.end());
    for (const std::uint32_t t : collected_) {
      if (t >= body.triangles.size() || stamps[t] == epoch_) continue;  // gathered already
      stamps[t] = epoch_;
      const std::optional<TriangleCorners> corners = body.triangle_at(t, surface.alpha);
      if (!corners) continue;  // a corrupt triangle is not there
      const TriangleCorners& now = *corners;
      const Vec3 centre = (now.a + now.b + now.c) / 3;
      Aabb box;
      box.grow(now.a);
      box.grow(now.b);
      box.grow(now.c);
      body_.push_back(b);
      triangle_.push_back(t);
      now_.push_back(now);
      normal_.push_back(unit_normal(now).value_or(Vec3::Zero()));
      centre_.push_back(centre);
      extent_.push_back(
          std::sqrt(std::max({(now.a - centre).squaredNorm(), (now.b - centre).squaredNorm(),
                              (now.c - centre).squaredNorm()})));
      bounds_.push_back(box);
    }
  }
}

}  // namespace felt
