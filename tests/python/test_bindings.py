"""The Python module against closed forms and against the program's own run.

Run by ctest with PYTHONPATH set to the module's folder (build/python) and
the source tree as the first argument.
"""
import csv
import math
import os
import re
import signal
import sys
import tempfile
import threading
import time
import tomllib
import unittest

import numpy as np

import darcydem

SOURCE = sys.argv.pop(1) if len(sys.argv) > 1 else os.getcwd()
sys.path.insert(0, os.path.join(SOURCE, "examples", "fluid_cases"))
import pumping_plot  # noqa: E402  (Theis's well, as the example's script takes it)
G = 9.80665


def write_scene(folder, text, name="scene.toml"):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path


ONE_SPHERE = """
[simulation]
dimension = 3
time_step = 1e-5

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e3
restitution = 0.5

[[particles]]
generator = "csv"
material = "sand"
file = "one.csv"

[[stage]]
name = "fall"
duration = 0.1
gravity = [0.0, 0.0, -9.80665]

[[stage]]
name = "float"
duration = 0.1
gravity = [0.0, 0.0, 0.0]
"""


class FreeFall(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp()
        with open(os.path.join(self.folder, "one.csv"), "w") as f:
            f.write("x,y,z,radius\n0.01,0.02,1.0,0.0005\n")
        self.model = darcydem.load(write_scene(self.folder, ONE_SPHERE))

    def test_falls_as_a_body_under_gravity(self):
        m = self.model
        self.assertEqual(m.dimension, 3)
        self.assertEqual(m.stages, ["fall", "float"])
        # load() starts at the first stage: its gravity applies.
        self.assertEqual(m.gravity, (0.0, 0.0, -G))
        m.step(10000)
        t = 10000 * 1e-5
        self.assertEqual(m.steps, 10000)
        # The time is the step summed 10 000 times: round-off of at most
        # n eps t = 1.1e-13 s.
        self.assertAlmostEqual(m.time, t, delta=1.1e-13)
        # The half-kick / drift / half-kick scheme is exact for a constant
        # force: z = z0 - g t^2 / 2 and v = -g t up to round-off, which
        # over 10 000 steps stays within 1e-12 m of the 0.049 m fallen.
        x = m.positions[0]
        self.assertAlmostEqual(x[0], 0.01, delta=1e-15)
        self.assertAlmostEqual(x[1], 0.02, delta=1e-15)
        self.assertAlmostEqual(x[2], 1.0 - 0.5 * G * t * t, delta=1e-12)
        self.assertAlmostEqual(m.velocities[0][2], -G * t, delta=1e-12)
        mass = 2650.0 * 4.0 / 3.0 * math.pi * 0.0005**3
        self.assertAlmostEqual(m.kinetic_energy(), 0.5 * mass * (G * t) ** 2, delta=1e-12 * mass * (G * t) ** 2)
        # The potential -m g.x = m G z; kinetic plus potential is the energy
        # at the start (m G 1 m) to the same round-off. No contact: no spring.
        self.assertAlmostEqual(m.gravitational_energy(), mass * G * x[2], delta=1e-15 * mass * G)
        self.assertAlmostEqual(m.kinetic_energy() + m.gravitational_energy(), mass * G * 1.0, delta=1e-12 * mass * G)
        self.assertEqual(m.elastic_energy(), 0.0)

    def test_the_energy_budget_follows_the_fall(self):
        # YADE's O.trackEnergy: from the step after it is turned on. Under a
        # constant force velocity Verlet is exact, so gravity's work is
        # m G times the drop to round-off (1e-12 of it), and it all went
        # into the kinetic energy: nothing dissipated, no boundary, no fluid.
        m = self.model
        self.assertFalse(m.track_energy)
        m.step(100)
        self.assertEqual(m.energy()["gravity_work"], 0.0)  # not tracked yet
        m.track_energy = True
        z0 = m.positions[0][2]
        k0 = m.kinetic_energy()
        m.step(5000)
        e = m.energy()
        mass = 2650.0 * 4.0 / 3.0 * math.pi * 0.0005**3
        work = mass * G * (z0 - m.positions[0][2])
        self.assertAlmostEqual(e["gravity_work"], work, delta=1e-12 * work)
        self.assertAlmostEqual(e["kinetic"] - k0, work, delta=1e-12 * work)
        self.assertEqual(e["kinetic"], m.kinetic_energy())
        self.assertEqual(e["gravitational"], m.gravitational_energy())
        for key in ("fluid_work", "boundary_work", "damping_dissipation", "contact_dissipation", "elastic",
                    "inserted_kinetic", "removed_kinetic"):
            self.assertEqual(e[key], 0.0, key)
        # What the works leave unexplained of the kinetic energy's gain since
        # tracking began (k0): round-off.
        self.assertAlmostEqual(e["unaccounted"], 0.0, delta=1e-12 * work)

    def test_a_stage_applied_from_python_changes_the_motion(self):
        m = self.model
        m.step(500)
        v = m.velocities[0][2]
        m.apply_stage("float")
        m.step(500)
        # Without gravity the sphere keeps its speed (nothing else acts),
        # after the first half kick, which applies the force evaluated
        # before the change (gravity), as at a stage change in a run:
        # v - g dt / 2.
        self.assertAlmostEqual(m.velocities[0][2], v - 0.5 * G * 1e-5, delta=1e-15)
        m.gravity = (0.0, 0.0, -1.0)
        self.assertEqual(m.gravity, (0.0, 0.0, -1.0))
        with self.assertRaises(ValueError):
            m.gravity = (0.0, -1.0)

    def test_a_sphere_added_between_steps_falls_freely(self):
        # YADE's O.bodies.append: a second sphere placed after 500 steps,
        # thrown sideways; its weight is its first force, so its path is
        # velocity Verlet's exact free fall from there (1e-12 m).
        m = self.model
        m.step(500)
        new_id = m.add_particle((0.05, 0.02, 0.9), 0.0005, "sand", velocity=(0.1, 0.0, 0.0))
        self.assertEqual(new_id, 1)
        self.assertEqual(m.particle_count, 2)
        self.assertEqual(m.inserted_count, 1)
        m.step(1000)
        t = 1000 * 1e-5
        x = m.positions[1]
        self.assertAlmostEqual(x[0], 0.05 + 0.1 * t, delta=1e-12)
        self.assertAlmostEqual(x[2], 0.9 - 0.5 * G * t * t, delta=1e-12)
        # The first one fell on undisturbed: 1500 steps from rest.
        t1 = 1500 * 1e-5
        self.assertAlmostEqual(m.positions[0][2], 1.0 - 0.5 * G * t1 * t1, delta=1e-12)
        # Refused, saying why: an unknown material, a bad radius, a grain too
        # small for the time step (its critical step below 1e-5 s).
        with self.assertRaisesRegex(ValueError, "material 'glass' is not one the scene's grains use \\('sand'\\)"):
            m.add_particle((0.0, 0.0, 0.5), 0.0005, "glass")
        with self.assertRaisesRegex(ValueError, "radius must be > 0 m"):
            m.add_particle((0.0, 0.0, 0.5), -1.0, "sand")
        with self.assertRaisesRegex(ValueError, "would need a time step of at most"):
            m.add_particle((0.0, 0.0, 0.5), 1e-7, "sand")
        self.assertEqual(m.particle_count, 2)
        self.assertEqual(m.inserted_count, 1)

    def test_a_clump_added_between_steps_falls_freely_as_it_stands(self):
        # YADE's O.bodies.appendClumped: a peanut of two spheres of radius a,
        # a apart, given where its members stand, added after 500 steps and
        # thrown sideways. Its mass is the union's by hand: two spheres less
        # their lens, pi (2a - d)^2 (d^2 + 4 a d) / (12 d) with d = a; its
        # centre of mass the midpoint; its weight its first force with no
        # moment, so it falls as velocity Verlet's exact parabola without
        # spin (1e-12 m, 1e-12 rad/s).
        m = self.model
        m.step(500)
        a = 0.0005
        members = [(0.05, 0.02, 0.9, a), (0.05 + a, 0.02, 0.9, a)]
        ids = m.add_clump(members, "sand", velocity=(0.1, 0.0, 0.0))
        self.assertEqual(ids, [1, 2])
        self.assertEqual(m.particle_count, 3)
        self.assertEqual(m.inserted_count, 2)
        self.assertEqual(len(m.clumps), 1)
        c = m.clumps[0]
        self.assertEqual(c["members"], [1, 2])
        lens = math.pi * a * a * (a * a + 4.0 * a * a) / (12.0 * a)
        volume = 2.0 * 4.0 / 3.0 * math.pi * a**3 - lens
        self.assertAlmostEqual(c["mass"], 2650.0 * volume, delta=1e-12 * 2650.0 * volume)
        self.assertAlmostEqual(m.inserted_mass, 2650.0 * volume, delta=1e-12 * 2650.0 * volume)
        for k in range(3):
            self.assertAlmostEqual(c["position"][k], (0.05 + 0.5 * a, 0.02, 0.9)[k], delta=1e-15)
        for row, given in zip((1, 2), members):
            for k in range(3):
                self.assertAlmostEqual(m.positions[row][k], given[k], delta=1e-15)
        m.step(1000)
        t = 1000 * 1e-5
        c = m.clumps[0]
        self.assertAlmostEqual(c["position"][0], 0.05 + 0.5 * a + 0.1 * t, delta=1e-12)
        self.assertAlmostEqual(c["position"][2], 0.9 - 0.5 * G * t * t, delta=1e-12)
        self.assertLess(max(abs(w) for w in c["angular_velocity"]), 1e-12)
        # Refused, saying why, the model unchanged: a member inside another,
        # a member of three numbers, an unknown material, a clump too small
        # for the time step.
        with self.assertRaisesRegex(ValueError, "add_clump: .*inside"):
            m.add_clump([(0.0, 0.0, 0.5, a), (0.0, 0.0, 0.5, 0.5 * a)], "sand")
        with self.assertRaisesRegex(ValueError, "member 1 must be \\[x, y, z, r\\]"):
            m.add_clump([(0.0, 0.0, 0.5, a), (0.0, 0.0, a)], "sand")
        with self.assertRaisesRegex(ValueError, "material 'glass' is not one the scene's grains use"):
            m.add_clump(members, "glass")
        with self.assertRaisesRegex(ValueError, "add_clump: the clump would need a time step of at most"):
            m.add_clump([(0.0, 0.0, 0.5, 1e-7), (1e-7, 0.0, 0.5, 1e-7)], "sand")
        self.assertEqual(m.particle_count, 3)
        self.assertEqual(len(m.clumps), 1)
        self.assertEqual(m.inserted_count, 2)
        self.assertAlmostEqual(m.inserted_mass, 2650.0 * volume, delta=1e-12 * 2650.0 * volume)

    def test_an_unknown_stage_names_those_there_are(self):
        with self.assertRaises(ValueError) as caught:
            self.model.apply_stage("settle")
        self.assertIn("no stage 'settle'", str(caught.exception))
        self.assertIn("'fall', 'float'", str(caught.exception))


class TerzaghiClosedForms(unittest.TestCase):
    """The closed forms scripts compare runs with (run_oedometer.py), on a
    layer with c_v = k / (gamma_w m_v) = 1 m^2/s and H = 1 m, so Tv = t."""
    LAYER = {"height": 1.0, "conductivity": 9806.65, "compressibility": 1.0}

    def test_the_degree_of_consolidation_is_the_textbook_one(self):
        # Tabulated U(Tv): 0.5 at 0.197, 0.9 at 0.848, 0.9313 at 1 (four
        # figures, hence 1e-3).
        for tv, u in ((0.197, 0.5), (0.848, 0.9), (1.0, 0.9313)):
            self.assertAlmostEqual(darcydem.consolidation_degree(tv, **self.LAYER), u, delta=1e-3)
        # A compressible fluid (storage equal to m_v: B = 1/2) adds the
        # immediate half: 1 - B (1 - U).
        half = dict(self.LAYER, compressibility=0.5, fluid_storage=0.5)
        self.assertAlmostEqual(darcydem.consolidation_degree(0.197, **half), 1 - 0.5 * (1 - 0.5), delta=1e-3)

    def test_the_pressure_starts_at_b_times_the_step_and_drains(self):
        half = dict(self.LAYER, compressibility=0.5, fluid_storage=0.5)
        self.assertEqual(darcydem.consolidation_pressure(0.0, 0.5, 1000.0, **half), 500.0)
        # Zero at the drained end; at the sealed end the first mode alone
        # once Tv = 1: B dsigma 4/pi exp(-pi^2/4) (the next, 1e-9 of it).
        self.assertAlmostEqual(darcydem.consolidation_pressure(1.0, 0.0, 1000.0, **half), 0.0, delta=1e-12)
        first_mode = 500.0 * 4 / math.pi * math.exp(-math.pi ** 2 / 4)
        self.assertAlmostEqual(darcydem.consolidation_pressure(1.0, 1.0, 1000.0, **half), first_mode,
                               delta=1e-6 * first_mode)


class Grading(unittest.TestCase):
    def test_a_two_size_mixture_by_hand(self):
        # Ten spheres of 1 mm and ten of 2 mm: the small ones carry 10 / 90
        # of the mass, so D10 = 1 mm and D30 ... D60 = 2 mm; as discs (mass
        # as d^2) 10 / 50, the same D's. Cu = 2, Cc = 2.
        radii = [0.5e-3] * 10 + [1e-3] * 10
        for dimension in (2, 3):
            g = darcydem.grading(radii, dimension=dimension)
            self.assertEqual((g["d10"], g["d30"], g["d60"]), (1e-3, 2e-3, 2e-3))
            self.assertEqual((g["uniformity"], g["curvature"]), (2.0, 2.0))

    def test_a_scenes_grains(self):
        # The column's 50 equal discs of 1 mm: every D is 1 mm.
        model = darcydem.load(os.path.join(SOURCE, "examples/column_settling/column.toml"))
        g = darcydem.grading(model.radii, dimension=model.dimension)
        self.assertEqual((g["d_min"], g["d10"], g["d60"], g["uniformity"]), (1e-3, 1e-3, 1e-3, 1.0))

    def test_bad_radii_are_refused(self):
        for radii in ([], [0.0], [float("nan")]):
            with self.assertRaises(ValueError):
                darcydem.grading(radii)
        with self.assertRaises(ValueError):
            darcydem.grading([1e-3], dimension=4)


class BadInput(unittest.TestCase):
    def test_a_bad_scene_raises_scene_error_with_file_line_and_key(self):
        folder = tempfile.mkdtemp()
        text = ONE_SPHERE.replace("restitution = 0.5", "restitution = 1.5")
        path = write_scene(folder, text, "bad.toml")
        with open(os.path.join(folder, "one.csv"), "w") as f:
            f.write("x,y,z,radius\n0.0,0.0,1.0,0.0005\n")
        line = text.splitlines().index("restitution = 1.5") + 1
        with self.assertRaises(darcydem.SceneError) as caught:
            darcydem.load(path)
        message = str(caught.exception)
        self.assertIn(f"bad.toml:{line}", message)
        self.assertIn("restitution", message)
        self.assertTrue(issubclass(darcydem.SceneError, ValueError))

    def test_a_missing_file_is_named(self):
        with self.assertRaises(Exception) as caught:
            darcydem.load("/nonexistent/scene.toml")
        self.assertIn("/nonexistent/scene.toml", str(caught.exception))

    def test_run_refuses_a_used_output_directory(self):
        folder = tempfile.mkdtemp()
        with open(os.path.join(folder, "one.csv"), "w") as f:
            f.write("x,y,z,radius\n0.0,0.0,1.0,0.0005\n")
        with self.assertRaises(ValueError) as caught:
            darcydem.run(write_scene(folder, ONE_SPHERE), out=folder)
        self.assertIn("not empty", str(caught.exception))


class SceneOverrides(unittest.TestCase):
    """load(..., set=...) and run(..., set=...): the scene changed as
    `--set PATH=VALUE` changes it, Python's values written as TOML."""

    COLUMN = os.path.join(SOURCE, "examples", "column_settling", "column.toml")

    def test_a_scene_set_from_python_is_the_file_edited_by_hand(self):
        folder = tempfile.mkdtemp()
        with open(self.COLUMN) as f:
            text = f.read()
        edited = text.replace("restitution = 0.5", "restitution = 0.3", 1).replace(
            "local_damping = 0.7", "local_damping = 0.5")
        by_hand = darcydem.load(write_scene(folder, edited))
        # numpy's float, Python's float: both TOML floats.
        model = darcydem.load(self.COLUMN, set={"contact.1.restitution": np.float64(0.3),
                                                "stage.settle.local_damping": 0.5})
        plain = darcydem.load(self.COLUMN)
        for m in (by_hand, model, plain):
            m.step(3000)
        np.testing.assert_array_equal(model.positions, by_hand.positions)
        self.assertFalse(np.array_equal(model.positions, plain.positions))
        out = os.path.join(folder, "run")
        summary = darcydem.run(self.COLUMN, out=out, set={"contact.1.restitution": 0.3})
        self.assertEqual(summary["status"], "completed")
        with open(os.path.join(out, "run.json")) as f:
            self.assertIn('"overrides": ["contact.1.restitution=0.3"],', f.read())

    def test_strings_booleans_lists_and_tables_are_toml(self):
        scene = os.path.join(SOURCE, "examples", "fluid_cases", "undrained_biaxial.toml")
        model = darcydem.load(scene, set={
            "wall.x_max.servo": {"target_stress": 2e5, "gain": 1e-5, "max_speed": 0.1, "load": "total"},
            "wall.top.point": np.array([0.0, 0.051]), "fluid.solver": "cg", "fluid.hold_forces": True,
            "fluid.bulk_modulus": 100000, "simulation.time_step": "auto", "fluid.grid.cells": [1, 2]})
        walls = {w["name"]: w for w in model.walls}
        self.assertEqual(walls["x_max"]["servo"], {"target_stress": 2e5})
        self.assertEqual(walls["top"]["point"][1], 0.051)
        self.assertEqual(model.fluid.cells, [1, 2])
        # K_f = 1e5 Pa instead of 2.2e9, the step "auto" and the grid split
        # in two cells, so that the water's stiffness counts against the
        # grains: the time step is nearly the dry one's fifth (6.67e-7 s),
        # against 1.98e-7 s with K_f = 2.2 GPa.
        self.assertGreater(model.time_step, 3 * darcydem.load(
            scene, set={"simulation.time_step": "auto", "fluid.grid.cells": [1, 2]}).time_step)

    def test_bad_overrides_are_refused_naming_them(self):
        for given, error, says in (
                ({"stage.settle.duration": -1.0}, darcydem.SceneError,
                 "--set stage.settle.duration=-1.0: error: [[stage]] #1 key 'duration': must be > 0"),
                ({"stage.settle.local_damping": "high"}, darcydem.SceneError,
                 "--set stage.settle.local_damping=\"high\": error"),
                ({"stage.shear.duration": 1.0}, darcydem.SceneError,
                 "has no [[stage]] named or numbered 'shear' (there are: 'settle'"),
                ({"stage.settle.duration": object()}, ValueError,
                 "set: the value for 'stage.settle.duration' is a object; give a number, str, bool, list or dict"),
                ({1: 0.5}, ValueError, "set: its keys are dotted paths")):
            with self.subTest(set=given):
                with self.assertRaisesRegex(error, re.escape(says)):
                    darcydem.load(self.COLUMN, set=given)


class FluidBoundaries(unittest.TestCase):
    """set_fluid_boundary: a side's or a patch's condition from Python, as a
    stage's fluid.boundary entry sets it."""

    def opened_both_ways(self, example, name):
        # The example's second stage only opens the side or patch: done by
        # the stage in one model and from Python in the other, at the same
        # step, the two go on bit for bit.
        path = os.path.join(SOURCE, "examples", "fluid_cases", example)
        by_stage, by_python = darcydem.load(path), darcydem.load(path)
        for model in (by_stage, by_python):
            model.step(3000)
        by_stage.apply_stage(by_stage.stages[1])
        by_python.set_fluid_boundary(name, flux={"times": [0.0, 0.02], "values": [0.0, 0.0134]})
        for model in (by_stage, by_python):
            model.step(3000)
        np.testing.assert_array_equal(by_python.positions, by_stage.positions)
        np.testing.assert_array_equal(by_python.fluid.pressure, by_stage.fluid.pressure)
        return by_python

    def test_a_side_opened_from_python_is_the_stages(self):
        model = self.opened_both_ways("upward_seepage_bed.toml", "z_min")
        # 3000 steps into the ramp: the inflow through the floor is the
        # ramp's Darcy velocity at that time over the floor's 6 x 6 mm.
        self.assertGreater(model.fluid.balance["inflow"], 0.0)

    def test_a_patch_opened_from_python_is_the_stages(self):
        self.opened_both_ways("bed_with_inlet.toml", "inlet")

    def test_a_side_closed_from_python_lets_no_water_through(self):
        # The hydrostatic bed settles with its top drained: water leaves.
        # Its top closed from Python (the only side open), no water crosses
        # any side any more: the inflow so far stays as it was, exactly.
        model = darcydem.load(os.path.join(SOURCE, "examples", "fluid_cases", "hydrostatic_bed.toml"))
        model.step(1000)
        model.set_fluid_boundary("z_max", no_flow=True)
        before = model.fluid.balance["inflow"]
        self.assertNotEqual(before, 0.0)
        model.step(500)
        self.assertEqual(model.fluid.balance["inflow"], before)

    def test_bad_conditions_are_refused(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "fluid_cases", "upward_seepage_bed.toml"))
        for kwargs, says in (
                ({"name": "z_mid", "pressure": 0.0}, "no side or patch \"z_mid\" (the grid's: x_min, x_max"),
                ({"name": "z_min"}, "give one of pressure (Pa: drained at that excess pressure), flux"),
                ({"name": "z_min", "pressure": 0.0, "no_flow": True}, "give one of pressure"),
                ({"name": "z_min", "flux": float("nan")}, "must be finite")):
            with self.subTest(**{k: str(v) for k, v in kwargs.items()}):
                with self.assertRaisesRegex(ValueError, re.escape(says)):
                    model.set_fluid_boundary(**kwargs)
        periodic = darcydem.load(os.path.join(SOURCE, "examples", "fluid_cases", "periodic_upward_seepage.toml"))
        with self.assertRaisesRegex(ValueError, "the scene is periodic along x"):
            periodic.set_fluid_boundary("x_min", no_flow=True)

    def test_draining_one_sealed_cell_must_keep_the_step(self):
        # The CU triaxial scene's one cell is never drained, so its
        # pressure is uniform and "auto" leaves the water's stiffness out
        # of the step (0.2 of the contacts' critical step, 6.7e-7 s).
        # Drained through a side the pressure varies and its gradient
        # stiffens the grains, to a critical step of 3.0e-7 s: refused at
        # that step, and the side stays sealed. With a step given below
        # that (1e-7 s, explicitly) the drained top is taken (the top
        # platen, which displaces the water behind it, still seals it).
        scene = os.path.join(SOURCE, "examples", "fluid_cases", "undrained_triaxial_packing.toml")
        model = darcydem.load(scene)
        with self.assertRaisesRegex(ValueError, r"draining \"z_max\" lets the one cell's pressure vary.*critical "
                                                r"step falls to 3\.0\d*e-07 s, below the scene's time step 6\.7"):
            model.set_fluid_boundary("z_max", pressure=0.0)
        with self.assertRaisesRegex(ValueError, "lets the one cell's pressure vary"):  # still sealed: refused again
            model.set_fluid_boundary("z_min", pressure=0.0)
        small = darcydem.load(scene, set={"simulation.time_step": 1e-7})
        small.set_fluid_boundary("z_max", pressure=0.0)  # taken: no error
        small.step(100)
        self.assertTrue(np.all(np.isfinite(small.positions)))


