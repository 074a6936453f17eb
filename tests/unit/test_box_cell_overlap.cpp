// The volume a box wall takes up in a fluid cell (box_cell_overlap.hpp),
// against hand-derived areas and volumes, symmetry and conservation.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "darcydem/fluid/box_cell_overlap.hpp"

namespace darcydem {
namespace {

// Every figure here is a sum of a few products of O(1) numbers: round-off
// leaves about 1e-15 of them; 1e-12 leaves room and still catches any
// wrong piece (the smallest piece tested is 1e-3).
constexpr double tol = 1e-12;

SolidBox<2> turned_square(double angle, const Vec<2>& centre, double half) {
  SolidBox<2> b;
  b.centre = centre;
  b.half = Vec<2>(half, half);
  b.axes = Eigen::Rotation2Dd(angle).toRotationMatrix();
  return b;
}

SolidBox<3> turned_box(const Eigen::Vector3d& axis, double angle, const Vec<3>& centre, const Vec<3>& half) {
  SolidBox<3> b;
  b.centre = centre;
  b.half = half;
  b.axes = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return b;
}

TEST(BoxCellOverlap, AlignedBoxIsTheProductOfItsIntervals) {
  SolidBox<3> b;
  b.centre = Vec<3>(0.5, 0.5, 0.5);
  b.half = Vec<3>(0.5, 0.25, 1.0);  // [0, 1] x [0.25, 0.75] x [-0.5, 1.5]
  // The cell [0.2, 2] x [0, 0.5] x [0, 1]: 0.8 x 0.25 x 1.
  EXPECT_NEAR(box_cell_volume(b, Vec<3>(0.2, 0.0, 0.0), Vec<3>(2.0, 0.5, 1.0)), 0.2, tol);
  EXPECT_EQ(box_cell_volume(b, Vec<3>(1.0, 0.0, 0.0), Vec<3>(2.0, 1.0, 1.0)), 0.0);  // touching only
  // A quarter turn about z swaps the extents along x and y: [0.25, 0.75] x [0, 1].
  b.axes = Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(b.grid_aligned());
  EXPECT_NEAR(box_cell_volume(b, Vec<3>(0.2, 0.0, 0.0), Vec<3>(2.0, 0.5, 1.0)), 0.5 * 0.5 * 1.0, tol);
}

TEST(BoxCellOverlap, SquareTurnedByAnEighthIsCutAsADiamond) {
  // The square of side 2 turned by 45 degrees about the origin is the
  // diamond |x| + |y| <= sqrt(2). Beyond x = c it is the triangle of apex
  // (sqrt 2, 0) and half-base sqrt(2) - c: area (sqrt(2) - c)^2.
  const SolidBox<2> b = turned_square(std::numbers::pi / 4, Vec<2>::Zero(), 1.0);
  EXPECT_FALSE(b.grid_aligned());
  const double r2 = std::numbers::sqrt2;
  for (double c : {0.0, 0.3, 0.5, 1.2, 1.4}) {
    const double expected = (r2 - c) * (r2 - c);
    EXPECT_NEAR(box_cell_volume(b, Vec<2>(c, -5.0), Vec<2>(5.0, 5.0)), expected, tol) << "c = " << c;
  }
  // The cell [0, 1] x [0, 1]: the quarter diamond (1) less the corner
  // beyond x + y = sqrt 2 that is inside the cell, the triangle with legs
  // 2 - sqrt 2 (vertices (1, sqrt2 - 1), (sqrt2 - 1, 1), (1, 1)).
  const double leg = 2.0 - r2;
  EXPECT_NEAR(box_cell_volume(b, Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0)), 1.0 - 0.5 * leg * leg, tol);
  // Inside the cell whole; the cell inside the box whole.
  EXPECT_NEAR(box_cell_volume(b, Vec<2>(-2.0, -2.0), Vec<2>(2.0, 2.0)), 4.0, tol);
  EXPECT_NEAR(box_cell_volume(b, Vec<2>(-0.5, -0.5), Vec<2>(0.5, 0.5)), 1.0, tol);
}

TEST(BoxCellOverlap, CubeTurnedAboutAnAxisIsAnExtrudedDiamond) {
  // The cube of side 2 turned by 45 degrees about z: the diamond of the
  // test above over -1 <= z <= 1. Beyond x = c: 2 (sqrt(2) - c)^2; with
  // the cell also cut at z = 0.25, a share of 0.75 of that height.
  const SolidBox<3> b =
      turned_box(Eigen::Vector3d::UnitZ(), std::numbers::pi / 4, Vec<3>::Zero(), Vec<3>::Ones());
  const double r2 = std::numbers::sqrt2;
  for (double c : {0.0, 0.4, 1.0}) {
    const double a = (r2 - c) * (r2 - c);
    EXPECT_NEAR(box_cell_volume(b, Vec<3>(c, -5.0, -5.0), Vec<3>(5.0, 5.0, 5.0)), 2.0 * a, tol);
    EXPECT_NEAR(box_cell_volume(b, Vec<3>(c, -5.0, 0.25), Vec<3>(5.0, 5.0, 5.0)), 0.75 * a, tol);
  }
}

TEST(BoxCellOverlap, CubeTurnedOntoItsDiagonalHasTheCapsOfATriangle) {
  // The unit cube [0, 1]^3 turned so that its main diagonal lies along z,
  // with the corner at the origin. The plane z = t (t <= 1/sqrt 3) cuts
  // from it the corner tetrahedron x + y + z <= sqrt(3) t of the cube's
  // own axes, of volume (sqrt(3) t)^3 / 6.
  SolidBox<3> b;
  const Eigen::Vector3d diagonal = Eigen::Vector3d::Ones().normalized();
  const Eigen::Matrix3d turn =
      Eigen::Quaterniond::FromTwoVectors(diagonal, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  b.axes = turn;
  b.half = Vec<3>::Constant(0.5);
  b.centre = turn * Vec<3>::Constant(0.5);
  for (double t : {0.1, 0.3, 0.5}) {
    const double s = std::sqrt(3.0) * t;
    EXPECT_NEAR(box_cell_volume(b, Vec<3>(-5.0, -5.0, -5.0), Vec<3>(5.0, 5.0, t)), s * s * s / 6.0, tol)
        << "t = " << t;
    // By the cube's central symmetry, the same beyond the far end's plane.
    EXPECT_NEAR(box_cell_volume(b, Vec<3>(-5.0, -5.0, std::sqrt(3.0) - t), Vec<3>(5.0, 5.0, 5.0)),
                s * s * s / 6.0, tol);
  }
}

TEST(BoxCellOverlap, AGridOfCellsSharesATurnedBoxWholeAndEachPartMovesSmoothly) {
  const SolidBox<3> box =
      turned_box(Eigen::Vector3d(1.0, 2.0, 3.0), 0.7, Vec<3>(0.13, -0.07, 0.21), Vec<3>(0.9, 0.35, 0.6));
  // Cells of 0.4 m over [-2, 2]^3: the box (within 1.6 m of its centre)
  // crosses many, on faces, edges and corners.
  auto sum_over_grid = [](const SolidBox<3>& b) {
    double sum = 0.0;
    for (int i = 0; i < 10; ++i) {
      for (int j = 0; j < 10; ++j) {
        for (int k = 0; k < 10; ++k) {
          const Vec<3> lo(-2.0 + 0.4 * i, -2.0 + 0.4 * j, -2.0 + 0.4 * k);
          sum += box_cell_volume(b, lo, lo + Vec<3>::Constant(0.4));
        }
      }
    }
    return sum;
  };
  EXPECT_NEAR(sum_over_grid(box), box.volume(), tol);
  // Point symmetry: the box centred at the origin has as much in the
  // octant x, y, z > 0 as in x, y, z < 0, for any turn.
  SolidBox<3> centred = box;
  centred.centre.setZero();
  EXPECT_NEAR(box_cell_volume(centred, Vec<3>::Zero(), Vec<3>::Constant(5.0)),
              box_cell_volume(centred, Vec<3>::Constant(-5.0), Vec<3>::Zero()), tol);
  // Moved in steps of length 1e-4 sqrt(3) m, the part in one cell changes
  // by at most the volume the box sweeps: its projection on a plane across
  // the motion (at most half its surface, 4 (h0 h1 + h1 h2 + h2 h0)) times
  // the step. And the grid still holds the whole box.
  const Vec<3> lo(0.0, -0.4, 0.0);
  const Vec<3> hi = lo + Vec<3>::Constant(0.4);
  const Vec<3>& h = box.half;
  const double bound = 4.0 * (h[0] * h[1] + h[1] * h[2] + h[2] * h[0]) * 1e-4 * std::sqrt(3.0);
  SolidBox<3> moving = box;
  double last = box_cell_volume(moving, lo, hi);
  double largest_jump = 0.0;
  for (int s = 0; s < 3000; ++s) {
    moving.centre += Vec<3>(1e-4, 1e-4, -1e-4);
    const double now = box_cell_volume(moving, lo, hi);
    largest_jump = std::max(largest_jump, std::abs(now - last));
    last = now;
    if (s % 500 == 0) {
      EXPECT_NEAR(sum_over_grid(moving), moving.volume(), tol) << "step " << s;
    }
  }
  EXPECT_LT(largest_jump, bound);
  EXPECT_GT(largest_jump, 0.0);
}

TEST(BoxCellOverlap, TurnedRectangleSharesItsAreaAmongCells) {
  const SolidBox<2> b = [] {
    SolidBox<2> r = turned_square(0.3, Vec<2>(0.05, 0.11), 0.0);
    r.half = Vec<2>(0.7, 0.2);
    return r;
  }();
  double sum = 0.0;
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j < 12; ++j) {
      const Vec<2> lo(-1.2 + 0.2 * i, -1.2 + 0.2 * j);
      sum += box_cell_volume(b, lo, lo + Vec<2>::Constant(0.2));
    }
  }
  EXPECT_NEAR(sum, 4.0 * 0.7 * 0.2, tol);
}

}  // namespace
}  // namespace darcydem
