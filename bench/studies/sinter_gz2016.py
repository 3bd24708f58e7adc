#!/usr/bin/env python3
"""The paper's single-track validation, its sweeps and its Fig. 13 ([GZ] §3) on the bed of the
deposit scene: writes docs/results/sinter-gz2016.md (+ the top-view and cross-section pictures)
and docs/results/sinter-sweeps.md (+ sinter-sweeps.png). Run with python3:
    POWDERBED_BUILD=build python3 bench/studies/sinter_gz2016.py [--no-sweeps|--fig13-only]
(--no-sweeps: the validation page only; --fig13-only: the Fig. 13 section of the sweeps page
only, replaced in place.)

The melt pool is measured as `sinter` does (thermal/include/powderbed/thermal/melt_pool.hpp):
on the plane x = Lx/2, the region whose peak temperature reached T_m = 1700 K; height above the
substrate from the particles the plane cuts, depth below the substrate's top face, width across
both. Every run uses the scene's defaults (explicit, 0.9 x the stable step, dT = 20 K) but
for the laser model and wetting, which each table names.
"""
import argparse
import os
import subprocess
import sys

from lib import apps, references, report
from lib.apps import pool_um, vaporised_by_size
from lib.melted import melted_mass, plate_plane

SCENE = apps.GZ2016_SINTER_SCENE
DEPOSIT_SCENE = apps.scene("gz2016-deposit.ini")
PAPER_MODEL = references.GZ2016_MELT_POOL_MODEL
PAPER_EXPERIMENT = references.GZ2016_MELT_POOL_EXPERIMENT
POWERS = [40, 80, 120, 160, 200, 250, 300, 350, 400]       # W at 2.0 m/s
SPEEDS = [0.4, 0.8, 1.2, 1.6, 2.0, 2.5, 3.0, 3.5, 4.0]     # m/s at 200 W


# [GZ] Table 3 beds for Fig. 13, dropped in the deposit scene's box: young-scale 1e4 (the 4 um
# fines set the time step; at the scene's 1e3 the bimodal bed takes ~30 min) and 60 ms of
# settling: a fine falls at its Stokes speed 2 r^2 rho g / (9 mu) ~ 1.3 cm/s, ~25 ms from the
# top of the drop (at 30 ms some were still in the air above the bed).
FIG13_PSDS = apps.GZ2016_TABLE3_PSDS


def fig13_beds():
    """[(name, bed path)] of the two Fig. 13 beds, deposited once (~2 min for the bimodal one)."""
    os.makedirs(apps.WORK, exist_ok=True)
    beds = []
    for k, (name, psd, count) in enumerate(FIG13_PSDS):
        path = os.path.join(apps.WORK, f"gz2016-fig13-{k}.h5")
        if not os.path.exists(path):
            subprocess.run([apps.app("deposit"), "--config", DEPOSIT_SCENE, "--psd", psd,
                            "--count", str(count), "--young-scale", "1e4", "--t-end", "0.06",
                            "--seed", "1", "--out", path], check=True, capture_output=True)
        beds.append((name, path))
    return beds


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
        section = np.array(f["melt/section_y"])  # nz x nx
        section = section[:plate_plane(f) + 1]  # up to the plate's top face
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


def picture(run_path, name, title):
    prefix = os.path.join(report.RESULTS, name)
    subprocess.run([sys.executable, os.path.join(apps.ROOT, "scripts", "plot_sinter.py"), run_path,
                    prefix, "--title", title], check=True)
    return os.path.basename(prefix)


# The variants of the validation table: (label, options). The laser model and wetting are set
# explicitly in each, so the table does not depend on the scene's defaults.
VARIANTS = [
    ("Beer-Lambert, substrate exp(-beta H_layer) ([GZ]'s text as written)",
     ["--laser.absorption", "beer-lambert", "--laser.substrate-shading", "layer"]),
    ("Beer-Lambert, substrate by bed column",
     ["--laser.absorption", "beer-lambert", "--laser.substrate-shading", "column"]),
    ("ray-traced, specular", ["--laser.absorption", "ray-trace", "--laser.reflection", "specular"]),
    ("ray-traced, diffuse", ["--laser.absorption", "ray-trace", "--laser.reflection", "diffuse"]),
    ("ray-traced, rough plate", ["--laser.absorption", "ray-trace", "--laser.reflection", "rough"]),
]
DEFAULT = ("ray-traced, rough plate", True)  # the scene's default: why in docs/sinter.md