class Clumps(unittest.TestCase):
    """examples/dem_cases/clump_pour.toml: 100 dumbbells and 100 trimers."""

    def setUp(self):
        self.model = darcydem.load(os.path.join(SOURCE, "examples/dem_cases/clump_pour.toml"))

    def test_members_stay_rigidly_apart_and_cannot_be_set_alone(self):
        m = self.model
        clumps = m.clumps
        self.assertEqual(len(clumps), 200)
        self.assertEqual(sorted({len(c["members"]) for c in clumps}), [2, 3])
        row = {int(n): k for k, n in enumerate(m.ids)}

        def distances():
            x = m.positions
            return [
                math.dist(x[row[a]], x[row[b]]) for c in m.clumps for a in c["members"] for b in c["members"] if a < b
            ]

        # A clump's mass is the volume of its members' union times the
        # density, by hand from their radii and places: a dumbbell's members
        # touch, a trimer's overlap in two lenses (the end spheres apart, so
        # inclusion-exclusion is exact with the lenses), counted once.
        # Round-off only (the 3D union's quadrature: 1e-12).
        r = m.radii
        x = m.positions

        def lens(a, b):
            d = math.dist(x[a], x[b])
            ra, rb = r[a], r[b]
            if d >= ra + rb:
                return 0.0
            return math.pi * (ra + rb - d) ** 2 * (d * d + 2.0 * d * (ra + rb) - 3.0 * (ra - rb) ** 2) / (12.0 * d)

        for c in clumps:
            k = [row[n] for n in c["members"]]
            volume = sum(4.0 / 3.0 * math.pi * r[i] ** 3 for i in k)
            if len(k) == 3:
                self.assertEqual(lens(k[0], k[2]), 0.0)
                volume -= lens(k[0], k[1]) + lens(k[1], k[2])
            self.assertAlmostEqual(c["mass"], 2650.0 * volume, delta=1e-11 * 2650.0 * volume)
        before = distances()
        m.step(30000)  # 0.05 s: they fall, land, turn and knock each other
        self.assertGreater(max(math.sqrt(sum(w * w for w in c["angular_velocity"])) for c in m.clumps), 1.0)
        # Members keep their distances to round-off of positions of 0.02 m.
        for d0, d in zip(before, distances()):
            self.assertAlmostEqual(d, d0, delta=1e-15)
        with self.assertRaisesRegex(ValueError, "member of clump"):
            m.set_particle_velocity(int(m.ids[0]), velocity=[0.0, 0.0, 1.0])
        with self.assertRaisesRegex(ValueError, "member of clump"):
            m.set_particle_fixed(int(m.ids[0]), True)


class CriticalStep(unittest.TestCase):
    """model.critical_time_step, the step "auto" takes its fraction of, and
    model.time_step set from Python."""

    def test_a_sliding_sphere_at_half_the_step_keeps_its_closed_form(self):
        # slip_to_roll.toml: a sphere launched sliding at v0 = 0.2 m/s on a
        # plane with friction 0.3 slides until 2 v0 / (7 mu g) = 0.0194 s,
        # its speed v0 - mu g t. At half the scene's step, for twice the
        # steps, it reaches the same time and speed; bound 1e-4 of v0, the
        # closed-form test's (the residual bounce of its settling, Contacts).
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "slip_to_roll.toml"))
        dt = model.time_step
        model.time_step = 0.5 * dt
        self.assertEqual(model.time_step, 0.5 * dt)
        n = round(0.015 / dt)
        model.step(2 * n)
        self.assertAlmostEqual(model.time, n * dt, delta=1e-9 * n * dt)
        self.assertAlmostEqual(model.velocities[0, 0], 0.2 - 0.3 * 9.81 * model.time, delta=1e-4 * 0.2)

    def test_a_bad_step_is_refused(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "slip_to_roll.toml"))
        for bad, says in ((0.0, "give a step in seconds, > 0 (not 0)"), (float("nan"), "(not nan)"),
                          (2.0 * model.critical_time_step, "is above the critical step of the particles")):
            with self.subTest(step=bad):
                with self.assertRaisesRegex(ValueError, re.escape("time_step: " + says) if says.startswith("give")
                                            else re.escape(says)):
                    model.time_step = bad
        # A pore fluid that steps every 5 DEM steps takes its interval at
        # the step it was made with: a change between is refused.
        bed = darcydem.load(os.path.join(SOURCE, "examples", "fluid_cases", "hydrostatic_bed.toml"),
                            set={"fluid.steps_per_update": 5})
        step = bed.time_step
        bed.step(3)
        with self.assertRaisesRegex(ValueError, re.escape("3 have gone since its last step") + ".*step\\(2\\)"):
            bed.time_step = 0.5 * step
        bed.step(2)
        bed.time_step = 0.5 * step
        self.assertEqual(bed.time_step, 0.5 * step)

    def test_the_critical_step_is_what_auto_took_its_fraction_of(self):
        # "auto" is 0.2 (the default safety_factor) of the critical step at
        # load: with the pore water's stiffness in a bed of many cells, and
        # without it in the CU triaxial test's one sealed cell, where it is
        # the contacts' step (3.374e-6 s, as `darcydem check` gives it).
        for example, sealed in (("hydrostatic_bed.toml", False), ("undrained_triaxial_packing.toml", True)):
            model = darcydem.load(os.path.join(SOURCE, "examples", "fluid_cases", example))
            with self.subTest(example=example):
                self.assertAlmostEqual(model.time_step / model.critical_time_step, 0.2, delta=1e-12)
                self.assertEqual(sealed, 3.37e-6 < model.critical_time_step < 3.38e-6)

