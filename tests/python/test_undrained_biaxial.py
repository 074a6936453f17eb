"""The CU biaxial test of a random packing (examples/fluid_cases/
undrained_biaxial.toml) against its dry constant-volume twin, run by
examples/fluid_cases/undrained_biaxial.py through the darcydem module: the
effective-stress principle of the coupling, on a packing whose response no
closed form gives, dense (it dilates) and loose (it liquefies). Run by ctest
with the source tree as the first argument, the module on PYTHONPATH and a
class to run (DenseSample, LooseSample), each about 40 s on one core."""
import importlib.util
import os
import sys
import unittest

SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else os.getcwd()
spec = importlib.util.spec_from_file_location("undrained_biaxial",
                                              os.path.join(SOURCE, "examples/fluid_cases/undrained_biaxial.py"))
biaxial = importlib.util.module_from_spec(spec)
spec.loader.exec_module(biaxial)
import darcydem  # noqa: E402

K_F = 2.2e9  # Pa, the scene's water
CELL_PRESSURE = 1e5  # Pa, the side platens' total stress


class DenseSample(unittest.TestCase):
    """Consolidated with the scene's friction of 0.02: dense (n0 0.191)."""

    @classmethod
    def setUpClass(cls):
        cls.undrained, cls.porosity = biaxial.shear(darcydem, False, 0.02)
        cls.dry, _ = biaxial.shear(darcydem, True, 0.02)

    def test_the_sealed_water_keeps_the_volume_by_its_compressibility(self):
        # Sealed, with rigid grains, the sample's area changes by the pore
        # water's: dA / A0 = -n0 u / K_f (u = K_f times the pore area's
        # relative loss). Tolerance 2 % of the largest n0 |u| / K_f
        # (1.2e-5), for what the platens' positions do not show: a plane
        # that displaces the water and stands in the grid's first layer of
        # cells takes 1e-5 of the layer's width it has not crossed as solid
        # in front of it (so that a platen on the grid's side stands on it;
        # PoreFluid::displaced_box). With one cell all four platens keep
        # theirs, 2.4e-7 m at the sides and 4.7e-7 m at the top and bottom
        # (3.7e-8 m^2 of water less than W H less the discs, as measured),
        # and as the sample shortens and widens these slivers lose by hand
        # 4.8e-7 m x 4.4e-4 m - 9.4e-7 m x 1.8e-4 m = 4e-11 m^2 per 1 % of
        # axial strain, 5e-8 of A0: 0.9 % of the scale at 2 %. Biot's law
        # taking the porosity of each step, and the area read from the
        # platens, add 1e-5 and 1e-12 of it. Measured: 0.9 %.
        # The constant-volume twin keeps its area to round-off (its
        # control), and with the drainage held open its u is zero.
        scale = self.porosity * max(abs(u) for u in self.undrained["pore_pressure"]) / K_F
        self.assertGreater(scale, 5e-6)  # the water took a pressure worth measuring
        worst = max(abs(da + self.porosity * u / K_F)
                    for da, u in zip(self.undrained["area_change"], self.undrained["pore_pressure"]))
        self.assertLess(worst, 2e-2 * scale)
        self.assertLess(max(abs(da) for da in self.dry["area_change"]), 1e-12)
        self.assertEqual(max(abs(u) for u in self.dry["pore_pressure"]), 0.0)

    def test_the_effective_stress_path_is_the_constant_volume_tests(self):
        # Terzaghi's principle in the coupling: the grains carry the total
        # stress less u, so a sealed sample of nearly incompressible water
        # follows the dry constant-volume path. The water's compressibility
        # parts them by about the skeleton's modulus (2e8 Pa, k_n over the
        # overlaps at 100 kPa) times n0 u / K_f, 2-3 kPa at 2 % (0.5 % of
        # p'). The packing's own slips part them more: two constant-volume
        # runs that differ only in how often the sides' speed is set (every
        # 40 or 50 steps) differ at these strains by up to 2.1 % of p' in
        # p' and 1.3 % of p' in q (2.9 % of q), growing with strain as the
        # 200 discs' slips go their own ways. Tolerance 5 % of p', above that
        # spread. Measured, undrained against constant volume: up to 1.0 %
        # of p' in p' and in q (at 1.75 %). A drained shear instead (the
        # drainage left open: u = 0, p' = sigma'_3 + q with sigma'_3 near
        # 100 kPa) fails by far: p' 179 against 127 kPa at 0.25 %, 197
        # against 269 at 1 % (checked by making the scene's shear drained).
        for k in range(1, 9):
            e1 = 0.0025 * k
            i, j = biaxial.at_strain(self.undrained, e1), biaxial.at_strain(self.dry, e1)
            (pu, qu), (pc, qc) = biaxial.p_q(self.undrained, i), biaxial.p_q(self.dry, j)
            with self.subTest(axial_strain=e1):
                self.assertLess(abs(pu - pc), 0.05 * pc)
                self.assertLess(abs(qu - qc), 0.05 * pc)

    def test_the_constant_volume_test_predicts_the_pore_pressure(self):
        # u = sigma_3 - sigma'_3(constant volume), with sigma_3 the total
        # cell pressure the side servos hold: 100 kPa plus their lag, the
        # sides' speed (0.005 m/s x W / H each, to keep the volume) over the
        # gain, 1e-5 m/(s N), and over H: 4.7 kPa by hand (W and H from the
        # run). Tolerance 5 kPa: the spread of sigma'_3 between two
        # constant-volume runs at these strains (up to 3.4 kPa, as above).
        # Measured: up to 1.1 kPa off (at 1.5 %; 0.25 kPa elsewhere). The
        # pore pressure itself ranges from +34 kPa (the dense packing first
        # contracts) to -134 kPa (then dilates).
        us = []
        for k in range(1, 9):
            e1 = 0.0025 * k
            i, j = biaxial.at_strain(self.undrained, e1), biaxial.at_strain(self.dry, e1)
            width, height = self.undrained["width"][i], self.undrained["height"][i]
            sigma_3 = CELL_PRESSURE + 0.005 * width / height / 1e-5 / height
            u = self.undrained["pore_pressure"][i]
            us.append(u)
            with self.subTest(axial_strain=e1):
                self.assertLess(abs(u - (sigma_3 - self.dry["sigma_x"][j])), 5e3)
        self.assertGreater(us[0], 2e4)
        self.assertLess(us[-1], -1e5)


