#pragma once
// Haptic device paths with what each update found, recorded to be replayed against other
// acceleration structures (De Boeck et al., thesis 1 §9): the same device positions must give
// the same contacts ("collision equivalence") whatever the structure.

#include <cstdint>
#include <expected>
#include <iosfwd>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace felt {

struct HapticRecord {
  double time = 0;           ///< s, of the device's script
  std::uint32_t device = 0;  ///< which device of the scene
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::uint32_t buttons = 0;
  bool in_contact = false;
  std::uint32_t body = 0;
  std::int32_t triangle = -1;
  Eigen::Vector3d proxy = Eigen::Vector3d::Zero();
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
};

/// CSV with a header line; doubles written exactly (17 significant digits).
void write_recording_header(std::ostream& out);
void write_record(std::ostream& out, const HapticRecord& record);

/// Reads what write_record wrote, or says which line is wrong and why.
std::expected<std::vector<HapticRecord>, std::string> read_recording(std::istream& in);

/// Whether `replayed` found what `recorded` found: both free, or both touching the same body
/// and triangle with proxies within `tolerance` metres.
bool collision_equivalent(const HapticRecord& recorded, const HapticRecord& replayed,
                          double tolerance);

}  // namespace felt
