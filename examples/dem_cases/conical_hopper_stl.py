#!/usr/bin/python3
"""Writes conical_hopper.stl, the mesh wall of conical_hopper.toml: a
cylinder of radius 15 mm on a cone that narrows at 30 degrees from the
vertical to an orifice of radius 6 mm at z = 0, in mm (the scene scales it
by 0.001), as an ASCII STL file. Each ring of the surface has `SIDES`
corners; the facets' normals point inwards, to the grains (a mesh wall is
touched from either side, so this is only for viewers)."""
import math
import pathlib

SIDES = 48
ORIFICE = 6.0  # mm, radius at z = 0
RADIUS = 15.0  # mm, the cylinder's
HALF_ANGLE = math.radians(30.0)  # the cone's, from the vertical
TOP = 45.0  # mm, the cylinder's top

cone_top = (RADIUS - ORIFICE) / math.tan(HALF_ANGLE)
rings = [(ORIFICE, 0.0), (RADIUS, cone_top), (RADIUS, TOP)]


def corner(ring, k):
    r, z = rings[ring]
    a = 2.0 * math.pi * (k % SIDES) / SIDES  # the seam closes on the first corner
    return (r * math.cos(a), r * math.sin(a), z)


def facet(out, a, b, c):
    # Normal (b - a) x (c - a), normalised.
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    size = math.sqrt(sum(x * x for x in n))
    out.append("  facet normal {:.9g} {:.9g} {:.9g}\n    outer loop\n".format(*(x / size for x in n)))
    for p in (a, b, c):
        out.append("      vertex {:.9g} {:.9g} {:.9g}\n".format(*p))
    out.append("    endloop\n  endfacet\n")


def main():
    out = ["solid conical_hopper\n"]
    for ring in range(len(rings) - 1):
        for k in range(SIDES):
            a, b = corner(ring, k), corner(ring, k + 1)
            c, d = corner(ring + 1, k), corner(ring + 1, k + 1)
            facet(out, a, c, b)  # inwards
            facet(out, b, c, d)
    out.append("endsolid conical_hopper\n")
    path = pathlib.Path(__file__).with_name("conical_hopper.stl")
    path.write_text("".join(out))
    print(f"{path}: {2 * SIDES * (len(rings) - 1)} facets")


if __name__ == "__main__":
    main()
