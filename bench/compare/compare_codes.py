#!/usr/bin/python3
"""darcydem against YADE and LIGGGHTS: the same settled bed, the same contacts.

A bed of 10^5 spheres (d = 1 mm) settled once by darcydem
(bench/compare/settle_bed.toml) is loaded by each code with the same linear
spring-dashpot contacts (k_n = k_t = 1000 N/m, friction 0.5, restitution
0.5), the same five walls, gravity and time step (7e-6 s), and advanced
with 1 and 2 threads (YADE: -j; LIGGGHTS: MPI ranks, its way of using
cores). The cost of a step is (T(N2) - T(N1)) / (N2 - N1) from two runs of
N1 and N2 steps, T each code's own timer of its stepping loop (darcydem:
run.json's wall_time), so loading, list building and output cancel out.
Each run also reports its contacts (between grains and with walls) and
(darcydem, YADE) the floor's load against the bed's weight, to show that
the codes hold the same bed at rest. With the codes darcydem_fluid and
yade_pfv, the bed also carries an upward seepage: darcydem's Darcy-Biot
grid against YADE's DEM-PFV (FlowEngine).

Needs yade and liggghts (scripts/install-deps.sh --compare). Writes
OUT (default bench/results/compare_codes.json); docs/PERFORMANCE.md has
the figures.

  /usr/bin/python3 bench/compare/compare_codes.py [--darcydem build/darcydem]
      [--work /tmp/darcydem_compare] [--steps 500 1500] [--threads 1 2]
      [--codes darcydem yade liggghts darcydem_fluid yade_pfv] [--side 0.11]
      [--p-bottom 30] [--out bench/results/compare_codes.json]
"""
import argparse
import datetime
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent

# The bed's material and contact (as in settle_bed.toml).
DENSITY = 2650.0
RADIUS = 0.0005
STIFFNESS = 1000.0
RESTITUTION = 0.5
TIME_STEP = 7e-6
SIDE = 0.11  # the settled bed's box, m
GRAVITY = 9.81


def run(cmd, log_path, env=None):
    """Runs cmd, its output to log_path; returns the process's wall time."""
    start = time.time()
    with open(log_path, "w") as log:
        proc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    elapsed = time.time() - start
    if proc.returncode != 0:
        sys.exit(f"compare_codes: {' '.join(map(str, cmd))} failed (exit {proc.returncode}); see {log_path}")
    return elapsed


def settled_bed(darcydem, work):
    """The bed's CSV, settled by darcydem once and kept in the work folder."""
    out = work / "settle"
    csv = out / "particles_final.csv"
    if not csv.exists():
        print("settling the bed (about 5 minutes on 2 cores) ...", flush=True)
        run([darcydem, "run", HERE / "settle_bed.toml", "-o", out, "--force"], work / "settle.log")
    return csv


def is_grain_row(line):
    """Whether a line of darcydem's particle CSV is a grain (not the header)."""
    return not line.startswith("#") and not line.startswith("x,")


def grains(csv):
    """The bed's grains as (x, y, z, radius), m."""
    return [tuple(float(v) for v in line.split(",")) for line in open(csv) if is_grain_row(line)]


def cropped_bed(csv, side, work):
    """The grains of the bed that lie wholly in [0, side]^2 (all of them at
    the bed's own side), as a CSV with the same header."""
    if side >= SIDE:
        return csv
    out = work / f"bed_{side}.csv"
    with open(csv) as f, open(out, "w") as g:
        for line in f:
            if not is_grain_row(line):
                g.write(line)
                continue
            x, y, _, r = (float(v) for v in line.split(","))
            if x + r <= side and y + r <= side:
                g.write(line)
    return out


def overlap_tolerance(csv):
    """The initial_overlap_tolerance that darcydem's end-state CSV asks for."""
    with open(csv) as f:
        for line in f:
            if not line.startswith("#"):
                break
            if "initial_overlap_tolerance" in line:
                return float(line.split("initial_overlap_tolerance")[1].split()[1].strip("=,;()"))
    return 0.05


