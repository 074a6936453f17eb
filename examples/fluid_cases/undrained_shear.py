#!/usr/bin/python3
"""A CU test of a random packing against its dry constant-volume twin: the
biaxial test of undrained_biaxial.toml (2D) or the triaxial test of
undrained_triaxial_packing.toml (3D), with the darcydem Python module built
next to the program.

    /usr/bin/python3 examples/fluid_cases/undrained_shear.py build/darcydem OUT [--scene SCENE]
        [--strain 0.02] [--compaction-friction 0.5] [--no-plot]

Both runs consolidate the same packing (the scene's stage "consolidate",
bit for bit the same), then shear it at the scene's platen speeds:
- undrained: the scene's stage "shear", the drainage shut, the side
  platens' servos holding the total cell pressure;
- constant volume: the same stage with the drainage held open at zero
  pressure (the water does nothing) and the side platens driven, every
  `chunk` steps, so that the sample's volume (2D: area) stays what it was,
  the sides opening alike (as DEM studies do a constant-volume test, the
  undrained test of incompressible water).
If the coupling is right, the effective stresses (the grains' loads on
the platens) follow the same path, and the pore pressure is the total cell
pressure less the constant-volume test's lateral stress. Consolidated with
the grains' friction at 0.5 (--compaction-friction 0.5), the packing is
looser; it contracts as it is sheared and liquefies: the effective
stresses fall to nothing (the biaxial one, porosity 0.240, at 0.54 % axial
strain; the triaxial one, 0.486, by 1.25 %) and the pore pressure takes
the whole cell pressure (static liquefaction, as in loose sand's undrained
tests), in both runs.

Writes OUT/undrained.csv and OUT/constant_volume.csv (axial strain;
sigma_1, sigma_3 the grains' stresses on the top platen and on the side
platens (3D: the mean of x_max's and y_max's), Pa; u, Pa; the volume's
(2D: area's) relative change; the sample's width, depth (2D: 1 m) and
height, m) and OUT/paths.png, and prints the paths side by side. Ctrl-C
stops it, writing the path of the run under way so far (none while the
packing consolidates). About 45 s (2D) or 40 s (3D) on one core.
"""
import argparse
import math
import os
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from darcydem_module import load_module  # noqa: E402
SCENE = os.path.join(HERE, "undrained_biaxial.toml")
COLUMNS = ("axial_strain", "sigma_1", "sigma_3", "pore_pressure", "volume_change", "width", "depth", "height")


class Interrupted(Exception):
    """Ctrl-C during a shear; `rows` holds the path so far."""

    def __init__(self, rows):
        super().__init__("interrupted")
        self.rows = rows


def stage(scene, name, scene_file):
    for s in scene["stage"]:
        if s.get("name") == name:
            return s
    raise ValueError(f"{scene_file}: no stage named '{name}'")


def lateral_walls(dimension):
    """The side platens by axis: x_min, x_max (and y_min, y_max in 3D)."""
    return (("x_min", "x_max"), ("y_min", "y_max"))[:dimension - 1]


def sample(model):
    """The walls by name, the sample's lateral widths (x, and y in 3D) and
    height, m; the platens top and bottom face along y (2D) or z (3D)."""
    w = {x["name"]: x for x in model.walls}
    d = model.dimension
    widths = [w[hi]["point"][k] - w[lo]["point"][k] for k, (lo, hi) in enumerate(lateral_walls(d))]
    return w, widths, w["top"]["point"][d - 1] - w["bottom"]["point"][d - 1]


def lateral_stress(w, dimension):
    """The grains' mean stress on the side platens x_max (and y_max), Pa."""
    return sum(w[hi]["stress"] for _, hi in lateral_walls(dimension)) / (dimension - 1)


