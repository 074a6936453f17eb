#!/usr/bin/python3
"""The vibrated bed of vibrated_bed.toml against the completely inelastic
bouncing ball.

    darcydem run examples/dem_cases/vibrated_bed.toml --out OUT
    /usr/bin/python3 examples/dem_cases/vibrated_plot.py OUT

The floor moves as y_f = A (1 - cos(omega s)), s from the shaking's start
(--start, s: the settling stage's duration; --amplitude, m; --frequency,
Hz; the scene's walls.floor oscillation with phase -90). A ball resting on
it leaves it where the floor's acceleration reaches -g, omega s =
arccos(-1 / Gamma), Gamma = A omega^2 / g, flies on the parabola of its
speed there and lands, stuck, where the parabola meets the floor again
(found by bisection). The bed's flights are the runs of probe rows
without a load on the floor ("floor_load"); the script prints, for the
first flight, the phases of take-off and landing against the ball's, and
plots the floor's height ("floor_y") and the bed's mean height ("bed_y",
less its height at the start) against omega s with the ball's flight in
OUT/vibrated.png.
"""
import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from triaxial_plot import read_columns  # noqa: E402  (probes.csv's columns by name)

G = 9.81  # m/s^2, the scene's gravity


def floor_height(amplitude, omega, s):
    return amplitude * (1.0 - math.cos(omega * s))


def ball(amplitude, frequency, g=G):
    """The inelastic bouncing ball on a floor y_f = A (1 - cos(omega s)):
    (take-off phase, landing phase, flight(s) -> height), phases omega s in
    rad, or None for the phases if Gamma <= 1 (it never leaves)."""
    omega = 2.0 * math.pi * frequency
    gamma = amplitude * omega * omega / g
    if gamma <= 1.0:
        return None, None, None
    lift = math.acos(-1.0 / gamma)
    s0 = lift / omega
    y0 = floor_height(amplitude, omega, s0)
    v0 = amplitude * omega * math.sin(lift)

    def flight(s):
        return y0 + v0 * (s - s0) - 0.5 * g * (s - s0) ** 2

    # The gap opens after take-off; bisect its first sign change, searched
    # from a twentieth of a period on in steps of a hundredth.
    gap = lambda s: flight(s) - floor_height(amplitude, omega, s)
    period = 1.0 / frequency
    a = s0 + 0.05 * period
    while gap(a + 0.01 * period) > 0.0:
        a += 0.01 * period
        if a > s0 + 10.0 * period:
            raise ValueError("the ball does not land within ten periods")
    b = a + 0.01 * period
    for _ in range(200):
        m = 0.5 * (a + b)
        a, b = (m, b) if gap(m) > 0.0 else (a, m)
    return lift, omega * 0.5 * (a + b), flight


def first_flight(p, start, frequency, after=0.5, before=3.0 * math.pi):
    """The phases (rad) at which the bed's longest run of probe rows without
    a floor load, between `after` and `before`, begins and ends."""
    omega = 2.0 * math.pi * frequency
    best = (0.0, 0.0)
    since = None
    for t, load in zip(p["time"], p["floor_load"]):
        phase = omega * (t - start)
        if phase < after or phase > before:
            continue
        if load == 0.0 and since is None:
            since = phase
        if load != 0.0 and since is not None:
            if phase - since > best[1] - best[0]:
                best = (since, phase)
            since = None
    return best


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", help="the run's output directory")
    ap.add_argument("--start", type=float, default=0.3, help="the shaking's start, s")
    ap.add_argument("--amplitude", type=float, default=0.0012425, help="the floor's amplitude, m")
    ap.add_argument("--frequency", type=float, default=20.0, help="Hz")
    ap.add_argument("--no-plot", action="store_true")
    a = ap.parse_args(argv)
    probes = Path(a.out) / "probes.csv"
    if not probes.exists():
        sys.exit(f"{probes}: no such file (run the scene first)")
    p = read_columns(probes)
    for k in ("time", "floor_load", "floor_y", "bed_y"):
        if k not in p:
            sys.exit(f"{probes}: no column '{k}' (the probes of vibrated_bed.toml are needed)")
    lift, land, flight = ball(a.amplitude, a.frequency)
    if lift is None:
        sys.exit("Gamma <= 1: a ball resting on the floor never leaves it")
    off, on = first_flight(p, a.start, a.frequency)
    print(f"Gamma = {a.amplitude * (2 * math.pi * a.frequency) ** 2 / G:.4f}")
    print(f"take-off: bed {off:.3f} rad, ball {lift:.3f} rad (arccos(-1/Gamma))")
    print(f"landing:  bed {on:.3f} rad, ball {land:.4f} rad")
    if a.no_plot:
        return 0
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    omega = 2.0 * math.pi * a.frequency
    rows = [i for i, t in enumerate(p["time"]) if t >= a.start]
    phase = [omega * (p["time"][i] - a.start) for i in rows]
    bed0 = p["bed_y"][rows[0]]
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(phase, [1e3 * p["floor_y"][i] for i in rows], label="floor")
    ax.plot(phase, [1e3 * (p["bed_y"][i] - bed0) for i in rows], label="bed's mean height (from its start)")
    s = [lift / omega + k * (land - lift) / omega / 100 for k in range(101)]
    ax.plot([omega * x for x in s], [1e3 * flight(x) for x in s], "k--", label="inelastic ball")
    ax.set_xlabel("omega t (rad)")
    ax.set_ylabel("height (mm)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(Path(a.out) / "vibrated.png", dpi=120)
    print(f"plot: {Path(a.out) / 'vibrated.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
