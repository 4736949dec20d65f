// felt watch in every format and encoding: the files it writes, read back, are the default
// scene's curtain (20 x 20 vertices, 722 triangles, within its bounds), and a VTK series is
// one ParaView opens.

#include <cmath>

#include "felt_cli_fixture.hpp"
#include "mesh_files.hpp"

namespace felt::test {
namespace {

struct WatchCase {
  const char* format;     ///< --format
  const char* extension;  ///< of each frame's file
  const char* encoding;   ///< a flag, or "" for float32
};

class FeltWatch : public FeltCliTest, public ::testing::WithParamInterface<WatchCase> {};

TEST_P(FeltWatch, WritesOneFileAFrameHoldingTheCurtain) {
  const WatchCase c = GetParam();
  std::vector<std::string> args = {"watch", "--frames",           "3",        "--rate", "30",
                                   "--out", dir_.path().string(), "--format", c.format};
  if (*c.encoding) args.push_back(c.encoding);
  const CommandResult r = felt(args);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");  // no progress display on a pipe
  EXPECT_NE(r.out.find("3 frames in " + dir_.path().string() + ", "), std::string::npos) << r.out;

  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir_.path())) {
    files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  std::vector<std::string> expected;
  for (int i = 0; i < 3; ++i) expected.push_back("frame_0000" + std::to_string(i) + c.extension);
  if (std::string(c.format) == "vtk") expected.push_back("frames.pvd");
  ASSERT_EQ(files, expected);

  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(expected[i]);
    const MeshFile mesh = read_mesh_file(dir_ / expected[i]);
    ASSERT_EQ(mesh.vertices.size(), 400u);
    EXPECT_EQ(mesh.triangles.size(), 722u);
    for (const auto& t : mesh.triangles) EXPECT_LT(*std::max_element(t.begin(), t.end()), 400u);
    // a 1 m curtain hanging from its top corners at y = 2 m in the plane z = 0: it sags and
    // its sides bow out a little
    for (const auto& v : mesh.vertices) {
      ASSERT_TRUE(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]));
      EXPECT_LE(std::abs(v[0]), 0.55);
      EXPECT_GT(v[1], 0.7);
      EXPECT_LE(v[1], 2.0001);
      EXPECT_LT(std::abs(v[2]), 0.2);
    }
    // pinned; 16-bit positions are within a 65535th of the bounds
    EXPECT_NEAR(mesh.vertices[0][0], -0.5, 1e-4);
    EXPECT_NEAR(mesh.vertices[0][1], 2, 1e-4);
    EXPECT_NEAR(mesh.vertices[0][2], 0, 1e-4);
  }
  if (std::string(c.format) == "vtk") {
    const CommandResult checked =
        run_command({FELT_PYTHON3, CHECK_VTK_PY, (dir_ / "frames.pvd").string()});
    EXPECT_EQ(checked.status, 0) << checked.err;
    EXPECT_EQ(checked.out, "curtain 400 722\ncurtain 400 722\ncurtain 400 722\n");
    const auto series = read_pvd(dir_ / "frames.pvd");
    ASSERT_EQ(series.size(), 3u);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(series[i].second, expected[i]);
    EXPECT_GE(series[0].first, 0);
    EXPECT_EQ(r.out.find(dir_.path().string() + "/frames.pvd: open it in ParaView\n"), 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(
    EachFormatAndEncoding, FeltWatch,
    ::testing::Values(WatchCase{"obj", ".obj", ""}, WatchCase{"obj", ".obj", "--quantized"},
                      WatchCase{"obj", ".obj", "--deltas"}, WatchCase{"ply", ".ply", ""},
                      WatchCase{"ply", ".ply", "--quantized"}, WatchCase{"ply", ".ply", "--deltas"},
                      WatchCase{"vtk", ".vtp", ""}, WatchCase{"vtk", ".vtp", "--quantized"},
                      WatchCase{"vtk", ".vtp", "--deltas"}),
    [](const auto& info) {
      std::string encoding = *info.param.encoding ? info.param.encoding + 2 : "float32";
      return std::string(info.param.format) + "_" + encoding;
    });

TEST_F(FeltCliTest, WatchWithNormalsWritesOneANormalPerVertex) {
  const CommandResult r =
      felt({"watch", "--frames", "1", "--out", dir_.path().string(), "--normals"});
  ASSERT_EQ(r.status, 0) << r.err;
  const MeshFile mesh = read_mesh_file(dir_ / "frame_00000.obj");
  ASSERT_EQ(mesh.normals.size(), 400u);
  for (const auto& n : mesh.normals) EXPECT_NEAR(std::hypot(n[0], n[1], n[2]), 1, 1e-3);
}

TEST_F(FeltCliTest, WatchRefusesAnUnknownFormat) {
  const CommandResult r = felt({"watch", "--out", dir_.path().string(), "--format", "stl"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "felt: --format must be obj, ply or vtk\n");
}

}  // namespace
}  // namespace felt::test
