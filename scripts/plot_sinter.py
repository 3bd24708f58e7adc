#!/usr/bin/env python3
"""Draws a sinter run (sinter --out RUN.h5) like [GZ] Fig. 11: peak temperatures over the whole
track, as a top view (substrate top face and particles from above) and as the cross-section on
the plane x = Lx/2 where the melt pool is measured (substrate section and the particles the plane
cuts), with the melting isotherm T_m drawn as a white line and the measured melt pool quoted.

Usage: scripts/plot_sinter.py RUN.h5 OUT_PREFIX [--title TEXT]
writes OUT_PREFIX-top.png and OUT_PREFIX-section.png.
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

UM = 1e6  # metres -> micrometres on the axes


def load(path):
    with h5py.File(path, "r") as f:
        if f.attrs.get("format") != "powderbed.sinter-run":
            sys.exit(f"plot_sinter: {path}: not a sinter run file")
        sub = f["substrate"].attrs
        melt = f["melt"]
        return {
            "origin": np.array(sub["origin"]),
            "spacing": np.array(sub["spacing"]),
            "nodes": np.array(sub["nodes"]).astype(int),
            # the plate's top plane (planes above it are room for a raised part); older files: the last
            "plate_plane": int(sub["plate_plane"]) if "plate_plane" in sub
            else int(np.array(sub["nodes"])[2]) - 1,
            "position": np.array(f["particles/position"]),
            "radius": np.array(f["particles/radius"]),
            "particle_peak": np.array(melt["particle"]),
            "top": np.array(melt["top"]),
            "section_x": np.array(melt["section_x"]),
            "t_m": float(melt.attrs["melting_point"]),
            "x_plane": float(melt.attrs["x_plane"]),
            "pool": [float(melt.attrs[k]) for k in ("height", "width", "depth")],
        }


def draw_particles(ax, centres, radii, peaks, norm, cmap, t_m):
    patches = [Circle((c[0] * UM, c[1] * UM), r * UM) for c, r in zip(centres, radii)]
    coll = PatchCollection(patches, cmap=cmap, norm=norm, linewidths=0.3)
    coll.set_array(peaks)
    coll.set_edgecolor(["white" if p >= t_m else "black" for p in peaks])
    ax.add_collection(coll)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run")
    parser.add_argument("prefix")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    r = load(args.run)
    (x0, y0, z_top), (dx, dy, dz), (nx, ny, nz) = r["origin"], r["spacing"], r["nodes"]
    t_m = r["t_m"]
    vmax = max(r["particle_peak"].max(initial=t_m), r["top"].max(), t_m)
    norm = matplotlib.colors.Normalize(vmin=r["top"].min(), vmax=vmax)
    cmap = plt.get_cmap("inferno")
    height, width, depth = (v * UM for v in r["pool"])
    pool_text = f"melt pool: height {height:.1f} um, width {width:.1f} um, depth {depth:.1f} um"

    # Top view: substrate peak on the top face, particles drawn from the lowest up.
    xs = (x0 + dx * np.arange(nx)) * UM
    ys = (y0 + dy * np.arange(ny)) * UM
    fig, ax = plt.subplots(figsize=(10, 5.6))
    ax.pcolormesh(xs, ys, r["top"], cmap=cmap, norm=norm, shading="auto")
    order = np.argsort(r["position"][:, 2])
    draw_particles(ax, r["position"][order, :2], r["radius"][order], r["particle_peak"][order],
                   norm, cmap, t_m)
    ax.contour(xs, ys, r["top"], levels=[t_m], colors="cyan", linewidths=1.0)
    ax.axvline(r["x_plane"] * UM, color="white", linestyle=":", linewidth=0.8)
    ax.set_aspect("equal")
    ax.set_xlim(xs[0], xs[-1])
    ax.set_ylim(ys[0], ys[-1])
    ax.set_xlabel("x (um)")
    ax.set_ylabel("y (um)")
    ax.set_title((args.title + "\n" if args.title else "") +
                 "peak temperature, top view (white edge: particle melted; cyan: substrate T_m)")
    fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, label="peak T (K)")
    fig.tight_layout()
    fig.savefig(args.prefix + "-top.png", dpi=130)
    plt.close(fig)

    # Cross-section on x = x_plane: substrate section and the circles the plane cuts.
    zs = (z_top + dz * (np.arange(nz) - r["plate_plane"])) * UM
    fig, ax = plt.subplots(figsize=(10, 5.2))
    ax.pcolormesh(ys, zs, r["section_x"], cmap=cmap, norm=norm, shading="auto")
    ax.contour(ys, zs, r["section_x"], levels=[t_m], colors="cyan", linewidths=1.2)
    offset = r["position"][:, 0] - r["x_plane"]
    cut = np.abs(offset) < r["radius"]
    cut_radius = np.sqrt(r["radius"][cut] ** 2 - offset[cut] ** 2)
    draw_particles(ax, r["position"][cut][:, 1:3], cut_radius, r["particle_peak"][cut], norm,
                   cmap, t_m)
    y_mid = (y0 + 0.5 * dy * (ny - 1)) * UM
    ax.set_xlim(y_mid - 150, y_mid + 150)
    ax.set_ylim(z_top * UM - 80, z_top * UM + 70)
    ax.set_aspect("equal")
    ax.set_xlabel("y (um)")
    ax.set_ylabel("z (um)")
    ax.set_title((args.title + "\n" if args.title else "") +
                 f"peak temperature on x = {r['x_plane'] * UM:.0f} um; {pool_text}")
    fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, label="peak T (K)")
    fig.tight_layout()
    fig.savefig(args.prefix + "-section.png", dpi=130)
    plt.close(fig)


if __name__ == "__main__":
    main()
