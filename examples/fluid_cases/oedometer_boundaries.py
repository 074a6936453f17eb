#!/usr/bin/python3
"""Why the 3D oedometer departs from Terzaghi by the 1-3 % it does: its ends.

Terzaghi's column lies between rigid ends. In oedometer.toml the grains'
contacts with the platen and the floor are as soft as their contacts with
each other, so part of the drained settlement S_d is not the packing's
strain but those contacts' compression, at the ends; and the top 0.1 mm of
the bed lies above the grid's drained top. That part settles with the end
it is at: at once at a drained end, last at a sealed one.

This script measures it and predicts its effect, without the coupled run:
1. it steps the drained twin (k x 1000) through the darcydem Python module
   and fits the grains' vertical displacement under the step with a
   quadratic, w(z) = a + b z + c z^2: the packing's strain -dw/dz (its
   bottom is a little stiffer than its top), the floor's contacts -a, the
   platen's contacts the rest of S_d;
2. it solves Terzaghi's equation in 1D by finite differences (160 layers,
   backward Euler) with that packing, the end compliances lumped into the
   end layers' storage and settlement, and the bed above the grid settling
   at once; for the top drained (oedometer.toml) and for the floor drained
   under an impermeable platen (the test's mirror, the grid to 17 mm);
3. it prints how far that model departs from the closed form with a
   uniform m_v = S_d / (H_bed dsigma), the test's expectation: the part of
   the test's errors that the ends explain.

    /usr/bin/python3 examples/fluid_cases/oedometer_boundaries.py build/darcydem

About 25 s (the twin's run). The test's figures, for comparison:
tests/verification/test_oedometer.cpp, docs/VERIFICATION.md.
"""
import os
import sys
import tempfile
import tomllib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_oedometer import SCENE, load_module, scene_constants, write_drained_twin  # noqa: E402

LAYERS = 160      # the 1D model's layers: its own discretisation error is below 0.01 %
TIME_STEP = 2e-5  # s, the 1D model's
FLOOR_PROBE = 0.000525  # m, oedometer.toml's floor_pressure probe: the bottom cells' centres
SEALED_GRID_TOP = 0.017  # m, the test's mirror: 16 layers of 1.0625 mm, past the platen
REPORT_TIMES = (0.005, 0.01, 0.02, 0.03, 0.05, 0.08)  # s after the step


def platen_z(model):
    return next(w["point"][2] for w in model.walls if w["name"] == "platen")


def measure_twin(module, scene):
    """The drained twin's settlement S_d under the load step and how it splits:
    (S_d, the packing's displacement fit w(z) (numpy coefficients), floor
    contacts, platen contacts, H_bed, porosity)."""
    with tempfile.TemporaryDirectory() as folder:
        model = module.load(write_drained_twin(folder))
        rest, load = scene["stage"][0], scene["stage"][1]
        model.step(int(round(rest["duration"] / model.time_step)))
        x0, z0 = model.positions.copy(), platen_z(model)
        porosity = float(np.mean(model.fluid.porosity))
        model.apply_stage(load["name"])
        model.step(int(round(0.05 / model.time_step)))  # the twin is done within 0.03 s
        x1, z1 = model.positions, platen_z(model)
    s_drained = z0 - z1
    w = np.polyfit(x0[:, 2], x1[:, 2] - x0[:, 2], 2)
    floor = -np.polyval(w, 0.0)
    packing = np.polyval(w, 0.0) - np.polyval(w, z0)
    return s_drained, w, floor, s_drained - packing - floor, z0, porosity


