#!/usr/bin/python3
"""The pumping test of pumping_well.toml: drawdown and recovery at its
piezometers and in the well's cell against Theis's well.

    darcydem run examples/fluid_cases/pumping_well.toml --out OUT
    /usr/bin/python3 examples/fluid_cases/pumping_plot.py OUT

A well pumping Q (m^2/s per metre, --rate) from t = 0 and shut off at t1
(--shut-off, s) draws the pressure down by Theis's
u(r, t) = -Q mu / (4 pi kappa) [E1(r^2 / (4 c t)) - E1(r^2 / (4 c (t - t1)))],
the second term from t1 on (a well injecting Q, superposed), with
c = kappa K_f / (mu n) (--permeability kappa, --viscosity mu,
--diffusivity c). The piezometers are probe columns at a distance r
(--piezometer NAME=r, m); the well's own cell ("well_pressure") reads the
pressure at Peaceman's radius r_e = h exp(-gamma) / (2 sqrt 2) = 0.1985 h
(--cell h, m), once the drawdown has spread over a few cells (t well
above h^2 / c; just after the start and the shut-off it lags). The script
prints each one's largest departure from Theis over Q mu / (4 pi kappa)
and plots them in OUT/pumping.png.
"""
import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "dem_cases"))
from triaxial_plot import read_columns  # noqa: E402  (probes.csv's columns by name)

EULER_GAMMA = 0.5772156649015329


def e1(x):
    """The exponential integral E1(x), x > 0: its series below 1, its
    continued fraction (modified Lentz) above, both to round-off."""
    if x <= 0.0:
        raise ValueError("E1 needs x > 0")
    if x <= 1.0:
        total, term = -EULER_GAMMA - math.log(x), 1.0
        for k in range(1, 40):
            term *= -x / k
            total -= term / k
        return total
    b = x + 1.0
    c = 1.0 / 1e-300
    d = 1.0 / b
    h = d
    for i in range(1, 200):
        a = -i * i
        b += 2.0
        d = 1.0 / (a * d + b)
        c = b + a / c
        delta = c * d
        h *= delta
        if abs(delta - 1.0) < 1e-16:
            break
    return h * math.exp(-x)


def theis(r, t, rate, viscosity, permeability, diffusivity, shut_off=math.inf):
    """Excess pressure, Pa, r from a well that pumps `rate` from t = 0 to
    `shut_off` (Theis with superposition); 0 at t <= 0."""
    scale = rate * viscosity / (4.0 * math.pi * permeability)
    u = -scale * e1(r * r / (4.0 * diffusivity * t)) if t > 0.0 else 0.0
    if t > shut_off:
        u += scale * e1(r * r / (4.0 * diffusivity * (t - shut_off)))
    return u


def peaceman_radius(cell):
    """Where the continuous solution equals the five-point lattice's at the
    source: h exp(-gamma) / (2 sqrt 2)."""
    return cell * math.exp(-EULER_GAMMA) / (2.0 * math.sqrt(2.0))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", help="the run's output directory (probes.csv)")
    parser.add_argument("--rate", type=float, default=2e-6, help="m^2/s per metre pumped out")
    parser.add_argument("--shut-off", type=float, default=0.1, help="s")
    parser.add_argument("--permeability", type=float, default=1e-10, help="m^2")
    parser.add_argument("--viscosity", type=float, default=1e-3, help="Pa s")
    parser.add_argument("--diffusivity", type=float, default=0.01, help="m^2/s: kappa K_f / (mu n)")
    parser.add_argument("--cell", type=float, default=0.01, help="m: the cells' side")
    parser.add_argument("--piezometer", action="append", default=None, help="NAME=r (m); default u_5cm=0.05 "
                        "and u_10cm=0.1")
    parser.add_argument("--no-plot", action="store_true", help="print only")
    args = parser.parse_args()
    probes = Path(args.out) / "probes.csv"
    if not probes.is_file():
        sys.exit(f"{probes}: no such file (run pumping_well.toml with --out {args.out} first)")
    p = read_columns(probes)
    gauges = {"well_pressure": peaceman_radius(args.cell)}
    for given in args.piezometer or ["u_5cm=0.05", "u_10cm=0.1"]:
        name, _, r = given.partition("=")
        gauges[name] = float(r)
    for name in gauges:
        if name not in p:
            sys.exit(f"{probes}: no column '{name}' (the piezometers: --piezometer NAME=r)")
    scale = args.rate * args.viscosity / (4.0 * math.pi * args.permeability)
    expected = {
        name: [theis(r, t, args.rate, args.viscosity, args.permeability, args.diffusivity, args.shut_off)
               for t in p["time"]]
        for name, r in gauges.items()
    }
    for name, r in gauges.items():
        worst = max(abs(u - e) for u, e in zip(p[name], expected[name]))
        print(f"{name} (r = {r:.4g} m): largest departure from Theis {worst:.4g} Pa, {worst / scale:.3g} of "
              f"Q mu / (4 pi kappa) = {scale:.4g} Pa")
    if args.no_plot:
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for name, r in gauges.items():
        line, = ax.plot(p["time"], p[name], label=f"{name}, r = {r * 100:.3g} cm")
        ax.plot(p["time"], expected[name], ":", color=line.get_color())
    ax.axvline(args.shut_off, color="grey", lw=0.8)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("excess pore pressure (Pa)")
    ax.set_title("drawdown and recovery; dotted: Theis")
    ax.legend()
    fig.tight_layout()
    out = Path(args.out) / "pumping.png"
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