def shear(darcydem, constant_volume, strain=0.02, chunk=50, scene_file=SCENE, log=None, compaction_friction=None):
    """Consolidates the scene's packing (with the grains' friction
    `compaction_friction` instead of the stage's if given: 0.5 packs them
    loosely) and shears it to `strain` (axial), undrained or at constant
    volume; returns a dict of lists (COLUMNS) read every `chunk` steps, and
    the porosity as the shear starts."""
    with open(scene_file, "rb") as f:
        scene = tomllib.load(f)
    shearing = stage(scene, "shear", scene_file)
    model = darcydem.load(scene_file)
    d = model.dimension
    closing = shearing["walls"]["bottom"]["velocity"][d - 1] - shearing["walls"]["top"]["velocity"][d - 1]
    model.apply_stage("consolidate")
    if compaction_friction is not None:
        model.set_friction(["sand", "sand"], compaction_friction)
    dt = model.time_step
    rows = {k: [] for k in COLUMNS}
    rows["dimension"] = d
    try:
        model.step(int(round(stage(scene, "consolidate", scene_file)["duration"] / dt)))
    except KeyboardInterrupt:
        raise Interrupted(rows) from None
    model.apply_stage("shear")
    _, widths0, height0 = sample(model)
    if strain > closing * shearing["duration"] / height0:
        raise ValueError(f"{scene_file}: the stage \"shear\" reaches an axial strain of "
                         f"{closing * shearing['duration'] / height0:.4g}, less than {strain}")
    volume0 = math.prod(widths0) * height0
    grains = sum((math.pi * r * r if d == 2 else 4.0 / 3.0 * math.pi * r ** 3) for r in model.radii)
    porosity = 1.0 - grains / volume0
    if constant_volume:
        model.set_fluid_source("drainage", pressure=0.0)
    try:
        while True:
            w, widths, height = sample(model)
            e1 = 1.0 - height / height0
            for k, v in zip(COLUMNS, (e1, w["top"]["stress"], lateral_stress(w, d),
                                      float(model.fluid.pressure.ravel()[0]),
                                      math.prod(widths) * height / volume0 - 1.0, widths[0],
                                      widths[1] if d == 3 else 1.0, height)):
                rows[k].append(v)
            if log and len(rows[k]) % 200 == 1:
                print(f"{'constant volume' if constant_volume else 'undrained'}: axial strain {e1:.4f} of "
                      f"{strain}", file=log, flush=True)
            if e1 >= strain:
                break
            if constant_volume:
                # The sides open alike by what keeps the volume at its
                # start once the platens have closed by `closing` over the
                # chunk: each width by the factor s.
                s = (volume0 / ((height - closing * chunk * dt) * math.prod(widths))) ** (1.0 / (d - 1))
                for k, (lo, hi) in enumerate(lateral_walls(d)):
                    speed = widths[k] * (s - 1.0) / (2.0 * chunk * dt)
                    model.set_wall_motion(hi, velocity=[speed if j == k else 0.0 for j in range(d)])
                    model.set_wall_motion(lo, velocity=[-speed if j == k else 0.0 for j in range(d)])
            model.step(chunk)
    except KeyboardInterrupt:
        raise Interrupted(rows) from None
    return rows, porosity


def at_strain(rows, e1):
    """The row index where the axial strain first reaches e1."""
    for i, e in enumerate(rows["axial_strain"]):
        if e >= e1:
            return i
    raise ValueError(f"the run stops at an axial strain of {rows['axial_strain'][-1]:.4g}, before {e1}")


def p_q(rows, i):
    """The mean and deviatoric effective stresses, Pa: in 2D half the sum
    and half the difference of the principal stresses; in 3D
    p' = (sigma'_1 + 2 sigma'_3) / 3 and q = sigma'_1 - sigma'_3."""
    s1, s3 = rows["sigma_1"][i], rows["sigma_3"][i]
    if rows["dimension"] == 2:
        return 0.5 * (s1 + s3), 0.5 * (s1 - s3)
    return (s1 + 2.0 * s3) / 3.0, s1 - s3


def write(rows, path):
    with open(path, "w") as f:
        f.write(",".join(COLUMNS) + "\n")
        for i in range(len(rows["axial_strain"])):
            f.write(",".join(repr(rows[k][i]) for k in COLUMNS) + "\n")


