#!/usr/bin/env python3
"""Draws a build's process map (docs/build.md "Process maps") from its map.json: one panel per
hatch spacing, laser power over scan speed, each point coloured by its region (dense, lack of
fusion, keyhole, balling; a second region as a ring), labelled with the porosity of the part's
interior (below its last layer), and the porosity's contours at 1, 5 and 10 % where the points
span an area. Written to PNG.tmp.<pid> and
renamed into place, so a killed run leaves no half picture.

`build --map.power ... --map.speed ...` runs it at the end (build/scripts/plot_build_map, with the
interpreter the build found); by hand: build/scripts/plot_build_map run/map.json run/map.png
Exit status: 0 drawn; 2 a bad file; 4 matplotlib, numpy missing (one line on stderr).
"""
import argparse
import json
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as err:
    sys.stderr.write(f"plot_build_map: {err} (Debian: python3-matplotlib python3-numpy)\n")
    sys.exit(4)

COLOURS = {"dense": "tab:green", "lack of fusion": "tab:orange", "keyhole": "tab:red",
           "balling": "tab:purple"}
CONTOURS = (0.01, 0.05, 0.10)  # porosity


class BadFile(Exception):
    pass


def load(path):
    try:
        with open(path) as f:
            data = json.load(f)
        points = data["map"]
        for p in points:
            for key in ("power", "speed", "hatch", "layer", "porosity", "regions"):
                p[key]  # noqa: B018 - a KeyError names what is missing
    except (OSError, ValueError, KeyError, TypeError) as err:
        raise BadFile(f"{path}: not a build map ({err!r}; accepted: the map.json of build --map.power ...)")
    if not points:
        raise BadFile(f"{path}: no points")
    return data


def contours(ax, points):
    """Porosity contours over (log v, P) where the points span an area."""
    v = np.log10([p["speed"] for p in points])
    power = np.array([p["power"] for p in points], dtype=float)
    porosity = np.array([p["porosity"] for p in points], dtype=float)
    levels = [c for c in CONTOURS if porosity.min() < c < porosity.max()]
    if len(points) < 3 or np.ptp(v) == 0 or np.ptp(power) == 0 or not levels:
        return
    try:
        lines = ax.tricontour(10 ** v, power, porosity, levels=levels, colors="0.3",
                              linewidths=1, linestyles="dashed")
    except (ValueError, RuntimeError):  # collinear points: no triangulation
        return
    ax.clabel(lines, fmt=lambda x: f"{x:.0%}", fontsize=7)


def panel(ax, points, hatch):
    for p in points:
        regions = p["regions"]
        ax.scatter(p["speed"], p["power"], s=170, c=COLOURS.get(regions[0], "tab:gray"),
                   edgecolors="k", zorder=3)
        if len(regions) > 1:
            ax.scatter(p["speed"], p["power"], s=340, facecolors="none",
                       edgecolors=COLOURS.get(regions[1], "tab:gray"), linewidths=2.5, zorder=2)
        ax.annotate(f"{p['porosity']:.1%}", (p["speed"], p["power"]), textcoords="offset points",
                    xytext=(0, 12), ha="center", fontsize=7)
    contours(ax, points)
    layer = points[0]["layer"]
    ax.set_title(f"hatch {hatch * 1e6:.0f} µm, layer {layer * 1e6:.0f} µm", fontsize=9)
    ax.set_xscale("log")
    speeds = sorted({p["speed"] for p in points})
    ax.set_xticks(speeds, [f"{v:g}" for v in speeds])
    ax.minorticks_off()
    powers = [p["power"] for p in points]
    span = max(powers) - min(powers) or max(powers)
    ax.set_xlim(min(speeds) / 1.35, max(speeds) * 1.35)
    ax.set_ylim(min(powers) - 0.15 * span, max(powers) + 0.2 * span)
    ax.grid(alpha=0.3)
    ax.set_xlabel("scan speed (m/s)")


def draw(data):
    hatches = sorted({p["hatch"] for p in data["map"]})
    fig, axes = plt.subplots(1, len(hatches), figsize=(4.8 * len(hatches) + 2.2, 4.6), squeeze=False)
    for ax, hatch in zip(axes[0], hatches):
        panel(ax, [p for p in data["map"] if p["hatch"] == hatch], hatch)
    axes[0][0].set_ylabel("laser power (W)")
    for name, colour in COLOURS.items():
        axes[0][-1].scatter([], [], c=colour, edgecolors="k", label=name)
    axes[0][-1].plot([], [], color="0.3", linestyle="dashed", label="porosity contours")
    axes[0][-1].legend(fontsize=8, loc="center left", bbox_to_anchor=(1.02, 0.5))
    fig.suptitle("build process map: the porosity of the part's interior (below its last layer) "
                 f"at each point (dense below {data.get('dense_porosity', 0.01):.0%})", fontsize=10)
    fig.tight_layout()
    return fig


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("map", help="a build's map.json")
    p.add_argument("png", help="the picture to write")
    args = p.parse_args()
    try:
        data = load(args.map)
    except BadFile as err:
        sys.stderr.write(f"plot_build_map: {err}\n")
        return 2
    fig = draw(data)
    temp = f"{args.png}.tmp.{os.getpid()}"
    try:
        fig.savefig(temp, dpi=120, format="png", bbox_inches="tight")
        os.replace(temp, args.png)
    finally:
        plt.close(fig)
        if os.path.exists(temp):
            os.remove(temp)
    print(args.png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
