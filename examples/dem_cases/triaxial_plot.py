#!/usr/bin/python3
"""The drained triaxial test of triaxial_test.toml or triaxial_cell.toml (or
the biaxial test of biaxial_test.toml, 2D): stress and strain.

    darcydem run examples/dem_cases/triaxial_test.toml --out OUT
    /usr/bin/python3 examples/dem_cases/triaxial_plot.py OUT

From the shear's start (--from, s; the compaction stage's duration) on,
with compression positive:
- axial strain eps_a = 1 - H / H0, H the platens' distance (probes "top"
  and "bottom"); volumetric strain eps_v = 1 - V / V0, V the walls' box;
- sigma_1 = probe "sigma_z" (the top platen's stress), sigma_3 the mean of
  "sigma_x" and "sigma_y" (the side walls'). In a cylindrical cell (a
  probe "radius", the cell's radius R) sigma_3 = "sigma_r", the cell's
  stress, and V = pi R^2 H. The deviator q = sigma_1 -
  sigma_3, the mean stress p = (sigma_1 + 2 sigma_3) / 3. In 2D (probes
  without "y_min": the biaxial test) sigma_1 = "sigma_y", sigma_3 =
  "sigma_x", p = (sigma_1 + sigma_3) / 2 and V the walls' area;
- the mobilised friction angle, sin(phi) = (sigma_1 - sigma_3) / (sigma_1 +
  sigma_3) (Mohr-Coulomb without cohesion), at its peak; and the dilatancy
  angle there, sin(psi) = -r / (2 - r), r = d eps_v / d eps_a the slope of a
  least-squares line through the points within --window of axial strain of
  the peak (positive psi: the sample dilates).
The porosity comes from the grains' volume in OUT/particles_final.csv, if
there, over the walls' box. Prints them, and plots q / p and eps_v against
eps_a in OUT/triaxial.png.
"""
import argparse
import csv
import math
import sys
from pathlib import Path

COLUMNS = ("time", "x_min", "x_max", "y_min", "y_max", "bottom", "top", "sigma_x", "sigma_y", "sigma_z")
COLUMNS_2D = ("time", "x_min", "x_max", "bottom", "top", "sigma_x", "sigma_y")
COLUMNS_CELL = ("time", "radius", "bottom", "top", "sigma_r", "sigma_z")


def dimension(p):
    """3 for a triaxial test's probes (a box's or a cell's), 2 for a biaxial
    test's (neither y_min nor radius)."""
    return 3 if "y_min" in p or "radius" in p else 2


def cell(p):
    """Whether the probes are a cylindrical cell's (a column "radius")."""
    return "radius" in p


