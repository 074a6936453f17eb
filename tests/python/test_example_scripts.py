"""The examples' Python scripts against beds whose answer is known by
construction. Run by ctest with the source tree as the first argument."""
import importlib.util
import math
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else os.getcwd()


def load(path):
    spec = importlib.util.spec_from_file_location(os.path.basename(path)[:-3], os.path.join(SOURCE, path))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


drum_profile = load("examples/dem_cases/drum_profile.py")
triaxial_plot = load("examples/dem_cases/triaxial_plot.py")
vibrated_plot = load("examples/dem_cases/vibrated_plot.py")
undrained_plot = load("examples/fluid_cases/undrained_triaxial_plot.py")
pumping_plot = load("examples/fluid_cases/pumping_plot.py")
undrained_shear = load("examples/fluid_cases/undrained_shear.py")


def tilted_bed(angle, spacing, drum_radius=8e-3, depth=-2e-3):
    """Centres on a triangular lattice of `spacing` inside a drum, below a
    plane through (0, depth) rising at `angle` degrees along +x."""
    slope = math.tan(math.radians(angle))
    row = spacing * math.sqrt(3.0) / 2.0
    x, z = [], []
    for j in range(-int(drum_radius / row) - 1, int(drum_radius / row) + 2):
        for i in range(-int(drum_radius / spacing) - 1, int(drum_radius / spacing) + 2):
            xi = (i + 0.5 * (j % 2)) * spacing
            zi = j * row
            if math.hypot(xi, zi) < drum_radius and zi <= depth + slope * xi:
                x.append(xi)
                z.append(zi)
    return x, z