DARCYDEM_SCENE = """\
# Written by bench/compare/compare_codes.py: the settled bed, {steps} steps.
[simulation]
dimension = 3
time_step = {dt}
skin = 1e-4
initial_overlap_tolerance = {tolerance}

[[material]]
name = "grain"
density = {density}

[[contact]]
materials = ["grain", "grain"]
law = "linear"
normal_stiffness = {stiffness}
tangential_stiffness_ratio = 1.0
restitution = {restitution}
friction = 0.5
{walls}
[[particles]]
generator = "csv"
material = "grain"
file = "{csv}"

[[probe]]
name = "contacts"
quantity = "contact_count"

[[probe]]
name = "floor_force"
quantity = "wall_force"
wall = "floor"
component = "z"

[[probe]]
name = "kinetic_energy"
quantity = "kinetic_energy"

{fluid}
[output]
probe_interval = 1.0

[[stage]]
name = "timed"
duration = {duration}
gravity = [0.0, 0.0, -{gravity}]
local_damping = 0.7
"""


def darcydem_walls(side):
    walls = [("floor", (0, 0, 0), (0, 0, 1)), ("x_min", (0, 0, 0), (1, 0, 0)),
             ("x_max", (side, 0, 0), (-1, 0, 0)), ("y_min", (0, 0, 0), (0, 1, 0)),
             ("y_max", (0, side, 0), (0, -1, 0))]
    text = ""
    for name, point, normal in walls:
        text += (f'\n[[wall]]\nname = "{name}"\npoint = {list(map(float, point))}\n'
                 f'normal = {list(map(float, normal))}\nmaterial = "grain"\n')
    return text + "\n"


FLUID = """
[fluid]
density = 1000.0
viscosity = 1.0e-3
bulk_modulus = 1e5
drag = "ergun"
solver = "cg"

[fluid.grid]
origin = [0.0, 0.0, 0.0]
cells = [{nx}, {nx}, {nz}]
size = [{h}, {h}, {hz}]

[fluid.permeability]
model = "kozeny_carman"

[fluid.boundary]
z_min = {{ type = "drained", pressure = {p_bottom} }}
z_max = {{ type = "drained", pressure = 0.0 }}
"""


def fluid_block(csv, side, p_bottom):
    """darcydem's pore fluid over the bed: cells of about 2.5 grains across,
    the grid's top 1 mm above the bed (YADE's lid is there), the excess
    pressure p_bottom on the floor and zero on top."""
    top = max(z + r for _, _, z, r in grains(csv))
    nx = round(side / 2.5e-3)
    nz = max(1, round((top + 1e-3) / 2.5e-3))
    return FLUID.format(nx=nx, nz=nz, h=side / nx, hz=(top + 1e-3) / nz, p_bottom=p_bottom)


def run_darcydem(darcydem, bed, steps, threads, work, p_bottom=None):
    csv, side = bed
    name = f"darcydem{'_fluid' if p_bottom is not None else ''}_{side}_{threads}t_{steps}"
    scene = work / f"{name}.toml"
    # The stage ends at the first step past its duration: half a step short
    # of N steps gives exactly N.
    scene.write_text(DARCYDEM_SCENE.format(
        steps=steps, dt=TIME_STEP, tolerance=overlap_tolerance(csv), density=DENSITY, stiffness=STIFFNESS,
        restitution=RESTITUTION, walls=darcydem_walls(side), csv=csv, duration=(steps - 0.5) * TIME_STEP,
        gravity=GRAVITY, fluid=fluid_block(csv, side, p_bottom) if p_bottom is not None else ""))
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    out = work / name
    process_seconds = run([darcydem, "run", scene, "-o", out, "--force"], work / f"{name}.log", env)
    summary = json.loads((out / "run.json").read_text())
    with open(out / "probes.csv") as f:
        header = f.readline().strip().split(",")
        last = f.readlines()[-1].strip().split(",")
    probes = dict(zip(header, map(float, last)))
    particles = summary["particles"]
    extra = {"fluid_cells": summary["fluid"]["cells"]} if "fluid" in summary else {}
    return extra | {"steps": summary["steps"], "loop_seconds": summary["wall_time"], "process_seconds": process_seconds,
            "particles": particles, "contacts": probes["contacts"],
            "floor_force": abs(probes["floor_force"]),
            "weight": particles * DENSITY * 4.0 / 3.0 * math.pi * RADIUS**3 * GRAVITY,
            "kinetic_energy": probes["kinetic_energy"], "version": summary["version"]}


