// The porosity probe (box_porosity): the grains' exact volume in a box.
#include <gtest/gtest.h>

#include <numbers>

#include "darcydem/generation/generators.hpp"
#include "darcydem/output/probes.hpp"

namespace darcydem {
namespace {

template <int D>
ParticleData<D> lattice(const Vec<D>& lo, const Vec<D>& hi, double spacing, double r) {
  ParticleData<D> p;
  const auto packing = lattice_packing<D>(lo, hi, spacing, r);
  for (std::size_t i = 0; i < packing.position.size(); ++i) p.add(packing.position[i], r, 2650.0, 0, false);
  return p;
}

// A square (2D) or cubic (3D) lattice is periodic with the spacing s, so a
// box spanning a whole number of periods along every axis holds the same
// solid volume wherever it lies: one grain per s^D, porosity 1 - pi r^2/s^2
// or 1 - (4/3) pi r^3/s^3. The boxes below start at arbitrary offsets and
// so cut grains along every face, edge and corner. Tolerance 1e-11 of the
// box: the closed forms are exact but for round-off (about 1e-15 of a grain
// each, summed over at most a few hundred cut grains).
TEST(BoxPorosity, AWholeNumberOfLatticePeriodsAnywhere) {
  const double s = 1e-3;
  const double r = 0.45e-3;
  {
    const auto p = lattice<2>(Vec<2>::Zero(), Vec<2>::Constant(12 * s), s, r);
    const double expected = 1.0 - std::numbers::pi * r * r / (s * s);
    for (const Vec<2>& lo :
         {Vec<2>(2.3 * s, 1.71 * s), Vec<2>(3.0 * s, 4.5 * s), Vec<2>(1.13 * s, 2.97 * s)}) {
      const Vec<2> hi = lo + Vec<2>(5 * s, 3 * s);
      EXPECT_NEAR(box_porosity<2>(p, lo, hi), expected, 1e-11) << lo.transpose();
    }
  }
  {
    const auto p = lattice<3>(Vec<3>::Zero(), Vec<3>::Constant(10 * s), s, r);
    const double expected = 1.0 - 4.0 / 3.0 * std::numbers::pi * r * r * r / (s * s * s);
    for (const Vec<3>& lo : {Vec<3>(2.3 * s, 1.71 * s, 3.05 * s), Vec<3>(1.5 * s, 1.5 * s, 1.5 * s)}) {
      const Vec<3> hi = lo + Vec<3>(4 * s, 3 * s, 5 * s);
      EXPECT_NEAR(box_porosity<3>(p, lo, hi), expected, 1e-11) << lo.transpose();
    }
  }
}

// The same lattices filling a period along every axis (12 and 10 spacings):
// a box of whole lattice periods across the period's ends holds the grains
// beyond them at their images, and so the same solid as anywhere else.
// Without the images it would be up to half empty.
TEST(BoxPorosity, AcrossThePeriodicEnds) {
  const double s = 1e-3;
  const double r = 0.45e-3;
  {
    const auto p = lattice<2>(Vec<2>::Zero(), Vec<2>::Constant(12 * s), s, r);
    PeriodicCell<2> periodic;
    periodic.set_axis(0, 0.0, 12 * s);
    periodic.set_axis(1, 0.0, 12 * s);
    const double expected = 1.0 - std::numbers::pi * r * r / (s * s);
    for (const Vec<2>& lo :
         {Vec<2>(9.3 * s, 10.71 * s), Vec<2>(-2.5 * s, 4.5 * s), Vec<2>(0.13 * s, 0.97 * s)}) {
      const Vec<2> hi = lo + Vec<2>(5 * s, 3 * s);
      EXPECT_NEAR(box_porosity<2>(p, lo, hi, periodic), expected, 1e-11) << lo.transpose();
    }
    // One whole period anywhere.
    EXPECT_NEAR(box_porosity<2>(p, Vec<2>(5.5 * s, 7.2 * s), Vec<2>(17.5 * s, 19.2 * s), periodic), expected,
                1e-11);
  }
  {
    const auto p = lattice<3>(Vec<3>::Zero(), Vec<3>::Constant(10 * s), s, r);
    PeriodicCell<3> periodic;
    for (int k = 0; k < 3; ++k) periodic.set_axis(k, 0.0, 10 * s);
    const double expected = 1.0 - 4.0 / 3.0 * std::numbers::pi * r * r * r / (s * s * s);
    const Vec<3> lo(8.3 * s, -1.71 * s, 7.05 * s);  // across three ends
    EXPECT_NEAR(box_porosity<3>(p, lo, lo + Vec<3>(4 * s, 3 * s, 5 * s), periodic), expected, 1e-11);
    EXPECT_GT(box_porosity<3>(p, lo, lo + Vec<3>(4 * s, 3 * s, 5 * s)), expected + 0.2) << "without images";
  }
}

// A box between the grains holds no solid (porosity 1 exactly); a box
// inside one grain is all solid; a box holding one grain whole and nothing
// else has the grain's volume.
TEST(BoxPorosity, EmptyFullAndOneGrain) {
  const double r = 1e-3;
  ParticleData<3> p;
  p.add(Vec<3>::Zero(), r, 2650.0, 0, false);
  p.add(Vec<3>(5e-3, 0.0, 0.0), r, 2650.0, 0, false);
  EXPECT_EQ(box_porosity<3>(p, Vec<3>(2e-3, -1e-3, -1e-3), Vec<3>(3e-3, 1e-3, 1e-3)), 1.0);
  EXPECT_NEAR(box_porosity<3>(p, Vec<3>::Constant(-0.5 * r), Vec<3>::Constant(0.5 * r)), 0.0, 1e-14);
  const double box = 3e-3 * 3e-3 * 3e-3;
  EXPECT_NEAR(box_porosity<3>(p, Vec<3>::Constant(-1.5e-3), Vec<3>::Constant(1.5e-3)),
              1.0 - 4.0 / 3.0 * std::numbers::pi * r * r * r / box, 1e-15);
}

}  // namespace
}  // namespace darcydem