class HydrostaticBed(unittest.TestCase):
    """examples/fluid_cases/hydrostatic_bed.toml from Python (issue 3's
    verification 3), and the same scene run as the program runs it."""

    @classmethod
    def setUpClass(cls):
        cls.scene = os.path.join(SOURCE, "examples", "fluid_cases", "hydrostatic_bed.toml")
        cls.out = os.path.join(tempfile.mkdtemp(), "out")
        cls.summary = darcydem.run(cls.scene, out=cls.out)
        cls.model = darcydem.load(cls.scene)
        cls.model.step(cls.summary["steps"])

    def test_run_returns_its_summary(self):
        s = self.summary
        self.assertEqual(s["status"], "completed")
        self.assertEqual(s["stages_completed"], ["settle"])
        self.assertEqual(s["steps"], round(0.1 / self.model.time_step))
        self.assertTrue(os.path.exists(os.path.join(self.out, "run.json")))

    def test_stepping_from_python_gives_the_run_of_the_program(self):
        # The same steps and fluid steps as the run: its particles_final.csv
        # (creation order, 17 digits) is these positions exactly.
        with open(os.path.join(self.out, "particles_final.csv")) as f:
            rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))][1:]
        final = np.array([[float(v) for v in r] for r in rows])
        self.assertEqual(final.shape, (self.model.particle_count, 4))
        np.testing.assert_array_equal(self.model.positions, final[:, :3])
        np.testing.assert_array_equal(self.model.radii, final[:, 3])

    def test_a_grain_is_not_added_inside_the_water_grid(self):
        # It would compress its cell's water at once; refused, the model
        # unchanged (the other tests share it).
        count = self.model.particle_count
        with self.assertRaisesRegex(ValueError, "must lie outside the fluid grid"):
            self.model.add_particle((0.003, 0.003, 0.004), 0.00049, "sand")
        self.assertEqual(self.model.particle_count, count)

    def test_the_floor_carries_the_submerged_weight(self):
        with open(self.scene, "rb") as f:
            spec = tomllib.load(f)
        rho_s = spec["material"][0]["density"]
        rho_f = spec["fluid"]["density"]
        volumes = 4.0 / 3.0 * np.pi * self.model.radii**3
        submerged = float(np.sum((rho_s - rho_f) * volumes)) * G
        floor = next(w for w in self.model.walls if w["name"] == "floor")
        # Issue 3: within 0.5 %.
        self.assertAlmostEqual(-floor["force"][2], submerged, delta=0.005 * submerged)
        # The excess pressure of settling has drained: below 1e-6 of the
        # bed's submerged stress at the floor (as the C++ test bounds it).
        stress = submerged / (0.006 * 0.006)
        self.assertLess(np.max(np.abs(self.model.fluid.pressure)), 1e-6 * stress)
        # So the water's force on the grains is their buoyancy alone, grain
        # by grain: rho_f g V_p upwards, the excess pressure's gradient
        # (below 1e-6 of the stress over a cell) and the drag of the grains
        # at rest leaving it within 1e-5 of it (measured: 1.4e-10
        # vertically, 2.6e-8 sideways).
        buoyancy = rho_f * G * volumes
        forces = self.model.fluid_forces
        self.assertEqual(forces.shape, (self.model.particle_count, 3))
        np.testing.assert_allclose(forces[:, 2], buoyancy, rtol=1e-5)
        np.testing.assert_allclose(forces[:, :2], 0.0, atol=1e-5 * float(np.max(buoyancy)))

    def test_each_grain_is_in_balance_with_its_contacts_weight_and_the_water(self):
        # model.forces, the resultant the step applied, is the contacts'
        # forces (model.contacts) plus the weight plus the water's force
        # (model.fluid_forces): to 1e-12 of the largest contact force
        # (round-off; measured 4e-17). With a pore fluid the contacts list
        # is taken from the same step.
        m = self.model
        with open(self.scene, "rb") as f:
            rho_s = tomllib.load(f)["material"][0]["density"]
        force, _ = contact_sums(m)
        force += (rho_s * 4.0 / 3.0 * np.pi * m.radii**3)[:, None] * np.array(m.gravity)
        force += m.fluid_forces
        scale = float(np.max(np.abs(m.contacts["force"])))
        np.testing.assert_allclose(m.forces, force, rtol=0.0, atol=1e-12 * scale)
        # The bed is at rest: every grain's resultant is below 1e-6 of it.
        self.assertLess(float(np.max(np.abs(m.forces))), 1e-6 * scale)

    def test_the_contacts_stress_and_fabric(self):
        m = self.model
        x = m.positions
        r = m.radii
        lo = [-0.001, -0.001, -0.001]
        hi = [0.007, 0.007, float(np.max(x[:, 2])) + 0.001]
        volume = float(np.prod(np.subtract(hi, lo)))
        # Soil statics (as the C++ HydrostaticBed): the grains at rest, each
        # carried by its contacts against its submerged weight W'_p, the
        # floor at z = 0 and the side walls frictionless, so the contacts'
        # stress over a box holding the bed gives V sigma'_zz = sum of
        # z_p W'_p (0.5 %, as there; measured there to 9 digits).
        with open(self.scene, "rb") as f:
            spec = tomllib.load(f)
        submerged = (spec["material"][0]["density"] - spec["fluid"]["density"]) * 4.0 / 3.0 * np.pi * r**3 * G
        moment = float(np.sum(x[:, 2] * submerged))
        sigma = m.stress(lo, hi)
        self.assertEqual(sigma.shape, (3, 3))
        self.assertAlmostEqual(volume * sigma[2, 2], moment, delta=0.005 * moment)
        # The fabric from the grains' positions alone: the unit normals of
        # the touching pairs, (1/N) sum n n^T (the walls' contacts left out),
        # to round-off.
        d = x[None, :, :] - x[:, None, :]
        dist = np.linalg.norm(d, axis=2)
        i, j = np.nonzero((dist < r[:, None] + r[None, :]) & np.triu(np.ones_like(dist, dtype=bool), 1))
        self.assertGreater(len(i), 100)  # the bed's 36 columns of 8 touch: 252
        n = d[i, j] / dist[i, j][:, None]
        fabric = m.fabric(lo, hi)
        np.testing.assert_allclose(fabric, n.T @ n / len(i), rtol=0.0, atol=1e-12)
        self.assertAlmostEqual(float(np.trace(fabric)), 1.0, delta=1e-12)
        with self.assertRaisesRegex(ValueError, "max must be greater than min along every axis; along z"):
            m.fabric(lo, [0.007, 0.007, -0.002])

    def test_an_interrupted_run_resumes_to_the_same_end(self):
        # Ctrl-C (SIGINT) once the run has started stepping (its probes.csv
        # is there; the whole run takes seconds): it stops between steps,
        # keeps its output and checkpoint, and resume=True ends where the
        # run that never stopped ended, particle for particle.
        out = os.path.join(tempfile.mkdtemp(), "out")

        def interrupt_once_running():
            while not os.path.exists(os.path.join(out, "probes.csv")):
                time.sleep(0.01)
            time.sleep(0.2)
            os.kill(os.getpid(), signal.SIGINT)

        timer = threading.Thread(target=interrupt_once_running)
        timer.start()
        first = darcydem.run(self.scene, out=out)
        timer.join()
        self.assertEqual(first["status"], "interrupted")
        self.assertTrue(first["checkpoint_written"])
        self.assertLess(first["steps"], self.summary["steps"])
        second = darcydem.run(self.scene, out=out, resume=True)
        self.assertEqual(second["status"], "completed")
        self.assertEqual(second["steps"], self.summary["steps"])
        with open(os.path.join(out, "particles_final.csv")) as a, open(
            os.path.join(self.out, "particles_final.csv")
        ) as b:
            rows = lambda f: [line for line in f if not line.startswith("#")]
            self.assertEqual(rows(a), rows(b))

    def test_ctrl_c_stops_a_step_between_steps(self):
        model = darcydem.load(self.scene)
        timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
        timer.start()
        with self.assertRaises(KeyboardInterrupt):
            model.step(10**9)
        timer.join()
        done = model.steps
        self.assertGreater(done, 0)
        self.assertLess(done, 10**9)
        model.step(10)
        self.assertEqual(model.steps, done + 10)

    def test_fluid_fields_are_indexed_by_cell(self):
        f = self.model.fluid
        self.assertEqual(f.cells, [3, 3, 4])
        self.assertEqual(f.spacing, (0.002, 0.002, 0.002))
        self.assertEqual(f.pressure.shape, (3, 3, 4))
        self.assertEqual(f.permeability.shape, (3, 3, 4, 3))
        self.assertEqual(f.darcy_velocity.shape, (3, 3, 4, 3))
        # The solid volume the porosities give equals the grains' own: the
        # settled bed lies within the grid, whose cells hold every grain
        # whole or in parts (exact overlaps, to round-off).
        # Grains pressed against the floor and the side walls (all on the
        # grid's sides) stick out of the grid by their contact overlap: the
        # caps beyond, pi h^2 (3 r - h) / 3, are not in any cell.
        cell_volume = 0.002**3
        solid = float(np.sum(1.0 - f.porosity)) * cell_volume
        r = self.model.radii
        x = self.model.positions
        outside = 0.0
        for beyond in (-x[:, 0], x[:, 0] - 0.006, -x[:, 1], x[:, 1] - 0.006, -x[:, 2]):
            h = np.maximum(0.0, r + beyond)
            outside += float(np.sum(np.pi * h**2 * (3.0 * r - h) / 3.0))
        grains = float(np.sum(4.0 / 3.0 * np.pi * r**3))
        self.assertGreater(outside, 0.0)
        self.assertAlmostEqual(solid, grains - outside, delta=1e-12 * grains)
        # The top layer holds fewer grains than the bottom one (the bed has
        # settled below the grid's top).
        self.assertGreater(f.porosity[:, :, 3].mean(), f.porosity[:, :, 0].mean())
        # Balance since the start: inflow = stored + pore change, to round-off.
        b = f.balance
        self.assertLess(abs(b["imbalance"]), 1e-12 * grains)
        self.assertAlmostEqual(f.pressure_at((0.003, 0.003, 0.001)), f.pressure[1, 1, 0], delta=1e-9)



class GradedGrid(unittest.TestCase):
    """examples/fluid_cases/graded_upward_seepage.toml: a grid graded along z."""

    def test_the_faces_and_the_cells_volumes(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "fluid_cases", "graded_upward_seepage.toml"))
        f = model.fluid
        faces = [np.array(a) for a in f.faces]
        self.assertEqual([len(a) for a in faces], [4, 4, 5])
        self.assertTrue(np.isnan(f.spacing[2]))
        self.assertAlmostEqual(f.spacing[0], 0.002, delta=1e-15)
        # ratio = 2: the top cell twice the bottom one, 8 mm in all.
        widths = np.diff(faces[2])
        self.assertAlmostEqual(widths[-1], 2.0 * widths[0], delta=1e-15)
        self.assertAlmostEqual(faces[2][-1], 0.008, delta=1e-15)
        # Each cell's porosity from its own volume (the widths' product).
        volume = np.einsum("i,j,k->ijk", np.diff(faces[0]), np.diff(faces[1]), widths)
        expected = 1.0 - f.solid_volume / volume
        self.assertLess(float(np.max(np.abs(f.porosity - expected))), 1e-12)


class PilePenetration(unittest.TestCase):
    """examples/fluid_cases/pile_penetration.toml stepped from Python: the
    rod, a box wall that displaces the pore fluid, pushed into the grid."""

    def test_the_rods_volume_in_the_grid_follows_its_position(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "fluid_cases", "pile_penetration.toml"))
        f = model.fluid
        # At the start its tip is 0.5 mm above the grid: nothing in it.
        self.assertEqual(float(np.sum(f.wall_volume)), 0.0)
        model.apply_stage("push")
        model.step(40000)  # 0.046 s at 20 mm/s: 0.93 mm down, 0.43 mm into the grid
        f = model.fluid
        rod = next(w for w in model.walls if w["name"] == "rod")
        tip = rod["point"][2] - 0.00575  # the box's centre is 5.75 mm above its tip
        self.assertLess(tip, 0.008)
        inside = 0.002 * 0.002 * (0.008 - tip)
        # All of it in the top middle cell, the rest nowhere (exact overlaps:
        # 1e-12 of it, round-off of the positions' sums).
        self.assertAlmostEqual(float(f.wall_volume[1, 1, 3]), inside, delta=1e-12 * inside)
        self.assertAlmostEqual(float(np.sum(f.wall_volume)), inside, delta=1e-12 * inside)
        # Porosity counts the grains and the rod, cell by cell.
        cell = 0.002**3
        expected = 1.0 - (f.solid_volume + f.wall_volume) / cell
        self.assertLess(float(np.max(np.abs(f.porosity - expected))), 1e-12)
        # Balance since the start: each step's imbalance is the pressure
        # solve's residual summed over the cells, and the scene's CG stops
        # at a residual of 1e-10 of the right-hand side, so 1e-10 of the
        # gross flow (every term's magnitude, step by step). Measured
        # 1.75e-11 of it (1.5e-19 m^3, 1.05e-12 of the grains' volume: the
        # bound before session 27 was 1e-12 of that volume, which the water
        # the grains carry across the drained top now exceeds).
        gross = f.balance["gross"]
        self.assertLess(abs(f.balance["imbalance"]), 1e-10 * gross)

class SealedPiston(unittest.TestCase):
    """examples/fluid_cases/consolidation_sealed_piston.toml: its two stages
    stepped from Python give the program's run, servo, water's thrust and
    all."""

    def test_stepping_both_stages_gives_the_run_of_the_program(self):
        scene = os.path.join(SOURCE, "examples", "fluid_cases", "consolidation_sealed_piston.toml")
        out = os.path.join(tempfile.mkdtemp(), "out")
        summary = darcydem.run(scene, out=out)
        self.assertEqual(summary["stages_completed"], ["settle", "load"])
        model = darcydem.load(scene)
        settle = round(1.5 / model.time_step)
        model.step(settle)
        model.apply_stage("load")
        model.step(summary["steps"] - settle)
        with open(os.path.join(out, "particles_final.csv")) as f:
            rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))][1:]
        final = np.array([[float(v) for v in r] for r in rows])
        np.testing.assert_array_equal(model.positions, final[:, :2])
        # The piston's water thrust is the pressure under it times its
        # width (1 mm): the top cell's, to the cell's O(h^2) (1e-3 of it
        # at most here, where the pressure has all but drained).
        piston = next(w for w in model.walls if w["name"] == "piston")
        top = float(model.fluid.pressure[0, -1])
        self.assertGreater(top, 0.0)
        self.assertAlmostEqual(piston["water_force"][1], top * 0.001, delta=1e-3 * top * 0.001)
        # Sideways the two side walls' pressures cancel, to round-off.
        self.assertLess(abs(piston["water_force"][0]), 1e-12 * abs(piston["water_force"][1]))


