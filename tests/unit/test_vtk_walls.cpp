// The walls' VTK file: a box's corners where the box is, an infinite plane
// drawn as a square (a line in 2D) in its plane, centred on the point of
// the plane nearest the middle of the drawing box and as wide as 1.1 of its
// diagonal; the cell types and counts ParaView reads.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "../common/vtk_text.hpp"
#include "darcydem/output/vtk.hpp"

namespace darcydem {
namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string temp_file(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (name + std::to_string(getpid()) + ".vtu")).string();
}

TEST(WallsVtu, PlateAndFloorIn3D) {
  Wall<3> plate;
  plate.shape = WallShape::box;
  plate.point = Vec<3>(1.0, 1.5, 1.0);
  plate.half = Vec<3>(1.0, 1.5, 0.0);  // x 0..2, y 0..3 at z = 1
  plate.force = Vec<3>(0.0, 0.0, -2.5);
  Wall<3> floor;
  floor.point = Vec<3>(5.0, 5.0, 0.0);
  floor.normal = Vec<3>(0.0, 0.0, 1.0);
  const std::string path = temp_file("walls3d_");
  write_walls_vtu<3>(path, {plate, floor}, Vec<3>(0, 0, 0), Vec<3>(2, 2, 2));
  const std::string text = read_all(path);
  std::filesystem::remove(path);
  EXPECT_NE(text.find("NumberOfPoints=\"12\" NumberOfCells=\"2\""), std::string::npos);
  const auto p = testing::vtk_array(text, "position");
  ASSERT_EQ(p.size(), 36U);
  const double plate_corners[8][3] = {{0, 0, 1}, {2, 0, 1}, {2, 3, 1}, {0, 3, 1},
                                      {0, 0, 1}, {2, 0, 1}, {2, 3, 1}, {0, 3, 1}};
  for (int c = 0; c < 8; ++c) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(p[3 * c + k], plate_corners[c][k]) << c;
  }
  // The floor: corners in z = 0 about (1, 1, 0), half-width 0.55 sqrt(12).
  const double half = 0.55 * std::sqrt(12.0);
  for (int c = 8; c < 12; ++c) {
    EXPECT_EQ(p[3 * c + 2], 0.0);
    EXPECT_NEAR(std::hypot(p[3 * c] - 1.0, p[3 * c + 1] - 1.0), half * std::sqrt(2.0), 1e-12);
  }
  EXPECT_EQ(testing::vtk_array(text, "offsets"), (std::vector<double>{8, 12}));
  EXPECT_EQ(testing::vtk_array(text, "types"), (std::vector<double>{12, 9}));  // hexahedron, quad
  EXPECT_EQ(testing::vtk_array(text, "force"), (std::vector<double>{0, 0, -2.5, 0, 0, 0}));
}