def run_yade(bed, steps, threads, work, p_bottom=None):
    csv, side = bed
    name = f"yade{'_pfv' if p_bottom is not None else ''}_{side}_{threads}t_{steps}"
    result = work / f"{name}.json"
    cmd = ["yade", "-n", "-x", f"-j{threads}", HERE / "yade_bed.py", csv, str(side), str(steps), result]
    if p_bottom is not None:
        cmd += ["pfv", str(p_bottom)]
    process_seconds = run(cmd, work / f"{name}.log")
    r = json.loads(result.read_text())
    extra = {k: v for k, v in r.items() if k.startswith("pfv_")}
    return extra | {"steps": r["steps"], "loop_seconds": r["loop_seconds"], "process_seconds": process_seconds,
            "particles": r["particles"], "contacts": r["grain_contacts"] + r["wall_contacts"], "floor_force": r["floor_force"],
            "weight": r["weight"], "kinetic_energy": r["kinetic_energy"], "version": r["version"],
            "contact_kn": r["contact_kn"], "contact_ks": r["contact_ks"]}


def liggghts_data(csv, side, work):
    """The bed as a LIGGGHTS data file (atom_style granular)."""
    data = work / f"bed_{side}.data"
    if data.exists():
        return data
    rows = grains(csv)
    top = max(z + r for _, _, z, r in rows)
    with open(data, "w") as f:
        f.write(f"darcydem settled bed\n\n{len(rows)} atoms\n1 atom types\n\n0 {side} xlo xhi\n0 {side} ylo yhi\n"
                f"0 {2.0 * top:.6g} zlo zhi\n\nAtoms\n\n")
        for k, (x, y, z, r) in enumerate(rows):
            f.write(f"{k + 1} 1 {2.0 * r:.17g} {DENSITY} {x!r} {y!r} {z!r}\n")
    return data


def run_liggghts(bed, steps, threads, work):
    csv, side = bed
    name = f"liggghts_{side}_{threads}t_{steps}"
    # hooke/stiffness without absolute damping: F = -gamma_n m* v_n, so
    # gamma_n = 2 zeta sqrt(k_n / m*) with zeta from the restitution (the
    # linear oscillator's closed form).
    m_eff = 0.5 * DENSITY * 4.0 / 3.0 * math.pi * RADIUS**3
    zeta = -math.log(RESTITUTION) / math.sqrt(math.pi**2 + math.log(RESTITUTION) ** 2)
    gamma = 2.0 * zeta * math.sqrt(STIFFNESS / m_eff)
    log = work / f"{name}.log"
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = ["mpirun", "-np", str(threads), "liggghts", "-in", HERE / "liggghts_bed.in", "-log", "none",
           "-var", "data", liggghts_data(csv, side, work), "-var", "steps", str(steps), "-var", "gamma", f"{gamma:.6g}",
           "-var", "side", str(side), "-var", "near_side", str(side - RADIUS)]
    process_seconds = run(cmd, log, env)
    text = log.read_text().splitlines()
    loop = next(line for line in text if line.startswith("Loop time of"))
    # "Loop time of T on P procs for N steps with A atoms"
    words = loop.split()
    header = next(i for i, line in enumerate(text) if line.split()[:2] == ["Step", "Atoms"])
    last = text[header + 2].split()  # the row at the run's end
    return {"steps": int(words[8]), "loop_seconds": float(words[3]), "process_seconds": process_seconds,
            "particles": int(words[11]),
            # contact/atom counts each pair twice; the walls' contacts are
            # the grains within a radius of a wall
            "contacts": float(last[4]) / 2.0 + float(last[5]),
            "kinetic_energy": float(last[2]) + float(last[3]), "version": text[0].strip(),
            "gamma_n": gamma}


