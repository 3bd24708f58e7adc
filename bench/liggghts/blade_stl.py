#!/usr/bin/env python3
"""Writes the recoater blade of a spread scene as an ASCII STL box for LIGGGHTS's fix mesh/surface.

The blade is a flat-bottomed box: leading (+x) face at x = FRONT, THICKNESS behind it, bottom
edge at z = BOTTOM (plate + gap), top at z = TOP, across the strip y in [YLO, YHI]. LIGGGHTS
3.8.0 aborts when a mesh vertex lies exactly on a periodic face (MPI_ABORT at the first run's
set-up, with no message on screen or in the log: seen here with the blade's vertices at y = 0 and
y = L_y), so the blade is inset across by INSET x (YHI - YLO) on each side (default 1e-3: 0.5 um
on a 0.5 mm strip, far below any particle, none of which can slip through). Triangles are wound
so that normals point out.
Usage: blade_stl.py OUT.stl FRONT THICKNESS BOTTOM TOP YLO YHI [--inset F]   (SI units, m)
"""
import argparse


def box_triangles(lo, hi):
    """The 12 triangles (3 vertices each, counter-clockwise seen from outside) of a box."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7),  # bottom (-z), top (+z)
             (0, 1, 5, 4), (3, 7, 6, 2),  # front in y (-y), back (+y)
             (0, 4, 7, 3), (1, 2, 6, 5)]  # trailing (-x), leading (+x)
    tris = []
    for a, b, c, d in quads:
        tris.append((v[a], v[b], v[c]))
        tris.append((v[a], v[c], v[d]))
    return tris


def normal(t):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
    ux, uy, uz = bx - ax, by - ay, bz - az
    wx, wy, wz = cx - ax, cy - ay, cz - az
    nx, ny, nz = uy * wz - uz * wy, uz * wx - ux * wz, ux * wy - uy * wx
    norm = (nx * nx + ny * ny + nz * nz) ** 0.5
    return nx / norm, ny / norm, nz / norm


def write_stl(path, tris, name="blade"):
    lines = [f"solid {name}"]
    for t in tris:
        lines.append("  facet normal {:.9e} {:.9e} {:.9e}".format(*normal(t)))
        lines.append("    outer loop")
        for p in t:
            lines.append("      vertex {!r} {!r} {!r}".format(*p))
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append(f"endsolid {name}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def blade(front, thickness, bottom, top, ylo, yhi, inset=1e-3):
    """The blade's box corners (lo, hi), inset across the strip."""
    if not (thickness > 0 and top > bottom and yhi > ylo and 0 <= inset < 0.5):
        raise ValueError(f"blade: thickness {thickness}, bottom {bottom}, top {top}, y [{ylo}, {yhi}], "
                         f"inset {inset} (accepted: thickness > 0, top > bottom, yhi > ylo, 0 <= inset < 0.5)")
    margin = inset * (yhi - ylo)
    return (front - thickness, ylo + margin, bottom), (front, yhi - margin, top)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out")
    for name in ("front", "thickness", "bottom", "top", "ylo", "yhi"):
        parser.add_argument(name, type=float)
    parser.add_argument("--inset", type=float, default=1e-3)
    a = parser.parse_args()
    try:
        lo, hi = blade(a.front, a.thickness, a.bottom, a.top, a.ylo, a.yhi, a.inset)
    except ValueError as err:
        parser.exit(2, f"blade_stl.py: {err}\n")
    write_stl(a.out, box_triangles(lo, hi))


if __name__ == "__main__":
    main()
