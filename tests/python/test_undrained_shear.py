"""CU tests of random packings against their dry constant-volume twins,
run by examples/fluid_cases/undrained_shear.py through the darcydem
module: the effective-stress principle of the coupling, on packings whose
response no closed form gives, dense (they dilate) and loose (they
liquefy). The biaxial test of discs (examples/fluid_cases/
undrained_biaxial.toml) and the triaxial test of spheres
(undrained_triaxial_packing.toml). Run by ctest with the source tree as the
first argument, the module on PYTHONPATH and a class to run (DenseSample,
LooseSample, DenseTriaxial, LooseTriaxial), each 35 to 50 s on one core."""
import importlib.util
import os
import sys
import unittest

SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else os.getcwd()
spec = importlib.util.spec_from_file_location("undrained_shear",
                                              os.path.join(SOURCE, "examples/fluid_cases/undrained_shear.py"))
cu = importlib.util.module_from_spec(spec)
spec.loader.exec_module(cu)
TRIAXIAL = os.path.join(SOURCE, "examples/fluid_cases/undrained_triaxial_packing.toml")
import darcydem  # noqa: E402

K_F = 2.2e9  # Pa, the scene's water
CELL_PRESSURE = 1e5  # Pa, the side platens' total stress
STRAINS = [0.0025 * k for k in range(1, 9)]  # the axial strains compared, 0.25 ... 2 %


def biaxial_lag(rows, i):
    """The biaxial scene's side platens' excess over the cell pressure, Pa:
    at constant area each side opens at 0.005 m/s x W / H (the platens close
    at 5 mm/s each), so each servo's load exceeds its target by that over
    the gain, 1e-5 m/(s N), and its stress by that over H."""
    return 0.005 * rows["width"][i] / rows["height"][i] / 1e-5 / rows["height"][i]


def triaxial_lag(rows, i):
    """The triaxial scene's side platens' excess over the cell pressure, Pa:
    at constant volume W^2 H each side opens at v W / (2 H) (v = 3 mm/s a
    platen's speed), so each servo's load exceeds its target by that over
    the gain, 1.25e-3 m/(s N), and its stress by that over W H:
    v / (2 gain H^2)."""
    return 0.003 / (2.0 * 1.25e-3 * rows["height"][i] ** 2)


class Twins(unittest.TestCase):
    """The checks of a sealed run (self.undrained) against its dry
    constant-volume twin (self.dry), both from the same packing; each test
    class below says why its tolerances are what they are."""

    def rows_at(self, e1):
        return cu.at_strain(self.undrained, e1), cu.at_strain(self.dry, e1)

    def assert_the_volume_follows_the_water(self, least_scale):
        # dV / V0 = -n0 u / K_f within 2 % of the largest n0 |u| / K_f, which
        # must exceed least_scale (the water took a pressure worth
        # measuring); the twin keeps its volume to round-off, its u zero.
        scale = self.porosity * max(abs(u) for u in self.undrained["pore_pressure"]) / K_F
        self.assertGreater(scale, least_scale)
        worst = max(abs(dv + self.porosity * u / K_F)
                    for dv, u in zip(self.undrained["volume_change"], self.undrained["pore_pressure"]))
        self.assertLess(worst, 2e-2 * scale)
        self.assertLess(max(abs(dv) for dv in self.dry["volume_change"]), 1e-12)
        self.assertEqual(max(abs(u) for u in self.dry["pore_pressure"]), 0.0)

    def assert_the_paths_agree(self, strains, least_p=0.0):
        # p' and q of the two runs within 5 % of the twin's p', which must
        # exceed least_p there.
        for e1 in strains:
            i, j = self.rows_at(e1)
            (pu, qu), (pc, qc) = cu.p_q(self.undrained, i), cu.p_q(self.dry, j)
            with self.subTest(axial_strain=e1):
                self.assertGreater(pc, least_p)
                self.assertLess(abs(pu - pc), 0.05 * pc)
                self.assertLess(abs(qu - qc), 0.05 * pc)

    def assert_the_twin_predicts_u(self, lag, tolerance):
        # u = sigma_3 - sigma'_3(twin), sigma_3 the cell pressure plus the
        # side servos' lag; returns u at each strain.
        us = []
        for e1 in STRAINS:
            i, j = self.rows_at(e1)
            u = self.undrained["pore_pressure"][i]
            us.append(u)
            with self.subTest(axial_strain=e1):
                self.assertLess(abs(u - (CELL_PRESSURE + lag(self.undrained, i) - self.dry["sigma_3"][j])), tolerance)
        return us

    def assert_liquefied(self, strains, lag):
        # p' below 1 % of the cell pressure in both runs, and u the cell
        # pressure plus the side servos' lag within 100 Pa.
        for e1 in strains:
            i, j = self.rows_at(e1)
            with self.subTest(axial_strain=e1):
                self.assertLess(cu.p_q(self.undrained, i)[0], 0.01 * CELL_PRESSURE)
                self.assertLess(cu.p_q(self.dry, j)[0], 0.01 * CELL_PRESSURE)
                self.assertAlmostEqual(self.undrained["pore_pressure"][i], CELL_PRESSURE + lag(self.undrained, i),
                                       delta=100.0)


