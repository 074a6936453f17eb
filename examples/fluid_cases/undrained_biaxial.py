#!/usr/bin/python3
"""The CU biaxial test of undrained_biaxial.toml against its dry
constant-volume twin, with the darcydem Python module built next to the
program.

    /usr/bin/python3 examples/fluid_cases/undrained_biaxial.py build/darcydem OUT [--strain 0.02]
        [--compaction-friction 0.5] [--no-plot]

Both runs consolidate the same packing (the scene's stage "consolidate",
bit for bit the same), then shear it at the scene's platen speeds:
- undrained: the scene's stage "shear", the drainage shut, the side
  platens' servos holding the total cell pressure;
- constant volume: the same stage with the drainage held open at zero
  pressure (the water does nothing) and the side platens driven, every
  `chunk` steps, so that the sample's area stays what it was (as DEM
  studies do a constant-volume test, the undrained test of incompressible
  water).
If the coupling is right, the effective stresses (the grains' loads on
the platens) follow the same path, and the pore pressure is the total cell
pressure less the constant-volume test's lateral stress. Consolidated with
the discs' friction at 0.5 (--compaction-friction 0.5), the packing is
loose (porosity 0.248), contracts as it is sheared and liquefies: the
effective stresses fall to nothing at 0.6 % axial strain and the pore
pressure takes the whole cell pressure (static liquefaction, as in loose
sand's undrained tests), in both runs.

Writes OUT/undrained.csv and OUT/constant_volume.csv (axial strain;
sigma_x, sigma_y the grains' stresses on the platens x_max and top, Pa;
u, Pa; the area's change; the sample's width and height, m) and
OUT/paths.png, and prints the paths side by side. Ctrl-C stops it, writing
the path of the run under way so far (none while the packing
consolidates). About 45 s on one core.
"""
import argparse
import os
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from darcydem_module import load_module  # noqa: E402
SCENE = os.path.join(HERE, "undrained_biaxial.toml")
COLUMNS = ("axial_strain", "sigma_x", "sigma_y", "pore_pressure", "area_change", "width", "height")


class Interrupted(Exception):
    """Ctrl-C during a shear; `rows` holds the path so far."""

    def __init__(self, rows):
        super().__init__("interrupted")
        self.rows = rows


def stage(scene, name):
    for s in scene["stage"]:
        if s.get("name") == name:
            return s
    sys.exit(f"{SCENE}: no stage named '{name}'")


def sample(model):
    """The walls by name, the sample's width and height, m."""
    w = {x["name"]: x for x in model.walls}
    return w, w["x_max"]["point"][0] - w["x_min"]["point"][0], w["top"]["point"][1] - w["bottom"]["point"][1]


