#include "device/haptic_recording.hpp"

#include <cmath>
#include <istream>
#include <ostream>
#include <sstream>

namespace felt {
namespace {

constexpr const char* kHeader =
    "time,device,x,y,z,buttons,contact,body,triangle,proxy_x,proxy_y,proxy_z,fx,fy,fz";
constexpr int kColumns = 15;

void put(std::ostream& out, const Eigen::Vector3d& v) {
  out << ',' << v.x() << ',' << v.y() << ',' << v.z();
}

}  // namespace

void write_recording_header(std::ostream& out) {
  out << kHeader << '\n';
}

void write_record(std::ostream& out, const HapticRecord& r) {
  const auto precision = out.precision(17);
  out << r.time << ',' << r.device;
  put(out, r.position);
  out << ',' << r.buttons << ',' << (r.in_contact ? 1 : 0) << ',' << r.body << ',' << r.triangle;
  put(out, r.proxy);
  put(out, r.force);
  out << '\n';
  out.precision(precision);
}

std::expected<std::vector<HapticRecord>, std::string> read_recording(std::istream& in) {
  std::string line;
  if (!std::getline(in, line) || line != kHeader) {
    return std::unexpected(std::string("line 1: expected the header \"") + kHeader + "\"");
  }
  std::vector<HapticRecord> records;
  for (std::size_t number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::istringstream fields(line);
    std::string field;
    double values[kColumns];
    int count = 0;
    bool ok = true;
    while (std::getline(fields, field, ',')) {
      if (count == kColumns) {
        ok = false;
        break;
      }
      std::istringstream number_text(field);
      ok = ok && (number_text >> values[count]) && number_text.eof();
      ++count;
    }
    if (!ok || count != kColumns) {
      return std::unexpected("line " + std::to_string(number) + ": expected " +
                             std::to_string(kColumns) + " numbers");
    }
    HapticRecord& r = records.emplace_back();
    r.time = values[0];
    r.device = static_cast<std::uint32_t>(values[1]);
    r.position = Eigen::Vector3d(values[2], values[3], values[4]);
    r.buttons = static_cast<std::uint32_t>(values[5]);
    r.in_contact = values[6] != 0;
    r.body = static_cast<std::uint32_t>(values[7]);
    r.triangle = static_cast<std::int32_t>(values[8]);
    r.proxy = Eigen::Vector3d(values[9], values[10], values[11]);
    r.force = Eigen::Vector3d(values[12], values[13], values[14]);
    if (!r.position.allFinite() || !std::isfinite(r.time)) {
      return std::unexpected("line " + std::to_string(number) + ": not finite");
    }
  }
  return records;
}

bool collision_equivalent(const HapticRecord& recorded, const HapticRecord& replayed,
                          double tolerance) {
  if (recorded.in_contact != replayed.in_contact) return false;
  if (!recorded.in_contact) return true;
  return recorded.body == replayed.body && recorded.triangle == replayed.triangle &&
         (recorded.proxy - replayed.proxy).norm() <= tolerance;
}

}  // namespace felt
