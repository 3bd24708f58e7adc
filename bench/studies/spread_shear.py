#!/usr/bin/env python3
"""Where the blade's powder goes: the velocity and solid fraction of the powder around the blade
of data/scenes/spread-blade.ini, in the blade's frame (issue 32: the layer it leaves is ~0.15
dense and its top lies ~68 µm below the blade's bottom).

Writes docs/results/spread-shear.md and spread-shear.png (matplotlib, Agg). Run with
/usr/bin/python3 after building deposit (POWDERBED_BUILD selects the build folder):
    POWDERBED_BUILD=build python3 bench/studies/spread_shear.py [--work DIR]

`deposit` writes no trajectory for a spread (--trajectory is a drop option), so each frame is
the scene's layer stopped while the blade is mid-travel: `deposit --config
data/scenes/spread-blade.ini --seed 1 --threads 1 --recoater.end X --recoater.settle 0
--recoater.overflow false --out eX.h5`, X = 0.9, 1.1, ..., 1.7 mm. The tool's x is start +
speed (t - delay) clamped at the end, so each such run is the full run's steps up to the moment
the blade's centre reaches X (nothing settles, nothing is removed); the bed file holds every
particle's velocity and /restart holds the tool's x. Each particle is cut into the points of a
9^3 lattice that lie inside it, each carrying its share of the sphere's volume, and the points
are binned by x - x_blade (-0.5 to +1 mm, 25 µm bins) and z (0 to 0.3 mm, 15 µm bins): per bin
the solid fraction (solid volume / bin volume, the strip's 0.5 mm width in y) and the
volume-weighted mean vx over the blade's speed U, the bins of the five frames summed together
(a steady state in the blade's frame). The table gives vx/U and the solid fraction in 15 µm
slices of z in three 25 µm columns: centred on the blade's mid-plane, on its trailing edge and
100 µm behind the edge; h_left = ∫ φ (1 - vx/U) dz over the gap is the solid the blade leaves
behind per plate area (the flux through a column in the blade's frame), to compare with the
solid height of the layer (layer density x gap); the whole layer is run too (its quick-look
density). The runs are kept in --work (default
out/studies/spread-shear) and reused; results.json there keeps the load of the call that ran
them.
"""
import argparse
import json
import os

import h5py
import numpy as np

from lib.apps import ROOT, app, run_json
from lib.report import load_average, machine, table_head, table_row, write_page
from lib.spread_scene import Scene

SCENE = os.path.join(ROOT, "data", "scenes", "spread-blade.ini")
WORK = os.path.join(ROOT, "out", "studies", "spread-shear")
FRAMES_MM = [0.9, 1.1, 1.3, 1.5, 1.7]
XI = np.arange(-500e-6, 1000e-6 + 1e-9, 25e-6)   # x - x_blade bin edges
Z = np.arange(0, 300e-6 + 1e-9, 15e-6)
LATTICE = 9


def frame_args(x_mm, out):
    """deposit's command for the frame at blade x = x_mm (mm); None: the scene's whole layer."""
    args = [app("deposit"), "--config", SCENE, "--seed", "1", "--threads", "1", "--out", out]
    if x_mm is None:
        return args
    return args + ["--recoater.end", f"{x_mm}e-3", "--recoater.settle", "0",
                   "--recoater.overflow", "false"]


def run_frames(work):
    """Runs the missing frames; returns results.json (the load before and after the runs)."""
    path = os.path.join(work, "results.json")
    if os.path.exists(path) and all(os.path.exists(os.path.join(work, f"e{x}.h5"))
                                    for x in FRAMES_MM + ["l"]):
        return json.load(open(path))
    os.makedirs(work, exist_ok=True)
    before, walls = load_average(), {}
    full, _ = run_json(frame_args(None, os.path.join(work, "l.h5")))
    for x in FRAMES_MM:
        summary, _ = run_json(frame_args(x, os.path.join(work, f"e{x}.h5")))
        walls[str(x)] = summary["wall_time"]
    result = {"walls": walls, "full": {"wall": full["wall_time"],
                                       "density": full["layers"][0]["density_under_gap"]},
              "machine": machine(before, load_average(), program=app("deposit"))}
    json.dump(result, open(path, "w"), indent=1)
    return result