class DenseSample(Twins):
    """Consolidated with the scene's friction of 0.02: dense (n0 0.196)."""

    @classmethod
    def setUpClass(cls):
        cls.undrained, cls.porosity = cu.shear(darcydem, False, 0.02)
        cls.dry, _ = cu.shear(darcydem, True, 0.02)

    def test_the_sealed_water_keeps_the_volume_by_its_compressibility(self):
        # Sealed, with rigid grains, the sample's area changes by the pore
        # water's: dA / A0 = -n0 u / K_f (u = K_f times the pore area's
        # relative loss). Tolerance 2 % of the largest n0 |u| / K_f
        # (1.5e-5), for what the platens' positions do not show: a plane
        # that displaces the water and stands in the grid's first layer of
        # cells takes 1e-5 of the layer's width it has not crossed as solid
        # in front of it (so that a platen on the grid's side stands on it;
        # PoreFluid::displaced_box). With one cell all four platens keep
        # theirs, 2.4e-7 m at the sides and 4.7e-7 m at the top and bottom
        # (3.7e-8 m^2 of water less than W H less the discs, as measured),
        # and as the sample shortens and widens these slivers lose by hand
        # 4.8e-7 m x 4.4e-4 m - 9.4e-7 m x 1.8e-4 m = 4e-11 m^2 per 1 % of
        # axial strain, 5e-8 of A0: 0.65 % of the scale at 2 %. Biot's law
        # taking the porosity of each step, and the area read from the
        # platens, add 1e-5 and 1e-12 of it. Measured: 0.69 %.
        # The constant-volume twin keeps its area to round-off (its
        # control), and with the drainage held open its u is zero.
        self.assert_the_volume_follows_the_water(5e-6)

    def test_the_effective_stress_path_is_the_constant_volume_tests(self):
        # Terzaghi's principle in the coupling: the grains carry the total
        # stress less u, so a sealed sample of nearly incompressible water
        # follows the dry constant-volume path. The water's compressibility
        # parts them by about the skeleton's modulus (2e8 Pa, k_n over the
        # overlaps at 100 kPa) times n0 u / K_f, 2-3 kPa at 2 % (0.5 % of
        # p'). The packing's own slips part them more: two constant-volume
        # runs that differ only in how often the sides' speed is set (every
        # 40 or 50 steps) differ at these strains by up to 0.13 % of p' in
        # p' and 0.16 % in q; at a time step of 6.7e-7 s (another
        # realization of the packing) by up to 1.8 % and 1.5 %, and up to
        # 2.1 % and 1.3 % at 1.98e-7 s (before session 48), growing with
        # strain as the 200 discs' slips go their own ways. Tolerance 5 % of
        # p', above that spread. Measured, undrained against constant
        # volume: up to 0.91 % of p' in p' and 0.49 % in q (at 1.25 %). A
        # drained shear instead (the drainage left open: u = 0, p' =
        # sigma'_3 + q with sigma'_3 near 100 kPa) fails by far: p' 179
        # against 127 kPa at 0.25 %, 197 against 269 at 1 % (session 47's
        # packing; checked by making the scene's shear drained).
        self.assert_the_paths_agree(STRAINS)

    def test_the_constant_volume_test_predicts_the_pore_pressure(self):
        # u = sigma_3 - sigma'_3(constant volume), with sigma_3 the total
        # cell pressure the side servos hold: 100 kPa plus their lag, the
        # sides' speed (0.005 m/s x W / H each, to keep the volume) over the
        # gain, 1e-5 m/(s N), and over H: 4.7 kPa by hand (W and H from the
        # run). Tolerance 5 kPa: the spread of sigma'_3 between two
        # constant-volume runs at these strains (up to 3.4 kPa in other
        # realizations, as above; 0.35 kPa in this one). Measured: up to
        # 1.5 kPa off (at 1.5 %). The pore pressure itself ranges from
        # +36 kPa (the dense packing first contracts) to -173 kPa at 2 %
        # (then dilates).
        us = self.assert_the_twin_predicts_u(biaxial_lag, 5e3)
        self.assertGreater(us[0], 2e4)
        self.assertLess(us[-1], -1e5)


