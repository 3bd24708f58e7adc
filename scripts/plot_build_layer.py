#!/usr/bin/env python3
"""Draws the pictures of one layer of a build (docs/build.md "Pictures") from its scan file
layer-NNN-scan.h5: PREFIX-top.png (the particles by what the scan made of them, over the
scanned columns), PREFIX-fusion.png (the lack-of-fusion map), PREFIX-height.png (the solid's
top above the plate) and PREFIX-section.png (a cross-section of the part so far: the solid that
melted and the solid that never did, its pores; thermal/part_porosity.hpp). Each is written to PREFIX-NAME.png.tmp.<pid> and renamed into place, so a
killed run leaves no half picture. Prints the pictures' paths, one a line.

`build` runs it after each layer (build/scripts/plot_build_layer, with the interpreter the build
found); by hand: build/scripts/plot_build_layer run/layer-001-scan.h5 run/layer-001
Exit status: 0 drawn; 2 a bad file; 4 matplotlib, numpy or h5py missing (one line on stderr).
"""
import argparse
import os
import re
import sys

try:
    import h5py
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.collections import EllipseCollection
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch
    from mpl_toolkits.axes_grid1 import make_axes_locatable
except ImportError as err:
    sys.stderr.write(f"plot_build_layer: {err} (Debian: python3-matplotlib python3-h5py)\n")
    sys.exit(4)

UM = 1e-6
# Particle states of /fusion/state (thermal/fusion.hpp) and the colours they are drawn in.
STATES = ((0, "powder", "#b8b0a0"), (1, "fused", "#e6550d"), (2, "vaporised", "#756bb1"),
          (3, "balled", "#252525"))
# Cells of /fusion/lack_of_fusion (thermal/lack_of_fusion.hpp) and their colours.
LOF_CELLS = ((0, "not scanned", "#e0e0e0"), (1, "bonded", "#31a354"),
             (2, "lack of fusion", "#de2d26"))
SCANNED = "#c6dbef"  # the scanned columns under the particles of the top view


class BadFile(Exception):
    pass


def dataset(f, path, shape=None):
    if path not in f:
        raise BadFile(f"{f.filename}: no {path} (accepted: a build's layer-NNN-scan.h5)")
    data = f[path][...]
    if shape is not None and data.shape != shape:
        raise BadFile(f"{f.filename}: {path} has shape {data.shape}, expected {shape}")
    return data


def load(path):
    """The layer's particles (x, y, z, r, state), the grid's node coordinates and its maps."""
    try:
        f = h5py.File(path, "r")
    except OSError as err:
        raise BadFile(f"{path}: cannot open ({err})") from None
    with f:
        position = dataset(f, "/particles/position")
        n = position.shape[0]
        surface = dataset(f, "/fusion/surface")
        grid = surface.shape[:2]
        return {
            "x": position[:, 0], "y": position[:, 1], "z": position[:, 2],
            "r": dataset(f, "/particles/radius", (n,)),
            "state": dataset(f, "/fusion/state", (n,)),
            "gx": surface[0, :, 0], "gy": surface[:, 0, 1],
            "height": dataset(f, "/fusion/height", grid),
            "lof": dataset(f, "/fusion/lack_of_fusion", grid),
            "lof_fraction": float(f["/fusion"].attrs.get("lack_of_fusion_fraction", np.nan)),
            "part_solid": dataset(f, "/part/solid_fraction"),
            "part_never": dataset(f, "/part/never_molten_fraction"),
            "part_scanned": dataset(f, "/part/scanned", grid),
            "part_layers": int(f["/part"].attrs["layers"]),
            "part_porosity": float(f["/part"].attrs["porosity"]),
            "interior_porosity": float(f["/part"].attrs.get("interior_porosity", np.nan)),
            "dz": float(f["/part"].attrs["dz"]),
        }


def extent_um(d):
    """The map's extent in um: each column owns the cell around its node."""
    gx, gy = d["gx"], d["gy"]
    dx = gx[1] - gx[0] if len(gx) > 1 else 1.0
    dy = gy[1] - gy[0] if len(gy) > 1 else 1.0
    return [(gx[0] - dx / 2) / UM, (gx[-1] + dx / 2) / UM, (gy[0] - dy / 2) / UM,
            (gy[-1] + dy / 2) / UM]


def figure(d):
    """A figure sized to the plate's aspect, with axes in um."""
    x0, x1, y0, y1 = extent_um(d)
    width = 10.0  # inches; the height follows the plate's aspect within [2.5, 12]
    fig, ax = plt.subplots(figsize=(width, min(12.0, max(2.5, width * (y1 - y0) / (x1 - x0) + 1.2))))
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x (µm), spreading direction")
    ax.set_ylabel("y (µm)")
    return fig, ax