def read_columns(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    if not rows:
        raise ValueError(f"{path} has no rows")
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def curves(p, start):
    """The test's curves from the probes' columns `p`, from time `start` on:
    a dict of lists eps_a, eps_v, sigma_1, sigma_3, q, p, phi (degrees) and
    volume (m^3)."""
    rows = [i for i, t in enumerate(p["time"]) if t >= start]
    if len(rows) < 2:
        raise ValueError(f"fewer than two probe rows from {start} s on (the run ends at {p['time'][-1]} s)")

    three = dimension(p) == 3
    cylinder = cell(p)

    def box(i):
        h = p["top"][i] - p["bottom"][i]
        if cylinder:
            return h, math.pi * p["radius"][i] ** 2 * h
        w = p["x_max"][i] - p["x_min"][i]
        d = p["y_max"][i] - p["y_min"][i] if three else 1.0
        h = p["top"][i] - p["bottom"][i]
        return h, w * d * h

    h0, v0 = box(rows[0])
    c = {k: [] for k in ("time", "eps_a", "eps_v", "sigma_1", "sigma_3", "q", "p", "phi", "volume")}
    for i in rows:
        h, v = box(i)
        s1 = p["sigma_z"][i] if three else p["sigma_y"][i]
        if cylinder:
            s3 = p["sigma_r"][i]
        else:
            s3 = 0.5 * (p["sigma_x"][i] + p["sigma_y"][i]) if three else p["sigma_x"][i]
        c["time"].append(p["time"][i])
        c["eps_a"].append(1.0 - h / h0)
        c["eps_v"].append(1.0 - v / v0)
        c["sigma_1"].append(s1)
        c["sigma_3"].append(s3)
        c["q"].append(s1 - s3)
        c["p"].append((s1 + 2.0 * s3) / 3.0 if three else 0.5 * (s1 + s3))
        c["phi"].append(math.degrees(math.asin((s1 - s3) / (s1 + s3))) if s1 + s3 > 0.0 else math.nan)
        c["volume"].append(v)
    return c


def peak(c, window=0.01):
    """Index of the largest mobilised friction angle, and the dilatancy angle
    (degrees) from the slope of eps_v against eps_a within `window` of it."""
    k = max(range(len(c["phi"])), key=lambda i: c["phi"][i] if not math.isnan(c["phi"][i]) else -math.inf)
    near = [i for i in range(len(c["eps_a"])) if abs(c["eps_a"][i] - c["eps_a"][k]) <= window]
    if len(near) < 2:
        raise ValueError(f"fewer than two points within {window} of axial strain of the peak")
    ma = sum(c["eps_a"][i] for i in near) / len(near)
    mv = sum(c["eps_v"][i] for i in near) / len(near)
    sxx = sum((c["eps_a"][i] - ma) ** 2 for i in near)
    if not sxx > 0.0:
        raise ValueError("the axial strain does not change near the peak")
    r = sum((c["eps_a"][i] - ma) * (c["eps_v"][i] - mv) for i in near) / sxx
    return k, math.degrees(math.asin(-r / (2.0 - r)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="the run's output directory")
    ap.add_argument("--from", dest="start", type=float, default=0.15,
                    help="s: the shear's start (the compaction stage's duration)")
    ap.add_argument("--window", type=float, default=0.01,
                    help="axial strain either side of the peak for the dilatancy's slope")
    args = ap.parse_args()
    out = Path(args.out)
    probes = out / "probes.csv"
    if not probes.is_file():
        sys.exit(f"triaxial_plot.py: {probes} not found; run the scene first (see --help)")
    try:
        p = read_columns(probes)
    except ValueError as e:
        sys.exit(f"triaxial_plot.py: {e}")
    for key in COLUMNS_CELL if cell(p) else COLUMNS if dimension(p) == 3 else COLUMNS_2D:
        if key not in p:
            sys.exit(f"triaxial_plot.py: {probes} has no column '{key}' (the probes of triaxial_test.toml or "
                     f"triaxial_cell.toml, or in 2D of biaxial_test.toml)")
    try:
        c = curves(p, args.start)
        k, psi = peak(c, args.window)
    except ValueError as e:
        sys.exit(f"triaxial_plot.py: {probes}: {e}")
    print(f"shear from {c['time'][0]:.4g} s: sigma_3 {c['sigma_3'][0]:.4g} Pa at the start, "
          f"axial strain to {c['eps_a'][-1]:.2%}")
    print(f"peak: friction angle {c['phi'][k]:.1f} degrees at axial strain {c['eps_a'][k]:.2%} "
          f"(q {c['q'][k]:.4g} Pa, p {c['p'][k]:.4g} Pa), dilatancy angle {psi:.1f} degrees")
    print(f"end: friction angle {c['phi'][-1]:.1f} degrees, volumetric strain {c['eps_v'][-1]:.2%} "
          f"(negative: dilated)")
    grains = out / "particles_final.csv"
    if grains.is_file():
        g = read_columns(grains)
        if dimension(p) == 3:
            solid = sum(4.0 / 3.0 * math.pi * r**3 for r in g["radius"])
        else:
            solid = sum(math.pi * r**2 for r in g["radius"])
        print(f"porosity: {1.0 - solid / c['volume'][0]:.4f} at the shear's start, "
              f"{1.0 - solid / c['volume'][-1]:.4f} at the end")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.5))
    ea = [100.0 * e for e in c["eps_a"]]
    a.plot(ea, [qi / pi for qi, pi in zip(c["q"], c["p"])], lw=1.0, label="q / p")
    a.plot(ea[k], c["q"][k] / c["p"][k], "ro", ms=5, label=f"peak: phi = {c['phi'][k]:.1f} degrees")
    a.set_xlabel("axial strain (%)")
    a.set_ylabel("stress ratio q / p")
    a.legend(fontsize=8)
    a.set_title("deviator over mean stress")
    b.plot(ea, [100.0 * e for e in c["eps_v"]], lw=1.0)
    b.axhline(0.0, color="grey", lw=0.6)
    b.set_xlabel("axial strain (%)")
    b.set_ylabel("volumetric strain (%), compression positive")
    b.set_title(f"dilatancy angle at the peak {psi:.1f} degrees")
    fig.tight_layout()
    fig.savefig(out / "triaxial.png", dpi=120)
    print(f"wrote {out / 'triaxial.png'}")


if __name__ == "__main__":
    main()