class LooseSample(unittest.TestCase):
    """Consolidated with the discs' friction at 0.5: loose (n0 0.248)."""

    @classmethod
    def setUpClass(cls):
        cls.undrained, cls.porosity = biaxial.shear(darcydem, False, 0.015, compaction_friction=0.5)
        cls.dry, _ = biaxial.shear(darcydem, True, 0.015, compaction_friction=0.5)

    def test_it_liquefies_and_the_water_takes_the_cell_pressure(self):
        # A loose packing contracts as it is sheared: sealed, its pore
        # pressure rises until the contacts carry nothing (static
        # liquefaction). Then u is the whole total lateral stress, the
        # cell pressure plus the side servos' lag: at constant volume the
        # sides open at 0.005 m/s x W / H each (the platens close at 5 mm/s
        # each), so their load exceeds the target by that speed over the
        # gain, 1e-5 m/(s N), and their stress by that over H: 4.97 kPa
        # by hand at 1 % axial strain (W and H from the run), 5.05 kPa at
        # 1.5 %. Tolerance 100 Pa: what the contacts still carry is below
        # 5 Pa, and the servo (time constant 1 / (gain x the water's
        # stiffness), microseconds) follows its speed's slow change.
        # Measured: 2.2, 1.1 and 0.8 Pa off at 1, 1.25 and 1.5 % axial
        # strain; p' below 5 Pa. Both runs liquefy by 1 %: p' below 1 % of
        # the cell pressure (the dense packing's p' is 270 kPa there).
        for e1 in (0.01, 0.0125, 0.015):
            i, j = biaxial.at_strain(self.undrained, e1), biaxial.at_strain(self.dry, e1)
            width, height = self.undrained["width"][i], self.undrained["height"][i]
            lag = 0.005 * width / height / 1e-5 / height
            with self.subTest(axial_strain=e1):
                self.assertLess(biaxial.p_q(self.undrained, i)[0], 0.01 * CELL_PRESSURE)
                self.assertLess(biaxial.p_q(self.dry, j)[0], 0.01 * CELL_PRESSURE)
                self.assertAlmostEqual(self.undrained["pore_pressure"][i], CELL_PRESSURE + lag, delta=100.0)

    def test_before_it_liquefies_the_paths_agree(self):
        # As for the dense packing, Terzaghi's principle: at 0.25 % the loose
        # packing still carries 108 kPa; the bound is the dense test's, 5 %
        # of p'. Measured: 0.16 % of p' in p', 0.07 % in q.
        i, j = biaxial.at_strain(self.undrained, 0.0025), biaxial.at_strain(self.dry, 0.0025)
        (pu, qu), (pc, qc) = biaxial.p_q(self.undrained, i), biaxial.p_q(self.dry, j)
        self.assertGreater(pc, 0.5 * CELL_PRESSURE)
        self.assertLess(abs(pu - pc), 0.05 * pc)
        self.assertLess(abs(qu - qc), 0.05 * pc)
        self.assertGreater(self.porosity, 0.24)  # looser than the dense packing's 0.191 by far


if __name__ == "__main__":
    unittest.main()