def draw_top(d, layer):
    fig, ax = figure(d)
    scanned = np.ma.masked_where(d["lof"] == 0, np.ones(d["lof"].shape))
    ax.imshow(scanned, origin="lower", extent=extent_um(d), cmap=ListedColormap([SCANNED]),
              interpolation="nearest")
    order = np.argsort(d["z"])  # the highest particles drawn last, as seen from above
    colours = {state: colour for state, _, colour in STATES}
    facecolors = [colours.get(int(s), "black") for s in d["state"][order]]
    ax.add_collection(EllipseCollection(
        2 * d["r"][order] / UM, 2 * d["r"][order] / UM, np.zeros(len(order)), units="xy",
        offsets=np.column_stack([d["x"][order], d["y"][order]]) / UM,
        offset_transform=ax.transData, facecolors=facecolors, edgecolors="0.25", linewidths=0.3))
    counts = {state: int(np.sum(d["state"] == state)) for state, _, _ in STATES}
    handles = [Patch(facecolor=c, edgecolor="0.25", label=f"{name} ({counts[s]})")
               for s, name, c in STATES]
    handles.append(Patch(facecolor=SCANNED, label="scanned area"))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1), borderaxespad=0)
    ax.set_title(f"layer {layer}: the particles after the scan, {len(order)} spread")
    return fig


def draw_fusion(d, layer):
    fig, ax = figure(d)
    colours = ListedColormap([c for _, _, c in LOF_CELLS])
    ax.imshow(d["lof"], origin="lower", extent=extent_um(d), cmap=colours, vmin=-0.5, vmax=2.5,
              interpolation="nearest")
    cells = d["lof"].size
    handles = [Patch(facecolor=c, edgecolor="0.25",
                     label=f"{name} ({np.sum(d['lof'] == v) / cells:.1%} of the plate)")
               for v, name, c in LOF_CELLS]
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1), borderaxespad=0)
    ax.set_title(f"layer {layer}: lack of fusion, {d['lof_fraction']:.1%} of the scanned area")
    return fig


def draw_height(d, layer):
    fig, ax = figure(d)
    h = d["height"] / UM
    image = ax.imshow(h, origin="lower", extent=extent_um(d), cmap="viridis", vmin=0,
                      vmax=max(float(h.max()), 1e-3), interpolation="nearest")
    # A bar as tall as the map, whatever the plate's aspect.
    bar = make_axes_locatable(ax).append_axes("right", size=0.2, pad=0.15)
    fig.colorbar(image, cax=bar, label="height (µm)")
    ax.set_title(f"layer {layer}: the solid's top, {h.min():.1f} to {h.max():.1f} µm above the plate")
    return fig


def draw_section(d, layer):
    """The part on the row of columns (fixed y) that holds the most of its core (the columns every
    layer scanned): each cell of dz coloured by what its solid is, molten once or never; height
    stretched, the part being thin."""
    core = d["part_scanned"] == d["part_layers"]
    j = int(np.argmax(core.sum(axis=1)))
    solid, never = d["part_solid"][:, j, :], d["part_never"][:, j, :]
    nk = solid.shape[0]
    rgba = np.ones((max(nk, 1), solid.shape[1], 4))
    molten_colour, never_colour = np.array([0.35, 0.45, 0.6]), np.array([0.87, 0.18, 0.15])
    if nk > 0:
        molten = np.clip(solid - never, 0, 1)[..., None]
        rgba[..., :3] = 1 - molten * (1 - molten_colour) - never[..., None] * (1 - never_colour)
    x0, x1, _, _ = extent_um(d)
    top = max(nk, 1) * d["dz"] / UM
    fig, ax = plt.subplots(figsize=(10.0, 3.2))
    ax.imshow(np.clip(rgba, 0, 1), origin="lower", extent=[x0, x1, 0, top], aspect="auto",
              interpolation="nearest")
    span = core[j]
    if span.any():
        xs = d["gx"][span] / UM
        ax.axvspan(xs.min(), xs.max(), ymin=0, ymax=0.03, color="0.2")
    ax.set_xlabel("x (µm), spreading direction")
    ax.set_ylabel("z above the plate (µm)")
    ax.legend(handles=[Patch(facecolor=molten_colour, label="solid, melted"),
                       Patch(facecolor=never_colour, label="solid, never molten (pores' powder)"),
                       Patch(facecolor="0.2", label="the core (every layer scanned)")],
              loc="upper left", bbox_to_anchor=(1.01, 1), borderaxespad=0)
    ax.set_title(f"layer {layer}: the part at y = {d['gy'][j] / UM:.0f} µm; porosity of the core "
                 f"{d['part_porosity']:.2%}, below the last layer {d['interior_porosity']:.2%} "
                 "(height stretched)")
    return fig


def save(fig, path):
    """Writes the picture to a temporary beside `path` and renames it into place."""
    temp = f"{path}.tmp.{os.getpid()}"
    try:
        fig.savefig(temp, dpi=120, format="png", bbox_inches="tight")
        os.replace(temp, path)
    finally:
        plt.close(fig)
        if os.path.exists(temp):
            os.remove(temp)


def layer_number(path):
    found = re.search(r"layer-(\d+)", os.path.basename(path))
    return int(found.group(1)) if found else "?"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scan", help="a build's layer-NNN-scan.h5")
    p.add_argument("prefix", help="the pictures go to PREFIX-top.png, PREFIX-fusion.png, "
                   "PREFIX-height.png, PREFIX-section.png")
    p.add_argument("--layer", type=int, help="the layer number in the titles (default: from the "
                   "file name)")
    args = p.parse_args()
    try:
        d = load(args.scan)
    except BadFile as err:
        sys.stderr.write(f"plot_build_layer: {err}\n")
        return 2
    layer = args.layer if args.layer is not None else layer_number(args.scan)
    for name, draw in (("top", draw_top), ("fusion", draw_fusion), ("height", draw_height),
                       ("section", draw_section)):
        path = f"{args.prefix}-{name}.png"
        save(draw(d, layer), path)
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
