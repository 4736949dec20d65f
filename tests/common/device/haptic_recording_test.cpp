#include "device/haptic_recording.hpp"

#include <sstream>

#include <gtest/gtest.h>

namespace felt {
namespace {

HapticRecord touching() {
  HapticRecord r;
  r.time = 0.1234567890123;
  r.device = 2;
  r.position = Eigen::Vector3d(0.1, -1.0 / 3.0, 2e-17);
  r.buttons = 1;
  r.in_contact = true;
  r.body = 3;
  r.triangle = 1234;
  r.proxy = Eigen::Vector3d(0.1, 0.02 / 3.0, 1e300);
  r.force = Eigen::Vector3d(-0, 4.0 / 7.0, 1e-300);
  return r;
}

TEST(HapticRecording, RoundTripsEveryFieldExactly) {
  HapticRecord free;
  free.time = 7;
  std::stringstream csv;
  write_recording_header(csv);
  write_record(csv, touching());
  write_record(csv, free);
  const auto read = read_recording(csv);
  ASSERT_TRUE(read) << read.error();
  ASSERT_EQ(read->size(), 2u);
  const HapticRecord& r = (*read)[0];
  const HapticRecord expected = touching();
  EXPECT_EQ(r.time, expected.time);
  EXPECT_EQ(r.device, expected.device);
  EXPECT_EQ(r.position, expected.position);
  EXPECT_EQ(r.buttons, expected.buttons);
  EXPECT_EQ(r.in_contact, expected.in_contact);
  EXPECT_EQ(r.body, expected.body);
  EXPECT_EQ(r.triangle, expected.triangle);
  EXPECT_EQ(r.proxy, expected.proxy);
  EXPECT_EQ(r.force, expected.force);
  EXPECT_FALSE((*read)[1].in_contact);
  EXPECT_EQ((*read)[1].triangle, -1);
}

TEST(HapticRecording, SaysWhichLineIsWrong) {
  std::stringstream no_header("1,2,3\n");
  EXPECT_EQ(read_recording(no_header).error().substr(0, 7), "line 1:");
  std::stringstream csv;
  write_recording_header(csv);
  write_record(csv, touching());
  csv << "1,2,3\n";
  EXPECT_EQ(read_recording(csv).error(), "line 3: expected 15 numbers");
  std::stringstream words;
  write_recording_header(words);
  words << "a,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n";
  EXPECT_EQ(read_recording(words).error(), "line 2: expected 15 numbers");
  std::stringstream nan;
  write_recording_header(nan);
  nan << "0,0,nan,0,0,0,0,0,0,0,0,0,0,0,0\n";
  EXPECT_FALSE(read_recording(nan));
}

TEST(HapticRecording, CollisionEquivalenceIsSameContactTriangleAndProxy) {
  const HapticRecord a = touching();
  HapticRecord b = a;
  EXPECT_TRUE(collision_equivalent(a, b, 1e-9));
  b.proxy.x() += 1e-6;
  EXPECT_FALSE(collision_equivalent(a, b, 1e-9));
  EXPECT_TRUE(collision_equivalent(a, b, 1e-5));
  b = a;
  b.triangle = 7;
  EXPECT_FALSE(collision_equivalent(a, b, 1));
  b = a;
  b.in_contact = false;
  EXPECT_FALSE(collision_equivalent(a, b, 1));
  HapticRecord free_a, free_b;
  free_b.proxy = Eigen::Vector3d(5, 5, 5);  // free updates compare only as free
  EXPECT_TRUE(collision_equivalent(free_a, free_b, 0));
}

}  // namespace
}  // namespace felt