def lattice():
    """Points of a LATTICE^3 grid in the unit cube that lie in the unit sphere (offsets/radius)."""
    c = (np.arange(LATTICE) + 0.5) / LATTICE * 2 - 1
    p = np.stack(np.meshgrid(c, c, c, indexing="ij"), -1).reshape(-1, 3)
    return p[(p ** 2).sum(1) <= 1]


def binned(work):
    """Solid volume and volume x vx per (xi, z) bin, summed over the frames; frames' count."""
    pts = lattice()
    vol = np.zeros((len(XI) - 1, len(Z) - 1))
    mom = np.zeros_like(vol)
    for x in FRAMES_MM:
        with h5py.File(os.path.join(work, f"e{x}.h5"), "r") as f:
            p = f["particles/position"][:]
            r = f["particles/radius"][:]
            v = f["particles/velocity"][:]
            tool_x = f["restart"].attrs["tool_x"]
        share = (4 / 3 * np.pi * r ** 3) / len(pts)
        xi = (p[:, 0, None] + r[:, None] * pts[None, :, 0] - tool_x).ravel()
        z = (p[:, 2, None] + r[:, None] * pts[None, :, 2]).ravel()
        w = np.repeat(share, len(pts))
        vol += np.histogram2d(xi, z, [XI, Z], weights=w)[0]
        mom += np.histogram2d(xi, z, [XI, Z], weights=w * np.repeat(v[:, 0], len(pts)))[0]
    return vol, mom