// A mesh wall: one triangle a facet, where the wall stands now (its
// facets in its own frame, turned by its axes and moved to its point), each
// cell with the wall's number and force; after it the next wall's cell.
TEST(WallsVtu, MeshFacetsAreTriangles) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertex = {{-1.0, -1.0, 0.0}, {1.0, -1.0, 0.0}, {1.0, 1.0, 0.0}, {-1.0, 1.0, 0.0}};
  mesh->triangle = {{0, 1, 2}, {0, 2, 3}};
  ASSERT_EQ(mesh->finish(), "");
  Wall<3> lid;
  lid.shape = WallShape::mesh;
  lid.mesh = mesh;
  lid.point = Vec<3>(0.0, 0.0, 2.0);
  // A quarter turn about z: (x, y) -> (-y, x).
  lid.axes = Eigen::AngleAxisd(std::numbers::pi / 2.0, Vec<3>::UnitZ()).toRotationMatrix();
  lid.force = Vec<3>(0.0, 0.0, 3.0);
  Wall<3> floor;
  floor.point = Vec<3>(0.0, 0.0, 0.0);
  floor.normal = Vec<3>(0.0, 0.0, 1.0);
  const std::string path = temp_file("walls_mesh_");
  write_walls_vtu<3>(path, {lid, floor}, Vec<3>(-1, -1, 0), Vec<3>(1, 1, 2));
  // With the force on each facet: facet 1 (area 2 m^2) takes (0.5, 0, 2.5) N.
  const std::vector<std::vector<Vec<3>>> shares = {{Vec<3>(-0.5, 0.0, 0.5), Vec<3>(0.5, 0.0, 2.5)}, {}};
  const std::string shared_path = temp_file("walls_mesh_shared_");
  write_walls_vtu<3>(shared_path, {lid, floor}, Vec<3>(-1, -1, 0), Vec<3>(1, 1, 2), &shares);
  const std::string shared = read_all(shared_path);
  std::filesystem::remove(shared_path);
  EXPECT_EQ(testing::vtk_array(shared, "force"), (std::vector<double>{-0.5, 0, 0.5, 0.5, 0, 2.5, 0, 0, 0}));
  // The normal part over the area: 0.5 / 2 and 2.5 / 2 Pa (the facets lie in
  // z = 2; turning them about z keeps their normal); 0 on the plane.
  EXPECT_EQ(testing::vtk_array(shared, "normal_stress"), (std::vector<double>{0.25, 1.25, 0.0}));
  const std::string text = read_all(path);
  std::filesystem::remove(path);
  EXPECT_NE(text.find("NumberOfPoints=\"10\" NumberOfCells=\"3\""), std::string::npos);
  const auto p = testing::vtk_array(text, "position");
  ASSERT_EQ(p.size(), 30U);
  // Facet 0: corners 0, 1, 2 turned: (1, -1), (1, 1), (-1, 1) at z = 2.
  const double facet0[3][3] = {{1, -1, 2}, {1, 1, 2}, {-1, 1, 2}};
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[3 * c + k], facet0[c][k], 1e-15) << c;
  }
  EXPECT_EQ(testing::vtk_array(text, "offsets"), (std::vector<double>{3, 6, 10}));
  EXPECT_EQ(testing::vtk_array(text, "types"), (std::vector<double>{5, 5, 9}));
  EXPECT_EQ(testing::vtk_array(text, "wall_id"), (std::vector<double>{0, 0, 1}));
  const auto f = testing::vtk_array(text, "force");
  ASSERT_EQ(f.size(), 9U);
  EXPECT_EQ(f[2], 3.0);
  EXPECT_EQ(f[5], 3.0);
  EXPECT_EQ(f[8], 0.0);
}

TEST(WallsVtu, SegmentAndSlopeIn2D) {
  Wall<2> pile;
  pile.shape = WallShape::box;
  pile.point = Vec<2>(0.02, 0.013);
  pile.half = Vec<2>(0.0, 0.007);
  Wall<2> slope;
  slope.point = Vec<2>(0.0, 0.0);
  slope.normal = Vec<2>(-0.6, 0.8);
  // A segment from (0, 0) to (2, 0) turned by 90 degrees about its middle:
  // from (1, -1) to (1, 1).
  Wall<2> turned;
  turned.shape = WallShape::box;
  turned.point = Vec<2>(1.0, 0.0);
  turned.half = Vec<2>(1.0, 0.0);
  turned.axes << std::cos(std::numbers::pi / 2), -1.0, 1.0, std::cos(std::numbers::pi / 2);
  const std::string path = temp_file("walls2d_");
  write_walls_vtu<2>(path, {pile, slope, turned}, Vec<2>(0, 0), Vec<2>(0.04, 0.03));
  const std::string text = read_all(path);
  std::filesystem::remove(path);
  EXPECT_NE(text.find("NumberOfPoints=\"10\" NumberOfCells=\"3\""), std::string::npos);
  const auto p = testing::vtk_array(text, "position");
  ASSERT_EQ(p.size(), 30U);
  const double turned_corners[4][2] = {{1, -1}, {1, 1}, {1, 1}, {1, -1}};
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(p[18 + 3 * c], turned_corners[c][0], 1e-15) << c;
    EXPECT_NEAR(p[19 + 3 * c], turned_corners[c][1], 1e-15) << c;
  }
  EXPECT_NEAR(p[0], 0.02, 1e-15);  // the pile's lower corner
  EXPECT_NEAR(p[1], 0.006, 1e-15);
  EXPECT_NEAR(p[7], 0.02, 1e-15);  // its upper one
  // The slope's line: both ends on the plane, 1.1 x 0.05 m apart, centred
  // on the point of it nearest (0.02, 0.015): (0.02, 0.015) - (-0.6 x 0.02 +
  // 0.8 x 0.015) n = (0.02, 0.015), which lies on it.
  const Vec<2> a(p[12], p[13]);
  const Vec<2> b(p[15], p[16]);
  EXPECT_NEAR(a.dot(slope.normal), 0.0, 1e-15);
  EXPECT_NEAR(b.dot(slope.normal), 0.0, 1e-15);
  EXPECT_NEAR((a - b).norm(), 1.1 * 0.05, 1e-15);
  EXPECT_NEAR((0.5 * (a + b) - Vec<2>(0.02, 0.015)).norm(), 0.0, 1e-15);
  EXPECT_EQ(testing::vtk_array(text, "types"), (std::vector<double>{9, 3, 9}));  // quad, line, quad
}

