#!/usr/bin/python3
"""The rotating drum of rotating_drum.toml: its torque and its bed's slope.

    darcydem run examples/dem_cases/rotating_drum.toml -o OUT
    /usr/bin/python3 examples/dem_cases/drum_profile.py OUT

prints and plots (OUT/drum.png):
- the drum's torque (probe "torque") against the moment of the grains'
  weight about its axis, M g x_cm (probe "x_mean", the mean centre of the
  grains, one size: their centre of mass), which it balances once the
  turning is steady: their means from --from (s) on;
- the dynamic angle of repose: the slope of the bed's free surface at the
  end of the run, a line fitted by least squares through the highest grain
  centre in each of --bins strips across the drum, the outer --trim strips
  on each side left out (they lie on the drum's wall, not the surface).
The grains come from OUT/particles_final.csv (x across, z up, the drum's
axis along y); M from their radii and --density.
"""
import argparse
import csv
import math
import sys
from pathlib import Path

G = 9.81


def read_columns(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def surface_angle(x, z, bins=12, trim=2):
    """Degrees from the horizontal of the line through the highest z in each
    of `bins` equal strips of x (without the `trim` outer strips on each
    side); positive when the surface rises along +x. Also returns the
    strips' points (centre of the strip, highest z)."""
    if bins - 2 * trim < 2:
        raise ValueError(f"bins = {bins} with trim = {trim} leaves fewer than two strips to fit")
    lo, hi = min(x), max(x)
    if not hi > lo:
        raise ValueError("the grains span no width across the drum")
    top = {}
    for xi, zi in zip(x, z):
        b = min(bins - 1, int((xi - lo) / (hi - lo) * bins))
        top[b] = max(top.get(b, -math.inf), zi)
    points = [(lo + (b + 0.5) * (hi - lo) / bins, top[b]) for b in range(trim, bins - trim) if b in top]
    if len(points) < 2:
        raise ValueError("fewer than two strips hold grains")
    mx = sum(p[0] for p in points) / len(points)
    mz = sum(p[1] for p in points) / len(points)
    slope = sum((p[0] - mx) * (p[1] - mz) for p in points) / sum((p[0] - mx) ** 2 for p in points)
    return math.degrees(math.atan(slope)), points


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="the run's output directory")
    ap.add_argument("--from", dest="start", type=float, default=1.2, help="s: the steady turning from here on")
    ap.add_argument("--density", type=float, default=2500.0, help="the grains' density, kg/m^3")
    ap.add_argument("--bins", type=int, default=12, help="strips across the drum for the surface")
    ap.add_argument("--trim", type=int, default=2, help="outer strips left out on each side")
    args = ap.parse_args()
    out = Path(args.out)
    probes, grains = out / "probes.csv", out / "particles_final.csv"
    for f in (probes, grains):
        if not f.is_file():
            sys.exit(f"drum_profile.py: {f} not found; run the scene first (see --help)")
    p = read_columns(probes)
    for key in ("time", "torque", "x_mean"):
        if key not in p:
            sys.exit(f"drum_profile.py: {probes} has no column '{key}' (the probes of rotating_drum.toml)")
    g = read_columns(grains)
    mass = sum(args.density * 4.0 / 3.0 * math.pi * r**3 for r in g["radius"])
    steady = [i for i, t in enumerate(p["time"]) if t >= args.start]
    if not steady:
        sys.exit(f"drum_profile.py: the run ends at {p['time'][-1]} s, before --from {args.start} s")
    torque = sum(p["torque"][i] for i in steady) / len(steady)
    weight = mass * G * sum(p["x_mean"][i] for i in steady) / len(steady)
    try:
        angle, points = surface_angle(g["x"], g["z"], args.bins, args.trim)
    except ValueError as e:
        sys.exit(f"drum_profile.py: {grains}: {e}")
    print(f"from {args.start} s on ({len(steady)} samples): mean torque {torque:.4g} N m, "
          f"M g x_cm {weight:.4g} N m ({torque / weight - 1.0:+.2%})")
    print(f"dynamic angle of repose at the end: {abs(angle):.1f} degrees ({len(points)} strips)")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.5))
    a.plot(p["time"], p["torque"], lw=0.6, label="drum torque (probe torque)")
    a.plot(p["time"], [mass * G * v for v in p["x_mean"]], lw=1.2, label="M g x_cm")
    a.axvline(args.start, color="grey", ls=":", lw=0.8)
    a.set_xlabel("time (s)")
    a.set_ylabel("moment about the axis (N m)")
    a.legend(fontsize=8)
    a.set_title(f"mean from {args.start} s: {torque:.3g} against {weight:.3g} N m")
    for xi, zi, ri in zip(g["x"], g["z"], g["radius"]):
        b.add_patch(plt.Circle((xi * 1e3, zi * 1e3), ri * 1e3, fill=False, lw=0.3))
    xs = [q[0] for q in points]
    mz = sum(q[1] for q in points) / len(points)
    mx = sum(xs) / len(xs)
    slope = math.tan(math.radians(angle))
    b.plot([xs[0] * 1e3, xs[-1] * 1e3], [(mz + slope * (xs[0] - mx)) * 1e3, (mz + slope * (xs[-1] - mx)) * 1e3],
           "r-", lw=1.5, label=f"free surface, {abs(angle):.1f} degrees")
    b.plot([q[0] * 1e3 for q in points], [q[1] * 1e3 for q in points], "r.", ms=4)
    b.set_aspect("equal")
    b.autoscale_view()
    b.set_xlabel("x (mm)")
    b.set_ylabel("z (mm)")
    b.legend(fontsize=8, loc="upper right")
    b.set_title("grains at the end (seen along the axis)")
    fig.tight_layout()
    fig.savefig(out / "drum.png", dpi=120)
    print(f"wrote {out / 'drum.png'}")


if __name__ == "__main__":
    main()
