"""What the sinter studies share: the [GZ] bed (deposited once from the paper's scene and kept in
out/studies/), one run of `sinter` with --json, and the paper's numbers."""
import os
import subprocess

from common import ROOT, app, run_json

SCENE = os.path.join(ROOT, "data", "scenes", "gz2016-sinter.ini")
DEPOSIT_SCENE = os.path.join(ROOT, "data", "scenes", "gz2016-deposit.ini")
WORK = os.path.join(ROOT, "out", "studies")
# [GZ] 2016, docs/physics.md §5: melt pool (height, width, depth) in um on the plane x = Lx/2.
PAPER_MODEL = (30.0, 85.0, 20.0)
PAPER_EXPERIMENT = (26.0, 75.0, 30.0)


def gz2016_bed():
    """The deposit scene's bed with seed 1 (about a minute the first time)."""
    os.makedirs(WORK, exist_ok=True)
    path = os.path.join(WORK, "gz2016-deposit.h5")
    if not os.path.exists(path):
        subprocess.run([app("deposit"), "--config", DEPOSIT_SCENE, "--seed", "1", "--out", path],
                       check=True, capture_output=True)
    return path


# [GZ] Table 3 beds for Fig. 13, dropped in the deposit scene's box: young-scale 1e4 (the 4 um
# fines set the time step; at the scene's 1e3 the bimodal bed takes ~30 min) and 60 ms of
# settling: a fine falls at its Stokes speed 2 r^2 rho g / (9 mu) ~ 1.3 cm/s, ~25 ms from the
# top of the drop (at 30 ms some were still in the air above the bed).
FIG13_PSDS = [
    ("550 of 30 +- 5 um", "gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6", 550),
    ("+ 3000 of 8 +- 2 um", "gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6,count=550"
                            "+gauss:mean=8e-6,sd=2e-6,min=4e-6,max=12e-6,count=3000", 3550),
]


def fig13_beds():
    """[(name, bed path)] of the two Fig. 13 beds, deposited once (~2 min for the bimodal one)."""
    os.makedirs(WORK, exist_ok=True)
    beds = []
    for k, (name, psd, count) in enumerate(FIG13_PSDS):
        path = os.path.join(WORK, f"gz2016-fig13-{k}.h5")
        if not os.path.exists(path):
            subprocess.run([app("deposit"), "--config", DEPOSIT_SCENE, "--psd", psd, "--count",
                            str(count), "--young-scale", "1e4", "--t-end", "0.06", "--seed", "1",
                            "--out", path], check=True, capture_output=True)
        beds.append((name, path))
    return beds


def run_sinter(bed, out_name, *extra, threads=1):
    """Runs sinter on `bed` with the paper's scene and `extra` options; returns (json, wall s).
    One thread by default: the studies compare settings, not machines (bench/studies/sinter_speed.py
    measures threads)."""
    out = os.path.join(WORK, out_name)
    args = [app("sinter"), "--config", SCENE, "--bed", bed, "--out", out, *extra]
    if threads:
        args += ["--threads", str(threads)]
    summary, wall = run_json(args)
    summary["out_path"] = out
    return summary, wall


def pool_um(summary):
    m = summary["melt_pool"]
    return m["height"] * 1e6, m["width"] * 1e6, m["depth"] * 1e6


def track_means(run_path, x_from=0.2e-3, x_to=0.8e-3, slices=121):
    """Melt-pool height, width and depth along the track: on each plane x in [x_from, x_to]
    (the steady part of the 1 mm track) the molten region is measured as on x = Lx/2 — the
    particles the plane cuts whose peak reached T_m, and the top-face nodes of the substrate at
    or above T_m in the node column nearest x; the depth from the peak temperatures of the
    section y = Ly/2 (the track's centre line) in that column, interpolated to T_m between nodes
    as melt_pool.cpp does. Returns {"height"|"width"|"depth": (mean, sd)} in um. One plane cuts
    only a handful of 27 um particles, so single-plane numbers jump by a particle radius; the
    mean over 121 planes shows the trend and the sd the spread."""
    import h5py
    import numpy as np
    with h5py.File(run_path, "r") as f:
        pos = np.array(f["particles/position"])
        rad = np.array(f["particles/radius"])
        peak = np.array(f["melt/particle"])
        top = np.array(f["melt/top"])
        section = np.array(f["melt/section_y"])  # nz x nx, k = nz - 1 the top face
        t_m = float(f["melt"].attrs["melting_point"])
        x0, y0, z_top = f["substrate"].attrs["origin"]
        dx, dy, dz = f["substrate"].attrs["spacing"]
    molten = peak >= t_m
    widths, heights, depths = [], [], []
    for x in np.linspace(x_from, x_to, slices):
        off = pos[:, 0] - x
        cut = molten & (np.abs(off) < rad)
        half = np.sqrt(np.maximum(rad[cut] ** 2 - off[cut] ** 2, 0))
        lo = list(pos[cut, 1] - half)
        hi = list(pos[cut, 1] + half)
        i = int(round((x - x0) / dx))
        hot = np.nonzero(top[:, i] >= t_m)[0]
        if hot.size:
            lo.append(y0 + dy * hot.min())
            hi.append(y0 + dy * hot.max())
        widths.append(max(hi) - min(lo) if lo else 0.0)
        heights.append(float((pos[cut, 2] + half).max() - z_top) if cut.any() else 0.0)
        col = section[::-1, i]  # from the top face down
        depth = 0.0
        if col[0] >= t_m:
            k = 0
            while k + 1 < len(col) and col[k + 1] >= t_m:
                k += 1
            depth = k * dz
            if k + 1 < len(col) and col[k] > col[k + 1]:
                depth += dz * min(1.0, (col[k] - t_m) / (col[k] - col[k + 1]))
        depths.append(depth)
    return {name: (float(np.mean(v)) * 1e6, float(np.std(v)) * 1e6)
            for name, v in (("height", heights), ("width", widths), ("depth", depths))}