class Silo(unittest.TestCase):
    """examples/dem_cases/silo_discharge.toml with 300 discs: grains fall
    out of the [domain] and are removed; the arrays keep the others in
    creation order, and the removed ones are counted."""

    def test_the_grains_left_and_those_removed(self):
        folder = tempfile.mkdtemp()
        with open(os.path.join(SOURCE, "examples", "dem_cases", "silo_discharge.toml")) as f:
            text = f.read()
        for old, new in (
            ("count = 1400", "count = 300"),
            ('name = "fill"\nduration = 0.6', 'name = "fill"\nduration = 0.2'),
            ('name = "discharge"\nduration = 1.5', 'name = "discharge"\nduration = 0.3'),
        ):
            self.assertIn(old, text)
            text = text.replace(old, new)
        scene = write_scene(folder, text, "silo.toml")
        out = os.path.join(folder, "out")
        summary = darcydem.run(scene, out=out)
        model = darcydem.load(scene)
        self.assertEqual(list(model.ids), list(range(300)))
        # Discs of unit thickness, 2500 kg/m^3: the mass per metre.
        radii = model.radii
        total = 2500.0 * math.pi * float(np.sum(radii**2))
        fill = round(0.2 / model.time_step)
        model.step(fill)
        model.apply_stage("discharge")
        model.step(summary["steps"] - fill)
        ids = model.ids
        self.assertGreater(model.removed_count, 0)
        self.assertEqual(len(ids) + model.removed_count, 300)
        self.assertEqual(model.particle_count, len(ids))
        self.assertTrue(np.all(np.diff(ids) > 0))
        # Each row is the particle its number says: its radius (drawn
        # between 0.8 and 1.2 mm, none two alike) is that particle's.
        np.testing.assert_array_equal(model.radii, radii[ids])
        # Those left are inside the domain, and with those removed they make
        # the scene's mass (a sum of 300 terms: round-off 1e-13 of it).
        x = model.positions
        self.assertTrue(np.all(x >= np.array([-0.05, -0.03])) and np.all(x <= np.array([0.13, 0.2])))
        left = 2500.0 * math.pi * float(np.sum(model.radii**2))
        self.assertAlmostEqual(left + model.removed_mass, total, delta=1e-13 * total)
        # The program's run removed the same grains and left them in the
        # same places (particles_final.csv is in creation order too).
        with open(os.path.join(out, "particles_final.csv")) as f:
            rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))][1:]
        final = np.array([[float(v) for v in r] for r in rows])
        np.testing.assert_array_equal(x, final[:, :2])
        np.testing.assert_array_equal(model.radii, final[:, 2])


class MeshWall(unittest.TestCase):
    """examples/dem_cases/conical_hopper.toml: its hopper is a mesh wall of
    192 facets read from an STL file in mm; model.walls describes it, with
    the area of the faceted surface worked out from its geometry."""

    def test_the_hopper_is_a_mesh_of_its_facets(self):
        scene = os.path.join(SOURCE, "examples", "dem_cases", "conical_hopper.toml")
        model = darcydem.load(scene)
        hopper = next(w for w in model.walls if w["name"] == "hopper")
        self.assertEqual(hopper["shape"], "mesh")
        self.assertEqual(hopper["facets"], 192)
        # 48 sides: a cylinder of radius 15 mm from the cone's top to 45 mm,
        # on a cone from radius 6 mm at z = 0 narrowing at 30 degrees. Each
        # side of the cylinder a rectangle, of the cone an isosceles
        # trapezoid between chords 2 r sin(pi / 48).
        sides = 48
        chord = lambda r: 2.0 * r * math.sin(math.pi / sides)
        cone_top = 9.0 / math.tan(math.radians(30.0))
        cylinder = sides * chord(15.0) * (45.0 - cone_top)
        slant = math.hypot(9.0 * math.cos(math.pi / sides), cone_top)
        cone = sides * 0.5 * (chord(6.0) + chord(15.0)) * slant
        # The file keeps 9 digits: 1e-8 of the area.
        self.assertAlmostEqual(hopper["area"], (cylinder + cone) * 1e-6, delta=1e-8 * (cylinder + cone) * 1e-6)
        # Its point is the middle of its bounding box (the file's z from 0
        # to 45 mm, x and y +-15 mm).
        np.testing.assert_allclose(hopper["point"], [0.0, 0.0, 0.0225], atol=1e-12)
        self.assertEqual(len(hopper["axes"]), 3)
        # The grains rained in land on it: after 0.1 s some press on the cone.
        model.step(round(0.1 / model.time_step))
        hopper = next(w for w in model.walls if w["name"] == "hopper")
        self.assertLess(hopper["force"][2], 0.0)


class Pluviation(unittest.TestCase):
    """examples/dem_cases/pluviation.toml, its rain stage alone: the inlet
    adds grains while Python steps, as it does in the program's run."""

    def test_stepping_adds_the_grains_of_the_run(self):
        folder = tempfile.mkdtemp()
        with open(os.path.join(SOURCE, "examples", "dem_cases", "pluviation.toml")) as f:
            text = f.read()
        settle = text.index('[[stage]]\nname = "settle"')
        text = text[:settle].replace('name = "rain"\nduration = 1.0', 'name = "rain"\nduration = 0.3')
        scene = write_scene(folder, text, "rain.toml")
        out = os.path.join(folder, "out")
        summary = darcydem.run(scene, out=out)
        model = darcydem.load(scene)
        self.assertEqual(model.particle_count, 0)
        model.step(summary["steps"])
        # 0.3 s at 3 kg/(s m), inserted every 10 ms from t = 0: 30 insertions
        # (the one due at 0.3 s comes after the stage), 0.9 kg/m due; what was
        # added is short of it by less than a grain of 1.2 mm.
        heaviest = 2650.0 * math.pi * 0.0012**2
        self.assertLessEqual(model.inserted_mass, 0.9 * (1 + 1e-9))
        self.assertGreater(model.inserted_mass, 0.9 - heaviest)
        self.assertEqual(model.particle_count, model.inserted_count)
        self.assertEqual(list(model.ids), list(range(model.inserted_count)))
        mass = 2650.0 * math.pi * float(np.sum(model.radii**2))
        self.assertAlmostEqual(mass, model.inserted_mass, delta=1e-12 * mass)
        # The same grains in the same places as the program's run.
        with open(os.path.join(out, "particles_final.csv")) as f:
            rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))][1:]
        final = np.array([[float(v) for v in r] for r in rows])
        self.assertEqual(final.shape, (model.particle_count, 3))
        np.testing.assert_array_equal(model.positions, final[:, :2])
        np.testing.assert_array_equal(model.radii, final[:, 2])

    def test_an_inlet_of_clumps_stopped_and_started_from_python(self):
        # examples/dem_cases/clump_pluviation.toml: the hopper rains peanuts
        # every 10 ms from t = 0 (time step 1.697e-5 s). After 2700 steps
        # (45.8 ms) five insertions have made 0.15 kg/m due, and it has added
        # less than that by less than a peanut. Stopped, it adds nothing
        # more; started again, it inserts at once: 0.18 kg/m due in all.
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "clump_pluviation.toml"))
        (hopper,) = model.inlets
        self.assertEqual(hopper["name"], "hopper")
        self.assertEqual(hopper["clump"], "peanut")
        self.assertTrue(hopper["active"])
        self.assertEqual(hopper["next_time"], 0.0)
        # The largest peanut: holding radius 1.2 mm, its union two discs of
        # 0.8 (template units) 1.2 apart less their lens.
        lens = 2.0 * 0.64 * math.acos(0.75) - 0.6 * math.sqrt(1.12)
        heaviest = 2650.0 * (2.0 * math.pi * 0.64 - lens) * (0.0012 / 1.4) ** 2
        model.step(2700)
        hopper = model.inlets[0]
        self.assertEqual(hopper["inserted"], len(model.clumps))
        self.assertEqual(hopper["particles"], 2 * hopper["inserted"])
        self.assertEqual(hopper["particles"], model.inserted_count)
        self.assertEqual(hopper["mass"], model.inserted_mass)
        self.assertAlmostEqual(hopper["mass"], sum(c["mass"] for c in model.clumps), delta=1e-12)
        self.assertLessEqual(hopper["mass"], 0.15 * (1 + 1e-9))
        self.assertGreater(hopper["mass"], 0.15 - heaviest)
        model.set_inlet_active("hopper", False)
        self.assertFalse(model.inlets[0]["active"])
        self.assertIsNone(model.inlets[0]["next_time"])
        model.step(2000)
        self.assertEqual(model.inlets[0]["inserted"], hopper["inserted"])
        model.set_inlet_active("hopper", True)
        self.assertEqual(model.inlets[0]["next_time"], model.time)
        model.step(1)
        self.assertLessEqual(model.inlets[0]["mass"], 0.18 * (1 + 1e-9))
        self.assertGreater(model.inlets[0]["mass"], 0.18 - heaviest)
        with self.assertRaisesRegex(ValueError, "no \\[\\[inlet\\]\\] 'hoper' \\(the scene's: 'hopper'\\)"):
            model.set_inlet_active("hoper", False)


class CementedChain(unittest.TestCase):
    """examples/dem_cases/cemented_chain.toml stepped from Python: the first
    stage's make_bonds bonds the chain as the model is loaded, the run's
    statics follow, and an overload breaks the top bond."""

    def test_bonds_hold_the_chain_and_break_when_overloaded(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "cemented_chain.toml"))
        self.assertEqual(model.bond_count, 10)
        self.assertEqual(model.broken_bonds, 0)
        self.assertEqual(model.make_bonds(), 0)  # all bonded already
        model.step(round(0.3 / model.time_step))
        # Every bond stretched by the weight below it: the lowest disc sunk
        # by 55 m g / k_n (as the program's run; bound as in test_bonds.cpp).
        m = 2500.0 * math.pi * 1e-6
        sink = 55.0 * m * 9.81 / 1e4
        self.assertAlmostEqual(model.positions[10, 1], -0.021 - sink, delta=1e-6 * sink)
        model.apply_stage("overload")
        model.step(round(0.05 / model.time_step))
        self.assertEqual(model.broken_bonds, 1)
        self.assertEqual(model.bond_count, 9)
        # A gap must lie below the skin (0.5 mm here).
        with self.assertRaisesRegex(ValueError, "below the skin"):
            model.make_bonds(gap=1e-3)


DRUM = """
[simulation]
dimension = 2
time_step = {dt!r}

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e4
friction = 0.5
rolling_friction = 0.2
restitution = 1.0

[[wall]]
name = "drum"
cylinder = {{ centre = [0.0, 0.0], radius = 0.005 }}
material = "sand"

[[wall]]
name = "floor"
point = [0.0, -0.01]
normal = [0.0, 1.0]
material = "sand"

[[particles]]
generator = "csv"
material = "sand"
file = "disc.csv"

[[stage]]
name = "turn"
duration = 5.0
gravity = [0.0, -9.81]
local_damping = 0.1
"""


class SpinningDrum(unittest.TestCase):
    """A disc at the bottom of a drum set turning from Python: as in
    test_cylinder_walls.cpp, it comes to rest rolling in place at
    tan(theta) = mu_r r / a, a = r - delta, and the drum's torque is
    -mu_r r N (R / a - 1)."""

    def setUp(self):
        self.folder = tempfile.mkdtemp()
        self.r, self.R = 5e-4, 5e-3
        with open(os.path.join(self.folder, "disc.csv"), "w") as f:
            f.write(f"x,y,radius\n0.0,{-(self.R - self.r)!r},{self.r!r}\n")
        self.mass = 2650.0 * math.pi * self.r**2
        dt = 0.05 * math.sqrt(self.mass / 1e4)
        self.model = darcydem.load(write_scene(self.folder, DRUM.format(dt=dt)))

    def test_the_drum_turned_from_python_holds_the_disc_at_its_rolling_angle(self):
        m = self.model
        drum = next(w for w in m.walls if w["name"] == "drum")
        self.assertEqual((drum["shape"], drum["angular_velocity"], drum["torque"]), ("cylinder", 0.0, 0.0))
        m.set_wall_motion("drum", angular_velocity=1.0)
        m.step(round(5.0 / m.time_step))
        x = m.positions[0]
        theta = math.atan2(x[0], -x[1])
        normal = self.mass * 9.81 * math.cos(theta)
        arm = self.r - normal / 1e4
        drum = next(w for w in m.walls if w["name"] == "drum")
        self.assertEqual(drum["angular_velocity"], 1.0)
        # After 5 s the swing has stilled to 1e-10 (test_cylinder_walls.cpp,
        # the same run; measured here 6.9e-11 and 5.2e-12); 1e-8 as there.
        # A drum left still would hold the disc at the bottom, theta = 0.
        print(f"drum from python: theta {theta / math.atan(0.2 * self.r / arm) - 1:+.2e}, "
              f"torque {drum['torque'] / (-0.2 * self.r * normal * (self.R / arm - 1.0)) - 1:+.2e}")
        self.assertAlmostEqual(theta / math.atan(0.2 * self.r / arm), 1.0, delta=1e-8)
        torque = -0.2 * self.r * normal * (self.R / arm - 1.0)
        self.assertAlmostEqual(drum["torque"] / torque, 1.0, delta=1e-8)
        m.set_wall_motion("drum", angular_velocity=0.0)
        self.assertEqual(next(w for w in m.walls if w["name"] == "drum")["angular_velocity"], 0.0)

    def test_bad_wall_motions_are_refused(self):
        m = self.model
        with self.assertRaisesRegex(ValueError, "no wall 'lid'.*'drum', 'floor'"):
            m.set_wall_motion("lid", velocity=[0.0, 1.0])
        with self.assertRaisesRegex(ValueError, "'floor' turns about the normal to the plane of the discs: give "
                                                "angular_velocity as a number"):
            m.set_wall_motion("floor", angular_velocity=[1.0])
        with self.assertRaisesRegex(ValueError, "give velocity"):
            m.set_wall_motion("drum")
        with self.assertRaisesRegex(ValueError, "finite"):
            m.set_wall_motion("drum", angular_velocity=float("nan"))
        with self.assertRaisesRegex(ValueError, "velocity: 2 numbers expected, 3 given"):
            m.set_wall_motion("floor", velocity=[0.0, 0.0, 1.0])
        with self.assertRaisesRegex(ValueError, "velocity must be finite"):
            m.set_wall_motion("floor", velocity=[0.0, float("inf")])
        # Nothing refused was set.
        self.assertEqual([(w["velocity"], w["angular_velocity"]) for w in m.walls], [((0.0, 0.0), 0.0)] * 2)
        m.set_wall_motion("floor", velocity=[0.0, -0.1])
        floor = next(w for w in m.walls if w["name"] == "floor")
        self.assertEqual(floor["velocity"], (0.0, -0.1))


