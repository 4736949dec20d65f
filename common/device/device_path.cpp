#include "device/device_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace felt {
namespace {

DeviceSample sampled(const std::vector<DeviceSample>& samples, double t) {
  if (samples.empty()) return {t, Eigen::Vector3d::Zero(), 0};
  const auto after =
      std::upper_bound(samples.begin(), samples.end(), t,
                       [](double time, const DeviceSample& s) { return time < s.time; });
  if (after == samples.begin()) return {t, samples.front().position, samples.front().buttons};
  if (after == samples.end()) return {t, samples.back().position, samples.back().buttons};
  const DeviceSample& before = *(after - 1);
  const double span = after->time - before.time;
  const double s = span > 0 ? (t - before.time) / span : 1;
  // buttons change at a sample, never in between
  return {t, before.position + s * (after->position - before.position), before.buttons};
}

}  // namespace

DeviceSample DevicePath::at(double t) const {
  t = std::max<double>(t, 0);
  if (shape == Shape::kSamples) return sampled(samples, t);
  const double phase = t / period;
  DeviceSample out{t, a, buttons};
  switch (shape) {
    case Shape::kLine: {
      const double cycle = phase - std::floor(phase);
      const double s = cycle < 0.5 ? 2 * cycle : 2 - 2 * cycle;
      out.position = a + s * (b - a);
      break;
    }
    case Shape::kCircle: {
      // an orthonormal basis (u, v) of the plane normal to the axis
      const Eigen::Vector3d n = axis.normalized();
      const Eigen::Vector3d u = n.unitOrthogonal();
      const Eigen::Vector3d v = n.cross(u);
      const double angle = 2 * std::numbers::pi * phase;
      out.position = a + radius * (std::cos(angle) * u + std::sin(angle) * v);
      break;
    }
    case Shape::kPress:
      out.position = a + std::min<double>(phase, 1) * (b - a);
      break;
    case Shape::kSamples:
      break;
  }
  return out;
}

}  // namespace felt
