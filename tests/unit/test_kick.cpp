// The half kick four particles at a time (simulation/kick.hpp) against the
// velocity-Verlet half kick written out per component:
//   f' = f - alpha |f| sign(v),  v += (f' / m - beta v) dt/2,
// for full and partial groups, fixed particles, and velocities of either sign
// and zero (where Cundall's damping does nothing).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "darcydem/simulation/kick.hpp"

namespace {

using darcydem::kick::kick_group;
using darcydem::kick::Settings;

/// The half kick of one component, as the formulas read.
double kicked(double v, double f, double inv_mass, const Settings& s) {
  const double sign = v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0);
  const double damped = f - s.local * std::abs(f) * sign;
  return v + (damped * inv_mass - s.viscous * v) * s.half_dt;
}

template <int W>
void check_group(int count, const Settings& s) {
  std::array<double, 4 * W> v{};
  std::array<double, 4 * W> f{};
  std::array<double, 4> inv_mass{};
  std::array<std::uint8_t, 4> fixed{};
  for (int l = 0; l < 4; ++l) {
    inv_mass[l] = 1.0 / (0.5 + l);
    fixed[l] = l == 2 ? 1 : 0;  // the third particle is fixed
    for (int c = 0; c < W; ++c) {
      const int k = W * l + c;
      // Velocities negative, zero and positive; forces of both signs.
      v[k] = (k % 3 == 0) ? 0.0 : ((k % 2 == 0) ? -0.25 * k : 0.125 * k);
      f[k] = (k % 2 == 0) ? 1.5 + k : -2.0 - k;
    }
  }
  auto v_after = v;
  kick_group<W>(v_after.data(), f.data(), inv_mass.data(), fixed.data(), count, s);
  for (int l = 0; l < 4; ++l) {
    for (int c = 0; c < W; ++c) {
      const int k = W * l + c;
      // Particles past `count` are not touched, nor are fixed ones.
      const double expected = (l >= count || fixed[l] != 0) ? v[k] : kicked(v[k], f[k], inv_mass[l], s);
      // The kernel may fuse a multiply and an add where the formula rounds
      // twice: a few units in the last place of the result.
      EXPECT_NEAR(v_after[k], expected, 4e-16 * (std::abs(expected) + 1.0))
          << "W " << W << ", count " << count << ", particle " << l << ", component " << c;
    }
  }
}

TEST(Kick, GroupsOfFourFollowTheHalfKickWithDamping) {
  const Settings none{0.0, 0.0, 1e-3};
  const Settings local{0.7, 0.0, 1e-3};
  const Settings both{0.3, 2.5, 1e-3};
  for (const Settings& s : {none, local, both}) {
    for (int count = 1; count <= 4; ++count) {
      check_group<1>(count, s);
      check_group<2>(count, s);
      check_group<3>(count, s);
    }
  }
}

TEST(Kick, LocalDampingOpposesTheVelocity) {
  // alpha = 1 removes a force along the velocity and doubles one against it:
  // a hand-derived case independent of the formula above.
  const Settings s{1.0, 0.0, 0.5};
  std::array<double, 3> v{1.0, -1.0, 0.0};
  const std::array<double, 3> f{2.0, 2.0, 2.0};
  const std::array<double, 1> inv_mass{1.0};
  const std::array<std::uint8_t, 1> fixed{0};
  kick_group<3>(v.data(), f.data(), inv_mass.data(), fixed.data(), 1, s);
  EXPECT_DOUBLE_EQ(v[0], 1.0);         // f' = 2 - 2 = 0
  EXPECT_DOUBLE_EQ(v[1], -1.0 + 2.0);  // f' = 2 + 2 = 4, times dt/2
  EXPECT_DOUBLE_EQ(v[2], 1.0);         // at rest: no damping, f' = 2
}

}  // namespace