TABLE_3D = """
[simulation]
dimension = 3
time_step = 1e-5

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e3
restitution = 0.5

[[wall]]
name = "table"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "sand"
rotation_centre = [0.01, 0.0, 0.0]

[[particles]]
generator = "csv"
material = "sand"
file = "one.csv"

[[stage]]
name = "rest"
duration = 0.1
"""


class TiltingTable(unittest.TestCase):
    """examples/dem_cases/tilting_table.toml with the table set turning
    from Python at twice its stage's rate: the block rides up with it, and
    the table's moment about its pivot is the block's weight on the
    vertical through its centre of mass, -M g (19 cos - 3 sin) mm
    (tests/verification/test_turning_walls.cpp, the same run by its
    stage: within 2.5e-5 after the start's jolt)."""

    def test_the_table_turned_from_python_carries_the_block(self):
        m = darcydem.load(os.path.join(SOURCE, "examples/dem_cases/tilting_table.toml"))
        m.step(round(0.05 / m.time_step))
        start = m.time
        table = next(w for w in m.walls if w["name"] == "table")
        self.assertEqual((table["shape"], table["angular_velocity"], table["rotation_centre"]),
                         ("box", 0.0, (0.0, 0.0)))
        # The tilt stage's damping (none), and twice its rate.
        m.apply_stage("tilt")
        m.set_wall_motion("table", angular_velocity=0.2)
        m.step(round(1.0 / m.time_step))
        table = next(w for w in m.walls if w["name"] == "table")
        tilt = 0.2 * (m.time - start)
        # Its axes turned by the tilt; the sum of a 1.2e5 steps' angles, so
        # 1e-10.
        self.assertAlmostEqual(table["axes"][0][0], math.cos(tilt), delta=1e-10)
        self.assertAlmostEqual(table["axes"][0][1], math.sin(tilt), delta=1e-10)
        self.assertAlmostEqual(table["point"][0], 0.02 * math.cos(tilt) + 0.001 * math.sin(tilt), delta=1e-12)
        mass = 15 * 2650.0 * math.pi * 1e-6
        expected = -mass * 9.81 * (0.019 * math.cos(tilt) - 0.003 * math.sin(tilt))
        print(f"tilting table from python: tilt {tilt:.4f} rad, torque {table['torque'] / expected - 1:+.2e}")
        self.assertAlmostEqual(table["torque"] / expected, 1.0, delta=2e-4)
        with self.assertRaisesRegex(ValueError, "'table' turns, and a servo moves a wall along a fixed direction"):
            m.set_wall_servo("table", gain=1e-3, max_speed=0.01, target_force=1.0, direction=[0.0, -1.0])

    def test_a_3d_plane_turns_about_its_vector(self):
        folder = tempfile.mkdtemp()
        with open(os.path.join(folder, "one.csv"), "w") as f:
            f.write("x,y,z,radius\n0.0,0.0,0.01,0.0005\n")
        m = darcydem.load(write_scene(folder, TABLE_3D))
        with self.assertRaisesRegex(ValueError, r"'table' is a plane or box, which turns about the axis of its "
                                                r"angular velocity through its rotation centre: give "
                                                r"angular_velocity = \[wx, wy, wz\]"):
            m.set_wall_motion("table", angular_velocity=0.5)
        m.set_wall_motion("table", angular_velocity=[0.0, 0.5, 0.0])
        m.step(1000)
        table = m.walls[0]
        self.assertEqual(table["angular_velocity"], (0.0, 0.5, 0.0))
        self.assertEqual(table["rotation_centre"], (0.01, 0.0, 0.0))
        # About +y the normal z goes to (sin, 0, cos); the point stays on
        # the plane through the pivot.
        tilt = 0.5 * m.time
        for got, want in zip(table["normal"], (math.sin(tilt), 0.0, math.cos(tilt))):
            self.assertAlmostEqual(got, want, delta=1e-12)
        m.set_wall_motion("table", angular_velocity=0)
        self.assertEqual(m.walls[0]["angular_velocity"], (0.0, 0.0, 0.0))


LATTICE = """
[simulation]
dimension = 2

[[material]]
name = "glass"
density = 2500.0

[[contact]]
materials = ["glass", "glass"]
law = "linear"
normal_stiffness = 1e8
restitution = 0.5

[[wall]]
name = "left"
point = [0.0, 0.0]
normal = [1.0, 0.0]
material = "glass"

[[wall]]
name = "right"
point = [0.008, 0.0]
normal = [-1.0, 0.0]
material = "glass"

[[wall]]
name = "floor"
point = [0.0, 0.0]
normal = [0.0, 1.0]
material = "glass"

[[wall]]
name = "lid"
point = [0.0, 0.008]
normal = [0.0, -1.0]
material = "glass"

[[particles]]
generator = "lattice"
material = "glass"
min = [0.0, 0.0]
max = [0.008, 0.008]
radius = 0.001

[[stage]]
name = "load"
duration = 0.06
local_damping = 0.7
"""


def ring_in_a_drum():
    """A model: a drum of 3 mm round a central disc and a ring of 5 discs of
    1 mm touching it (2D), the glass of LATTICE."""
    import math
    folder = tempfile.mkdtemp()
    with open(os.path.join(folder, "ring.csv"), "w") as f:
        f.write("x,y,radius\n0,0,0.001\n")
        for j in range(5):
            a = 2.0 * math.pi * j / 5 + 0.3
            f.write(f"{0.002 * math.cos(a)},{0.002 * math.sin(a)},0.001\n")
    text = LATTICE.split("[[wall]]")[0] + """
[[wall]]
name = "drum"
material = "glass"
cylinder = { centre = [0.0, 0.0], radius = 0.003 }

[[particles]]
generator = "csv"
file = "ring.csv"
material = "glass"

[[stage]]
name = "load"
duration = 0.06
local_damping = 0.7
"""
    return darcydem.load(write_scene(folder, text))


class StressServo(unittest.TestCase):
    """A square lattice of 4 x 4 discs between four walls made stress servos
    from Python (10 kPa along x, 20 along y), as in test_triaxial.cpp: each
    side squeezed by 5 F / k_n, F = the stress x the other side / 4."""

    def setUp(self):
        self.folder = tempfile.mkdtemp()
        self.model = darcydem.load(write_scene(self.folder, LATTICE))

    def test_walls_made_servos_from_python_squeeze_the_lattice_as_by_hand(self):
        m = self.model
        self.assertEqual([w["servo"] for w in m.walls], [None] * 4)
        gain = 5.0 / (4.0 * 1e8 * 1e-3)  # settles in about 1 ms
        stress = {"left": 1e4, "right": 1e4, "floor": 2e4, "lid": 2e4}
        for name, s in stress.items():
            m.set_wall_servo(name, gain=gain, max_speed=0.01, target_stress=s)
        m.apply_stage("load")
        m.step(round(0.06 / m.time_step))
        walls = {w["name"]: w for w in m.walls}
        sides = [0.008, 0.008]
        for _ in range(50):
            sides = [0.008 - 5.0 * 1e4 * sides[1] / 4.0 / 1e8, 0.008 - 5.0 * 2e4 * sides[0] / 4.0 / 1e8]
        width = walls["right"]["point"][0] - walls["left"]["point"][0]
        height = walls["lid"]["point"][1] - walls["floor"]["point"][1]
        print(f"lattice from python: squeezes {(0.008 - width) / (0.008 - sides[0]) - 1:+.2e}, "
              f"{(0.008 - height) / (0.008 - sides[1]) - 1:+.2e}")
        # The servos' error decays as exp(-t / 1 ms) over 60 ms: round-off
        # is left (9e-13 in the C++ test); 1e-6 as there. The walls' stress
        # is the target.
        self.assertAlmostEqual((0.008 - width) / (0.008 - sides[0]), 1.0, delta=1e-6)
        self.assertAlmostEqual((0.008 - height) / (0.008 - sides[1]), 1.0, delta=1e-6)
        for name, s in stress.items():
            self.assertAlmostEqual(walls[name]["stress"] / s, 1.0, delta=1e-6)
            self.assertEqual(walls[name]["servo"], {"target_stress": s})

    def test_bad_servos_are_refused(self):
        m = self.model
        with self.assertRaisesRegex(ValueError, "no wall 'top'"):
            m.set_wall_servo("top", gain=1.0, max_speed=1.0, target_stress=1.0)
        with self.assertRaisesRegex(ValueError, "give one of target_force"):
            m.set_wall_servo("lid", gain=1.0, max_speed=1.0)
        with self.assertRaisesRegex(ValueError, "give one of target_force"):
            m.set_wall_servo("lid", gain=1.0, max_speed=1.0, target_force=1.0, target_stress=1.0)
        with self.assertRaisesRegex(ValueError, "the target must be finite and >= 0"):
            m.set_wall_servo("lid", gain=1.0, max_speed=1.0, target_stress=-1.0)
        with self.assertRaisesRegex(ValueError, "gain must be finite and > 0"):
            m.set_wall_servo("lid", gain=0.0, max_speed=1.0, target_stress=1.0)
        with self.assertRaisesRegex(ValueError, "max_speed must be finite and > 0"):
            m.set_wall_servo("lid", gain=1.0, max_speed=float("nan"), target_stress=1.0)
        with self.assertRaisesRegex(ValueError, "direction is for box walls"):
            m.set_wall_servo("lid", gain=1.0, max_speed=1.0, target_force=1.0, direction=[0.0, -1.0])
        self.assertEqual([w["servo"] for w in m.walls], [None] * 4)  # nothing refused was set
        m.set_wall_servo("lid", gain=1.0, max_speed=1.0, target_force=2.0)
        self.assertEqual(next(w for w in m.walls if w["name"] == "lid")["servo"], {"target_force": 2.0})

    def test_a_drum_made_a_servo_from_python_closes_on_a_ring_as_by_hand(self):
        """A drum of 3 mm round a central disc and a ring of 5 discs of 1 mm
        touching it, made a stress servo at 10 kPa from Python (as
        test_triaxial.cpp's DrumClosingOnARingOfDiscs): each ring disc
        carries F = stress x 2 pi R / 5 through two contacts in series, so
        R = 3 mm / (1 + 4 pi stress / (5 k_n))."""
        import math
        m = ring_in_a_drum()
        with self.assertRaisesRegex(ValueError, "a cylinder's servo changes its radius"):
            m.set_wall_servo("drum", gain=1.0, max_speed=1.0, target_force=1.0, direction=[1.0, 0.0])
        gain = 2.0 / (5 * 1e8 * 1e-3)  # settles in about 1 ms
        m.set_wall_servo("drum", gain=gain, max_speed=0.01, target_stress=1e4)
        m.apply_stage("load")
        m.step(round(0.06 / m.time_step))
        drum = m.walls[0]
        expected = 0.003 / (1.0 + 4.0 * math.pi * 1e4 / (5 * 1e8))
        print(f"drum from python: squeeze {(0.003 - drum['radius']) / (0.003 - expected) - 1:+.2e}")
        # As in the C++ test (2e-10 there): round-off is left; 1e-6.
        self.assertAlmostEqual((0.003 - drum["radius"]) / (0.003 - expected), 1.0, delta=1e-6)
        self.assertAlmostEqual(drum["stress"] / 1e4, 1.0, delta=1e-6)
        self.assertAlmostEqual(drum["radial_load"] / (1e4 * 2.0 * math.pi * drum["radius"]), 1.0, delta=1e-6)
        self.assertEqual(drum["servo"], {"target_stress": 1e4})

    def test_a_drum_opened_at_a_set_rate_from_python(self):
        """radial_velocity: the radius grows at the rate, and a servo ends."""
        with self.assertRaisesRegex(ValueError, "wall 'lid' is not a cylinder, and only a cylinder changes its"):
            self.model.set_wall_motion("lid", radial_velocity=0.01)
        m = ring_in_a_drum()
        with self.assertRaisesRegex(ValueError, "radial_velocity must be a finite number"):
            m.set_wall_motion("drum", radial_velocity=float("inf"))
        m.set_wall_servo("drum", gain=1.0, max_speed=0.01, target_stress=1e4)
        m.set_wall_motion("drum", radial_velocity=0.002)
        self.assertIsNone(m.walls[0]["servo"])
        steps = 1000
        m.step(steps)
        # The radius is summed step by step: round-off, 1e-15 m of 3 mm.
        self.assertAlmostEqual(m.walls[0]["radius"], 0.003 + 0.002 * steps * m.time_step, delta=1e-15)


