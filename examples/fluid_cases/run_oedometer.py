#!/usr/bin/python3
"""The 3D oedometer against Terzaghi, as tests/verification/test_oedometer.cpp
checks it, with plots. Runs oedometer.toml and its drained twin (the same
scene with a permeability 1000 times larger, so that the water leaves at
once and the settlement is the skeleton's alone), takes m_v from the twin,
and compares the coupled run with Terzaghi's closed form (storage m_v +
n/K_f, B = m_v / (m_v + n/K_f)), taken from the darcydem Python module built
next to the program (the tests' closed forms, analysis/seepage_analytic.hpp).

    /usr/bin/python3 examples/fluid_cases/run_oedometer.py build/darcydem out/oedometer

Writes OUT/coupled/ and OUT/drained/ (the runs), OUT/oedometer.png
(settlement and floor pressure against time; pressure isochrones) and
prints the errors. About half a minute on 2 cores (the runs' logs:
OUT/coupled.log, OUT/drained.log). Why it departs from Terzaghi by the
1-3 % it does: oedometer_boundaries.py.
"""
import csv
import math
import os
import subprocess
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from darcydem_module import load_module  # noqa: E402
SCENE = os.path.join(HERE, "oedometer.toml")
GAMMA_W_G = 9.80665  # standard gravity, m/s^2


def probes(out):
    with open(os.path.join(out, "probes.csv")) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def platen_area(scene):
    """The platen's area, m^2: the box's floor between its side walls."""
    walls = {w["name"]: w for w in scene["wall"]}
    return walls["x_high"]["point"][0] * walls["y_high"]["point"][1]


def scene_constants(scene):
    """From oedometer.toml: k (m/s, vertical), K_f (Pa), gamma_w (N/m^3) and
    the load step dsigma (Pa), the servo's rise from the rest stage to the
    load stage over the box's floor."""
    fluid = scene["fluid"]
    area = platen_area(scene)
    rest, load = scene["stage"][0], scene["stage"][1]
    dsigma = (load["walls"]["platen"]["servo"]["target_force"] -
              rest["walls"]["platen"]["servo"]["target_force"]) / area
    return (fluid["permeability"]["hydraulic_conductivity"][2], fluid["bulk_modulus"],
            fluid["density"] * GAMMA_W_G, dsigma)


