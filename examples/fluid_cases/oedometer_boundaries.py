#!/usr/bin/python3
"""Why the 3D oedometer departs from Terzaghi: its ends and its servo.

Terzaghi's column lies between rigid ends and takes its load step at once.
In oedometer.toml the grains' contacts with the platen and the floor are as
soft as their contacts with each other, so part of the drained settlement
S_d is not the packing's strain but those contacts' compression, at the
ends; and the top 0.1 mm of the bed lies above the grid's drained top. That
part settles with the end it is at: at once at a drained end, last at a
sealed one. And the platen's servo moves it at gain x the load's shortfall,
so while the bed settles the load trails its target by the settlement's
rate / (gain x area): 2.4 % of the step at 5 ms, 0.9 % at 20 ms.

This script measures the ends and predicts the effect of both, without the
coupled run:
1. it steps the drained twin (k x 1000) through the darcydem Python module
   and fits the grains' vertical displacement under the step with a
   quadratic, w(z) = a + b z + c z^2: the packing's strain -dw/dz (its
   bottom is a little stiffer than its top), the floor's contacts -a, the
   platen's contacts the rest of S_d;
2. it solves Terzaghi's equation in 1D by finite differences (160 layers,
   backward Euler) with that packing, the end compliances lumped into the
   end layers' storage and settlement, the bed above the grid settling
   with the load, and the load either stepped at once or driven by the
   servo; for the top drained (oedometer.toml) and for the floor drained
   under an impermeable platen (the test's mirror, the grid to 17 mm);
3. it prints how far that model departs from the closed form with a
   uniform m_v = S_d / (H_bed dsigma), the test's expectation: the part of
   the test's errors that the ends and the servo explain.

    /usr/bin/python3 examples/fluid_cases/oedometer_boundaries.py build/darcydem

About 25 s (the twin's run). The test's figures, for comparison:
tests/verification/test_oedometer.cpp, docs/VERIFICATION.md.
"""
import math
import os
import sys
import tempfile
import tomllib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_oedometer import SCENE, load_module, platen_area, scene_constants, write_drained_twin  # noqa: E402

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


def one_d_model(top_drained, grid_top, twin, dsigma, k, k_f, gamma_w, servo):
    """Terzaghi's equation on the water column with the measured ends and
    the servo's lag: per time after the step, (time, settlement, pressure
    at the sealed end's probe, load). `servo` is the servo's gain times the platen's
    area (m/s per Pa): the platen moves at that times the load's shortfall,
    so the load trails its target by the settlement's rate / servo."""
    s_drained, w, floor, platen, bed_height, porosity = twin
    column = grid_top if top_drained else bed_height  # the water the grid holds
    dz = column / LAYERS
    centres = (np.arange(LAYERS) + 0.5) * dz
    compliance = -np.polyval(np.polyder(w), centres) * dz / dsigma  # m/Pa, each layer's skeleton
    compliance[0 if top_drained else -1] += (floor if top_drained else platen) / dsigma  # the sealed end's contacts
    storage = compliance + porosity * dz / k_f
    above_grid = np.polyval(w, grid_top) - np.polyval(w, bed_height) if top_drained else 0.0
    at_once = (platen + above_grid if top_drained else floor) / dsigma  # m/Pa, settling with the load
    # Backward Euler in the layers' pressures u and the load sigma (from 0):
    #   storage du/dt = compliance dsigma/dt + c (u_up - 2 u + u_down),
    #   c = k / gamma_w / dz, the drained face u = 0 half a layer beyond the
    #   last centre, the sealed face no flow;
    #   sigma = dsigma - dS/dt / servo, S = sum compliance (sigma - u) + at_once sigma.
    c = k / gamma_w / dz
    n = LAYERS
    drained, sealed = (n - 1, 0) if top_drained else (0, n - 1)
    a = np.zeros((n + 1, n + 1))
    a[:n, :n] = np.diag(storage / TIME_STEP + 2.0 * c) - c * (np.eye(n, k=1) + np.eye(n, k=-1))
    a[drained, drained] += c
    a[sealed, sealed] -= c
    a[:n, n] = -compliance / TIME_STEP
    a[n, :n] = -compliance / (TIME_STEP * servo)
    a[n, n] = 1.0 + (np.sum(compliance) + at_once) / (TIME_STEP * servo)
    inverse = np.linalg.inv(a)
    u, sigma = np.zeros(n), 0.0
    probe = FLOOR_PROBE if top_drained else column  # the floor probe; the platen's face
    rows = []
    for step in range(1, int(round(0.15 / TIME_STEP)) + 1):
        settled = float(np.sum(compliance * (sigma - u))) + at_once * sigma
        rhs = np.concatenate([storage / TIME_STEP * u - compliance / TIME_STEP * sigma,
                              [dsigma + settled / (TIME_STEP * servo)]])
        x = inverse @ rhs
        u, sigma = x[:n], x[n]
        settled = float(np.sum(compliance * (sigma - u))) + at_once * sigma
        rows.append((step * TIME_STEP, settled, float(np.interp(probe, centres, u)), sigma))
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
    servo = scene["stage"][1]["walls"]["platen"]["servo"]["gain"] * platen_area(scene)  # m/s per Pa
    for top_drained, grid_top in ((True, grid["cells"][2] * grid["size"][2]), (False, SEALED_GRID_TOP)):
        terzaghi = {"height": grid_top, "conductivity": k, "compressibility": m_v,
                    "fluid_storage": porosity / k_f, "unit_weight": gamma_w}
        distance = grid_top - FLOOR_PROBE if top_drained else grid_top

        def errors_of(rows):
            out = []
            for t, settled, pressure, load in rows:
                closed_s = s_drained * module.consolidation_degree(t, **terzaghi)
                closed_u = module.consolidation_pressure(t, distance, dsigma, **terzaghi)
                out.append((t, (settled - closed_s) / s_drained, (pressure - closed_u) / (b * dsigma),
                            1.0 - load / dsigma))
            return out

        models = [errors_of(one_d_model(top_drained, grid_top, twin, dsigma, k, k_f, gamma_w, lag))
                  for lag in (math.inf, servo)]
        where = "the floor's pressure" if top_drained else "the platen's water thrust"
        print(f"\n{'drained at the top' if top_drained else 'drained at the floor, impermeable platen'}: the 1D "
              f"model against the closed form (settlement in % of S_d, {where} in % of B dsigma)")
        for name, errors in zip(("with these ends, the step at once", "with these ends and the servo's lag"),
                                models):
            late = [e for e in errors if e[0] >= 0.005 - 1e-12]
            rms_s = np.sqrt(np.mean([e[1] ** 2 for e in late]))
            rms_u = np.sqrt(np.mean([e[2] ** 2 for e in late]))
            print(f"  {name}: RMS from 5 ms on {100 * rms_s:.2f} % and {100 * rms_u:.2f} %")
        for t_report in REPORT_TIMES:
            at_once, lagging = (min(e, key=lambda r: abs(r[0] - t_report)) for e in models)
            print(f"  t = {1e3 * at_once[0]:5.1f} ms: settlement {100 * at_once[1]:+.2f} % / {100 * lagging[1]:+.2f} %, "
                  f"pressure {100 * at_once[2]:+.2f} % / {100 * lagging[2]:+.2f} % (the load "
                  f"{100 * lagging[3]:.2f} % short)")

if __name__ == "__main__":
    main()
