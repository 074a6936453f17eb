// A consolidated-undrained triaxial test (examples/fluid_cases/
// undrained_triaxial.toml): the cubic lattice of 3 x 3 x 3 frictionless
// spheres of the B check, consolidated drained under 100 Pa all round, then
// sealed and sheared by its top platen at a constant speed while the side
// platens' servos hold the total cell pressure, then held.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "darcydem/simulation/runner.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

using namespace darcydem;

TEST(UndrainedTriaxial, TakesSkemptonsAAndTheElasticStressPath) {
  // Expected, by hand (independent of the run). The lattice's skeleton:
  // along each axis N x N independent columns of N spheres and N + 1
  // contacts in series (the platens' included), so each effective stress
  // follows its own axis's strain with E = N k_n / (2 r (N + 1)) = 750 kPa
  // (frictionless: no contact turns). Sealed, with incompressible grains,
  // the water's pressure follows the sample's volume strain, u = c e_v with
  // c = K_f / n, n the porosity as the shear starts. Sheared by an axial strain e1 under a
  // constant total cell pressure, each side's effective stress falls by u,
  // so it swells by e3 = u / E, and e_v = e1 - 2 e3: u = e1 c E / (E + 2 c)
  // (22.49 Pa at e1 = 1.5e-4). The axial effective stress rises by E e1 and
  // the deviator by E e1 + u; Skempton's A = u / (B (E e1 + u)) = 1/3 with
  // B = 1 / (1 + n (E / 3) / K_f), whatever K_f.
  // Tolerances: 1e-3 of each change, for the geometry's change (strains of
  // 1e-4: the servos and the stress probe take the present sides, the
  // closed form the first ones) and the servos' residual at the hold's end.
  // Measured: u 1.4e-5 off, the water's thrust on the top platen and the
  // sides' fall 1.3e-5 off u, the axial stress 2e-5, A 1e-6; the sides'
  // swell 2.9e-4 off their effective stress's fall over E, by hand
  // 4.1e-4 (the stress over the present section, shrunk by e1 - e3) - 2.7e-4
  // (a column's section, that of the consolidated sample) + 1.3e-4 (the
  // strain over the consolidated side). Along the shear, where the side
  // servos lag the pressure by 2 % of u, u = c e_v still holds at every
  // probe row to 1e-3 of the final u (measured 2.4e-4: Biot's law with the
  // porosity of each step). Drained first, u below 1e-4 of the cell
  // pressure at the consolidation's end.
  const std::string out = darcydem::testing::temp_dir("undrained_triaxial");
  ASSERT_FALSE(
      darcydem::testing::run_example<3>("examples/fluid_cases/undrained_triaxial.toml", out).interrupted);
  const auto probes = darcydem::testing::read_probes(out + "/probes.csv");
  const auto& t = probes.at("time");

  const int n = 3;
  const double r = 0.0005, kn = 1e3, kf = 1.19e5, cell_pressure = 100.0;
  const double modulus = n * kn / (2.0 * r * (n + 1));
  auto side = [&](const char* axis, std::size_t j) {
    return probes.at(std::string(axis) + "_high_" + axis)[j] -
           probes.at(std::string(axis) + "_low_" + axis)[j];
  };
  // The consolidation's end (it lasts 0.03 s) and the hold's.
  std::size_t consolidated = 0;
  while (t[consolidated + 1] <= 0.03 - 1e-9) ++consolidated;
  const std::size_t last = t.size() - 1;
  const std::size_t c0 = consolidated;
  const auto& u = probes.at("pore_pressure");
  // The porosity as the shear starts: the spheres' volume in the sample
  // that the consolidation has shrunk by 4e-4 (it was 1 - pi / 6).
  const double spheres = n * n * n * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double porosity = 1.0 - spheres / (side("x", c0) * side("y", c0) * side("z", c0));
  const double c = kf / porosity;
  const double b = 1.0 / (1.0 + porosity * (modulus / 3.0) / kf);
  auto strain = [&](const char* axis, std::size_t j) { return 1.0 - side(axis, j) / side(axis, c0); };
  auto volume_strain = [&](std::size_t j) { return strain("x", j) + strain("y", j) + strain("z", j); };

  EXPECT_LT(std::abs(u[c0]), 1e-4 * cell_pressure);
  const double e1 = strain("z", last);
  const double u_expected = e1 * c * modulus / (modulus + 2.0 * c);
  const double axial_rise = probes.at("axial_stress")[last] - probes.at("axial_stress")[c0];
  // The water's thrust on the top platen over its present area: the total
  // axial stress is the grains' plus the water's.
  const double area = side("x", last) * side("y", last);
  const double water = probes.at("axial_water")[last] / area;
  const double deviator = axial_rise + water;  // the sides' total stress stays the cell pressure
  const double skempton_a = u[last] / (b * deviator);
  const double swell = -strain("x", last);
  const double lateral_fall = probes.at("lateral_stress")[c0] - probes.at("lateral_stress")[last];
  std::printf(
      "undrained triaxial: e1 = %.6e; u = %.6f Pa (closed form %.6f), the water on the top platen %.6f Pa; "
      "axial effective stress up by %.6f Pa (E e1 = %.6f); A = %.6f; the sides' effective stress down by "
      "%.6f Pa, "
      "their swell %.6e (its fall / E = %.6e)\n",
      e1, u[last], u_expected, water, axial_rise, modulus * e1, skempton_a, lateral_fall, swell,
      lateral_fall / modulus);
  EXPECT_NEAR(e1, 1.5e-4, 1e-3 * 1.5e-4);  // the top platen's push, 4.5e-7 m over the 3 mm side
  EXPECT_NEAR(u[last] / u_expected, 1.0, 1e-3);
  EXPECT_NEAR(water / u[last], 1.0, 1e-3);
  EXPECT_NEAR(axial_rise / (modulus * e1), 1.0, 1e-3);
  EXPECT_NEAR(skempton_a, 1.0 / 3.0, 1e-3 / 3.0);
  EXPECT_NEAR(lateral_fall / u[last], 1.0, 1e-3);
  EXPECT_NEAR(swell / (lateral_fall / modulus), 1.0, 1e-3);
  EXPECT_NEAR(strain("y", last) / strain("x", last), 1.0, 1e-6);
  // Along the shear: Biot's law, u = c e_v, at every probe row.
  double worst = 0.0;
  for (std::size_t j = c0; j <= last; ++j) worst = std::max(worst, std::abs(u[j] - c * volume_strain(j)));
  std::printf("undrained triaxial: |u - c e_v| <= %.3e Pa along the shear (%.2e of u)\n", worst,
              worst / u[last]);
  EXPECT_LT(worst, 1e-3 * u[last]);
}