# Each variant's run fuses what melted, levelled as build levels a layer (w/2; docs/sinter.md
# "Fusion"): the bead's height is what a section of the track shows.
FUSE = ["--fuse", "--fuse.level", "27e-6"]


def variant_runs(bed):
    runs = []
    for label, options in VARIANTS:
        for wetting in (False, True):
            tag = label.split(",")[0].split()[0].lower() + "-" + options[-1] + ("-wet" if wetting else "")
            s, wall = apps.sinter(SCENE, bed, f"gz2016-{tag}.h5", *options, "--effects.wetting",
                                  "true" if wetting else "false", *FUSE)
            s["track"] = track_means(s["out_path"])
            runs.append((label, wetting, s, wall))
    return runs


# The plate's rms roughness sigma (m) of the rough-plate default, swept with wetting on: from a
# mirror (0) through polished (0.1 um) to ground and as-built plates (1-3 um).
ROUGHNESS = [0, 0.05e-6, 0.1e-6, 0.3e-6, 1e-6, 3e-6]


def roughness_runs(bed):
    runs = []
    for sigma in ROUGHNESS:
        s, wall = apps.sinter(SCENE, bed, f"gz2016-roughness-{sigma * 1e6:g}.h5", "--laser.absorption",
                              "ray-trace", "--laser.reflection", "rough", "--laser.roughness",
                              f"{sigma:g}", "--effects.wetting", "true")
        s["track"] = track_means(s["out_path"])
        runs.append((sigma, s, wall))
    return runs


# Speeds of the evaporation table at 200 W: [GZ]'s 2 m/s, the issue's 1 m/s, and a slow track.
EVAPORATION_SPEEDS = [2.0, 1.0, 0.5]


def evaporation_runs(bed):
    runs = []
    for v in EVAPORATION_SPEEDS:
        s, wall = apps.sinter(SCENE, bed, f"gz2016-evaporation-{v:g}.h5", "--speed", f"{v:g}")
        runs.append((v, s, melted_mass(s["out_path"]), wall))
    return runs


def evaporation_table(runs):
    out = ["| v (m/s) | evaporated: particles / substrate (ng) | melted (ng) | evaporated / melted | "
           "T_max particles / substrate (K) | vaporised particles | wall (s) |",
           "|---|---|---|---|---|---|---|"]
    for v, s, melted, wall in runs:
        part = s["evaporated_mass_particles"]
        sub = s["evaporated_mass"] - part
        out.append(f"| {v:g} | {part * 1e12:.3g} / {sub * 1e12:.3g} | {melted * 1e12:.4g} | "
                   f"{s['evaporated_mass'] / melted * 100:.2f} % | "
                   f"{s['max_temperature_particles']:.0f} / {s['max_temperature_substrate']:.0f} | "
                   f"{s['particles_vaporised']} | {wall:.1f} |")
    return out


def specular_share_at_normal(sigma, wavelength=1.07e-6):
    """exp(-(4 pi sigma / lambda)^2): thermal/include/powderbed/thermal/rough_reflection.hpp."""
    import math
    return math.exp(-(4 * math.pi * sigma / wavelength) ** 2)


def roughness_table(runs):
    out = ["| plate sigma (um) | specular share at normal incidence | height / width / depth on "
           "x = Lx/2 (um) | track width (um) | track depth (um) | absorptance (run / bed) | "
           "T_max (K) | wall (s) |", "|---|---|---|---|---|---|---|---|"]
    for sigma, s, wall in runs:
        h, w, d = pool_um(s)
        out.append(f"| {sigma * 1e6:g} | {specular_share_at_normal(sigma):.3f} | {h:.1f} / {w:.1f} / "
                   f"{d:.1f} | {fmt_track(s['track'], 'width')} | {fmt_track(s['track'], 'depth')} | "
                   f"{s['absorptance']:.3f} / {s['ray_trace']['bed_absorptance']:.3f} | "
                   f"{s['max_temperature']:.0f} | {wall:.1f} |")
    return out


