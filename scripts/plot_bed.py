#!/usr/bin/env python3
"""Draws a bed file (HDF5, docs/bed-format.md) to a PNG with true radii.

2D beds: the disks. 3D beds: a top view (x-y) and a side view (x-z) of the spheres as circles,
drawn back to front so nearer particles cover farther ones.
Usage: scripts/plot_bed.py BED.h5 OUT.png [--color radius|z|temperature|phase] [--title TEXT]
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Circle, Rectangle  # noqa: E402


def load(path):
    with h5py.File(path, "r") as f:
        if f.attrs.get("format") != "powderbed.bed":
            sys.exit(f"plot_bed: {path}: not a powderbed bed file")
        bed = {
            "dimension": int(f.attrs["dimension"]),
            "lower": np.array(f["domain"].attrs["lower"]),
            "upper": np.array(f["domain"].attrs["upper"]),
            "position": np.array(f["particles/position"]),
            "radius": np.array(f["particles/radius"]),
        }
        for name in ("temperature", "phase"):
            if f"particles/{name}" in f:
                bed[name] = np.array(f[f"particles/{name}"])
    return bed


def draw(ax, centres, radii, values, lower, upper, cmap, norm, um):
    order = np.argsort(values[1]) if values[1] is not None else np.arange(len(radii))
    patches = [Circle(centres[i] / um, radii[i] / um) for i in order]
    coll = PatchCollection(patches, cmap=cmap, norm=norm, edgecolor="k", linewidth=0.2)
    coll.set_array(values[0][order])
    ax.add_collection(coll)
    ax.add_patch(Rectangle(lower / um, *((upper - lower) / um), fill=False, lw=0.8))
    ax.set_xlim(lower[0] / um, upper[0] / um)
    ax.set_ylim(lower[1] / um, upper[1] / um)
    ax.set_aspect("equal")
    return coll


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("bed")
    parser.add_argument("out")
    parser.add_argument("--color", default="radius", choices=["radius", "z", "temperature", "phase"])
    parser.add_argument("--title", default=None)
    args = parser.parse_args()
    bed = load(args.bed)
    pos, rad = bed["position"], bed["radius"]
    if args.color in ("temperature", "phase") and args.color not in bed:
        sys.exit(f"plot_bed: {args.bed}: no /particles/{args.color} to colour by")
    colour = {"radius": rad, "z": pos[:, 2]}.get(args.color, bed.get(args.color))
    lo_c, hi_c = float(colour.min()), float(colour.max())
    if hi_c <= lo_c:  # one value (a monodisperse bed): a narrow band around it
        pad = abs(lo_c) * 0.01 or 1.0
        lo_c, hi_c = lo_c - pad, hi_c + pad
    norm = matplotlib.colors.Normalize(lo_c, hi_c)
    cmap = "viridis"
    um = 1e-6
    lo, hi = bed["lower"], bed["upper"]
    if bed["dimension"] == 2:
        fig, ax = plt.subplots(figsize=(6, 6 * (hi[1] - lo[1]) / (hi[0] - lo[0]) + 0.6))
        coll = draw(ax, pos[:, :2], rad, (colour, None), lo[:2], hi[:2], cmap, norm, um)
        ax.set_xlabel("x (µm)")
        ax.set_ylabel("y (µm)")
        axes = [ax]
    else:
        # Top view: higher particles drawn last; side view: particles with larger y (farther from
        # a viewer at y = -inf) drawn first.
        height = max(hi[2] - lo[2], 4 * rad.max())
        top_hi = np.array([hi[0], hi[1]])
        ratio_top = (hi[1] - lo[1]) / (hi[0] - lo[0])
        ratio_side = min(pos[:, 2].max() + rad.max() - lo[2], height) / (hi[0] - lo[0])
        fig, axes = plt.subplots(2, 1, figsize=(9, 9 * (ratio_top + ratio_side) + 1.2),
                                 gridspec_kw={"height_ratios": [ratio_top, max(ratio_side, 0.05)]})
        coll = draw(axes[0], pos[:, [0, 1]], rad, (colour, pos[:, 2]), lo[:2], top_hi, cmap, norm, um)
        axes[0].set_ylabel("y (µm)")
        axes[0].set_title("top view", fontsize=9, loc="left")
        side_hi = np.array([hi[0], lo[2] + ratio_side * (hi[0] - lo[0])])
        draw(axes[1], pos[:, [0, 2]], rad, (colour, -pos[:, 1]), np.array([lo[0], lo[2]]), side_hi, cmap, norm, um)
        axes[1].set_xlabel("x (µm)")
        axes[1].set_ylabel("z (µm)")
        axes[1].set_title("side view (from y = −∞)", fontsize=9, loc="left")
    label = {"radius": "radius (m)", "z": "z (m)", "temperature": "temperature (K)", "phase": "phase"}[args.color]
    fig.colorbar(coll, ax=axes, label=label, shrink=0.8)
    if args.title:
        fig.suptitle(args.title)
    fig.savefig(args.out, dpi=110)


if __name__ == "__main__":
    main()