def shear(darcydem, constant_volume, strain=0.02, chunk=50, scene_file=SCENE, log=None, compaction_friction=None):
    """Consolidates the scene's packing (with the discs' friction
    `compaction_friction` instead of the stage's if given: 0.5 packs them
    loosely) and shears it to `strain` (axial), undrained or at constant
    volume; returns a dict of lists (COLUMNS) read every `chunk` steps, and
    the porosity as the shear starts."""
    with open(scene_file, "rb") as f:
        scene = tomllib.load(f)
    closing = stage(scene, "shear")["walls"]["bottom"]["velocity"][1] - stage(scene, "shear")["walls"]["top"][
        "velocity"][1]
    model = darcydem.load(scene_file)
    model.apply_stage("consolidate")
    if compaction_friction is not None:
        model.set_friction(["sand", "sand"], compaction_friction)
    dt = model.time_step
    rows = {k: [] for k in COLUMNS}
    try:
        model.step(int(round(stage(scene, "consolidate")["duration"] / dt)))
    except KeyboardInterrupt:
        raise Interrupted(rows) from None
    model.apply_stage("shear")
    _, width0, height0 = sample(model)
    area0 = width0 * height0
    grains = sum(3.141592653589793 * r * r for r in model.radii)
    porosity = 1.0 - grains / area0
    if constant_volume:
        model.set_fluid_source("drainage", pressure=0.0)
    try:
        while True:
            w, width, height = sample(model)
            e1 = 1.0 - height / height0
            for k, v in zip(COLUMNS, (e1, w["x_max"]["stress"], w["top"]["stress"],
                                      float(model.fluid.pressure.ravel()[0]), width * height / area0 - 1.0, width,
                                      height)):
                rows[k].append(v)
            if log and len(rows[k]) % 200 == 1:
                print(f"{'constant volume' if constant_volume else 'undrained'}: axial strain {e1:.4f} of "
                      f"{strain}", file=log, flush=True)
            if e1 >= strain:
                break
            if constant_volume:
                # The sides open by what keeps width x height at its start
                # once the platens have closed by `closing` over the chunk.
                speed = (area0 / (height - closing * chunk * dt) - width) / (2.0 * chunk * dt)
                model.set_wall_motion("x_max", velocity=[speed, 0.0])
                model.set_wall_motion("x_min", velocity=[-speed, 0.0])
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
    """The mean and deviatoric effective stresses (2D: half the sum and
    half the difference of the principal stresses), Pa."""
    return 0.5 * (rows["sigma_x"][i] + rows["sigma_y"][i]), 0.5 * (rows["sigma_y"][i] - rows["sigma_x"][i])


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
    ap.add_argument("--strain", type=float, default=0.02, help="axial strain to shear to (default 0.02)")
    ap.add_argument("--compaction-friction", type=float, default=None,
                    help="the discs' friction while they consolidate (default: the scene's, 0.02, a dense "
                         "packing; 0.5 packs them loosely, and the loose packing liquefies)")
    ap.add_argument("--no-plot", action="store_true")
    args = ap.parse_args()
    if not 0.0 < args.strain <= 0.025:
        sys.exit(f"--strain {args.strain}: give an axial strain in (0, 0.025], the scene's shear stage reaches "
                 "0.025")
    darcydem = load_module(args.darcydem)
    os.makedirs(args.out, exist_ok=True)
    if args.compaction_friction is not None and not 0.0 <= args.compaction_friction <= 0.5:
        sys.exit(f"--compaction-friction {args.compaction_friction}: give a friction in [0, 0.5], the scene's "
                 "[[contact]] of sand / sand has 0.5")
    runs = {}
    for name, constant_volume in (("undrained", False), ("constant_volume", True)):
        try:
            runs[name], porosity = shear(darcydem, constant_volume, args.strain, log=sys.stdout,
                                         compaction_friction=args.compaction_friction)
        except Interrupted as stopped:
            write(stopped.rows, os.path.join(args.out, name + ".csv"))
            sys.exit(f"interrupted: the {name} path so far is in {os.path.join(args.out, name + '.csv')}")
        write(runs[name], os.path.join(args.out, name + ".csv"))
    undrained, dry = runs["undrained"], runs["constant_volume"]
    print(f"porosity at the shear's start {porosity:.4f}")
    print(" e1 (%)   p' und    p' cv   q und    q cv   (kPa)   u     sigma_3 - sigma'_x(cv)")
    step = args.strain / 8
    for k in range(1, 9):
        try:
            i, j = at_strain(undrained, k * step), at_strain(dry, k * step)
        except ValueError:
            break
        (pu, qu), (pc, qc) = p_q(undrained, i), p_q(dry, j)
        u = undrained["pore_pressure"][i]
        total = undrained["sigma_x"][i] + u
        print(f"{100 * k * step:6.3f} {pu / 1e3:8.1f} {pc / 1e3:8.1f} {qu / 1e3:7.1f} {qc / 1e3:7.1f}        "
              f"{u / 1e3:7.1f} {(total - dry['sigma_x'][j]) / 1e3:7.1f}")
    if not args.no_plot:
        plot(undrained, dry, os.path.join(args.out, "paths.png"))
        print(f"plot: {os.path.join(args.out, 'paths.png')}")


if __name__ == "__main__":
    main()