def bead(summary):
    """The fused bead's height (sinter --fuse's `bead_*`): on x = Lx/2 / mean ± sd over the track."""
    f = summary["fusion"]
    return (f"{f['bead_height'] * 1e6:.1f} / {f['bead_height_mean'] * 1e6:.1f} ± "
            f"{f['bead_height_sd'] * 1e6:.1f}")


def fmt_track(track, key):
    mean, sd = track[key]
    return f"{mean:.1f} ± {sd:.1f}"


def variant_table(runs):
    """The variants' rows under [GZ]'s model and experiment."""
    lines = [
        "| run | wetting | height / width / depth on x = Lx/2 (um) | track height (um) | "
        "track width (um) | track depth (um) | bead on x = Lx/2 / over the track (um) | T_max (K) | "
        "absorptance (run / bed) | molten / vaporised | wetted caps / bridges | energy balance | "
        "wall (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
        f"| [GZ] 2016 model (dt = 5e-9 s) | - | {PAPER_MODEL[0]:.0f} / {PAPER_MODEL[1]:.0f} / "
        f"{PAPER_MODEL[2]:.0f} | - | - | - | {PAPER_MODEL[0]:.0f} | - | - | - | - | - | ~3 CPU hours |",
        f"| [GZ] 2016 experiment | - | {PAPER_EXPERIMENT[0]:.0f} / {PAPER_EXPERIMENT[1]:.0f} / "
        f"{PAPER_EXPERIMENT[2]:.0f} | - | - | - | {PAPER_EXPERIMENT[0]:.0f} | - | - | - | - | - | - |",
    ]
    for label, wetting, s, wall in runs:
        h, w, d = pool_um(s)
        bed_abs = s["ray_trace"]["bed_absorptance"] if "ray_trace" in s else None
        absorb = f"{s['absorptance']:.3f}" + (f" / {bed_abs:.3f}" if bed_abs is not None else "")
        bold = "**" if (label, wetting) == DEFAULT else ""
        lines.append(
            f"| {bold}{label}{bold} | {'on' if wetting else 'off'} | {bold}{h:.1f} / {w:.1f} / "
            f"{d:.1f}{bold} | {fmt_track(s['track'], 'height')} | {fmt_track(s['track'], 'width')} | "
            f"{fmt_track(s['track'], 'depth')} | {bead(s)} | {s['max_temperature']:.0f} | {absorb} | "
            f"{s['particles_molten']} / {s['particles_vaporised']} | "
            f"{s['substrate_wetted']} / {s['bridges']} | {s['energy_balance_error']:.1e} | "
            f"{wall:.1f} |")
    return "\n".join(lines)


def validation(bed, machine):
    runs = variant_runs(bed)
    default = next(r for r in runs if (r[0], r[1]) == DEFAULT)
    beer = next(r for r in runs if r[0].startswith("Beer-Lambert, substrate exp") and not r[1])
    s, rt = default[2], default[2]["ray_trace"]
    values = {
        "machine": machine, "variant_table": variant_table(runs),
        "layer_height": f"{s['layer_height'] * 1e6:.1f}", "layer_porosity": f"{s['porosity']:.3f}",
        "extinction": f"{s['extinction']:.3g}", "beta_h": f"{s['extinction'] * s['layer_height']:.2f}",
        "traces": rt["traces"], "to_particles": f"{rt['particles']:.3f}",
        "to_substrate": f"{rt['substrate']:.3f}", "escaped": f"{rt['escaped']:.3f}",
        "outside": f"{rt['outside']:.3f}", "dropped": f"{rt['dropped']:.1e}",
        "hits": f"{rt['hits_per_ray']:.2f}",
        "roughness_table": "\n".join(roughness_table(roughness_runs(bed))),
        "evaporation_table": "\n".join(evaporation_table(evaporation_runs(bed))),
        "pic": picture(s["out_path"], "sinter-gz2016", "sinter, [GZ] scene, 200 W, 2 m/s"),
        "pic_bl": picture(beer[2]["out_path"], "sinter-gz2016-beer-lambert",
                          "sinter, Beer-Lambert, no wetting, 200 W, 2 m/s"),
    }
    return report.write_page("sinter-gz2016.md", report.fill_template("sinter-gz2016.md.in", values))