class CyclicPiston(unittest.TestCase):
    """examples/fluid_cases/consolidation_sealed_piston.toml's piston cycled from Python."""

    EXAMPLE = os.path.join(SOURCE, "examples", "fluid_cases", "consolidation_sealed_piston.toml")
    CYCLE = {"amplitude": 0.25, "frequency": 1.5, "phase": -90.0}
    RAMP = {"times": [0.0, 0.1], "values": [0.26, 0.3]}

    def settled(self, path):
        model = darcydem.load(path)
        model.step(20000)  # 0.18 s of settling: enough to compare two runs
        model.apply_stage("load")
        return model

    def test_a_cycle_set_from_python_is_the_stages(self):
        with open(self.EXAMPLE) as f:
            text = f.read()
        servo = "servo = { target_force = 0.51, gain = 0.1"
        self.assertIn(servo, text)
        cycled = os.path.join(tempfile.mkdtemp(), "cycled.toml")
        with open(cycled, "w") as f:
            f.write(text.replace(servo, "servo = { target_force = { times = [0.0, 0.1], values = [0.26, 0.3] }, "
                                        "cycle = { amplitude = 0.25, frequency = 1.5, phase = -90.0 }, gain = 0.1"))
        by_stage = self.settled(cycled)
        by_python = self.settled(self.EXAMPLE)
        start = by_python.time
        by_python.set_wall_servo("piston", gain=0.1, max_speed=0.05, target_force=self.RAMP, cycle=self.CYCLE,
                                 direction=[0.0, -1.0], load="total")
        steps = 20000
        by_stage.step(steps)
        by_python.step(steps)
        # The same target from the same start, on the same load: bit for bit.
        np.testing.assert_array_equal(by_python.positions, by_stage.positions)
        piston = next(w for w in by_python.walls if w["name"] == "piston")
        self.assertEqual(piston["servo"]["cycle"]["amplitude"], 0.25)
        self.assertEqual(piston["servo"]["cycle"]["frequency"], 1.5)
        self.assertAlmostEqual(piston["servo"]["cycle"]["phase"], -90.0, delta=1e-12)
        # The target of the last step, taken at its start (0.18 s in, past
        # the ramp's 0.1 s): 0.3 - 0.25 cos(2 pi f s), s from the call
        # (round-off: 1e-12 N).
        s = by_python.time - by_python.time_step - start
        self.assertGreater(s, 0.1)
        self.assertAlmostEqual(piston["servo"]["target_force"], 0.3 - 0.25 * math.cos(3.0 * math.pi * s),
                               delta=1e-12)
        # Without load="total" the servo pushes the grains alone to the
        # target: another run.
        grains_only = self.settled(self.EXAMPLE)
        grains_only.set_wall_servo("piston", gain=0.1, max_speed=0.05, target_force=self.RAMP, cycle=self.CYCLE,
                                   direction=[0.0, -1.0])
        grains_only.step(steps)
        self.assertFalse(np.array_equal(grains_only.positions, by_stage.positions))

    def test_bad_cycles_are_refused(self):
        model = darcydem.load(self.EXAMPLE)
        for bad, message in [
            ([0.25, 1.5], "give cycle = "),
            ({"amplitude": 0.25}, "give cycle = "),
            ({"amplitude": 0.25, "frequency": 1.5, "period": 1.0}, "cycle has no key 'period'"),
            ({"amplitude": 0.3, "frequency": 1.5}, "at most the target \\(0.26\\)"),
            ({"amplitude": 0.25, "frequency": 0.0}, "frequency must be > 0 Hz"),
            ({"amplitude": 0.25, "frequency": 1.5, "phase": math.inf}, "phase must be finite"),
        ]:
            with self.subTest(bad=bad), self.assertRaisesRegex(ValueError, message):
                model.set_wall_servo("piston", gain=0.1, max_speed=0.05, target_force=0.26, cycle=bad)
        for bad, message in [
            ("high", "must be a number or {'times'"),
            ({"times": [0.0, 1.0]}, "must be a number or {'times'"),
            ({"times": [0.0, 1.0], "values": [1.0]}, "the same, non-zero length"),
            ({"times": [1.0, 0.0], "values": [1.0, 2.0]}, "increase strictly"),
            ({"times": [0.0, 1.0], "values": [1.0, -2.0]}, "finite and >= 0, got -2"),
            ({"times": [0.0], "values": [1.0], "start": 2.0}, "the target has no key 'start'"),
        ]:
            with self.subTest(bad=bad), self.assertRaisesRegex(ValueError, message):
                model.set_wall_servo("piston", gain=0.1, max_speed=0.05, target_force=bad)
        # A cycle may not take the schedule's least value below 0.
        with self.assertRaisesRegex(ValueError, "at most the target \\(0.2\\)"):
            model.set_wall_servo("piston", gain=0.1, max_speed=0.05, target_force={"times": [0.0, 1.0],
                                 "values": [0.5, 0.2]}, cycle={"amplitude": 0.25, "frequency": 1.0})
        with self.assertRaisesRegex(ValueError, "load must be 'grains'"):
            model.set_wall_servo("piston", gain=0.1, max_speed=0.05, target_force=0.26, load="water")
        with self.assertRaisesRegex(ValueError, "wall 'floor' does not"):
            model.set_wall_servo("floor", gain=0.1, max_speed=0.05, target_force=0.26, load="total")


class PumpingWell(unittest.TestCase):
    """examples/fluid_cases/pumping_well.toml's well, read and shut off from Python."""

    EXAMPLE = os.path.join(SOURCE, "examples", "fluid_cases", "pumping_well.toml")

    def test_a_well_shut_off_from_python_is_the_stages_and_recovers_as_theis_says(self):
        by_stage = darcydem.load(self.EXAMPLE)
        by_python = darcydem.load(self.EXAMPLE)
        sources = by_python.fluid.sources
        self.assertEqual([s["name"] for s in sources], ["well"])
        self.assertEqual(sources[0]["cell"], [20, 20])
        self.assertEqual(sources[0]["position"], [0.205, 0.205])
        self.assertFalse(sources[0]["drain"])  # a plain source, always "open"
        self.assertTrue(sources[0]["open"])
        for model in (by_stage, by_python):
            model.step(1000)  # 0.1 s of pumping
        self.assertEqual(by_python.fluid.sources[0]["inflow"], -2e-6)
        by_stage.apply_stage("recover")
        by_python.set_fluid_source("well", inflow=0.0)
        for model in (by_stage, by_python):
            model.step(1000)
        self.assertEqual(by_python.fluid.sources[0]["inflow"], 0.0)
        # The same shut-off at the same step: bit for bit.
        self.assertTrue(np.array_equal(by_stage.fluid.pressure, by_python.fluid.pressure))
        # Theis, shut off at 0.1 s, 5 cm from the well at 0.2 s (c = 0.01
        # m^2/s): -Q mu / (4 pi kappa) (E1(r^2 / 4 c t) - E1(r^2 / 4 c (t - 0.1))),
        # within the lattice's correction at 5 cells and 2e-3 of the scale
        # (as the C++ test APumpingTestDrawsDownAndRecoversAsTheisSays).
        scale = 2e-6 * 1e-3 / (4.0 * math.pi * 1e-10)
        expected = pumping_plot.theis(0.05, 0.2, 2e-6, 1e-3, 1e-10, 0.01, shut_off=0.1)
        u = by_python.fluid.pressure_at([0.255, 0.205])
        self.assertAlmostEqual(u, expected, delta=scale * (1.0 / 150.0 + 2e-3))
        # The water balance, the well's 2e-7 m^2 out in it: to round-off.
        balance = by_python.fluid.balance
        self.assertLess(abs(balance["imbalance"]), 1e-9 * balance["gross"])
        self.assertGreater(balance["gross"], 2e-7)

    def test_a_wells_bore_is_below_its_cell_by_its_inflow_over_its_well_index(self):
        # The example's well given a radius of 1 mm (its cell's equivalent
        # radius is 0.1985 x 1 cm): pumping Q out for 0.1 s, its bore sits
        # below its cell by Q mu / (2 pi kappa) ln(r_e / r_w) = 2 ln(1.985)
        # of Q mu / (4 pi kappa) (the well index's closed form, by hand).
        model = darcydem.load(self.EXAMPLE, set={"fluid.source.well.radius": 1e-3})
        model.step(1000)
        well = model.fluid.sources[0]
        self.assertEqual(well["radius"], 1e-3)
        scale = 2e-6 * 1e-3 / (4.0 * math.pi * 1e-10)
        r_e = 0.01 * math.exp(-0.5772156649015329) / (2.0 * math.sqrt(2.0))
        cell = model.fluid.pressure[20, 20]
        self.assertAlmostEqual(well["well_pressure"] - cell, -2.0 * scale * math.log(r_e / 1e-3),
                               delta=1e-12 * scale)
        self.assertAlmostEqual(well["well_index"], 2.0 * math.pi * 1e-10 / (1e-3 * math.log(r_e / 1e-3)),
                               delta=1e-12 * well["well_index"])
        self.assertEqual(darcydem.load(self.EXAMPLE).fluid.sources[0]["well_index"], 0.0)  # no radius

    def test_bad_sources_are_refused(self):
        model = darcydem.load(self.EXAMPLE)
        with self.assertRaisesRegex(ValueError, r'no \[\[fluid.source\]\] named "wel" \(the scene has: well\)'):
            model.set_fluid_source("wel", inflow=0.0)
        with self.assertRaisesRegex(ValueError, "the inflow must be a number or"):
            model.set_fluid_source("well", inflow="off")
        with self.assertRaisesRegex(ValueError, "the inflow's times and values must have the same"):
            model.set_fluid_source("well", inflow={"times": [0.0, 1.0], "values": [0.0]})
        with self.assertRaisesRegex(ValueError, "the inflow must be finite, got nan"):
            model.set_fluid_source("well", inflow=float("nan"))
        with self.assertRaisesRegex(ValueError, "give one of inflow"):
            model.set_fluid_source("well", inflow=0.0, pressure=1.0)
        with self.assertRaisesRegex(ValueError, "give one of inflow"):
            model.set_fluid_source("well")
        # A pressure held in the well's cell (a well at a set head): exact
        # there, and the water it takes comes in by the sides.
        held = darcydem.load(self.EXAMPLE)
        held.set_fluid_source("well", pressure=-5.0)
        held.step(1000)
        self.assertEqual(held.fluid.sources[0]["type"], "pressure")
        self.assertAlmostEqual(held.fluid.pressure[20, 20], -5.0, delta=1e-10)
        self.assertLess(held.fluid.sources[0]["inflow"], 0.0)  # it pumps
        balance = held.fluid.balance
        self.assertLess(abs(balance["imbalance"]), 1e-9 * balance["gross"])
        # A ramp is taken from now.
        model.step(10)
        model.set_fluid_source("well", inflow={"times": [0.0, 0.01], "values": [0.0, 1e-6]})
        model.step(50)  # 0.005 s into the ramp: half of it
        self.assertAlmostEqual(model.fluid.sources[0]["inflow"], 5e-7, delta=1e-15)



class ScreenedWell(unittest.TestCase):
    """examples/fluid_cases/screened_well.toml: a well screened through some cells of a 3D aquifer."""

    EXAMPLE = os.path.join(SOURCE, "examples", "fluid_cases", "screened_well.toml")

    def test_a_screen_through_the_whole_aquifer_is_theiss_well_in_every_layer(self):
        # Screened from floor to roof, between no-flow ones: the flow is
        # horizontal and alike in the 8 layers, so each cell takes Q / 8
        # (to the solver's tolerance, by symmetry), and 5 cm out the
        # drawdown is Theis's for Q / H per metre (c = 0.01 m^2/s), within
        # the lattice's correction at 5 cells and 2e-3 of the scale, as the
        # 2D pumping test's.
        model = darcydem.load(self.EXAMPLE, set={"fluid.source.well.screen": [0.0, 0.08]})
        model.step(1000)  # 0.1 s of pumping
        well = model.fluid.sources[0]
        self.assertEqual(well["screen"], [0.0, 0.08])
        self.assertEqual(well["position"], [0.155, 0.155, 0.04])
        cells = well["screen_cells"]
        self.assertEqual([c["cell"] for c in cells], [[15, 15, k] for k in range(8)])
        q = -4e-6
        self.assertEqual(well["inflow"], q)
        for c in cells:
            self.assertAlmostEqual(c["inflow"], q / 8, delta=1e-9 * -q)
        per_metre = q / 0.08
        scale = -per_metre * 1e-3 / (4.0 * math.pi * 1e-10)
        expected = pumping_plot.theis(0.05, 0.1, -per_metre, 1e-3, 1e-10, 0.01)
        for z in (0.005, 0.045, 0.075):
            self.assertAlmostEqual(model.fluid.pressure_at([0.205, 0.155, z]), expected,
                                   delta=scale * (1.0 / 150.0 + 2e-3))

    def test_a_partial_screen_draws_most_at_its_end(self):
        # Screened over the lower half: the cells' shares add up to the
        # well's inflow, and the top cell of the screen, which the water
        # also reaches from the unscreened aquifer above, draws more than
        # the one below it (per metre of screen: the cells are alike).
        model = darcydem.load(self.EXAMPLE)
        model.step(500)
        cells = model.fluid.sources[0]["screen_cells"]
        self.assertEqual(len(cells), 4)
        self.assertAlmostEqual(sum(c["inflow"] for c in cells), -4e-6, delta=1e-9 * 4e-6)
        self.assertLess(cells[3]["inflow"], cells[2]["inflow"])
        self.assertLess(cells[3]["inflow"], cells[1]["inflow"])
        self.assertAlmostEqual(model.fluid.sources[0]["well_index"], sum(c["well_index"] for c in cells),
                               delta=1e-12 * model.fluid.sources[0]["well_index"])
        self.assertIsNone(darcydem.load(PumpingWell.EXAMPLE).fluid.sources[0]["screen"])

class SaveAndLoad(unittest.TestCase):
    """model.save and darcydem.load(scene, checkpoint=...), YADE's O.save and O.load, on the sealed-piston
    column (pore fluid, servo, two stages)."""

    EXAMPLE = os.path.join(SOURCE, "examples", "fluid_cases", "consolidation_sealed_piston.toml")

    def same_state(self, a, b):
        self.assertEqual(a.steps, b.steps)
        self.assertEqual(a.time, b.time)
        np.testing.assert_array_equal(a.positions, b.positions)
        np.testing.assert_array_equal(a.velocities, b.velocities)
        np.testing.assert_array_equal(a.fluid.pressure, b.fluid.pressure)
        self.assertEqual([w["point"] for w in a.walls], [w["point"] for w in b.walls])
        self.assertEqual([w["servo"] for w in a.walls], [w["servo"] for w in b.walls])

    def test_a_saved_model_goes_on_bit_for_bit(self):
        path = os.path.join(tempfile.mkdtemp(), "state.bin")
        model = darcydem.load(self.EXAMPLE)
        model.step(20000)
        model.apply_stage("load")  # the sealed top, the servo on the total load raised to 0.51 N
        model.set_wall_servo("piston", gain=0.1, max_speed=0.05, target_force=0.26, direction=[0.0, -1.0],
                             load="total", cycle={"amplitude": 0.25, "frequency": 1.5, "phase": -90.0})
        model.step(3000)
        model.save(path)
        model.step(4000)
        loaded = darcydem.load(self.EXAMPLE, checkpoint=path)
        self.assertEqual(loaded.steps, 23000)
        loaded.step(4000)
        # The same 4000 steps from the same state, the servo's cycle, the
        # sealed top and the pore water's pressures with it: bit for bit.
        self.same_state(model, loaded)
        # Without the saved state the model starts over and differs.
        fresh = darcydem.load(self.EXAMPLE)
        fresh.step(4000)
        self.assertFalse(np.array_equal(fresh.positions, model.positions))

    def test_an_interrupted_run_goes_on_in_python(self):
        out = os.path.join(tempfile.mkdtemp(), "out")
        summary = darcydem.run(self.EXAMPLE, out=out, stop_at_step=5000)
        self.assertEqual(summary["status"], "interrupted")
        self.assertTrue(summary["checkpoint_written"])
        loaded = darcydem.load(self.EXAMPLE, checkpoint=os.path.join(out, "checkpoint.bin"))
        self.assertGreaterEqual(loaded.steps, 5000)
        # The run's steps are the model's (README: stepping from Python gives
        # the program's run), so a model stepped as far is the same.
        stepped = darcydem.load(self.EXAMPLE)
        stepped.step(loaded.steps)
        self.same_state(stepped, loaded)
        loaded.step(2000)
        stepped.step(2000)
        self.same_state(stepped, loaded)

    def test_what_does_not_fit_is_refused(self):
        folder = tempfile.mkdtemp()
        path = os.path.join(folder, "state.bin")
        model = darcydem.load(self.EXAMPLE)
        model.step(10)
        model.save(path)
        with self.assertRaisesRegex(darcydem.CheckpointError, "no checkpoint to resume from"):
            darcydem.load(self.EXAMPLE, checkpoint=os.path.join(folder, "missing.bin"))
        other = os.path.join(SOURCE, "examples", "fluid_cases", "consolidation_column.toml")
        with self.assertRaisesRegex(darcydem.CheckpointError, "written for a scene with hash"):
            darcydem.load(other, checkpoint=path)
        # A model's save has no output for `darcydem run --resume` to go on with.
        out = os.path.join(folder, "out")
        os.makedirs(out)
        os.replace(path, os.path.join(out, "checkpoint.bin"))
        with open(os.path.join(out, "probes.csv"), "w") as f:
            f.write("time\n")
        with self.assertRaisesRegex(darcydem.CheckpointError, "saved by a Python model"):
            darcydem.run(self.EXAMPLE, out=out, resume=True)


