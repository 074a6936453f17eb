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


if __name__ == "__main__":
    unittest.main(verbosity=2)
