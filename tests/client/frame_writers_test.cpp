// felt's frame writers: a small known frame written as OBJ, PLY and VTK and read back by an
// independent reader (tests/client/mesh_files.cpp), and the VTK files checked by Python's XML
// parser (check_vtk.py).

#include "frame_writers.hpp"

#include <gtest/gtest.h>

#include "mesh_files.hpp"
#include "run_command.hpp"
#include "scratch_directory.hpp"

namespace felt::test {
namespace {

using client::DecodedBody;
using client::DecodedFrame;
using client::MeshFormat;

const std::vector<std::uint32_t> kSheetTriangles = {0, 1, 2, 0, 2, 3};
const std::vector<std::uint32_t> kTetTriangles = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};

/// Two bodies: a square sheet with a name XML must escape, and a tetrahedron's surface.
/// Coordinates far from the origin and tiny ones: six significant digits would change them.
DecodedFrame two_bodies(bool tet_normals) {
  DecodedFrame frame;
  frame.scene_id = 7;
  frame.step = 1234;
  frame.sim_time = 1.234;
  DecodedBody sheet;
  sheet.body_id = 0;
  sheet.name = "sheet <1> & \"2\"";
  sheet.positions = {1234.5678f, 1.0f / 3, -2e-7f, 1235.5678f, 1.0f / 3, 0.0f,
                     1235.5678f, 4.0f / 3, 1e-30f, 1234.5678f, 4.0f / 3, 0.0f};
  sheet.normals = {0, 0, 1, 0, 0, 1, 0.6f, 0, 0.8f, 0, 0, 1};
  sheet.triangles = &kSheetTriangles;
  DecodedBody tet;
  tet.body_id = 2;
  tet.name = "tet";
  tet.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (tet_normals) tet.normals = {-0.57735f, -0.57735f, -0.57735f, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  tet.triangles = &kTetTriangles;
  frame.bodies = {sheet, tet};
  return frame;
}

std::vector<std::array<float, 3>> triples(const std::vector<DecodedBody>& bodies,
                                          std::vector<float> DecodedBody::*values) {
  std::vector<std::array<float, 3>> out;
  for (const DecodedBody& body : bodies) {
    const std::vector<float>& v = body.*values;
    for (std::size_t i = 0; i + 2 < v.size(); i += 3) out.push_back({v[i], v[i + 1], v[i + 2]});
  }
  return out;
}

/// The frame's triangles with every body's indices after the vertices of those before it.
std::vector<std::array<std::uint32_t, 3>> all_triangles(const DecodedFrame& frame) {
  std::vector<std::array<std::uint32_t, 3>> out;
  std::uint32_t first = 0;
  for (const DecodedBody& body : frame.bodies) {
    const auto& t = *body.triangles;
    for (std::size_t i = 0; i + 2 < t.size(); i += 3) {
      out.push_back({first + t[i], first + t[i + 1], first + t[i + 2]});
    }
    first += static_cast<std::uint32_t>(body.positions.size() / 3);
  }
  return out;
}

/// check_vtk.py on `files`: its exit status and what it printed.
CommandResult check_vtk(const std::vector<std::string>& files) {
  std::vector<std::string> argv = {FELT_PYTHON3, CHECK_VTK_PY};
  argv.insert(argv.end(), files.begin(), files.end());
  return run_command(argv);
}

class FrameWriters : public ::testing::TestWithParam<MeshFormat> {
 protected:
  /// `frame` written in the format under test, read back.
  MeshFile written(const DecodedFrame& frame) {
    const auto file = dir_ / (std::string("frame") + client::mesh_extension(GetParam()));
    EXPECT_TRUE(client::write_frame(file, frame, GetParam()));
    return read_mesh_file(file);
  }

  ScratchDirectory dir_;
};

TEST_P(FrameWriters, AFrameReadsBackVertexForVertexAndTriangleForTriangle) {
  const DecodedFrame frame = two_bodies(true);
  const MeshFile mesh = written(frame);
  EXPECT_EQ(mesh.vertices, triples(frame.bodies, &DecodedBody::positions));
  EXPECT_EQ(mesh.normals, triples(frame.bodies, &DecodedBody::normals));
  EXPECT_EQ(mesh.triangles, all_triangles(frame));
  if (GetParam() != MeshFormat::kPly) {  // PLY has one mesh and no names
    EXPECT_EQ(mesh.names, (std::vector<std::string>{"sheet <1> & \"2\"", "tet"}));
  }
}

TEST_P(FrameWriters, NormalsAreWrittenOnlyForTheBodiesThatHaveThem) {
  const DecodedFrame frame = two_bodies(false);
  const MeshFile mesh = written(frame);
  EXPECT_EQ(mesh.vertices.size(), 8u);
  // a PLY vertex has normals or not, for every body
  EXPECT_EQ(mesh.normals.size(), GetParam() == MeshFormat::kPly ? 0u : 4u);
  EXPECT_EQ(mesh.triangles, all_triangles(frame));
}

TEST_P(FrameWriters, ABodyWhoseTrianglesAreUnknownHasVerticesOnly) {
  DecodedFrame frame = two_bodies(true);
  frame.bodies[0].triangles = nullptr;
  const MeshFile mesh = written(frame);
  EXPECT_EQ(mesh.vertices.size(), 8u);
  ASSERT_EQ(mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{4, 6, 5}));
}

INSTANTIATE_TEST_SUITE_P(EachFormat, FrameWriters,
                         ::testing::Values(MeshFormat::kObj, MeshFormat::kPly, MeshFormat::kVtk),
                         [](const auto& info) {
                           return std::string(client::mesh_extension(info.param)).substr(1);
                         });

TEST(FrameWriters, AParaViewSeriesListsEachStepsFileAtItsExactTime) {
  ScratchDirectory dir;
  // a scene that has run for hours: frames 1/60 s apart differ in the seventh digit
  const std::vector<std::pair<double, std::string>> series = {
      {12345.0, "frame_00000.vtp"}, {12345.0 + 1.0 / 60, "frame_00001.vtp"}};
  for (const auto& [time, name] : series) {
    DecodedFrame frame = two_bodies(true);
    frame.sim_time = time;
    ASSERT_TRUE(client::write_frame(dir / name, frame, MeshFormat::kVtk));
  }
  ASSERT_TRUE(client::write_pvd(dir / "frames.pvd", series));
  EXPECT_EQ(read_pvd(dir / "frames.pvd"), series);
  const CommandResult checked = check_vtk({(dir / "frames.pvd").string()});
  EXPECT_EQ(checked.status, 0) << checked.err;
  EXPECT_EQ(checked.out,
            "sheet <1> & \"2\" 4 2\ntet 4 4\n"
            "sheet <1> & \"2\" 4 2\ntet 4 4\n");
}

TEST(FrameWriters, AFileThatCannotBeWrittenIsReported) {
  ScratchDirectory dir;
  const auto missing = dir / "no" / "such" / "directory";
  EXPECT_FALSE(client::write_frame(missing / "frame.obj", two_bodies(true), MeshFormat::kObj));
  EXPECT_FALSE(client::write_pvd(missing / "frames.pvd", {{0, "frame_00000.vtp"}}));
}

TEST(FrameWriters, FormatsAreNamedAsWatchTakesThem) {
  MeshFormat format;
  ASSERT_TRUE(client::parse_mesh_format("ply", format));
  EXPECT_EQ(format, MeshFormat::kPly);
  ASSERT_TRUE(client::parse_mesh_format("vtk", format));
  EXPECT_STREQ(client::mesh_extension(format), ".vtp");
  EXPECT_FALSE(client::parse_mesh_format("stl", format));
}

}  // namespace
}  // namespace felt::test