def plot(phi, u, scene, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    half, gap = scene.thickness / 2 * 1e6, scene.gap * 1e6
    fig, axes = plt.subplots(2, 1, figsize=(8, 5.2), sharex=True)
    ext = [XI[0] * 1e6, XI[-1] * 1e6, Z[0] * 1e6, Z[-1] * 1e6]
    shown = np.where(phi > 0.02, u, np.nan)
    for ax, data, label, kw in ((axes[0], shown, "vx / U", dict(cmap="coolwarm", vmin=-1, vmax=2)),
                                (axes[1], phi, "solid fraction", dict(cmap="viridis", vmin=0,
                                                                     vmax=0.65))):
        im = ax.imshow(data.T, origin="lower", extent=ext, aspect="auto", **kw)
        fig.colorbar(im, ax=ax, label=label)
        ax.add_patch(plt.Rectangle((-half, gap), 2 * half, Z[-1] * 1e6 - gap, fill=True,
                                   facecolor="0.85", edgecolor="k"))
        ax.set_ylabel("z (µm)")
    axes[1].set_xlabel("x − x_blade (µm; the blade moves to +x)")
    axes[0].set_title(f"blade frame, {len(FRAMES_MM)} frames (blade at "
                      f"{FRAMES_MM[0]}-{FRAMES_MM[-1]} mm); vx/U blank where φ < 0.02",
                      fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def region(vol, mom, speed, x0, x1, z0, z1):
    """Volume-weighted vx/U and solid over the bins with centres in [x0, x1) x [z0, z1)."""
    xc, zc = (XI[:-1] + XI[1:]) / 2, (Z[:-1] + Z[1:]) / 2
    m = ((xc >= x0) & (xc < x1))[:, None] & ((zc >= z0) & (zc < z1))[None, :]
    return mom[m].sum() / vol[m].sum() / speed


def conclusion(vol, mom, cu, cphi, h_left, speed, gap, half, full):
    """The page's reading of the numbers (a sentence each, the values from this run)."""
    heap = region(vol, mom, speed, half, half + 150e-6, gap, Z[-1])
    entry = region(vol, mom, speed, half, half + 25e-6, 0, gap)
    entry_low = region(vol, mom, speed, half, half + 25e-6, 0, 15e-6)
    entry_top = region(vol, mom, speed, half, half + 25e-6, gap - 15e-6, gap)
    cells = (XI[1] - XI[0]) * (Z[1] - Z[0]) * Scene(SCENE, {}).ly * len(FRAMES_MM)
    entry_phi = vol[np.argmin(abs(XI[:-1] - half)), :int(round(gap / (Z[1] - Z[0])))] / cells
    heap_phi = vol[(XI[:-1] >= half) & (XI[:-1] < half + 150e-6)][:, Z[:-1] >= gap].mean() / cells
    far = region(vol, mom, speed, XI[0], XI[0] + 50e-6, 0, 60e-6)
    mid_u, mid_phi = cu[0], cphi[0]
    top = ~np.isnan(mid_u)
    return [
        f"The powder is not carried along in the gap. What moves with the blade is the heap in "
        f"front of it above the gap's height (vx/U = {heap:.2f} over the 150 µm in front of the "
        f"leading edge, z > {gap * 1e6:.0f} µm), a wall ~150 µm thick at φ ~{heap_phi:.2f}. "
        "Below the "
        "gap's height the heap's bottom is sheared over the plate before it reaches the blade: at "
        f"the leading edge it moves at {entry:.2f} U on average ({entry_low:.1f} U at the plate, "
        f"{entry_top:.1f} U at the blade's bottom) and is already dilated (φ "
        f"{entry_phi.min():.2f}-{entry_phi.max():.2f}). Under the blade it moves at "
        f"{np.nanmin(mid_u):.2f}-{np.nanmax(mid_u[top]):.2f} U, a shear profile from the plate "
        "up, and the gap is only partly filled: φ "
        f"{mid_phi[0]:.2f}-{mid_phi[1]:.2f} in its lowest 30 µm, {mid_phi[-2]:.2f} at 60-75 µm "
        f"and {mid_phi[-1]:.2f} against the blade's bottom: the flat bottom barely touches "
        "powder. The gap's top at the leading edge moves nearly with the heap and adds little "
        "to the layer (φ (1 − vx/U) is small there); what passes under the blade is the slower "
        "powder near the plate. Behind the "
        f"trailing edge the layer keeps drifting forward ({np.nanmean(cu[1][:4]):.2f} U at the "
        f"edge, {np.nanmean(cu[2][:4]):.2f} U 100 µm behind, {far:.2f} U 400-500 µm behind, "
        "z < 60 µm): it is still slowing half a millimetre behind. The solid that passes back "
        "under the blade, "
        f"∫ φ (1 − vx/U) dz = {min(h_left) * 1e6:.1f}-{max(h_left) * 1e6:.1f} µm over the three "
        f"columns, is the layer: a density of {min(h_left) / gap:.2f}-{max(h_left) / gap:.2f} "
        f"over the {gap * 1e6:.0f} µm gap, the ~0.15 of spread-density.md (the whole layer's "
        f"quick look here: {full:.3f}). So no layer moves with the blade at ~U inside the gap; "
        "the whole gap is a shear "
        "zone between the heap at U and the plate, and the layer is sparse because the heap's "
        "sheared, dilated bottom (not a dense bed) is what the blade's edge leaves behind.",
    ]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--work", default=WORK)
    args = parser.parse_args()
    scene = Scene(SCENE, {})
    stored = run_frames(args.work)
    speed, gap, half, ly = scene.speed, scene.gap, scene.thickness / 2, scene.ly
    vol, mom = binned(args.work)
    cell = (XI[1] - XI[0]) * ly * (Z[1] - Z[0]) * len(FRAMES_MM)
    phi = vol / cell
    with np.errstate(invalid="ignore", divide="ignore"):
        u = mom / vol / speed
    plot(phi, u, scene, os.path.join(ROOT, "docs", "results", "spread-shear.png"))

    # The table's columns: 25 µm wide, centred on the blade's mid-plane, its trailing edge and
    # 100 µm behind the edge (the bins above are 25 µm from the edge: these are their own sums).
    pts = lattice()
    cols = [("mid-plane", 0.0), ("trailing edge", -half), ("100 µm behind", -half - 100e-6)]
    zc = np.arange(0, gap + 1e-12, 15e-6)
    cvol = np.zeros((len(cols), len(zc) - 1))
    cmom = np.zeros_like(cvol)
    for x in FRAMES_MM:
        with h5py.File(os.path.join(args.work, f"e{x}.h5"), "r") as f:
            p, r = f["particles/position"][:], f["particles/radius"][:]
            v, tool_x = f["particles/velocity"][:], f["restart"].attrs["tool_x"]
        w = np.repeat((4 / 3 * np.pi * r ** 3) / len(pts), len(pts))
        xi = (p[:, 0, None] + r[:, None] * pts[None, :, 0] - tool_x).ravel()
        z = (p[:, 2, None] + r[:, None] * pts[None, :, 2]).ravel()
        vx = np.repeat(v[:, 0], len(pts))
        for i, (_, c) in enumerate(cols):
            m = np.abs(xi - c) < 12.5e-6
            cvol[i] += np.histogram(z[m], zc, weights=w[m])[0]
            cmom[i] += np.histogram(z[m], zc, weights=w[m] * vx[m])[0]
    cphi = cvol / (25e-6 * ly * 15e-6 * len(FRAMES_MM))
    with np.errstate(invalid="ignore", divide="ignore"):
        cu = cmom / cvol / speed
    h_left = [float(np.nansum(cphi[i] * (1 - np.nan_to_num(cu[i])) * 15e-6)) for i in range(3)]
    h_moving = [float(np.nansum(cphi[i] * np.nan_to_num(cu[i]) * 15e-6)) for i in range(3)]

    def fmt(i, k):
        return "—" if cvol[i, k] == 0 else f"{cu[i, k]:.2f} / {cphi[i, k]:.2f}"

    rows = [*table_head("z (µm)", *(f"{name}: vx/U / φ" for name, _ in cols))]
    for k in range(len(zc) - 1):
        rows.append(table_row(f"{zc[k] * 1e6:.0f}–{zc[k + 1] * 1e6:.0f}",
                              *(fmt(i, k) for i in range(3))))
    rows.append(table_row("∫ φ (1 − vx/U) dz (µm)", *(f"{h * 1e6:.1f}" for h in h_left)))
    rows.append(table_row("∫ φ vx/U dz (µm)", *(f"{h * 1e6:.1f}" for h in h_moving)))
    stats = {"cols": [c for c, _ in cols], "u": cu.tolist(), "phi": cphi.tolist(),
             "h_left": h_left, "h_moving": h_moving, "zc": zc.tolist()}
    json.dump(stats, open(os.path.join(args.work, "columns.json"), "w"), indent=1)
    cmd = " ".join(["deposit"] + [os.path.relpath(a, ROOT) if a == SCENE else a
                                  for a in frame_args("X", "eX.h5")[1:]])
    lines = [
        "# The powder around the blade: velocity and solid fraction in the blade's frame",
        "",
        f"`python3 bench/studies/spread_shear.py` (method in the script's docstring): "
        f"{len(FRAMES_MM)} frames, `{cmd}` for X = {', '.join(map(str, FRAMES_MM))} mm (the "
        "scene's layer stopped as the blade's centre reaches X; `deposit` writes no trajectory "
        "for a spread: `--trajectory` exits 2 with recoater.tool), one thread, wall "
        f"{', '.join(f'{w:.1f}' for w in stored['walls'].values())} s; the whole layer "
        f"(`deposit --config data/scenes/spread-blade.ini --seed 1 --threads 1 --out l.h5`) "
        f"{stored['full']['wall']:.1f} s, quick-look density {stored['full']['density']:.3f}.  ",
        stored["machine"],
        "",
        "![vx/U and solid fraction around the blade](spread-shear.png)",
        "",
        f"Blade: 200 µm thick, bottom at z = {gap * 1e6:.0f} µm, trailing edge at x − x_blade = "
        f"−{half * 1e6:.0f} µm, U = {speed} m/s. Columns 25 µm wide centred where named; each "
        "cell vx/U (volume-weighted) / solid fraction φ, the five frames together. The last "
        "two rows: the solid per plate area that stays behind the blade (flux through the column "
        "in the blade's frame, over U) and that moves with it.",
        "",
        *rows,
        "",
        *conclusion(vol, mom, cu, cphi, h_left, speed, gap, half, stored['full']['density']),
    ]
    print(write_page("spread-shear.md", "\n".join(lines) + "\n"))


if __name__ == "__main__":
    main()