# The two models of the sweeps: the scene's default and Beer-Lambert as [GZ]'s text has it.
SWEEP_MODELS = apps.GZ2016_LASER_MODELS


def sweep_table(title, unit, rows):
    out = [f"| {title} ({unit}) | height / width / depth on x = Lx/2 (um) | track height (um) | "
           "track width (um) | track depth (um) | T_max (K) | absorptance | molten / vaporised | "
           "wall (s) |",
           "|---|---|---|---|---|---|---|---|---|"]
    for x, s, wall in rows:
        h, w, d = pool_um(s)
        out.append(f"| {x:g} | {h:.1f} / {w:.1f} / {d:.1f} | {fmt_track(s['track'], 'height')} | "
                   f"{fmt_track(s['track'], 'width')} | {fmt_track(s['track'], 'depth')} | "
                   f"{s['max_temperature']:.0f} | {s['absorptance']:.3f} | "
                   f"{s['particles_molten']} / {s['particles_vaporised']} | {wall:.1f} |")
    return out


def sweeps(bed, machine):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    results = []
    for name, options in SWEEP_MODELS:
        tag = "default" if not options else "beer-lambert"
        power_rows, speed_rows = [], []
        for p in POWERS:
            s, wall = apps.sinter(SCENE, bed, f"power-{tag}-{p}.h5", *options, "--power", str(p))
            s["track"] = track_means(s["out_path"])
            power_rows.append((p, s, wall))
        for v in SPEEDS:
            s, wall = apps.sinter(SCENE, bed, f"speed-{tag}-{v}.h5", *options, "--speed", str(v))
            s["track"] = track_means(s["out_path"])
            speed_rows.append((v, s, wall))
        results.append((name, power_rows, speed_rows))

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    for (name, power_rows, speed_rows), style in zip(results, ("-", "--")):
        for ax, rows in ((axes[0], power_rows), (axes[1], speed_rows)):
            xs = [r[0] for r in rows]
            ax.plot(xs, [r[1]["track"]["width"][0] for r in rows], "o" + style, color="C0",
                    label=f"width, {name}")
            ax.plot(xs, [r[1]["track"]["depth"][0] for r in rows], "s" + style, color="C3",
                    label=f"depth, {name}")
            ax.plot(xs, [r[1]["track"]["height"][0] for r in rows], "^" + style, color="C2",
                    label=f"height, {name}")
    axes[0].set_xlabel("laser power P (W), v = 2.0 m/s")
    axes[1].set_xlabel("scan speed v (m/s), P = 200 W")
    for ax in axes:
        ax.set_ylabel("melt pool, track mean (um)")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("sinter on the [GZ] bed: track-mean melt pool (solid: default, dashed: Beer-Lambert)")
    fig.tight_layout()
    fig.savefig(os.path.join(report.RESULTS, "sinter-sweeps.png"), dpi=120)
    lines = [
        "# The [GZ] 2016 sweeps with sinter",
        "",
        "Generated by `bench/studies/sinter_gz2016.py`: the scene and bed of "
        "docs/results/sinter-gz2016.md, one option changed per run (power 40–400 W at 2.0 m/s, "
        "speed 0.4–4.0 m/s at 200 W, [GZ] §3), for the scene's default model (ray-traced "
        "absorption, rough plate, with wetting) and for Beer-Lambert as [GZ]'s text has it without "
        "wetting. Melt pool on x = Lx/2 and track mean ± sd over 121 planes between x = 0.2 and "
        "0.8 mm, as in docs/results/sinter-gz2016.md. One thread each.",
        "",
        machine,
    ]
    for name, power_rows, speed_rows in results:
        lines += ["", f"## {name}: power at 2.0 m/s", "", *sweep_table("P", "W", power_rows),
                  "", f"## {name}: speed at 200 W", "", *sweep_table("v", "m/s", speed_rows)]
    lines += [
        "",
        "Slower tracks and higher powers vaporise the particles under the beam: a particle whose "
        "temperature passes T_v + dT/2 has left the bed as vapour and is taken out of the "
        "network and out of the ray tracer's scene (its energy stays booked), so temperatures "
        "stay finite. The substrate has no such loss (docs/sinter.md), so depths at the highest "
        "powers and slowest speeds are upper bounds.",
        "",
        "![sweeps](sinter-sweeps.png)",
    ]
    return report.write_page("sinter-sweeps.md", "\n".join(lines) + "\n")