def write_drained_twin(folder):
    """oedometer.toml with k 1000 times larger (the water leaves at once),
    written to FOLDER/oedometer_drained.toml; its path."""
    text = open(SCENE).read()
    k_given = "hydraulic_conductivity = [2e-4, 2e-4, 2e-4]"
    if k_given not in text:
        sys.exit(f"{SCENE}: no '{k_given}' to make the drained twin from")
    twin = os.path.join(folder, "oedometer_drained.toml")
    with open(twin, "w") as f:
        bed = os.path.join(HERE, "oedometer_bed.csv")
        f.write(text.replace(k_given, "hydraulic_conductivity = [0.2, 0.2, 0.2]").replace(
            'file = "oedometer_bed.csv"', f'file = "{bed}"'))
    return twin


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    darcydem, out = sys.argv[1], sys.argv[2]
    if not (os.path.isfile(darcydem) and os.access(darcydem, os.X_OK)):
        sys.exit(f"{darcydem}: not an executable darcydem (build it with scripts/build.sh)")
    module = load_module(darcydem)
    with open(SCENE, "rb") as f:
        scene = tomllib.load(f)
    os.makedirs(out, exist_ok=True)
    twin = write_drained_twin(out)
    # The two runs side by side, a thread each (850 grains gain little from two).
    print("running the coupled scene and its drained twin ...", flush=True)
    runs = []
    for name, path in (("coupled", SCENE), ("drained", twin)):
        log = open(os.path.join(out, f"{name}.log"), "w")
        runs.append((name, log, subprocess.Popen(
            [darcydem, "run", path, "-o", os.path.join(out, name), "--force", "-j", "1"], stdout=log,
            stderr=subprocess.STDOUT)))
    for name, log, run in runs:
        if run.wait() != 0:
            sys.exit(f"the {name} run failed: see {log.name}")
        log.close()

    grid = scene["fluid"]["grid"]
    height = grid["cells"][2] * grid["size"][2]
    k, k_f, gamma_w, dsigma = scene_constants(scene)
    t0_target = scene["stage"][0]["duration"]

    c, d = probes(os.path.join(out, "coupled")), probes(os.path.join(out, "drained"))
    # The row of the step: the one nearest the load stage's start (the stage
    # ends on a whole time step, within one of it; a row is written there).
    def step_row(p):
        return min(range(len(p["time"])), key=lambda i: abs(p["time"][i] - t0_target))
    i0, i0_drained = step_row(c), step_row(d)
    t0, z0 = c["time"][i0], c["platen_z"][i0]
    s_drained = d["platen_z"][i0_drained] - d["platen_z"][-1]
    porosity = c["porosity"][i0]
    m_v = s_drained / (z0 * dsigma)
    storage = porosity / k_f
    b = m_v / (m_v + storage)
    c_v = k / (gamma_w * (m_v + storage))
    print(f"drained settlement {s_drained * 1e6:.3f} um: m_v {m_v:.4e} 1/Pa; n {porosity:.4f}, "
          f"B {b:.4f}, c_v {c_v:.4e} m^2/s, t_c = H^2/c_v {height * height / c_v:.4f} s")

    rows = [i for i in range(i0 + 1, len(c["time"])) if c["time"][i] > t0]  # the step's row is written twice
    times = [c["time"][i] - t0 for i in rows]
    settled = [(z0 - c["platen_z"][i]) * 1e6 for i in rows]
    floor = [c["floor_pressure"][i] for i in rows]
    terzaghi = {"height": height, "conductivity": k, "compressibility": m_v, "fluid_storage": storage,
                "unit_weight": gamma_w}
    floor_distance = height - 0.5 * grid["size"][2]  # from the drained top
    closed_s = [s_drained * module.consolidation_degree(t, **terzaghi) * 1e6 for t in times]
    closed_u = [module.consolidation_pressure(t, floor_distance, dsigma, **terzaghi) for t in times]
    # From 5 ms on, as the test: before, the servo brings the load up and
    # the compression wave crosses the bed, which Terzaghi leaves out.
    late = [i for i, t in enumerate(times) if t >= 0.005]
    rms_s = math.sqrt(sum((settled[i] - closed_s[i]) ** 2 for i in late) / len(late)) / (s_drained * 1e6)
    rms_u = math.sqrt(sum((floor[i] - closed_u[i]) ** 2 for i in late) / len(late)) / (b * dsigma)
    print(f"from 5 ms on: RMS settlement error {100 * rms_s:.2f} % of S_d; floor pressure {100 * rms_u:.2f} % "
          f"of B dsigma")

    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    ax[0].plot(times, settled, label="darcydem")
    ax[0].plot(times, closed_s, "k--", label="Terzaghi, m_v of the drained twin")
    ax[0].set_xlabel("time since the load step (s)")
    ax[0].set_ylabel("settlement of the platen (um)")
    ax[1].plot(times, floor, label="darcydem")
    ax[1].plot(times, closed_u, "k--", label="Terzaghi")
    ax[1].set_xlabel("time since the load step (s)")
    ax[1].set_ylabel("excess pressure at the floor's cells (Pa)")
    for a in ax[:2]:
        a.axvline(0.005, color="0.6", linewidth=0.8, linestyle=":", label="errors measured from here")
    ax[0].legend()
    ax[1].legend()
    layers = grid["cells"][2]
    for j, t_plot in enumerate((0.005, 0.01, 0.02, 0.05, 0.1)):
        row = min(range(len(times)), key=lambda i: abs(times[i] - t_plot))
        z = [(layers - 1 - n + 0.5) * grid["size"][2] for n in range(layers)]  # depth of u_n below the top
        u = [c[f"u_{n}"][rows[row]] for n in range(layers)]
        colour = f"C{j}"
        ax[2].plot(u, [x * 1e3 for x in z], "o", color=colour, label=f"t = {t_plot} s")
        fine = [height * i / 100 for i in range(101)]
        ax[2].plot([module.consolidation_pressure(times[row], x, dsigma, **terzaghi) for x in fine],
                   [x * 1e3 for x in fine], "-", color=colour)
    ax[2].invert_yaxis()
    ax[2].set_xlabel("excess pore pressure (Pa)")
    ax[2].set_ylabel("depth below the drained top (mm)")
    ax[2].set_title("points: darcydem; lines: Terzaghi")
    ax[2].legend(fontsize=8)
    fig.suptitle(f"3D oedometer, 850 spheres: load step {dsigma:.0f} Pa, B = {b:.3f}")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "oedometer.png"), dpi=110)
    print(f"plot: {os.path.join(out, 'oedometer.png')}")


if __name__ == "__main__":
    main()
