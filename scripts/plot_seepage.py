#!/usr/bin/python3
"""Plots of the seepage column, like the paper's Figs. 3 and 4.

    plot_seepage.py OUT_DIR                 uplift.png and pressure.png in OUT_DIR
    plot_seepage.py --compare PNG DIR...    uplift of several runs (e.g. the three K_f) in one figure

Reads the files darcydem writes for [analysis] kind = "seepage_column":
uplift.csv, uplift_analytic.csv, pressure.csv, pressure_analytic.csv, seepage.json.
"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]} if rows else {}


def label_of(run_dir):
    with open(os.path.join(run_dir, "seepage.json")) as f:
        info = json.load(f)
    return info, "K_f = {:.0e} Pa".format(info["bulk_modulus"])


def plot_uplift(ax, run_dir, colour):
    info, label = label_of(run_dir)
    sim = read_csv(os.path.join(run_dir, "uplift.csv"))
    ana = read_csv(os.path.join(run_dir, "uplift_analytic.csv"))
    ax.plot(sim["time"], [1e3 * s for s in sim["uplift"]], "-", color=colour, lw=2, label=label + ", darcydem")
    ax.plot(ana["time"], [1e3 * s for s in ana["uplift"]], "o", color=colour, ms=3, markevery=25,
            label=label + ", analytical (storage m_v + n/K_f)")
    ax.plot(ana["time"], [1e3 * s for s in ana["uplift_incompressible"]], ":", color="0.4", lw=1)
    return info


def single(run_dir):
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    info = plot_uplift(ax, run_dir, "C0")
    ax.set_xlabel("time since the inflow started (s)")
    ax.set_ylabel("uplift of the column top (mm)")
    ax.set_title("Uplift (RMS error {:.2f} % of the final uplift)".format(100 * info["uplift_rms_error"]))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(os.path.join(run_dir, "uplift.png"), dpi=120)
    plt.close(fig)

    sim = read_csv(os.path.join(run_dir, "pressure.csv"))
    ana = read_csv(os.path.join(run_dir, "pressure_analytic.csv"))
    fig, ax = plt.subplots(figsize=(5.2, 5.6))
    times = sorted(set(sim["time"]))
    for i, t in enumerate(times):
        colour = "C{}".format(i % 10)
        d = [1e3 * z for z, tt in zip(sim["depth"], sim["time"]) if tt == t]
        p = [u for u, tt in zip(sim["pressure"], sim["time"]) if tt == t]
        da = [1e3 * z for z, tt in zip(ana["depth"], ana["time"]) if tt == t]
        pa = [u for u, tt in zip(ana["pressure"], ana["time"]) if tt == t]
        ax.plot(p, d, "-", color=colour, label="t = {:g} s".format(t))
        ax.plot(pa, da, "o", color=colour, ms=3)
    ax.invert_yaxis()
    ax.set_xlabel("excess pore pressure (Pa)")
    ax.set_ylabel("depth below the drained top (mm)")
    ax.set_title("Pore pressure: lines darcydem, points analytical\n(max error {:.2f} % of {:.0f} Pa)".format(
        100 * info["pressure_max_error"], info["steady_bottom_pressure"]), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(run_dir, "pressure.png"), dpi=120)
    plt.close(fig)


def compare(png, run_dirs):
    fig, ax = plt.subplots(figsize=(7, 4.6))
    for i, d in enumerate(run_dirs):
        plot_uplift(ax, d, "C{}".format(i))
    ax.plot([], [], ":", color="0.4", label="paper's analytical (incompressible fluid)")
    ax.set_xlabel("time since the inflow started (s)")
    ax.set_ylabel("uplift of the column top (mm)")
    ax.set_title("Seepage column: uplift against the analytical solution")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    plt.close(fig)


def main(argv):
    if len(argv) >= 3 and argv[0] == "--compare":
        compare(argv[1], argv[2:])
    elif len(argv) == 1:
        single(argv[0])
    else:
        sys.stderr.write(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