def fig13(machine):
    """[GZ] Fig. 13: 550 particles of 30 +- 5 um in [20, 40] um against the same plus 3,000 of
    8 +- 2 um in [4, 12] um, 200 W, 2 m/s: which particles vaporise, for both models."""
    rows = []
    for name, bed in fig13_beds():
        for model, options in SWEEP_MODELS:
            tag = "default" if not options else "beer-lambert"
            s, wall = apps.sinter(SCENE, bed, f"fig13-{name}-{tag}.h5", *options)
            fine, coarse, n_fine, n_coarse = vaporised_by_size(s["out_path"], 3130.0, 16e-6)
            rows.append((name, model, s, wall, fine, coarse, n_fine, n_coarse))
    lines = [
        "",
        "## [GZ] Fig. 13: fines vaporise",
        "",
        "Beds deposited by `bench/studies/sinter_gz2016.py` `fig13_beds` (the deposit scene's box "
        "and drop with the Table 3 PSDs, young-scale 1e4 to keep the fines' time step affordable "
        "(docs/results/deposit-accuracy.md has what softening costs) and 60 ms of settling, so "
        "the fines falling at their Stokes speed have landed), the "
        "paper's scene at 200 W, 2 m/s. Vaporised: peak temperature at or above T_v = 3130 K; "
        "fines are particles under 16 um in diameter. deposit draws each size from the mixture's "
        "number fractions (550 : 3000), so the bimodal bed's split is near, not exactly, "
        "550 + 3000 (the counts in brackets).",
        "",
        machine,
        "",
        "| bed | model | height / width / depth (um) | T_max (K) | absorptance | molten | "
        "vaporised fines (of) | vaporised coarse (of) | wall (s) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for name, model, s, wall, fine, coarse, n_fine, n_coarse in rows:
        h, w, d = pool_um(s)
        lines.append(f"| {name} | {model} | {h:.1f} / {w:.1f} / {d:.1f} | "
                     f"{s['max_temperature']:.0f} | {s['absorptance']:.3f} | "
                     f"{s['particles_molten']} | {fine} ({n_fine}) | {coarse} ({n_coarse}) | "
                     f"{wall:.1f} |")
    lines += ["", "As in [GZ], it is the fines that vaporise, under either model: a particle's heat "
              "capacity grows as r^3 and the power it takes as r^2, so a fine of 8 um reaches T_v "
              "where a 30 um particle only melts. The fines also cover the gaps, so the bed with "
              "fines absorbs more of the beam."]
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    only = parser.add_mutually_exclusive_group()
    only.add_argument("--no-sweeps", action="store_true", help="the validation page only")
    only.add_argument("--fig13-only", action="store_true",
                      help="the Fig. 13 section of the sweeps page only (replaced in place)")
    args = parser.parse_args()
    load = report.load_average()
    bed = apps.gz2016_bed()
    path = os.path.join(report.RESULTS, "sinter-sweeps.md")
    if args.fig13_only:
        text = report.read_page("sinter-sweeps.md").split("\n## [GZ] Fig. 13")[0].rstrip("\n")
        section = fig13(report.machine(load))
        print(report.write_page("sinter-sweeps.md", text + "\n" + "\n".join(section) + "\n"))
        return
    print(validation(bed, report.machine(load)))
    if not args.no_sweeps:
        sweeps(bed, report.machine(load))
        with open(path, "a") as f:
            f.write("\n".join(fig13(report.machine(load))) + "\n")
        print(path)


if __name__ == "__main__":
    main()
