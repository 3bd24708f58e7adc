#!/usr/bin/env python3
"""Draws the top view of a spread layer from `bedstat BED --spread --height-map MAP.csv` to a PNG.

The CSV has one row per raster cell (x, y of its centre, height of the powder surface above the
plate, covered 0/1; SI units, x fastest; docs/spread-layer.md). The image shows the height in um
with bare plate (covered = 0) in grey, x along the spreading direction.
Usage: scripts/plot_height_map.py MAP.csv OUT.png [--title TEXT] [--vmax HEIGHT_M]
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def load(path):
    """The map as 2D arrays (ny x nx) of height and covered, and the cell centres' x and y."""
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if header != ["x", "y", "height", "covered"]:
            sys.exit(f"plot_height_map: {path}: header {header} (accepted: x,y,height,covered)")
        rows = np.array([[float(v) for v in row] for row in reader if row])
    if rows.size == 0:
        sys.exit(f"plot_height_map: {path}: no cells")
    xs, ys = np.unique(rows[:, 0]), np.unique(rows[:, 1])
    if len(xs) * len(ys) != len(rows):
        sys.exit(f"plot_height_map: {path}: {len(rows)} cells are not a {len(xs)} x {len(ys)} raster")
    height = rows[:, 2].reshape(len(ys), len(xs))
    covered = rows[:, 3].reshape(len(ys), len(xs)) > 0.5
    return xs, ys, height, covered


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("map")
    parser.add_argument("out")
    parser.add_argument("--title", default=None)
    parser.add_argument("--vmax", type=float, default=None, help="top of the colour scale (m)")
    args = parser.parse_args()
    xs, ys, height, covered = load(args.map)
    um = 1e-6
    dx = xs[1] - xs[0] if len(xs) > 1 else 1.0
    dy = ys[1] - ys[0] if len(ys) > 1 else 1.0
    extent = [(xs[0] - dx / 2) / um, (xs[-1] + dx / 2) / um, (ys[0] - dy / 2) / um, (ys[-1] + dy / 2) / um]
    shown = np.ma.masked_where(~covered, height / um)
    cmap = plt.get_cmap("viridis").copy()
    cmap.set_bad("0.6")  # bare plate
    width = 10.0
    aspect = (extent[3] - extent[2]) / (extent[1] - extent[0])
    fig, ax = plt.subplots(figsize=(width, max(2.0, width * aspect + 1.2)))
    image = ax.imshow(shown, origin="lower", extent=extent, cmap=cmap, vmin=0,
                      vmax=None if args.vmax is None else args.vmax / um, interpolation="nearest")
    ax.set_xlabel("x (um), spreading direction")
    ax.set_ylabel("y (um)")
    ax.set_aspect("equal")
    ax.set_title(args.title or f"{args.map}: coverage {covered.mean():.3f}, grey = bare plate")
    fig.colorbar(image, ax=ax, label="height above plate (um)", shrink=0.8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=150)
    print(f"plot_height_map: wrote {args.out} ({len(xs)} x {len(ys)} cells)")


if __name__ == "__main__":
    main()
