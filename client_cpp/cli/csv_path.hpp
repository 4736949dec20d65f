#pragma once
// A device path from a CSV file of samples (felt touch --path csv).

#include <string>

#include "device/device_path.hpp"

namespace felt::cli {

/// Reads "time, x, y, z[, buttons]" lines (times increasing; blank lines, # comments and a
/// header starting with "time" skipped) into a sampled path. Throws UsageError naming the
/// file and the line of the first fault.
DevicePath read_csv_path(const std::string& file);

}  // namespace felt::cli