class ShakingTable(unittest.TestCase):
    """examples/dem_cases/vibrated_bed.toml's floor shaken from Python."""

    def settled(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "vibrated_bed.toml"))
        model.step(round(0.3 / model.time_step))
        return model

    def test_an_oscillation_set_from_python_is_the_stages(self):
        shake = {"amplitude": [0.0, 0.0012425], "frequency": 20.0, "phase": -90.0}
        by_stage = self.settled()
        by_stage.apply_stage("shake")
        by_python = self.settled()
        by_python.apply_stage("shake")
        by_python.set_wall_motion("floor", oscillation=False)  # stopped, then started again now
        by_python.set_wall_motion("floor", oscillation=shake)
        start = by_python.time
        steps = 5000
        by_stage.step(steps)
        by_python.step(steps)
        # The same sine from the same start: the same run, bit for bit.
        np.testing.assert_array_equal(by_python.positions, by_stage.positions)
        # The floor is where the sine puts it: A (1 - cos(omega t)), its
        # steps' moves summing to it to round-off (1e-15 m per step).
        omega = 2.0 * math.pi * 20.0
        floor = next(w for w in by_python.walls if w["name"] == "floor")
        self.assertEqual(floor["oscillation"]["amplitude"], (0.0, 0.0012425))
        self.assertEqual(floor["oscillation"]["frequency"], 20.0)
        self.assertAlmostEqual(floor["oscillation"]["phase"], -90.0, delta=1e-12)
        self.assertEqual(floor["oscillation"]["start"], start)
        t = by_python.time - start
        self.assertAlmostEqual(floor["point"][1], 0.0012425 * (1.0 - math.cos(omega * t)), delta=1e-15 * steps)
        # Its velocity the mean over the last step: the sine's slope at the
        # step's middle, A omega sin(omega (t - dt/2)), to (omega dt)^2 / 24
        # (1e-8; 1e-6 of A omega allowed).
        middle = t - 0.5 * by_python.time_step
        self.assertAlmostEqual(floor["velocity"][1], 0.0012425 * omega * math.sin(omega * middle),
                               delta=1e-6 * 0.0012425 * omega)

    def test_bad_oscillations_are_refused(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "vibrated_bed.toml"))
        for bad, message in [
            (True, "or False to stop one"),
            ([0.0, 0.001], "or False to stop one"),
            ({"amplitude": [0.0, 0.001]}, "'frequency': Hz"),
            ({"amplitude": [0.0, 0.001], "frequency": 20.0, "period": 1.0}, "oscillation has no key 'period'"),
            ({"amplitude": [0.0, 0.0], "frequency": 20.0}, "amplitude must be finite and not all zero"),
            ({"amplitude": [0.0, 0.001], "frequency": -1.0}, "frequency must be > 0 Hz"),
            ({"amplitude": [0.0, 0.001], "frequency": 20.0, "phase": math.nan}, "phase must be finite"),
            ({"amplitude": [0.0, 0.0, 0.001], "frequency": 20.0}, "2 numbers expected, 3 given"),
        ]:
            with self.subTest(bad=bad), self.assertRaisesRegex(ValueError, message):
                model.set_wall_motion("floor", oscillation=bad)
        model.set_wall_servo("floor", gain=1e-3, max_speed=0.01, target_force=1.0)
        with self.assertRaisesRegex(ValueError, "has a servo, which sets its place from its load"):
            model.set_wall_motion("floor", oscillation={"amplitude": [0.0, 0.001], "frequency": 20.0})
        model.set_wall_motion("floor", velocity=[0.0, 0.0], oscillation={"amplitude": [0.0, 0.001], "frequency": 5})
        with self.assertRaisesRegex(ValueError, "oscillates, and a servo sets its place"):
            model.set_wall_servo("floor", gain=1e-3, max_speed=0.01, target_force=1.0)


def rows_of(model, numbers):
    """Each particle number's row in the model's per-particle arrays."""
    row = {int(n): k for k, n in enumerate(model.ids)}
    return np.array([row[int(n)] for n in numbers], dtype=int)


def contact_sums(model):
    """The contacts' resultant force and moment about the centre on each
    particle, summed from model.contacts (the force on the second particle
    is the opposite of the first's), with the particles' weight added to
    the force. A wall contact acts on its particle alone."""
    c = model.contacts
    d = model.dimension
    n = model.particle_count
    pair = c["particles"][:, 1] >= 0
    i = rows_of(model, c["particles"][:, 0])
    j = rows_of(model, c["particles"][pair, 1])
    force = np.zeros((n, d))
    np.add.at(force, i, c["force"])
    np.add.at(force, j, -c["force"][pair])
    x = model.positions
    moment = np.zeros(n) if d == 2 else np.zeros((n, 3))
    np.add.at(moment, i, np.cross(c["point"] - x[i], c["force"]))
    np.add.at(moment, j, np.cross(c["point"][pair] - x[j], -c["force"][pair]))
    return force, moment


# 5804 discs in a hexagonal lattice settling between walls: more than the
# 4096 above which the simulation keeps its particles sorted in space, so
# its pairs are not in the order of their numbers.
HEXAGONAL_BED = """[simulation]
dimension = 2
time_step = "auto"

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e4
restitution = 0.5
friction = 0.5

[[wall]]
name = "floor"
point = [0.0, 0.0]
normal = [0.0, 1.0]
material = "sand"

[[wall]]
name = "left"
point = [0.0, 0.0]
normal = [1.0, 0.0]
material = "sand"

[[wall]]
name = "right"
point = [0.08, 0.0]
normal = [-1.0, 0.0]
material = "sand"

[[particles]]
generator = "lattice"
material = "sand"
min = [0.0, 0.0]
max = [0.08, 0.064]
radius = 0.0005
arrangement = "hexagonal"

[[stage]]
name = "settle"
duration = 0.02
gravity = [0.0, -9.81]
"""


class Contacts(unittest.TestCase):
    """model.contacts, forces and torques against statics by hand and
    Newton's laws grain by grain."""

    def test_each_bond_of_the_chain_carries_the_weight_below_it(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "cemented_chain.toml"))
        model.step(round(0.3 / model.time_step))
        c = model.contacts
        # Ten bonds, disc k - 1 to disc k, the lower number first.
        np.testing.assert_array_equal(c["particles"], [[k, k + 1] for k in range(10)])
        np.testing.assert_array_equal(c["wall"], -1)
        self.assertTrue(np.all(c["bonded"]))
        # Bond k (from the top) holds the 10 - k discs below it in tension
        # (a negative normal force), its stretch that over k_n = 1e4 N/m,
        # along the chain's axis (downwards from the upper disc); its
        # point midway between the centres. The chain has come to rest
        # (the same settling as test_bonds_hold_the_chain..., bound 1e-6
        # there): to 1e-6 of the weight.
        mg = 2500.0 * math.pi * 1e-6 * 9.81
        below = 10.0 - np.arange(10)
        np.testing.assert_allclose(c["normal_force"], -below * mg, rtol=0.0, atol=1e-6 * mg)
        np.testing.assert_allclose(c["overlap"], -below * mg / 1e4, rtol=0.0, atol=1e-6 * mg / 1e4)
        np.testing.assert_allclose(c["normal"], np.tile([0.0, -1.0], (10, 1)), atol=1e-12)
        x = model.positions
        np.testing.assert_allclose(c["point"], 0.5 * (x[:-1] + x[1:]), rtol=0.0, atol=1e-12)
        np.testing.assert_allclose(c["shear_force"], 0.0, atol=1e-6 * mg)
        np.testing.assert_array_equal(c["bending_moment"], 0.0)  # a pin: no moment
        # The fixed disc's resultant is the chain's pull on it, its
        # support's reaction: the ten discs' weight, downwards.
        self.assertAlmostEqual(model.forces[0, 1], -10.0 * mg, delta=1e-6 * mg)
        self.assertEqual(model.angular_velocities.shape, (11,))
        self.assertEqual(model.torques.shape, (11,))

    def test_a_sphere_set_sliding_with_backspin_rolls_on_as_by_hand(self):
        # examples/dem_cases/slip_to_roll.toml's sphere (r = 1 mm) on the
        # floor, set from Python to v0 = 0.3 m/s along x with backspin
        # w0 = -100 rad/s about y (its contact point slides at
        # v0 - r w0 = 0.4 m/s). Friction keeps its angular momentum about
        # the contact point, m v + (I / r) w (I = 2/5 m r^2), so it rolls
        # on at (5 v0 + 2 r w0) / 7 = 0.185714 m/s. The same bound as the
        # program's slip-to-roll test (test_single_particle.cpp): 1e-3.
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "slip_to_roll.toml"))
        model.track_energy = True
        model.step(1)
        r, v0, w0 = 1e-3, 0.3, -100.0
        mass = 2500.0 * 4.0 / 3.0 * math.pi * r**3
        inertia = 0.4 * mass * r**2
        before = 0.5 * mass * float(np.sum(model.velocities[0] ** 2)) + 0.5 * inertia * float(
            np.sum(model.angular_velocities[0] ** 2))
        model.set_particle_velocity(0, velocity=[v0, 0.0, 0.0], angular_velocity=[0.0, w0, 0.0])
        np.testing.assert_array_equal(model.velocities[0], [v0, 0.0, 0.0])
        np.testing.assert_array_equal(model.angular_velocities[0], [0.0, w0, 0.0])
        model.step(round(0.1 / model.time_step))
        rolling = (5.0 * v0 + 2.0 * r * w0) / 7.0
        self.assertAlmostEqual(model.velocities[0, 0], rolling, delta=1e-3 * rolling)
        self.assertAlmostEqual(model.angular_velocities[0, 1], rolling / r, delta=1e-3 * rolling / r)
        # The kinetic energy the call gave it is external work, and the
        # budget still closes: without it 'unaccounted' would be that
        # work, 2.8e-7 J. What is left is the round-off of the steps' sums
        # (thousands of steps, each about 1e-16 of the energy; measured
        # 2e-12 of it): below 1e-9 of it.
        e = model.energy()
        given = 0.5 * mass * v0**2 + 0.5 * inertia * w0**2 - before
        self.assertAlmostEqual(e["external_work"], given, delta=1e-12 * given)
        self.assertLess(abs(e["unaccounted"]), 1e-9 * given)

    def test_friction_set_from_python_slows_a_sliding_sphere_as_by_hand(self):
        # slip_to_roll.toml's sphere launched at v0 = 0.2 m/s without spin,
        # its friction lowered from the [[contact]]'s 0.3 to 0.1 from Python:
        # while it slides, friction decelerates it at mu g and spins it up at
        # 5 mu g / (2 r), so it slides until t = 2 v0 / (7 mu g) = 0.0583 s
        # (0.0194 s with 0.3). At t = 0.03 s it still slides, at
        # v0 - mu g t = 0.170570 m/s (with 0.3 it would already roll at
        # 5 v0 / 7 = 0.142857). The normal force swings about m g as the
        # sphere settles on its spring, but its impulse beyond m g t is the
        # sphere's vertical momentum, zero again once it rests: bound 1e-4
        # of v0 (its residual bounce, damped by e = 0.5 over five periods of
        # 6.4 ms). Measured: 2e-12 in the speed, 3.8e-6 in the spin (the
        # tangential spring stretched at the contact).
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "slip_to_roll.toml"))
        self.assertEqual(model.friction(["glass", "glass"]), 0.3)
        model.set_friction(["glass", "glass"], 0.1)
        self.assertEqual(model.friction(["glass", "glass"]), 0.1)
        model.step(round(0.03 / model.time_step))
        g, mu, v0, r = 9.81, 0.1, 0.2, 1e-3
        t = model.time
        self.assertAlmostEqual(model.velocities[0, 0], v0 - mu * g * t, delta=1e-4 * v0)
        self.assertAlmostEqual(model.angular_velocities[0, 1] * r, 2.5 * mu * g * t, delta=1e-4 * v0)
        # Back to the [[contact]]'s 0.3: it rolls on at 5/7 of its speed and
        # spin's balance, (5 v + 2 r w) / 7, as the slip-to-roll test.
        model.set_friction(["glass", "glass"], 0.3)
        rolling = (5.0 * model.velocities[0, 0] + 2.0 * r * model.angular_velocities[0, 1]) / 7.0
        model.step(round(0.05 / model.time_step))
        self.assertAlmostEqual(model.velocities[0, 0], rolling, delta=1e-3 * rolling)

    def test_bad_frictions_are_refused(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "fluid_cases", "undrained_biaxial.toml"))
        for materials, mu, says in (
                (["sand"], 0.1, "must name exactly two materials"),
                (["sand", "clay"], 0.1, "no material 'clay' (the scene's materials: 'sand', 'platen')"),
                (["platen", "platen"], 0.1, "the pair platen / platen has no [[contact]]"),
                (["sand", "platen"], 0.3, "the [[contact]] of sand / platen has no friction"),
                (["sand", "sand"], float("nan"), "friction must be a finite number >= 0, got nan"),
                (["sand", "sand"], -1.0, "friction must be a finite number >= 0, got -1")):
            with self.subTest(materials=materials, friction=mu):
                with self.assertRaisesRegex(ValueError, re.escape(says)):
                    model.set_friction(materials, mu)
        self.assertEqual(model.friction(["sand", "sand"]), 0.02)  # the first stage's, unchanged
        with self.assertRaisesRegex(ValueError, re.escape("friction: no material 'clay'")):
            model.friction(["sand", "clay"])

    def test_a_fixed_grain_set_moving_keeps_its_velocity(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "cemented_chain.toml"))
        top = model.positions[0].copy()
        model.set_particle_velocity(0, velocity=[0.0, 0.01])
        steps = round(0.05 / model.time_step)
        model.step(steps)
        # Driven, not integrated: x0 + v t, to round-off.
        self.assertAlmostEqual(model.positions[0, 1], top[1] + 0.01 * steps * model.time_step, delta=1e-12)
        self.assertEqual(model.velocities[0, 1], 0.01)
        model.set_particle_velocity(3, angular_velocity=2.0)
        self.assertEqual(model.angular_velocities[3], 2.0)

    def test_a_chain_let_go_falls_as_a_body_and_a_grain_fixed_keeps_its_velocity(self):
        # The cemented chain hung from its fixed top disc, then without
        # damping (stage "overload" with gravity set back to g) let go: the
        # eleven discs, bonded, fall with their centre of mass at g (their
        # bonds' forces cancel in pairs): y0 + v0 t - g t^2 / 2, v0 the
        # mean velocity at release (equal discs). Velocity Verlet's free
        # fall is exact, so only round-off is left: 1e-12 m.
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "cemented_chain.toml"))
        model.step(round(0.3 / model.time_step))
        model.apply_stage("overload")
        model.gravity = (0.0, -9.81)
        model.track_energy = True
        np.testing.assert_array_equal(model.fixed, [True] + [False] * 10)
        model.set_particle_fixed(0, False)
        self.assertFalse(model.fixed[0])
        y0 = float(np.mean(model.positions[:, 1]))
        v0 = float(np.mean(model.velocities[:, 1]))
        steps = round(0.05 / model.time_step)
        model.step(steps)
        t = steps * model.time_step
        self.assertAlmostEqual(float(np.mean(model.positions[:, 1])), y0 + v0 * t - 0.5 * 9.81 * t * t, delta=1e-12)
        self.assertEqual(model.broken_bonds, 0)
        # Fixed in flight, the lowest disc keeps its velocity: driven at it.
        v = model.velocities[10].copy()
        x = model.positions[10].copy()
        mass = 2500.0 * math.pi * 1e-6
        kinetic = 0.5 * mass * float(np.sum(v**2)) + 0.25 * mass * 1e-6 * float(model.angular_velocities[10] ** 2)
        model.set_particle_fixed(10)
        model.step(100)
        np.testing.assert_array_equal(model.velocities[10], v)
        np.testing.assert_allclose(model.positions[10], x + 100 * model.time_step * v, rtol=0.0, atol=1e-15)
        # The budget: the top disc let go at rest brought nothing in; the
        # lowest one fixed took its kinetic energy out as external work
        # (to 1e-12 of it), and the rest closes (round-off, 1e-9 of it).
        e = model.energy()
        self.assertAlmostEqual(e["external_work"], -kinetic, delta=1e-12 * kinetic)
        self.assertLess(abs(e["unaccounted"]), 1e-9 * kinetic)
        with self.assertRaisesRegex(ValueError, "set_particle_fixed: there is no particle 12"):
            model.set_particle_fixed(12)

    def test_bad_particle_velocities_are_refused(self):
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "cemented_chain.toml"))
        with self.assertRaisesRegex(ValueError, "there is no particle 11 .*11 particles"):
            model.set_particle_velocity(11, velocity=[0.0, 0.0])
        with self.assertRaisesRegex(ValueError, "there is no particle -1"):
            model.set_particle_velocity(-1, velocity=[0.0, 0.0])
        with self.assertRaisesRegex(ValueError, "give velocity"):
            model.set_particle_velocity(1)
        with self.assertRaisesRegex(ValueError, "2 numbers expected, 3 given"):
            model.set_particle_velocity(1, velocity=[0.0, 0.0, 0.0])
        with self.assertRaisesRegex(ValueError, "a disc turns in the plane"):
            model.set_particle_velocity(1, angular_velocity=[0.0, 0.0, 1.0])
        with self.assertRaisesRegex(ValueError, "velocity must be finite"):
            model.set_particle_velocity(1, velocity=[math.nan, 0.0])
        with self.assertRaisesRegex(ValueError, "angular_velocity must be finite"):
            model.set_particle_velocity(1, angular_velocity=math.inf)
        sphere = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "slip_to_roll.toml"))
        with self.assertRaisesRegex(ValueError, r"a sphere's angular_velocity is a vector"):
            sphere.set_particle_velocity(0, angular_velocity=1.0)
        # Nothing was changed by the calls refused.
        np.testing.assert_array_equal(model.velocities, 0.0)

    def check_newton(self, model, density):
        # Each grain's resultant, as the step applied it, is its contacts'
        # forces plus its weight: the list leaves none out and signs each
        # one right. The same sums in another order: to 1e-12 of the
        # largest contact force (round-off).
        force, moment = contact_sums(model)
        r = model.radii
        volume = 4.0 / 3.0 * np.pi * r**3 if model.dimension == 3 else np.pi * r**2
        force += (density * volume)[:, None] * np.array(model.gravity)
        scale = float(np.max(np.abs(model.contacts["force"])))
        np.testing.assert_allclose(model.forces, force, rtol=0.0, atol=1e-12 * scale)
        return moment, scale

    def test_every_grain_of_a_silo_is_in_balance_with_its_contacts(self):
        # 1400 discs rained into a silo (2D), walls and friction; 0.2 s in,
        # grains still falling onto the heap: the dashpots act too.
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "silo_discharge.toml"))
        model.step(round(0.2 / model.time_step))
        c = model.contacts
        self.assertGreater(len(c["wall"]), 1000)
        self.assertGreater(int(np.sum(c["wall"] >= 0)), 20)
        self.assertGreater(float(np.max(np.abs(c["shear_force"]))), 0.0)
        moment, scale = self.check_newton(model, 2500.0)
        # Without rolling resistance the moment about a grain's centre is
        # its contacts' forces' alone, at their points.
        np.testing.assert_allclose(model.torques, moment, rtol=0.0, atol=1e-12 * scale * 1e-3)
        # Rows sorted by particle number, the lower first in a pair; a
        # wall contact's point lies on its grain's surface less the
        # overlap, along its normal.
        first, second = c["particles"].T
        pair = second >= 0
        self.assertTrue(np.all(first[pair] < second[pair]))
        self.assertTrue(np.all(np.diff(first) >= 0))
        wall = ~pair
        x = model.positions[rows_of(model, first[wall])]
        arm = np.einsum("ij,ij->i", c["point"][wall] - x, c["normal"][wall])
        r = model.radii[rows_of(model, first[wall])]
        np.testing.assert_allclose(arm, r - c["overlap"][wall], rtol=0.0, atol=1e-15)
        names = {w["name"] for w in model.walls}
        self.assertTrue({model.walls[k]["name"] for k in c["wall"][wall]} <= names)

    def test_every_grain_of_a_bed_sorted_in_space_is_in_balance_with_its_contacts(self):
        folder = tempfile.mkdtemp()
        model = darcydem.load(write_scene(folder, HEXAGONAL_BED))
        self.assertGreater(model.particle_count, 4096)
        model.step(round(0.02 / model.time_step))
        moment, scale = self.check_newton(model, 2650.0)
        np.testing.assert_allclose(model.torques, moment, rtol=0.0, atol=1e-12 * scale * 1e-3)
        first, second = model.contacts["particles"].T
        self.assertTrue(np.all(first[second >= 0] < second[second >= 0]))

    def test_every_grain_of_a_periodic_bed_is_in_balance_with_its_contacts(self):
        # 200 spheres settling, periodic along x and y: pairs across the
        # period touch through their nearest images.
        model = darcydem.load(os.path.join(SOURCE, "examples", "dem_cases", "periodic_bed.toml"))
        model.step(round(0.1 / model.time_step))
        c = model.contacts
        self.assertGreater(len(c["wall"]), 100)
        x = model.positions
        first, second = c["particles"].T
        pair = second >= 0
        # Some pair touches across the period: its centres farther apart
        # than its radii reach.
        d = np.linalg.norm(x[rows_of(model, second[pair])] - x[rows_of(model, first[pair])], axis=1)
        self.assertGreater(float(np.max(d)), 0.003)
        self.check_newton(model, 2650.0)