class DrumProfile(unittest.TestCase):
    def test_the_slope_of_a_bed_cut_by_a_plane(self):
        # Each strip's highest centre sits at the strip's rising end, within
        # one lattice row plus one spacing's rise (about 0.03 mm at a spacing
        # of 0.02 mm) below the plane. Taking the strip's centre for its x
        # shifts every point alike, which leaves the slope alone; what is
        # left is that lattice noise over strips spanning about 9 mm: a slope
        # off by at most about 2 x 0.03 / 4.5 = 0.013 rad, 0.8 degrees.
        # Measured: 0.03 to 0.04 degrees. 1 degree bounds it; a sign or an
        # axis swapped is off by 40 degrees or more.
        for angle in (-35.0, -25.0, 20.0):
            x, z = tilted_bed(angle, 2e-5)
            fitted, points = drum_profile.surface_angle(x, z, bins=12, trim=2)
            print(f"bed cut at {angle} degrees: fitted {fitted:.3f} over {len(points)} strips")
            self.assertEqual(len(points), 8)
            self.assertAlmostEqual(fitted, angle, delta=1.0)

    def test_too_few_strips_are_refused(self):
        with self.assertRaisesRegex(ValueError, "fewer than two strips"):
            drum_profile.surface_angle([0.0, 1.0], [0.0, 0.0], bins=4, trim=2)
        with self.assertRaisesRegex(ValueError, "no width"):
            drum_profile.surface_angle([1.0, 1.0], [0.0, 1.0])

    def test_a_missing_run_is_named(self):
        out = tempfile.mkdtemp()
        r = subprocess.run([sys.executable, os.path.join(SOURCE, "examples/dem_cases/drum_profile.py"), out],
                           capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn(os.path.join(out, "probes.csv") + " not found", r.stderr)


def triaxial_probes(phi_of_strain, psi, steps=200, strain=0.1, start=0.15, dim=3, cell=False):
    """Probe columns of a triaxial test made by hand: the platens close
    (eps_a = 1 - H / H0 from 0 to `strain`), sigma_3 = 100 kPa, sigma_1 such
    that sin(phi) = (s1 - s3) / (s1 + s3) with phi = phi_of_strain(eps_a)
    degrees, and the volume V = V0 (1 - eps_v) with eps_v = r eps_a, r =
    -2 sin(psi) / (1 - sin(psi)) (a constant dilatancy angle psi). A row
    before `start` (the compaction) must be left out. With dim = 2 a
    biaxial test's: no y walls, sigma_1 on the top as "sigma_y", V an area.
    With cell = True a cylindrical cell's: its radius R and stress sigma_r,
    V = pi R^2 H."""
    h0, w0 = 0.025, 0.012
    s3 = 1e5
    r = -2.0 * math.sin(math.radians(psi)) / (1.0 - math.sin(math.radians(psi)))
    columns = triaxial_plot.COLUMNS_CELL if cell else triaxial_plot.COLUMNS if dim == 3 else triaxial_plot.COLUMNS_2D
    p = {k: [] for k in columns}

    def row(t, eps_a, s1, volume_factor):
        h = h0 * (1.0 - eps_a)
        if cell:
            radius = math.sqrt(w0 * w0 * h0 * volume_factor / (math.pi * h))
            values = (("time", t), ("radius", radius), ("bottom", 0.001), ("top", 0.001 + h), ("sigma_r", s3),
                      ("sigma_z", s1))
        elif dim == 3:
            w = math.sqrt(w0 * w0 * h0 * volume_factor / h)
            values = (("time", t), ("x_min", -w / 2), ("x_max", w / 2), ("y_min", 0.0), ("y_max", w),
                      ("bottom", 0.001), ("top", 0.001 + h), ("sigma_x", s3 * 1.01), ("sigma_y", s3 * 0.99),
                      ("sigma_z", s1))
        else:
            w = w0 * h0 * volume_factor / h
            values = (("time", t), ("x_min", -w / 2), ("x_max", w / 2), ("bottom", 0.001), ("top", 0.001 + h),
                      ("sigma_x", s3), ("sigma_y", s1))
        for k, v in values:
            p[k].append(v)

    row(start - 0.05, 0.2, 5e5, 2.0)  # the compaction: nothing like the test
    for i in range(steps + 1):
        eps_a = strain * i / steps
        sin_phi = math.sin(math.radians(phi_of_strain(eps_a)))
        row(start + i * 1e-3, eps_a, s3 * (1.0 + sin_phi) / (1.0 - sin_phi), 1.0 - r * eps_a)
    return p


class TriaxialPlot(unittest.TestCase):
    def test_the_peak_and_dilatancy_of_a_test_made_by_hand(self):
        # The curves are exact functions of the columns, so the peak angle
        # and the dilatancy angle come back to round-off (measured 1e-13
        # degrees): 1e-9 bounds it. Taking sigma_3 as one side wall's stress
        # (1 % off) gives a peak of 31.76 degrees for 32, the logarithmic
        # volumetric strain for 1 - V / V0 a psi of 9.90 for 10: both caught.
        # A cylindrical cell's (its radius and sigma_r for the box's sides)
        # likewise; a volume linear in R (the lateral surface's) or without
        # H would not give psi back.
        for phi_peak, psi, dim, cell in ((32.0, 10.0, 3, False), (28.0, -3.0, 3, False), (33.0, 12.0, 2, False),
                                         (31.0, 8.0, 3, True)):
            probes = triaxial_probes(lambda e: phi_peak - 2000.0 * (e - 0.03) ** 2, psi, dim=dim, cell=cell)
            self.assertEqual(triaxial_plot.dimension(probes), dim)
            c = triaxial_plot.curves(probes, 0.15)
            k, fitted_psi = triaxial_plot.peak(c, 0.01)
            print(f"made in {dim}D{' (cell)' if cell else ''} with phi {phi_peak}, psi {psi}: peak "
                  f"{c['phi'][k]:.12f} at {c['eps_a'][k]:.4f}, psi {fitted_psi:.12f}")
            self.assertAlmostEqual(c["phi"][k], phi_peak, delta=1e-9)
            self.assertAlmostEqual(c["eps_a"][k], 0.03, delta=1e-12)
            self.assertAlmostEqual(fitted_psi, psi, delta=1e-9)
            self.assertAlmostEqual(c["eps_v"][0], 0.0, delta=1e-15)
            sin_phi = math.sin(math.radians(phi_peak))
            q_over_p = 6.0 * sin_phi / (3.0 - sin_phi) if dim == 3 else 2.0 * sin_phi
            self.assertAlmostEqual(c["q"][k] / c["p"][k], q_over_p, delta=1e-12)

    def test_a_run_too_short_is_refused(self):
        with self.assertRaisesRegex(ValueError, "fewer than two probe rows from 10.0 s on"):
            triaxial_plot.curves(triaxial_probes(lambda e: 30.0, 0.0), 10.0)

    def test_a_missing_run_is_named(self):
        out = tempfile.mkdtemp()
        r = subprocess.run([sys.executable, os.path.join(SOURCE, "examples/dem_cases/triaxial_plot.py"), out],
                           capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn(os.path.join(out, "probes.csv") + " not found", r.stderr)



class VibratedPlot(unittest.TestCase):
    """vibrated_plot.py's ball and flights, against the hand's."""

    A, F = 0.0012425, 20.0  # the example's floor: Gamma = A (2 pi f)^2 / g = 2.0001

    def test_the_ball_leaves_at_arccos_and_lands_on_the_floor(self):
        lift, land, flight = vibrated_plot.ball(self.A, self.F)
        omega = 2.0 * math.pi * self.F
        gamma = self.A * omega**2 / vibrated_plot.G
        # Take-off where the floor's acceleration is -g (exact).
        self.assertAlmostEqual(lift, math.acos(-1.0 / gamma), delta=1e-15)
        # Landing: the parabola meets the floor there (bisection to
        # round-off: 1e-15 m) and stays above it in between.
        s = land / omega
        self.assertAlmostEqual(flight(s), vibrated_plot.floor_height(self.A, omega, s), delta=1e-15)
        for k in range(1, 100):
            x = (lift + k * (land - lift) / 100) / omega
            self.assertGreater(flight(x), vibrated_plot.floor_height(self.A, omega, x))
        # Half a radian into the next cycle, as the C++ test's bisection
        # gives (ShakingWalls: 6.7534 rad).
        self.assertAlmostEqual(land, 6.7534, delta=1e-4)
        # Gamma at or below 1: it never leaves.
        self.assertEqual(vibrated_plot.ball(0.4 * self.A, self.F), (None, None, None))

    def test_the_first_flight_is_found_in_the_probes(self):
        # A bed that flies as the ball, probed every 1e-4 s from the
        # shaking's start at 0.3 s: no floor load while it flies.
        lift, land, _ = vibrated_plot.ball(self.A, self.F)
        omega = 2.0 * math.pi * self.F
        times = [0.3 + 1e-4 * k for k in range(2000)]
        loads = [0.0 if lift < omega * (t - 0.3) < land else 1.0 for t in times]
        p = {"time": times, "floor_load": loads}
        off, on = vibrated_plot.first_flight(p, 0.3, self.F)
        # Within a probe interval (omega 1e-4 s = 0.0126 rad) of the ball's.
        self.assertLess(abs(off - lift), omega * 1e-4)
        self.assertLess(abs(on - land), omega * 1e-4)

    def test_a_missing_run_is_refused(self):
        out = tempfile.mkdtemp()
        r = subprocess.run([sys.executable, os.path.join(SOURCE, "examples/dem_cases/vibrated_plot.py"), out],
                           capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("probes.csv: no such file (run the scene first)", r.stderr)

class UndrainedTriaxialPlot(unittest.TestCase):
    """undrained_triaxial_plot.py's closed form and its reading of a run."""

    SCRIPT = "examples/fluid_cases/undrained_triaxial_plot.py"

    def test_the_closed_form_has_the_elastic_limits(self):
        # Skempton's A of an elastic skeleton is 1/3 whatever K_f; with
        # incompressible water (K_f -> infinity) the sample keeps its
        # volume, e1 = 2 e3, so u = E e1 / 2 and the effective stress path
        # is vertical (p' constant); with no water (K_f -> 0) u = 0 and the
        # path is the drained one, dq/dp' = 3.
        for kf in (1e3, 1.19e5, 1e7):
            lattice = undrained_plot.Lattice(3, 5e-4, 1e3, kf, 0.4762)
            p, q = lattice.path(1e-4, 100.0)
            self.assertAlmostEqual(lattice.pore_pressure(1e-4) / (lattice.b * q), 1.0 / 3.0, delta=1e-14)
        stiff = undrained_plot.Lattice(3, 5e-4, 1e3, 1e15, 0.4762)
        self.assertAlmostEqual(stiff.modulus, 750e3, delta=1e-9)  # 3 k_n / (2 r 4)
        self.assertAlmostEqual(stiff.pore_pressure(1e-4) / (0.5 * 750e3 * 1e-4), 1.0, delta=1e-8)
        self.assertAlmostEqual(stiff.path(1e-4, 100.0)[0], 100.0, delta=1e-6)
        dry = undrained_plot.Lattice(3, 5e-4, 1e3, 1e-9, 0.4762)
        p, q = dry.path(1e-4, 100.0)
        self.assertAlmostEqual(q / (p - 100.0), 3.0, delta=1e-9)

    def run_on(self, rows, *options):
        out = tempfile.mkdtemp()
        names = ["time", "pore_pressure", "axial_stress", "lateral_stress",
                 "x_low_x", "x_high_x", "y_low_y", "y_high_y", "z_low_z", "z_high_z"]
        with open(os.path.join(out, "probes.csv"), "w") as f:
            f.write(",".join(names) + "\n")
            for r in rows:
                f.write(",".join(repr(r[k]) for k in names) + "\n")
        return subprocess.run([sys.executable, os.path.join(SOURCE, self.SCRIPT), out, "--no-plot", *options],
                              capture_output=True, text=True)

    def test_a_sample_that_follows_the_lattice_gives_its_a(self):
        # A sample made by hand: consolidated to sides of 3 mm (1 - 1e-4),
        # then sheared to e1 = 1.5e-4 as the lattice's closed form says,
        # with K_f = 1e5 Pa (not the default: given on the command line).
        side0 = 3e-3 * (1.0 - 1e-4)
        spheres = 27 * 4.0 / 3.0 * math.pi * 5e-4**3
        lattice = undrained_plot.Lattice(3, 5e-4, 1e3, 1e5, 1.0 - spheres / side0**3)
        rows = []
        for k in range(71):
            t = 1e-3 * k
            e1 = 1.5e-4 * max(0.0, min(1.0, (t - 0.03) / 0.03))
            u = lattice.pore_pressure(e1)
            lateral = side0 * (1.0 + u / lattice.modulus)
            rows.append({"time": t, "pore_pressure": u, "axial_stress": 100.0 + lattice.modulus * e1,
                         "lateral_stress": 100.0 - u, "x_low_x": 0.0, "x_high_x": lateral, "y_low_y": 0.0,
                         "y_high_y": lateral, "z_low_z": 0.0, "z_high_z": side0 * (1.0 - e1)})
        out = self.run_on(rows, "--bulk-modulus", "1e5")
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertIn("Skempton's A = 0.3333", out.stdout)  # the printed A, to its four digits
        expected = lattice.pore_pressure(1.5e-4)
        self.assertIn(f"u = {expected:.4f} Pa (closed form {expected:.4f})", out.stdout)

    def test_a_missing_or_short_run_is_refused(self):
        out = tempfile.mkdtemp()
        r = subprocess.run([sys.executable, os.path.join(SOURCE, self.SCRIPT), out], capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("probes.csv: no such file", r.stderr)
        short = [{"time": 1e-3 * k, "pore_pressure": 0.0, "axial_stress": 100.0, "lateral_stress": 100.0,
                  "x_low_x": 0.0, "x_high_x": 3e-3, "y_low_y": 0.0, "y_high_y": 3e-3, "z_low_z": 0.0,
                  "z_high_z": 3e-3} for k in range(20)]
        r = self.run_on(short)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("before the shear", r.stderr)


class PumpingPlot(unittest.TestCase):
    """pumping_plot.py's Theis and E1 against tabulated values, and its
    reading of a run."""

    SCRIPT = "examples/fluid_cases/pumping_plot.py"

    def test_e1_takes_its_tabulated_values(self):
        # Abramowitz and Stegun's table 5.1 (to the digits given there).
        for x, value in ((0.1, 1.8229239584193906), (0.5, 0.5597735947761608), (1.0, 0.21938393439552029),
                         (2.0, 0.04890051070806112), (5.0, 1.1482955912753257e-3), (10.0, 4.156968929685324e-6)):
            self.assertAlmostEqual(pumping_plot.e1(x) / value, 1.0, delta=1e-13, msg=f"E1({x})")
        # The series and the continued fraction meet at 1 without a jump:
        # just above, E1 falls at its slope there, -exp(-1) / 1.
        step = pumping_plot.e1(1.0 + 1e-9) - pumping_plot.e1(1.0)
        self.assertAlmostEqual(step / (-1e-9 * math.exp(-1.0)), 1.0, delta=1e-5)
        with self.assertRaises(ValueError):
            pumping_plot.e1(0.0)

    def test_theis_recovers_and_peacemans_radius(self):
        args = (2e-6, 1e-3, 1e-10, 0.01)
        scale = 2e-6 * 1e-3 / (4.0 * math.pi * 1e-10)
        # Late in the pumping, Jacob's straight line: -scale (-gamma - ln(r^2 / 4 c t)).
        u = pumping_plot.theis(0.001, 10.0, *args)
        self.assertAlmostEqual(u / (-scale * (-0.5772156649015329 - math.log(1e-6 / 0.4))), 1.0, delta=1e-6)
        # Long after the shut-off it recovers: scale ln(t / (t - t1)) -> 0.
        late = pumping_plot.theis(0.05, 1000.0, *args, shut_off=0.1)
        self.assertAlmostEqual(late, -scale * math.log(1000.0 / 999.9), delta=1e-6 * scale)
        self.assertEqual(pumping_plot.theis(0.05, 0.0, *args), 0.0)
        self.assertAlmostEqual(pumping_plot.peaceman_radius(1.0), 0.198506, delta=1e-6)

    def test_a_run_that_follows_theis_departs_by_nothing(self):
        out = tempfile.mkdtemp()
        times = [0.005 * k for k in range(41)]
        args = (2e-6, 1e-3, 1e-10, 0.01)
        with open(os.path.join(out, "probes.csv"), "w") as f:
            f.write("time,well_pressure,u_5cm,u_10cm\n")
            for t in times:
                row = [pumping_plot.theis(r, t, *args, shut_off=0.1)
                       for r in (pumping_plot.peaceman_radius(0.01), 0.05, 0.1)]
                f.write(",".join(repr(v) for v in [t] + row) + "\n")
        r = subprocess.run([sys.executable, os.path.join(SOURCE, self.SCRIPT), out, "--no-plot"],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("u_5cm (r = 0.05 m): largest departure from Theis 0 Pa", r.stdout)
        self.assertIn("well_pressure (r = 0.001985 m): largest departure from Theis 0 Pa", r.stdout)
        r = subprocess.run([sys.executable, os.path.join(SOURCE, self.SCRIPT), out, "--no-plot", "--piezometer",
                            "u_7cm=0.07"], capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("no column 'u_7cm'", r.stderr)
        r = subprocess.run([sys.executable, os.path.join(SOURCE, self.SCRIPT), tempfile.mkdtemp()],
                           capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("probes.csv: no such file", r.stderr)



class UndrainedShearScript(unittest.TestCase):
    """undrained_shear.py's reading of a path and its refusals (the runs
    themselves: tests/python/test_undrained_shear.py)."""

    SCRIPT = "examples/fluid_cases/undrained_shear.py"

    def test_p_and_q_of_a_path_made_by_hand(self):
        rows = {"axial_strain": [0.0, 0.001, 0.002], "sigma_3": [1e5, 9e4, 8e4], "sigma_1": [1e5, 2e5, 3e5],
                "pore_pressure": [0.0, 1e4, 2e4], "volume_change": [0.0, 0.0, 0.0], "dimension": 2}
        self.assertEqual(undrained_shear.at_strain(rows, 0.0015), 2)
        self.assertEqual(undrained_shear.p_q(rows, 1), (1.45e5, 5.5e4))  # half the sum, half the difference
        with self.assertRaisesRegex(ValueError, "stops at an axial strain of 0.002, before 0.003"):
            undrained_shear.at_strain(rows, 0.003)
        rows["dimension"] = 3  # p' = (sigma_1 + 2 sigma_3) / 3 = 380 kPa / 3, q = sigma_1 - sigma_3
        p, q = undrained_shear.p_q(rows, 1)
        self.assertAlmostEqual(p, 3.8e5 / 3.0, delta=1e-9)
        self.assertEqual(q, 1.1e5)

    @staticmethod
    def stand_in(dimension):
        """A stand-in for the module: a sample 10 mm wide (and deep) and
        20 mm high whose platens close 1 um per chunk, Ctrl-C on the fourth
        chunk of the shear; it records the side platens' motions."""

        class Model:
            time_step = 1e-6
            radii = [1e-3]

            def __init__(self):
                self.dimension = dimension
                self.steps, self.height, self.motions = 0, 0.02, {}
                pressure = type("Cells", (), {"ravel": lambda cells: [5.0]})()
                self.fluid = type("Fluid", (), {"pressure": pressure})()

            @property
            def walls(self):
                def plane(name, axis, at):
                    point = [0.0] * dimension
                    point[axis] = at
                    return {"name": name, "point": tuple(point), "stress": 1e5}
                sides = [plane("x_min", 0, 0.0), plane("x_max", 0, 0.01)]
                if dimension == 3:
                    sides += [plane("y_min", 1, 0.0), plane("y_max", 1, 0.01)]
                return sides + [plane("bottom", dimension - 1, 0.0), plane("top", dimension - 1, self.height)]

            def apply_stage(self, name):
                self.stage = name

            def set_fluid_source(self, name, pressure):
                self.drainage = pressure

            def set_wall_motion(self, name, velocity):
                self.motions[name] = velocity

            def step(self, n):
                if self.stage == "shear":
                    self.steps += 1
                    if self.steps == 4:
                        raise KeyboardInterrupt
                    self.height -= 1e-6

        model = Model()
        return model, type("darcydem", (), {"load": staticmethod(lambda scene: model)})

    def test_ctrl_c_keeps_the_path_so_far(self):
        model, fake = self.stand_in(2)
        with self.assertRaises(undrained_shear.Interrupted) as stopped:
            undrained_shear.shear(fake, False, 0.02)
        rows = stopped.exception.rows
        self.assertEqual(len(rows["axial_strain"]), 4)  # read before each chunk, the fourth stopped
        self.assertAlmostEqual(rows["axial_strain"][-1], 3e-6 / 0.02, delta=1e-15)
        self.assertEqual(rows["pore_pressure"], [5.0] * 4)

    def test_the_twin_opens_the_sides_alike_to_keep_the_volume(self):
        # 3D, the triaxial scene's platens (3 mm/s each, 50 steps of 1 us a
        # chunk: 0.3 um closer). The stand-in's sides stay put while its
        # height falls 1 um a chunk, so at the fourth chunk the 10 x 10 x
        # 20 mm sample keeps its W^2 H only if each width grows by the
        # factor sqrt(20 mm / (20 mm - 3 um - 0.3 um)), each side moving
        # half that over the chunk, the y sides as the x sides.
        model, fake = self.stand_in(3)
        scene = os.path.join(SOURCE, "examples/fluid_cases/undrained_triaxial_packing.toml")
        with self.assertRaises(undrained_shear.Interrupted):
            undrained_shear.shear(fake, True, 0.0005, scene_file=scene)
        self.assertEqual(model.drainage, 0.0)  # the twin's water does nothing
        s = (0.02 / (0.02 - 3e-6 - 0.3e-6)) ** 0.5  # the chunk read at H = 20 mm - 3 um
        speed = 0.01 * (s - 1.0) / (2.0 * 50 * 1e-6)
        self.assertAlmostEqual(model.motions["x_max"][0], speed, delta=1e-12)
        self.assertAlmostEqual(model.motions["x_min"][0], -speed, delta=1e-12)
        self.assertEqual(model.motions["y_max"], [0.0, model.motions["x_max"][0], 0.0])
        self.assertEqual(model.motions["y_min"], [0.0, -model.motions["x_max"][0], 0.0])

    def test_a_strain_beyond_the_stage_is_refused(self):
        # The biaxial scene's shear closes the platens at 10 mm/s for
        # 0.11 s: 1.1 mm of the stand-in's 20 mm, 5.5 %.
        _, fake = self.stand_in(2)
        with self.assertRaisesRegex(ValueError, "reaches an axial strain of 0.055, less than 0.1"):
            undrained_shear.shear(fake, False, 0.1)
        r = subprocess.run([sys.executable, os.path.join(SOURCE, self.SCRIPT), "build/darcydem", tempfile.mkdtemp(),
                            "--strain", "1.5"], capture_output=True, text=True)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("--strain 1.5: give an axial strain in (0, 1)", r.stderr)

if __name__ == "__main__":
    unittest.main(verbosity=2)
