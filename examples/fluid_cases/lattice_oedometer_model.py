#!/usr/bin/python3
"""Why the cubic-lattice oedometer departs from Terzaghi: its ends, its
servo and its grains' inertia.

oedometer_cubic_lattice.toml is the simplest 3D skeleton: chains of
spheres on linear contacts, so its drained settlement is known by hand.
Its floor pressure still runs 1.7 % of B dsigma above Terzaghi's closed
form at 10 ms. This script takes that apart with a quasi-static 1D model
of the lattice as the grid sees it, fed with the load a run measured:
- the chain's 17 contacts (floor, 15 between spheres, platen), each
  compressed by (sigma - u)/k_n over its column's area, u interpolated
  between the cell centres (flat at the sealed floor, zero at the drained
  top);
- each cell's solid velocity the mean of its spheres', a face's the mean of
  its two cells', the drained top's that of the cell below it (as
  PoreFluid carries the pore water with the skeleton); storage n h / K_f,
  Darcy between centres, backward Euler;
- the load: the platen's measured force (its servo), or a step at once.
The model has no inertia, like Terzaghi. So with the step at once it
gives the ends' share (the floor's contact settles last, the platen's at
once: 2 of the 17), with the measured load the ends' and the servo's, and
the run less the model is the grains' inertia: the step reaches the floor
as a compression wave that rings for a few ms.

It runs two variants of the scene (about a minute):
1. the scene as it is, its probes every 20 us, the load stage cut to 51 ms;
2. its grains 100 times lighter, loaded from rest (no gravity, the servo
   from 0 to 0.036 N; the chains are linear from touch, so S_d is the
   same), as tests/verification/test_oedometer.cpp runs it.

    /usr/bin/python3 examples/fluid_cases/lattice_oedometer_model.py build/darcydem

It prints, at a few times after the step, the floor cell's pressure less
the closed form's (% of B dsigma) for the model with the step at once,
the model with the run's load, and the run. docs/VERIFICATION.md has the
figures.
"""
import math
import os
import subprocess
import sys
import tempfile
import tomllib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_oedometer import load_module, platen_area, probes  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "oedometer_cubic_lattice.toml")
TIME_STEP = 2e-6  # s, the model's
REPORT_TIMES = (0.003, 0.005, 0.0075, 0.01, 0.015, 0.02, 0.03, 0.05)  # s after the step
REST_STAGE = ("duration = 0.25\ngravity = [0.0, 0.0, -9.80665]\nlocal_damping = 0.7\n[stage.walls.platen]\n"
              "servo = { target_force = 0.036, gain = 1.0, max_speed = 0.05 }")
VARIANTS = {
    "as it is": [("probe_interval = 0.0005", "probe_interval = 0.00002"),
                 ("name = \"load\"\nduration = 0.15", "name = \"load\"\nduration = 0.051")],
    "grains 100 x lighter, from rest": [
        ("density = 2650.0", "density = 26.5"), (REST_STAGE, "duration = 1e-5"),
        ("target_force = 0.072", "target_force = 0.036"),
        ("name = \"load\"\nduration = 0.15", "name = \"load\"\nduration = 0.051"),
        ("probe_interval = 0.0005", "probe_interval = 0.00002")],
}


def lattice(scene):
    """The chain's geometry and the constants: (spheres per column, contact
    pitch, cells along z, cell height, column area, k_n, K_f, k, gamma_w)."""
    radius = scene["particles"][0]["radius"]
    pitch = 2.0 * radius
    cells, h = scene["fluid"]["grid"]["cells"][2], scene["fluid"]["grid"]["size"][2]
    spheres = round(cells * h / pitch)
    if abs(h / pitch - round(h / pitch)) > 1e-9:
        sys.exit("the model needs cells a whole number of spheres high (faces through contacts)")
    k_n = scene["contact"][0]["normal_stiffness"]
    fluid = scene["fluid"]
    gamma_w = fluid["density"] * 9.80665
    k = fluid["permeability"]["hydraulic_conductivity"][2]
    return spheres, pitch, cells, h, pitch * pitch, k_n, fluid["bulk_modulus"], k, gamma_w