PERIODIC_LATTICE = """
[simulation]
dimension = 2
time_step = "auto"
skin = 0.0002

[periodic]
x = [0.0, 0.01]
y = [0.0, 0.01]

[[material]]
name = "m"
density = 2650.0

[[contact]]
materials = ["m", "m"]
law = "linear"
normal_stiffness = 1e5
restitution = 1.0

[[particles]]
generator = "lattice"
material = "m"
min = [0.0, 0.0]
max = [0.01, 0.01]
radius = 0.0005

[[stage]]
name = "rest"
duration = 0.1
"""


class PeriodicCell(unittest.TestCase):
    """A 10 x 10 square lattice of touching discs (r = 0.5 mm, k_n = 1e5 N/m)
    in a periodic cell, deformed from Python as a stage's periodic_cell."""

    def setUp(self):
        self.folder = tempfile.mkdtemp()
        self.model = darcydem.load(write_scene(self.folder, PERIODIC_LATTICE))

    def test_the_servo_brings_the_lattice_to_the_spacings_of_its_targets(self):
        m = self.model
        self.assertEqual(m.cell["controls"], ["strain_rate", "strain_rate"])
        m.set_cell(x={"stress": 2000.0}, y={"stress": 1000.0}, gain=1e-3, max_strain_rate=0.2)
        m.step(40000)
        cell = m.cell
        # The spacings a, b carrying the targets: k_n (2r - a) = 2000 b and
        # k_n (2r - b) = 1000 a (one spring per disc along each axis over
        # the area a b per disc), a linear system.
        k, d = 1e5, 1e-3
        a_star, b_star = np.linalg.solve([[k, 2000.0], [1000.0, k]], [d * k, d * k])
        # 1e-9: the servo's time constant (about 1e-5 s) is far below the
        # 0.5 s stepped, so what is left is round-off.
        self.assertAlmostEqual(cell["length"][0] / 10 / a_star, 1.0, delta=1e-9)
        self.assertAlmostEqual(cell["length"][1] / 10 / b_star, 1.0, delta=1e-9)
        self.assertAlmostEqual(cell["stress"][0][0], 2000.0, delta=2e-3)
        self.assertAlmostEqual(cell["stress"][1][1], 1000.0, delta=1e-3)
        self.assertEqual(cell["controls"], ["stress", "stress"])
        # Switched to a set rate along x: the cell follows (1 + rate dt)^n.
        before = m.cell["length"][0]
        m.set_cell(x={"strain_rate": -0.01})
        m.step(1000)
        self.assertAlmostEqual(m.cell["length"][0] / (before * (1 - 0.01 * m.time_step) ** 1000), 1.0,
                               delta=1e-12)
        self.assertEqual(m.cell["strain_rate"][0], -0.01)

    def test_the_servo_holds_the_total_stress_with_pore_water(self):
        # The lattice with pore water (2 x 2 cells spanning the period,
        # K_f = 10 kPa), held at a total stress of 1500 Pa along both axes:
        # the springs' stress plus the water's pressure. (A square lattice
        # of frictionless discs has no shear stiffness: the water's small
        # differences of pressure between cells put it out of line, and the
        # water ends up carrying most of the load.)
        fluid = (
            '[fluid]\ndensity = 1000.0\nviscosity = 1.0e-3\nbulk_modulus = 1e4\ndrag = "darcy"\n'
            '[fluid.grid]\norigin = [0.0, 0.0]\ncells = [2, 2]\nsize = [0.005, 0.005]\n'
            '[fluid.permeability]\nmodel = "constant"\nhydraulic_conductivity = [0.1, 0.1]\n\n')
        m = darcydem.load(write_scene(tempfile.mkdtemp(), PERIODIC_LATTICE.replace("[[stage]]", fluid + "[[stage]]")))
        self.assertFalse(m.fluid_drained)
        m.set_cell(x={"stress": 1500.0}, y={"stress": 1500.0}, gain=1e-3, max_strain_rate=0.2, load="total")
        m.step(120000)
        cell = m.cell
        u = float(np.mean(m.fluid.pressure))
        # 1 Pa: the proportional servo lags by its rate / gain (0.1 Pa at
        # the end).
        self.assertAlmostEqual(cell["stress"][0][0] + u, 1500.0, delta=1.0)
        self.assertAlmostEqual(cell["stress"][1][1] + u, 1500.0, delta=1.0)
        self.assertGreater(u, 100.0)
        # The water's pressure is Biot's law over the strain, K_f ln(A_p0 /
        # A_p), A_p the cell's area less the discs'. 1e-3: each backward
        # Euler step adds the square of its pore strain, and the servo
        # swings the cell to and fro (measured: 1.4e-4).
        solid = 100 * np.pi * 5e-4 ** 2
        length = cell["length"]
        biot = 1e4 * np.log((1e-4 - solid) / (length[0] * length[1] - solid))
        self.assertAlmostEqual(u / biot, 1.0, delta=1e-3)
        # Drained from Python: the pressure is released and the contacts
        # take the whole load.
        m.fluid_drained = True
        m.step(60000)
        self.assertTrue(m.fluid_drained)
        self.assertEqual(float(np.max(np.abs(m.fluid.pressure))), 0.0)
        self.assertAlmostEqual(m.cell["stress"][0][0], 1500.0, delta=1.0)
        self.assertAlmostEqual(m.cell["stress"][1][1], 1500.0, delta=1.0)

    def test_bad_motions_are_refused(self):
        m = self.model
        for kwargs, message in [
            ({"load": "total"}, "needs a [fluid]"),
            ({"load": "water"}, "load must be 'grains' or 'total'"),
            ({"x": {"stress": 1.0}}, "gain"),
            ({"x": {"stress": 1.0, "strain_rate": 1.0}}, "must be {'strain_rate'"),
            ({"x": 3.0}, "must be {'strain_rate'"),
            ({"z": {"strain_rate": 1.0}}, "no z axis"),
            ({"x": {"strain_rate": 1e9}}, "below 1e-3 / time step"),
            ({"gain": -1.0}, "gain must be finite and > 0"),
        ]:
            with self.assertRaises(ValueError) as caught:
                m.set_cell(**kwargs)
            self.assertIn(message, str(caught.exception))
        self.assertEqual(m.cell["controls"], ["strain_rate", "strain_rate"])
        self.assertEqual(m.cell["strain_rate"], (0.0, 0.0))
        # A scene that does not repeat along every axis has no cell to deform.
        folder = tempfile.mkdtemp()
        with open(os.path.join(folder, "one.csv"), "w") as f:
            f.write("x,y,z,radius\n0.0,0.0,0.1,0.005\n")
        one = darcydem.load(write_scene(folder, ONE_SPHERE))
        self.assertIsNone(one.cell)
        with self.assertRaises(ValueError) as caught:
            one.set_cell(x={"strain_rate": -0.01})
        self.assertIn("must repeat along every axis", str(caught.exception))


if __name__ == "__main__":
    unittest.main(verbosity=2)