TEST(WallsVtu, CylindersAreDrawnOnTheirSurface) {
  // 3D: radius 0.5 about the axis (0, 0.6, 0.8) through (1, 1, 1), drawn
  // across the view centred on the point of the axis nearest the middle
  // of the drawing box (1, 1, 1): every point 0.5 from the axis, 0.55
  // sqrt(12) along it either way.
  Wall<3> cell;
  cell.shape = WallShape::cylinder;
  cell.point = Vec<3>(1.0, 1.0, 1.0) - 2.0 * Vec<3>(0.0, 0.6, 0.8);
  cell.axis = Vec<3>(0.0, 0.6, 0.8);
  cell.radius = 0.5;
  const std::string path = temp_file("walls_cyl3d_");
  write_walls_vtu<3>(path, {cell}, Vec<3>(0, 0, 0), Vec<3>(2, 2, 2));
  const std::string text = read_all(path);
  std::filesystem::remove(path);
  EXPECT_NE(text.find("NumberOfPoints=\"130\" NumberOfCells=\"1\""), std::string::npos);
  const auto p = testing::vtk_array(text, "position");
  ASSERT_EQ(p.size(), 390U);
  const double along = 0.55 * std::sqrt(12.0);
  for (int c = 0; c < 130; ++c) {
    const Vec<3> d = Vec<3>(p[3 * c], p[3 * c + 1], p[3 * c + 2]) - Vec<3>(1.0, 1.0, 1.0);
    const double a = d.dot(cell.axis);
    EXPECT_NEAR(std::abs(a), along, 1e-14) << c;
    EXPECT_NEAR((d - a * cell.axis).norm(), 0.5, 1e-14) << c;
  }
  EXPECT_EQ(testing::vtk_array(text, "types"), (std::vector<double>{6}));  // a triangle strip
  // 2D: a closed line round the circle of radius 2 about (1, -1).
  Wall<2> drum;
  drum.shape = WallShape::cylinder;
  drum.point = Vec<2>(1.0, -1.0);
  drum.radius = 2.0;
  const std::string path2 = temp_file("walls_cyl2d_");
  write_walls_vtu<2>(path2, {drum}, Vec<2>(0, 0), Vec<2>(1, 1));
  const std::string text2 = read_all(path2);
  std::filesystem::remove(path2);
  const auto q = testing::vtk_array(text2, "position");
  ASSERT_EQ(q.size(), 3U * 65U);
  for (int c = 0; c < 65; ++c) {
    EXPECT_NEAR(std::hypot(q[3 * c] - 1.0, q[3 * c + 1] + 1.0), 2.0, 1e-14) << c;
    EXPECT_EQ(q[3 * c + 2], 0.0);
  }
  EXPECT_NEAR(q[0], q[3 * 64], 1e-14);  // closed
  EXPECT_NEAR(q[1], q[3 * 64 + 1], 1e-14);
  EXPECT_EQ(testing::vtk_array(text2, "types"), (std::vector<double>{4}));  // a poly-line
}

}  // namespace
}  // namespace darcydem