def quasi_static_model(scene, load_of, times):
    """The floor cell's pressure (Pa) at `times` after the step, the load
    increment (Pa) at time t being load_of(t)."""
    spheres, pitch, cells, h, column, k_n, k_f, k, gamma_w = lattice(scene)
    porosity = 1.0 - math.pi / 6.0
    height = cells * h
    centres = (np.arange(cells) + 0.5) * h

    def weights(z):  # u at z from the cell pressures
        w = np.zeros(cells)
        if z <= centres[0]:
            w[0] = 1.0
        elif z >= centres[-1]:
            w[-1] = 1.0 - (z - centres[-1]) / (height - centres[-1])  # to 0 at the drained top
        else:
            i = int((z - centres[0]) // h)
            f = (z - centres[i]) / h
            w[i], w[i + 1] = 1.0 - f, f
        return w

    # Contact c at z = c pitch compresses by column (sigma - u(z_c)) / k_n;
    # sphere s sits on contacts 0..s: its displacement -sum of them.
    at_contacts = np.array([weights(c * pitch) for c in range(spheres + 1)])
    below = np.tril(np.ones((spheres, spheres + 1)))
    per_cell = spheres // cells
    cell_mean = np.zeros((cells, spheres))
    for j in range(cells):
        cell_mean[j, j * per_cell:(j + 1) * per_cell] = 1.0 / per_cell
    face = np.zeros((cells + 1, cells))  # the faces' solid velocity from the cells'
    for f in range(1, cells):
        face[f, f - 1] = face[f, f] = 0.5
    face[cells, cells - 1] = 1.0  # the drained top: the cell below it
    divergence = np.zeros((cells, cells + 1))
    for j in range(cells):
        divergence[j, j], divergence[j, j + 1] = -1.0, 1.0
    compliance = column / k_n
    skeleton = divergence @ face @ cell_mean @ below  # cells' water out per unit contact compression
    of_sigma = -compliance * skeleton @ np.ones(spheres + 1)
    of_u = compliance * skeleton @ at_contacts
    storage = porosity * h / k_f
    g = k / gamma_w / h
    darcy = np.diag(np.full(cells, 2.0 * g)) - g * (np.eye(cells, k=1) + np.eye(cells, k=-1))
    darcy[0, 0] -= g  # the sealed floor: one neighbour
    darcy[-1, -1] += g  # the drained top: one neighbour and the half cell to u = 0
    left = storage * np.eye(cells) + of_u
    inverse = np.linalg.inv(left / TIME_STEP + darcy)
    u, sigma, t, out = np.zeros(cells), 0.0, 0.0, []
    pending = list(times)
    while pending:
        t += TIME_STEP
        s = load_of(t)
        u = inverse @ (left @ u / TIME_STEP - of_sigma * (s - sigma) / TIME_STEP)
        sigma = s
        if t >= pending[0] - 1e-12:
            out.append(u[0])
            pending.pop(0)
    return out


def run_variant(exe, swaps, folder):
    with open(SCENE) as f:
        text = f.read()
    for old, new in swaps:
        if text.count(old) != 1:
            sys.exit(f"{SCENE}: expected one '{old[:40]}'")
        text = text.replace(old, new)
    path = os.path.join(folder, "scene.toml")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(folder, "out")
    with open(os.path.join(folder, "run.log"), "w") as log:
        subprocess.run([exe, "run", path, "-o", out], check=True, stdout=log, stderr=subprocess.STDOUT)
    with open(path, "rb") as f:
        return tomllib.load(f), probes(out)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    exe = sys.argv[1]
    module = load_module(exe)
    for name, swaps in VARIANTS.items():
        print(f"running the lattice, {name} ...", flush=True)
        with tempfile.TemporaryDirectory() as folder:
            scene, pr = run_variant(exe, swaps, folder)
        spheres, pitch, cells, h, column, k_n, k_f, k, gamma_w = lattice(scene)
        area = platen_area(scene)
        t = np.array(pr["time"])
        start = scene["stage"][0]["duration"]
        step = int(np.argmin(np.abs(t - start)))
        before = pr["platen_load"][step] / area
        after = scene["stage"][1]["walls"]["platen"]["servo"]["target_force"] / area
        dsigma = after - before
        s_drained = (spheres + 1) * dsigma * column / k_n
        height = cells * h
        m_v = s_drained / (pr["platen_z"][step] * dsigma)
        porosity = pr["porosity"][step]
        b = m_v / (m_v + porosity / k_f)
        terzaghi = {"height": height, "conductivity": k, "compressibility": m_v,
                    "fluid_storage": porosity / k_f, "unit_weight": gamma_w}
        after_step = t[step:] - t[step]
        measured = np.array(pr["platen_load"][step:]) / area - before

        def load_of(time):
            return float(np.interp(time, after_step, measured))

        at_once = quasi_static_model(scene, lambda time: dsigma, REPORT_TIMES)
        with_load = quasi_static_model(scene, load_of, REPORT_TIMES)
        print(f"  S_d {s_drained * 1e6:.3f} um by hand, B {b:.4f}; the floor cell's pressure less Terzaghi's, "
              "% of B dsigma:")
        print("   t (ms)  model, step at once  model, the run's load   the run  (the run less the model)")
        for time, m0, m1 in zip(REPORT_TIMES, at_once, with_load):
            closed = module.consolidation_pressure(time, height - 0.5 * h, dsigma, **terzaghi)
            j = step + int(np.argmin(np.abs(after_step - time)))
            run = pr["u_0"][j]
            scale = 100.0 / (b * dsigma)
            print(f"  {1e3 * time:7.1f}  {scale * (m0 - closed):+19.2f}  {scale * (m1 - closed):+21.2f}"
                  f"  {scale * (run - closed):+8.2f}  ({scale * (run - m1):+.2f})")


if __name__ == "__main__":
    main()