def one_d_model(top_drained, grid_top, twin, dsigma, k, k_f, gamma_w):
    """Terzaghi's equation on the water column with the measured ends: times
    and (settlement, pressure at the sealed end's probe) after the step."""
    s_drained, w, floor, platen, bed_height, porosity = twin
    column = grid_top if top_drained else bed_height  # the water the grid holds
    dz = column / LAYERS
    centres = (np.arange(LAYERS) + 0.5) * dz
    compliance = -np.polyval(np.polyder(w), centres) * dz / dsigma  # m/Pa, each layer's skeleton
    compliance[0 if top_drained else -1] += (floor if top_drained else platen) / dsigma  # the sealed end's contacts
    storage = compliance + porosity * dz / k_f
    above_grid = np.polyval(w, grid_top) - np.polyval(w, bed_height) if top_drained else 0.0
    at_once = platen + above_grid if top_drained else floor
    # Backward Euler: storage du/dt = c d2u/dz2, c = k / gamma_w; drained face u = 0
    # half a layer from the last centre, sealed face no flow.
    c = k / gamma_w / dz
    a = np.diag(storage / TIME_STEP + 2.0 * c) - c * (np.eye(LAYERS, k=1) + np.eye(LAYERS, k=-1))
    drained, sealed = (-1, 0) if top_drained else (0, -1)
    a[drained, drained] += c
    a[sealed, sealed] -= c
    step = np.linalg.inv(a) * (storage / TIME_STEP)
    u = compliance / storage * dsigma  # the undrained response
    probe = FLOOR_PROBE if top_drained else column  # the floor probe; the platen's face
    rows = []
    for n in range(1, int(round(0.15 / TIME_STEP)) + 1):
        u = step @ u
        settled = float(np.sum(compliance * (dsigma - u))) + at_once
        rows.append((n * TIME_STEP, settled, float(np.interp(probe, centres, u))))
    return rows


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    module = load_module(sys.argv[1])
    with open(SCENE, "rb") as f:
        scene = tomllib.load(f)
    grid = scene["fluid"]["grid"]
    k, k_f, gamma_w, dsigma = scene_constants(scene)

    print("stepping the drained twin ...", flush=True)
    twin = measure_twin(module, scene)
    s_drained, w, floor, platen, bed_height, porosity = twin
    packing = s_drained - floor - platen
    strain = [-np.polyval(np.polyder(w), z) / (packing / bed_height) for z in (0.0, bed_height)]
    print(f"drained settlement S_d {s_drained * 1e6:.3f} um: the packing {packing * 1e6:.3f} um "
          f"({100 * packing / s_drained:.1f} %), the floor's contacts {floor * 1e6:.3f} um, the platen's "
          f"{platen * 1e6:.3f} um ({100 * platen / s_drained:.1f} %); the packing's strain at its bottom and top "
          f"{strain[0]:.3f} and {strain[1]:.3f} of its mean; bed {bed_height * 1e3:.3f} mm, n {porosity:.4f}")
    m_v = s_drained / (bed_height * dsigma)
    b = m_v / (m_v + porosity / k_f)
    for top_drained, grid_top in ((True, grid["cells"][2] * grid["size"][2]), (False, SEALED_GRID_TOP)):
        terzaghi = {"height": grid_top, "conductivity": k, "compressibility": m_v,
                    "fluid_storage": porosity / k_f, "unit_weight": gamma_w}
        distance = grid_top - FLOOR_PROBE if top_drained else grid_top
        errors = []
        for t, settled, pressure in one_d_model(top_drained, grid_top, twin, dsigma, k, k_f, gamma_w):
            closed_s = s_drained * module.consolidation_degree(t, **terzaghi)
            closed_u = module.consolidation_pressure(t, distance, dsigma, **terzaghi)
            errors.append((t, (settled - closed_s) / s_drained, (pressure - closed_u) / (b * dsigma)))
        late = [e for e in errors if e[0] >= 0.005 - 1e-12]
        rms_s = np.sqrt(np.mean([e[1] ** 2 for e in late]))
        rms_u = np.sqrt(np.mean([e[2] ** 2 for e in late]))
        where = "the floor's pressure" if top_drained else "the platen's water thrust"
        print(f"\n{'drained at the top' if top_drained else 'drained at the floor, impermeable platen'}: the 1D "
              f"model with these ends against the closed form, from 5 ms on: settlement RMS "
              f"{100 * rms_s:.2f} % of S_d, {where} {100 * rms_u:.2f} % of B dsigma")
        for t_report in REPORT_TIMES:
            t, e_s, e_u = min(errors, key=lambda e: abs(e[0] - t_report))
            print(f"  t = {1e3 * t:5.1f} ms: settlement {100 * e_s:+.2f} %, pressure {100 * e_u:+.2f} %")


if __name__ == "__main__":
    main()
