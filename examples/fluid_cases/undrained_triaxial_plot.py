#!/usr/bin/python3
"""The consolidated-undrained triaxial test of undrained_triaxial.toml: its
pore pressure, deviator and effective stress path against the closed form
of its cubic lattice.

    darcydem run examples/fluid_cases/undrained_triaxial.toml --out OUT
    /usr/bin/python3 examples/fluid_cases/undrained_triaxial_plot.py OUT

From the consolidation's end (--consolidated, s) the axial strain e1 is
the top and base platens' approach over their distance then, the pore
pressure u the probe "pore_pressure", the effective stresses the grains'
load on the top and a side platen ("axial_stress", "lateral_stress"), so
p' = (s1' + 2 s3') / 3 and q = s1' - s3'. The lattice of N x N x N spheres
of radius r (--grains-per-side, --radius, --normal-stiffness k_n,
--bulk-modulus K_f) has the modulus E = N k_n / (2 r (N + 1)) along each
axis; sealed under a constant cell pressure, u = e1 c E / (E + 2 c) with
c = K_f / n (n: its porosity as the shear starts), s1' rises by E e1 and
s3' falls by u. The script prints Skempton's A = u / (B (s1 - s3)) at the
end (1/3 for the lattice, B = 1 / (1 + n E / (3 K_f))) and plots u and q
against e1 and the path in the p'-q plane in OUT/undrained_triaxial.png.
"""
import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "dem_cases"))
from triaxial_plot import read_columns  # noqa: E402  (probes.csv's columns by name)


class Lattice:
    """The closed form of a sealed cubic lattice sheared under a constant
    cell pressure."""

    def __init__(self, grains_per_side, radius, normal_stiffness, bulk_modulus, porosity):
        n = grains_per_side
        self.modulus = n * normal_stiffness / (2.0 * radius * (n + 1))
        self.porosity = porosity
        self.c = bulk_modulus / porosity
        self.b = 1.0 / (1.0 + porosity * self.modulus / (3.0 * bulk_modulus))

    def pore_pressure(self, e1):
        return e1 * self.c * self.modulus / (self.modulus + 2.0 * self.c)

    def path(self, e1, p0):
        """(p', q) after an axial strain e1 from the isotropic p0."""
        u = self.pore_pressure(e1)
        return p0 + (self.modulus * e1 - 2.0 * u) / 3.0, self.modulus * e1 + u


def shear(p, consolidated):
    """The probe rows from the consolidation's end on, each (e1, u, p', q),
    and the index of the first."""
    t = p["time"]
    start = max(j for j in range(len(t)) if t[j] <= consolidated + 1e-12)
    height = [hi - lo for hi, lo in zip(p["z_high_z"], p["z_low_z"])]
    rows = []
    for j in range(start, len(t)):
        s1 = p["axial_stress"][j]
        s3 = p["lateral_stress"][j]
        rows.append((1.0 - height[j] / height[start], p["pore_pressure"][j], (s1 + 2.0 * s3) / 3.0, s1 - s3))
    return rows, start


def sample_volume(p, j):
    return math.prod(p[f"{a}_high_{a}"][j] - p[f"{a}_low_{a}"][j] for a in "xyz")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", help="the run's output directory (probes.csv)")
    parser.add_argument("--consolidated", type=float, default=0.03, help="s: the consolidation stage's end")
    parser.add_argument("--grains-per-side", type=int, default=3)
    parser.add_argument("--radius", type=float, default=5e-4, help="m")
    parser.add_argument("--normal-stiffness", type=float, default=1e3, help="N/m")
    parser.add_argument("--bulk-modulus", type=float, default=1.19e5, help="Pa, the pore water's K_f")
    parser.add_argument("--no-plot", action="store_true", help="print only")
    args = parser.parse_args()
    probes = Path(args.out) / "probes.csv"
    if not probes.is_file():
        sys.exit(f"{probes}: no such file (run undrained_triaxial.toml with --out {args.out} first)")
    p = read_columns(probes)
    if p["time"][-1] <= args.consolidated:
        sys.exit(f"{probes}: the run ends at {p['time'][-1]} s, before the shear (--consolidated {args.consolidated})")
    rows, start = shear(p, args.consolidated)
    n = args.grains_per_side
    spheres = n**3 * 4.0 / 3.0 * math.pi * args.radius**3
    lattice = Lattice(n, args.radius, args.normal_stiffness, args.bulk_modulus, 1.0 - spheres / sample_volume(p, start))
    e1, u, p_eff, q = rows[-1]
    u0, p0, q0 = rows[0][1], rows[0][2], rows[0][3]
    a = (u - u0) / (lattice.b * (q - q0))
    print(
        f"e1 = {e1:.4e}: u = {u - u0:.4f} Pa (closed form {lattice.pore_pressure(e1):.4f}), "
        f"q = {q - q0:.4f} Pa (closed form {lattice.path(e1, p0)[1]:.4f}), p' = {p_eff:.4f} Pa "
        f"(closed form {lattice.path(e1, p0)[0]:.4f}); Skempton's A = {a:.4f} (B = {lattice.b:.5f})"
    )
    if args.no_plot:
        return
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    strains = [r[0] for r in rows]
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2))
    left.plot([1e2 * s for s in strains], [r[3] - q0 for r in rows], label="q, deviator")
    left.plot([1e2 * s for s in strains], [r[1] - u0 for r in rows], label="u, pore pressure")
    ends = [0.0, max(strains)]
    left.plot([1e2 * s for s in ends], [lattice.path(s, p0)[1] for s in ends], "k:", label="closed form")
    left.plot([1e2 * s for s in ends], [lattice.pore_pressure(s) for s in ends], "k:")
    left.set_xlabel("axial strain (%)")
    left.set_ylabel("Pa")
    left.legend()
    right.plot([r[2] for r in rows], [r[3] for r in rows], label="effective stress path")
    right.plot(*zip(*[lattice.path(s, p0) for s in ends]), "k:", label="closed form")
    right.plot([p0, p0 + max(r[3] for r in rows) / 3.0], [0.0, max(r[3] for r in rows)], "--", color="grey",
               label="total stress path")
    right.set_xlabel("p' (Pa)")
    right.set_ylabel("q (Pa)")
    right.legend()
    fig.tight_layout()
    out = Path(args.out) / "undrained_triaxial.png"
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