def cpu_model():
    for line in Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return platform.processor()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--darcydem", default=str(ROOT / "build" / "darcydem"), help="the darcydem program")
    parser.add_argument("--work", default="/tmp/darcydem_compare",
                        help="folder for the runs; the settled bed is kept there (settle/) and reused")
    parser.add_argument("--steps", type=int, nargs=2, default=[500, 1500], metavar=("N1", "N2"),
                        help="the two runs' lengths; a step costs (T(N2) - T(N1)) / (N2 - N1)")
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2],
                        help="thread counts (LIGGGHTS: MPI ranks)")
    parser.add_argument("--codes", nargs="+", default=["darcydem", "yade", "liggghts"],
                        choices=["darcydem", "yade", "liggghts", "darcydem_fluid", "yade_pfv"],
                        help="darcydem_fluid and yade_pfv: the same bed with upward seepage (darcydem's "
                             "Darcy-Biot grid against YADE's DEM-PFV)")
    parser.add_argument("--side", type=float, default=SIDE,
                        help="the grains of the bed wholly in [0, SIDE]^2 only, with the side walls there, m "
                             "(default the whole bed; Debian 12's YADE FlowEngine aborts on the whole bed, "
                             "see docs/PERFORMANCE.md)")
    parser.add_argument("--p-bottom", type=float, default=30.0,
                        help="the seepage runs' excess pressure on the floor, Pa (the bed's submerged "
                             "weight is about 70 Pa per unit area of floor)")
    parser.add_argument("--out", default=str(ROOT / "bench" / "results" / "compare_codes.json"),
                        help="the results' JSON file")
    args = parser.parse_args()
    n1, n2 = args.steps
    if not 0 < n1 < n2:
        sys.exit(f"compare_codes: --steps needs 0 < N1 < N2, got {n1} {n2}")
    for tool in {"yade": ["yade"], "yade_pfv": ["yade"], "liggghts": ["liggghts", "mpirun"]}.items():
        if tool[0] in args.codes:
            for exe in tool[1]:
                if shutil.which(exe) is None:
                    sys.exit(f"compare_codes: '{exe}' is not installed; run scripts/install-deps.sh --compare")
    darcydem = Path(args.darcydem)
    if not darcydem.exists():
        sys.exit(f"compare_codes: {darcydem} not found; build darcydem first (cmake --build build)")
    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    if not 0.005 <= args.side <= SIDE:
        sys.exit(f"compare_codes: --side must be from 0.005 to {SIDE} m, got {args.side}")
    bed = (cropped_bed(settled_bed(darcydem, work), args.side, work), args.side)

    runners = {"darcydem": lambda steps, t: run_darcydem(darcydem, bed, steps, t, work),
               "yade": lambda steps, t: run_yade(bed, steps, t, work),
               "liggghts": lambda steps, t: run_liggghts(bed, steps, t, work),
               "darcydem_fluid": lambda steps, t: run_darcydem(darcydem, bed, steps, t, work, args.p_bottom),
               "yade_pfv": lambda steps, t: run_yade(bed, steps, t, work, args.p_bottom)}
    results = []
    for threads in args.threads:
        for code in args.codes:
            short = runners[code](n1, threads)
            long = runners[code](n2, threads)
            per_step = (long["loop_seconds"] - short["loop_seconds"]) / (long["steps"] - short["steps"])
            entry = {"code": code, "threads": threads, "seconds_per_step": per_step,
                     "particle_steps_per_second": long["particles"] / per_step,
                     "contacts_per_particle": long["contacts"] / long["particles"], "short_run": short,
                     "long_run": long}
            if "floor_force" in long:
                entry["floor_force_over_weight"] = long["floor_force"] / long["weight"]
            results.append(entry)
            print(f"{code:9s} {threads} thread(s): {per_step * 1e3:8.2f} ms per step, "
                  f"{entry['particle_steps_per_second'] / 1e6:6.2f} M particle-steps/s, "
                  f"{entry['contacts_per_particle']:.3f} contacts per grain", flush=True)
    report = {"date": datetime.date.today().isoformat(), "machine": {"cpu": cpu_model(), "cores": os.cpu_count()},
              "bed": str(bed[0]), "side": args.side, "time_step": TIME_STEP, "steps": [n1, n2], "results": results}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(report, indent=2, default=str) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
