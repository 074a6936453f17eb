#!/usr/bin/python3
"""The fluidization curve of fluidized_bed.toml: inlet pressure against inflow.

    darcydem run examples/fluid_cases/fluidized_bed.toml -o OUT
    /usr/bin/python3 examples/fluid_cases/fluidization_curve.py OUT

writes OUT/fluidization_curve.png: the excess pressure at the inlet (probe
"inlet_pressure") against the superficial velocity q through the floor,
with the two lines of the textbook curve:
- the fixed bed, Darcy's law with Kozeny-Carman's permeability at the bed's
  porosity when the inflow starts: u = mu q H / kappa(n), kappa = d^2 n^3 /
  (150 (1 - n)^2), H = 2 x the grains' mean height, n = 1 - V_s / (A H);
- the fluidized bed, the submerged weight per area W' / A.
They cross at the minimum fluidization velocity, which it prints. The
grains' volume V_s comes from OUT/particles_final.csv; the densities,
viscosity, diameter and the cell's area are the scene's (options below).
"""
import argparse
import csv
import math
import sys
from pathlib import Path


def read_columns(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="the run's output directory")
    ap.add_argument("--area", type=float, default=16e-6, help="the bed's plan area, m^2 (4 x 4 mm)")
    ap.add_argument("--solid-density", type=float, default=2650.0, help="kg/m^3")
    ap.add_argument("--fluid-density", type=float, default=1000.0, help="kg/m^3")
    ap.add_argument("--viscosity", type=float, default=1e-3, help="Pa s")
    ap.add_argument("--diameter", type=float, default=1e-3, help="Kozeny-Carman's d, m")
    args = ap.parse_args()
    out = Path(args.out)
    probes = out / "probes.csv"
    grains = out / "particles_final.csv"
    for f in (probes, grains):
        if not f.is_file():
            sys.exit(f"fluidization_curve.py: {f} not found; run the scene first (see --help)")
    p = read_columns(probes)
    for key in ("time", "inflow", "inlet_pressure", "mean_height"):
        if key not in p:
            sys.exit(f"fluidization_curve.py: {probes} has no column '{key}' (the probes of fluidized_bed.toml)")
    with open(grains, newline="") as f:
        radii = [float(r["radius"]) for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    solid = sum(4.0 / 3.0 * math.pi * r**3 for r in radii)
    weight = (args.solid_density - args.fluid_density) * 9.80665 * solid / args.area

    q = [v / args.area for v in p["inflow"]]
    start = next(i for i, v in enumerate(q) if v > 0.0)
    height = 2.0 * p["mean_height"][start]
    n = 1.0 - solid / (args.area * height)
    kappa = args.diameter**2 * n**3 / (150.0 * (1.0 - n) ** 2)
    resistance = args.viscosity * height / kappa  # Pa per m/s
    q_mf = weight / resistance
    print(f"bed at the start of the inflow: height {height * 1e3:.3f} mm, porosity {n:.4f}; "
          f"W'/A = {weight:.3f} Pa; Kozeny-Carman's minimum fluidization velocity {q_mf * 1e3:.2f} mm/s")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    qs = [v * 1e3 for v in q[start:]]
    ax.plot(qs, p["inlet_pressure"][start:], ".", ms=3, label="darcydem: inlet pressure")
    top = max(qs)
    ax.plot([0.0, q_mf * 1e3], [0.0, weight], "k--", lw=1, label="fixed bed: Darcy, Kozeny-Carman")
    ax.plot([q_mf * 1e3, top], [weight, weight], "k-", lw=1, label="fluidized: W' / A")
    ax.set_xlabel("superficial velocity q (mm/s)")
    ax.set_ylabel("excess pressure at the inlet (Pa)")
    ax.set_title("Fluidization curve")
    ax.legend(loc="lower right")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "fluidization_curve.png", dpi=120)
    print(f"wrote {out / 'fluidization_curve.png'}")


if __name__ == "__main__":
    main()
