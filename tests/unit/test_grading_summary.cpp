// The grading summary of the run log and `darcydem check`: D10 ... D60 by
// mass, Cu and Cc, against hand-worked mixtures.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "darcydem/particles/grading.hpp"

namespace darcydem {
namespace {

TEST(GradingSummary, EqualGrainsAreUniform) {
  const std::vector<double> r(1000, 0.5e-3);
  const GradingSummary g = grading_of<3>(r);
  EXPECT_EQ(g.d10, 1e-3);
  EXPECT_EQ(g.d60, 1e-3);
  EXPECT_EQ(g.uniformity(), 1.0);
  EXPECT_EQ(g.curvature(), 1.0);
  EXPECT_EQ(describe_grading<3>(r), "grains: all d = 1 mm\n");
}

TEST(GradingSummary, TwoSizesByHand) {
  // Ten spheres of 1 mm and ten of 2 mm: the small ones carry 10 / (10 +
  // 10 x 8) = 1/9 of the mass, so D10 = 1 mm and D30 = D50 = D60 = 2 mm;
  // Cu = 2, Cc = 4 / 2 = 2. As discs (mass as d^2) the small ones carry 10
  // / 50 = 0.2: D10 = 1 mm still, D30 = 2 mm.
  std::vector<double> r(10, 0.5e-3);
  r.insert(r.end(), 10, 1e-3);
  const GradingSummary s = grading_of<3>(r);
  EXPECT_EQ(s.d_min, 1e-3);
  EXPECT_EQ(s.d_max, 2e-3);
  EXPECT_EQ(s.d10, 1e-3);
  EXPECT_EQ(s.d30, 2e-3);
  EXPECT_EQ(s.d60, 2e-3);
  EXPECT_DOUBLE_EQ(s.uniformity(), 2.0);
  EXPECT_DOUBLE_EQ(s.curvature(), 2.0);
  // 25 discs of 1 mm and 5 of 2 mm: 25 / (25 + 20) = 0.556 of the mass is
  // fine, so D50 = 1 mm and D60 = 2 mm: Cu = 2, Cc = 1 / 2.
  std::vector<double> q(25, 0.5e-3);
  q.insert(q.end(), 5, 1e-3);
  const GradingSummary c = grading_of<2>(q);
  EXPECT_EQ(c.d30, 1e-3);
  EXPECT_EQ(c.d50, 1e-3);
  EXPECT_EQ(c.d60, 2e-3);
  EXPECT_DOUBLE_EQ(c.curvature(), 0.5);
  EXPECT_EQ(describe_grading<2>(q),
            "grains: d 1 to 2 mm; by mass D10 1, D30 1, D50 1, D60 2 mm, Cu 2, Cc 0.5\n");
  EXPECT_THROW(grading_of<3>({}), std::invalid_argument);
}

}  // namespace
}  // namespace darcydem