def plot(undrained, constant_volume, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    for rows, style, name in ((undrained, "-", "undrained (coupled)"), (constant_volume, "--", "constant volume (dry)")):
        n = len(rows["axial_strain"])
        p, q = zip(*(p_q(rows, i) for i in range(n)))
        a.plot([x / 1e3 for x in p], [x / 1e3 for x in q], style, label=name)
        b.plot([100 * e for e in rows["axial_strain"]], [x / 1e3 for x in q], style, label=name)
    n = len(undrained["axial_strain"])
    b.plot([100 * e for e in undrained["axial_strain"]], [u / 1e3 for u in undrained["pore_pressure"]], ":",
           label="pore pressure u (undrained)")
    a.set_xlabel("p' (kPa)")
    a.set_ylabel("q (kPa)")
    a.set_title("effective stress paths")
    b.set_xlabel("axial strain (%)")
    b.set_ylabel("q, u (kPa)")
    for ax in (a, b):
        ax.grid(True)
        ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("darcydem", help="the darcydem program (its Python module is in python/ next to it)")
    ap.add_argument("out", help="output directory")
    ap.add_argument("--scene", default=SCENE,
                    help="the CU scene: undrained_biaxial.toml (2D, the default) or "
                         "undrained_triaxial_packing.toml (3D), or one like them")
    ap.add_argument("--strain", type=float, default=0.02, help="axial strain to shear to (default 0.02)")
    ap.add_argument("--compaction-friction", type=float, default=None,
                    help="the grains' friction while they consolidate (default: the scene's, 0.02, a dense "
                         "packing; 0.5 packs them loosely)")
    ap.add_argument("--no-plot", action="store_true")
    args = ap.parse_args()
    if not 0.0 < args.strain < 1.0:
        sys.exit(f"--strain {args.strain}: give an axial strain in (0, 1), within what the scene's stage "
                 "\"shear\" reaches (0.025 the examples')")
    if args.compaction_friction is not None and not 0.0 <= args.compaction_friction <= 0.5:
        sys.exit(f"--compaction-friction {args.compaction_friction}: give a friction in [0, 0.5], the "
                 "examples' [[contact]] of sand / sand has 0.5")
    darcydem = load_module(args.darcydem)
    os.makedirs(args.out, exist_ok=True)
    runs = {}
    for name, constant_volume in (("undrained", False), ("constant_volume", True)):
        try:
            runs[name], porosity = shear(darcydem, constant_volume, args.strain, scene_file=args.scene,
                                         log=sys.stdout, compaction_friction=args.compaction_friction)
        except Interrupted as stopped:
            write(stopped.rows, os.path.join(args.out, name + ".csv"))
            sys.exit(f"interrupted: the {name} path so far is in {os.path.join(args.out, name + '.csv')}")
        except (ValueError, OSError, tomllib.TOMLDecodeError) as e:
            sys.exit(str(e))
        write(runs[name], os.path.join(args.out, name + ".csv"))
    undrained, dry = runs["undrained"], runs["constant_volume"]
    print(f"porosity at the shear's start {porosity:.4f}")
    print(" e1 (%)   p' und    p' cv   q und    q cv   (kPa)   u     sigma_3 - sigma'_3(cv)")
    step = args.strain / 8
    for k in range(1, 9):
        i, j = at_strain(undrained, k * step), at_strain(dry, k * step)
        (pu, qu), (pc, qc) = p_q(undrained, i), p_q(dry, j)
        u = undrained["pore_pressure"][i]
        total = undrained["sigma_3"][i] + u
        print(f"{100 * k * step:6.3f} {pu / 1e3:8.1f} {pc / 1e3:8.1f} {qu / 1e3:7.1f} {qc / 1e3:7.1f}        "
              f"{u / 1e3:7.1f} {(total - dry['sigma_3'][j]) / 1e3:7.1f}")
    if not args.no_plot:
        plot(undrained, dry, os.path.join(args.out, "paths.png"))
        print(f"plot: {os.path.join(args.out, 'paths.png')}")


if __name__ == "__main__":
    main()