class LooseSample(Twins):
    """Consolidated with the discs' friction at 0.5: loose (n0 0.240)."""

    @classmethod
    def setUpClass(cls):
        cls.undrained, cls.porosity = cu.shear(darcydem, False, 0.015, compaction_friction=0.5)
        cls.dry, _ = cu.shear(darcydem, True, 0.015, compaction_friction=0.5)

    def test_it_liquefies_and_the_water_takes_the_cell_pressure(self):
        # A loose packing contracts as it is sheared: sealed, its pore
        # pressure rises until the contacts carry nothing (static
        # liquefaction). Then u is the whole total lateral stress, the
        # cell pressure plus the side servos' lag: at constant volume the
        # sides open at 0.005 m/s x W / H each (the platens close at 5 mm/s
        # each), so their load exceeds the target by that speed over the
        # gain, 1e-5 m/(s N), and their stress by that over H: 4.95 kPa
        # by hand at 1 % axial strain (W and H from the run), 5.03 kPa at
        # 1.5 % (biaxial_lag). Tolerance 100 Pa: what the contacts still
        # carry is below 14 Pa, and the servo (time constant 1 / (gain x the water's
        # stiffness), microseconds) follows its speed's slow change.
        # Measured: 2.1, 2.0 and 0.4 Pa off at 1, 1.25 and 1.5 % axial
        # strain; p' below 14 Pa. Both runs liquefy by 0.54 %: p' below 1 %
        # of the cell pressure (the dense packing's p' is 270 kPa at 1 %).
        self.assert_liquefied((0.01, 0.0125, 0.015), biaxial_lag)

    def test_before_it_liquefies_the_paths_agree(self):
        # As for the dense packing, Terzaghi's principle: at 0.05 % the loose
        # packing still carries 95 kPa, at 0.25 % 38 kPa (u 68 kPa); the
        # bound is the dense test's, 5 % of p'. Measured: 0.09 % and 2.0 %
        # of p' in p', 0.05 % and 0.34 % in q.
        self.assert_the_paths_agree((5e-4, 0.0025), least_p=0.3 * CELL_PRESSURE)
        self.assertGreater(self.porosity, 0.22)  # looser than the dense packing's 0.196 by far


