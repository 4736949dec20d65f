// The CSV samples felt touch --path csv reads: what it takes, and the file and line of what it
// does not.

#include "cli/csv_path.hpp"

#include <fstream>

#include <gtest/gtest.h>

#include "cli/command_errors.hpp"
#include "scratch_directory.hpp"

namespace felt::test {
namespace {

class CsvPath : public ::testing::Test {
 protected:
  /// `text` as a file of the scratch directory; its path.
  std::string file(const std::string& text) {
    const std::string path = (dir_ / "path.csv").string();
    std::ofstream(path) << text;
    return path;
  }
  /// The message read_csv_path throws for `text`: a usage error, with no server code.
  std::string fault(const std::string& text) {
    try {
      cli::read_csv_path(file(text));
    } catch (const cli::UsageError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return "";
  }

  ScratchDirectory dir_;
};

TEST_F(CsvPath, ReadsSamplesWithOrWithoutButtons) {
  const DevicePath path =
      cli::read_csv_path(file("time,x,y,z,buttons\n"
                              "# a press\n"
                              "0, 0.1, 1.2, 0.05\n"
                              "\n"
                              "0.5,0.1,1.2,-0.01,1\r\n"
                              "  1  0.2  1.3  0  3  \n"));
  EXPECT_EQ(path.shape, DevicePath::Shape::kSamples);
  ASSERT_EQ(path.samples.size(), 3u);
  EXPECT_EQ(path.samples[0].time, 0);
  EXPECT_EQ(path.samples[0].position, Eigen::Vector3d(0.1, 1.2, 0.05));
  EXPECT_EQ(path.samples[0].buttons, 0u);
  EXPECT_EQ(path.samples[1].time, 0.5);
  EXPECT_EQ(path.samples[1].position, Eigen::Vector3d(0.1, 1.2, -0.01));
  EXPECT_EQ(path.samples[1].buttons, 1u);
  EXPECT_EQ(path.samples[2].position, Eigen::Vector3d(0.2, 1.3, 0));
  EXPECT_EQ(path.samples[2].buttons, 3u);
}

TEST_F(CsvPath, ABadLineIsNamedByItsNumber) {
  const std::string f = (dir_ / "path.csv").string();
  const std::string head = "time,x,y,z\n0,0,1,0\n";
  EXPECT_EQ(fault(head + "0.1,0,1\n"), f + ":3: expected time, x, y, z[, buttons]");
  EXPECT_EQ(fault(head + "0.1,0,one,0\n"), f + ":3: expected time, x, y, z[, buttons]");
  EXPECT_EQ(fault(head + "# note\n0.1,0,1,0,-1\n"),
            f + ":4: buttons must be a whole number, not \"-1\"");
  EXPECT_EQ(fault(head + "0.1,0,1,0,x\n"), f + ":3: buttons must be a whole number, not \"x\"");
  EXPECT_EQ(fault(head + "0.1,0,1,0,1,7\n"), f + ":3: more than time, x, y, z and buttons");
  EXPECT_EQ(fault(head + "0,0,1,0\n"), f + ":3: times must increase");
}

TEST_F(CsvPath, AFileWithoutSamplesOrNoFileAtAllIsRefused) {
  const std::string f = (dir_ / "path.csv").string();
  EXPECT_EQ(fault("time,x,y,z\n# nothing yet\n"), f + ": no samples");
  try {
    cli::read_csv_path((dir_ / "missing.csv").string());
    ADD_FAILURE() << "no error";
  } catch (const cli::UsageError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot read " + (dir_ / "missing.csv").string());
  }
}

}  // namespace
}  // namespace felt::test
