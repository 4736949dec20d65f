#include "scene/obj_reader.hpp"

#include <sstream>

#include <gtest/gtest.h>

#include "core/geometry/mesh_topology.hpp"

namespace felt {
namespace {

std::expected<TriangleMesh, std::string> parse(const std::string& text) {
  std::istringstream in(text);
  return read_obj(in, "test.obj");
}

TEST(ObjReader, ReadsPositionsTexcoordsAndTriangulatesPolygons) {
  const auto mesh = parse(R"(# a quad and a triangle
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1 4/4/1
f 2//1 5//1 -3//1
g ignored
usemtl ignored
)");
  ASSERT_TRUE(mesh) << mesh.error();
  EXPECT_EQ(mesh->positions.size(), 5u);
  ASSERT_EQ(mesh->triangles.size(), 3u);
  EXPECT_EQ(mesh->triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh->triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(mesh->triangles[2], (Triangle{1, 4, 2}));  // -3 is the third-last vertex
  ASSERT_EQ(mesh->uv.size(), 5u);
  EXPECT_EQ(mesh->uv[2], Vec2(1, 1));
}

TEST(ObjReader, ErrorsNameTheLine) {
  EXPECT_EQ(parse("v 0 0 0\nv 1 0 0\nf 1 2 3\n").error(), "test.obj:3: face index 3 out of range");
  EXPECT_EQ(parse("v 0 0\n").error(), "test.obj:1: bad vertex");
  EXPECT_EQ(parse("v 0 0 0\nv 1 0 0\nf 1 2\n").error(),
            "test.obj:3: a face needs at least 3 corners");
  EXPECT_EQ(parse("v 0 0 0\nf 1 x 1\n").error(), "test.obj:2: bad face corner \"x\"");
  EXPECT_EQ(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/4 2 3\n").error(),
            "test.obj:4: texture index 4 out of range");
  EXPECT_EQ(parse("v 0 0 0\n").error(), "test.obj: no faces");
  EXPECT_EQ(parse("v nan 0 0\n").error(), "test.obj:1: bad vertex");
}

TEST(ObjReader, CoordinatesBeyondAMillionMetresAreRefusedWithTheirLine) {
  // 1e300 is a finite double: it loaded, and the cloth's masses and energies became NaN
  EXPECT_EQ(parse("v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n").error(),
            "test.obj:2: vertex coordinate outside ±1e6 m");
  EXPECT_EQ(parse("v 0 0 -1000001\n").error(), "test.obj:1: vertex coordinate outside ±1e6 m");
  EXPECT_TRUE(parse("v 0 0 0\nv 1e6 0 0\nv 0 -1e6 0\nf 1 2 3\n"));
}

TEST(ObjReader, TheBunnyIsAClosedManifold) {
  const auto mesh = read_obj_file(std::string(FELT_SCENE_DIR) + "/meshes/bunny.obj");
  ASSERT_TRUE(mesh) << mesh.error();
  EXPECT_EQ(mesh->positions.size(), 1839u);
  EXPECT_EQ(mesh->triangles.size(), 3674u);
  // Euler characteristic of a sphere: V − E + F = 2
  const auto edges = static_cast<long>(unique_edge_count(mesh->triangles));
  EXPECT_EQ(1839 - edges + 3674, 2);
}

}  // namespace
}  // namespace felt