class DenseTriaxial(Twins):
    """The triaxial test of 500 spheres consolidated with the scene's
    friction of 0.02 (n0 0.436; the walls' box leaves room at its sides)."""

    @classmethod
    def setUpClass(cls):
        cls.undrained, cls.porosity = cu.shear(darcydem, False, 0.02, scene_file=TRIAXIAL)
        cls.dry, _ = cu.shear(darcydem, True, 0.02, scene_file=TRIAXIAL)

    def test_the_sealed_water_keeps_the_volume_by_its_compressibility(self):
        # dV / V0 = -n0 u / K_f, as for the discs (DenseSample), and the
        # tolerance, 2 % of the largest n0 |u| / K_f (5.2e-6), for the same
        # reason: each platen keeps a sliver of 1e-5 of the cell's width it
        # has not crossed (1.5e-7 m at the sides, 2.9e-7 m at the top and
        # bottom), and as the sample shortens and widens by 2 % the sides'
        # slivers lose 2 x 2 x 1.5e-7 m x 3.2e-6 m^2 and the platens' gain
        # 2 x 2.9e-7 m x 2.9e-6 m^2: net 2.4e-13 m^3 by hand, 6e-8 of V0,
        # 1.1 % of the scale. Measured: 0.97 %. The constant-volume twin
        # keeps its volume to round-off and its u is zero.
        self.assert_the_volume_follows_the_water(3e-6)

    def test_the_effective_stress_path_is_the_constant_volume_tests(self):
        # Terzaghi's principle, as for the discs: p' = (sigma'_1 +
        # 2 sigma'_3) / 3 and q = sigma'_1 - sigma'_3 of the sealed test
        # against the dry constant-volume test's. Tolerance 5 % of p', the
        # biaxial test's: two constant-volume runs that differ only in how
        # often the sides' speed is set (every 40 or 50 steps) differ by up
        # to 0.32 % of p' in p' and 0.45 % in q (at 2 %), the 500 spheres'
        # slips going their own ways as the strain grows; the biaxial
        # test's 200 discs, up to 2.1 %. Measured, undrained against
        # constant volume: up to 0.46 % of p' in p' (at 1.5 %) and 0.76 %
        # in q (at 2 %).
        self.assert_the_paths_agree(STRAINS)

    def test_the_constant_volume_test_predicts_the_pore_pressure(self):
        # u = sigma_3 - sigma'_3(constant volume), sigma_3 the cell pressure
        # plus the side servos' lag (triaxial_lag, 1.8 kPa by hand with the
        # run's H). Tolerance 1.5 kPa: four times the spread of sigma'_3
        # between the two constant-volume runs above (up to 0.35 kPa at
        # 2 %, growing with strain), as the undrained run's slips part
        # from the twin's alike. Measured: up to 0.54 kPa off (at 1.5 %).
        # The pore pressure ranges from +23 kPa (the packing first
        # contracts) to -26 kPa at 2 % (then dilates).
        us = self.assert_the_twin_predicts_u(triaxial_lag, 1.5e3)
        self.assertGreater(us[0], 1.5e4)  # it first contracts
        self.assertLess(us[-1], -1.5e4)  # then dilates


class LooseTriaxial(Twins):
    """The triaxial test consolidated with the spheres' friction at 0.5:
    loose (n0 0.486)."""

    @classmethod
    def setUpClass(cls):
        cls.undrained, cls.porosity = cu.shear(darcydem, False, 0.02, scene_file=TRIAXIAL,
                                               compaction_friction=0.5)
        cls.dry, _ = cu.shear(darcydem, True, 0.02, scene_file=TRIAXIAL, compaction_friction=0.5)

    def test_it_liquefies_and_the_water_takes_the_cell_pressure(self):
        # The loose packing of spheres contracts as it is sheared (the
        # deviator never passes 6 kPa) and, sealed, its pore pressure
        # rises until the contacts carry nothing, by 1.25 % axial strain in
        # both runs; the water then takes the whole total lateral stress:
        # the cell pressure plus the side servos' lag (triaxial_lag,
        # 1.8 kPa by hand). Tolerance 100 Pa, the biaxial test's
        # (LooseSample) for the same reasons. Measured: 4.3 to 4.6 Pa off
        # at 1.5, 1.75 and 2 % axial strain; p' below 3 Pa in both runs.
        self.assert_liquefied((0.015, 0.0175, 0.02), triaxial_lag)

    def test_before_it_collapses_the_paths_agree(self):
        # At 0.03 % axial strain the packing still carries 96 kPa, at
        # 0.5 % 38 kPa (u 65 kPa); the bound is the dense test's, 5 % of
        # p'. Measured: 0.02 % and 0.13 % of p' in p', 0.01 % and 0.001 %
        # in q. From 0.5 % to 1.25 % the skeleton collapses, and there the
        # two runs part by up to 4.9 kPa in p' (at 1 %, where p' is 10 kPa)
        # and not within 5 % of p': sealed, the sample contracts by
        # n0 u / K_f = 2e-5 more than its twin, worth about k_n / d
        # (1e8 Pa) times that, 2 kPa, as the contacts unload; and two
        # constant-volume runs (the sides' speed set every 40 or 50 steps)
        # part by 1.6 kPa there themselves.
        self.assert_the_paths_agree((3e-4, 0.005), least_p=0.3 * CELL_PRESSURE)
        self.assertGreater(self.porosity, 0.47)  # looser than the dense packing's 0.436 by far


if __name__ == "__main__":
    unittest.main()
