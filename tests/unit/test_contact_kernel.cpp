// The contact kernel's tangential history on a turning contact plane.
#include <gtest/gtest.h>

#include <cmath>

#include "darcydem/contact/contact_kernel.hpp"

namespace darcydem {
namespace {

// A history is turned into the contact plane with its length kept: h = (3,
// 0, 4) e onto the plane normal to z becomes (5, 0, 0) e (to 1e-15, the
// series' and square root's round-off). Below e ~ 1e-154, |h|^2 is
// subnormal and its reciprocal overflows to infinity: a history already in
// the plane then got 0 x inf = NaN for its length factor. Such histories
// arise from the rolling springs of a settled bed at rest (found as NaN
// kinetic energy after 0.9 s of settling with rolling resistance); they
// must stay finite and, in the plane, unchanged.
TEST(ContactKernel, HistoryTurnedIntoThePlaneKeepsItsLength) {
  const Vec<3> n(0.0, 0.0, 1.0);
  for (double e : {1.0, 1e-100, 1e-155, 1e-160, 1e-170}) {
    Vec<3> h(3.0 * e, 0.0, 4.0 * e);
    rotate_into_plane<3, 3>(h, n);
    ASSERT_TRUE(h.allFinite()) << "scale " << e;
    if (e * e > 1e-300) {
      EXPECT_NEAR(h.x(), 5.0 * e, 1e-15 * e) << "scale " << e;
      EXPECT_EQ(h.z(), 0.0) << "scale " << e;
    }
  }
  // A history lying in the plane is unchanged.
  Vec<3> h(1e-160, 2e-160, 0.0);
  rotate_into_plane<3, 3>(h, n);
  EXPECT_EQ(h, Vec<3>(1e-160, 2e-160, 0.0));
}

}  // namespace
}  // namespace darcydem
