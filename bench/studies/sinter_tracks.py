#!/usr/bin/env python3
"""Melt pools of measured single tracks (data/validation/): sinter, in each model variant this
build offers, and the uncalibrated Eagar–Tsai solution beside the measured width and depth.

Every row of data/validation/*.csv is one track. Rows on a bare plate run sinter on an empty bed
(a bed file with a domain and no particles: sinter's bare substrate), with the row's --material,
--power, --speed and --spot (the 1/e^2 radius) and the plate at the row's temperature; the
substrate is sized from Eagar–Tsai's pool for the row (long enough for the pool on x = Lx/2 to
be quasi-steady, wide and deep enough for the Dirichlet faces to stay cold) and its grid spacing
is the finest of 5, 7.5, 10, 12.5, 15, 20 um whose estimated cost fits the budget of a run
(--budget, 60 s of one thread). The [GZ] row is on a powder layer: it runs the [GZ] scene on its
deposited bed (data/scenes/gz2016-sinter.ini, data/scenes/gz2016-deposit.ini seed 1).

Variants: "today" (evaporation, depression off, constant optics), "+evaporation", "+depression",
"+fresnel" (--laser.optics fresnel) and "all"; `sinter --help` says which options the build has,
and a variant whose options it lacks is reported as not available in this build.

Absorptivity: sinter's comes from the material's file (the flat metal's optics; 0.33 for 316L,
[GZ]); Eagar–Tsai's is the flat surface's Fresnel absorptance at normal incidence (0.354 for
316L, n = 3.2 + 4.3i) or, without an index for the material, its file's value. Neither is fitted
to a track.

Writes docs/results/sinter-tracks.md (from bench/studies/templates/sinter-tracks.md.in) and
sinter-tracks.png; keeps its runs and results in out/studies/sinter-tracks/. Run:
    POWDERBED_BUILD=build python3 bench/studies/sinter_tracks.py [--quick] [--from-json]
--quick runs three tracks (a smoke run; its page is marked so), --from-json rewrites the page from
the stored results.
"""
import argparse
import csv
import glob
import json
import math
import os
import re
import subprocess
import sys
import time

from lib import apps, references, report
from lib.materials import constant_properties, material

WORK = os.path.join(apps.WORK, "sinter-tracks")
DATA = os.path.join(apps.ROOT, "data", "validation")
RESULTS_JSON = os.path.join(WORK, "results.json")

# The CMU IN625 rows carry no spot (data/validation/cmu-in625-eos-m270.csv): the 1/e^2 radius
# assumed for them, an assumption and not data (the page says so).
ASSUMED_SPOT = 50e-6
QUICK = ["N01", "N05", "P195-v0.8"]
GRIDS = [5e-6, 7.5e-6, 10e-6, 12.5e-6, 15e-6, 20e-6]
COST_PER_NODE_STEP = 16e-9  # s of one thread, first guess; the runs update it

# name -> options; an option whose name the build lacks makes the variant unavailable. "today"
# sets what it can explicitly, so that it keeps meaning today's model when the defaults change.
NEW_OPTIONS = {"effects.evaporation": ("false", "true"), "effects.depression": ("false", "true"),
               "laser.optics": ("constant", "fresnel")}
VARIANTS = [("today", []),
            ("+evaporation", ["effects.evaporation"]),
            ("+depression", ["effects.depression"]),
            ("+fresnel", ["laser.optics"]),
            ("all", ["effects.evaporation", "effects.depression", "laser.optics"])]


# ------------------------------------------------------------------------------------------------
# data

def read_rows():
    """Every row of data/validation/*.csv as a dict (numbers as float, empty as None), with the
    file it came from."""
    rows = []
    for path in sorted(glob.glob(os.path.join(DATA, "*.csv"))):
        with open(path) as f:
            lines = [line for line in f if not line.startswith("#")]
        for r in csv.DictReader(lines):
            row = {}
            for key, value in r.items():
                value = (value or "").strip()
                try:
                    row[key] = float(value) if value else None
                except ValueError:
                    row[key] = value
            row["file"] = os.path.basename(path)
            row["id"] = row["case"] if isinstance(row["case"], str) else f"{row['case']:g}"
            row["spot_assumed"] = row["spot_radius_m"] is None
            if row["spot_assumed"]:
                row["spot_radius_m"] = ASSUMED_SPOT
            rows.append(row)
    return rows


def eagar_tsai_absorptivity(name):
    """The flat surface's absorptance for Eagar–Tsai: Fresnel at normal incidence of the material
    file's index of the solid (sinter's optics), else the file's absorptivity."""
    props = material(name)[0]
    if "index_n_solid" in props and "index_k_solid" in props:
        index = complex(float(props["index_n_solid"]), float(props["index_k_solid"]))
        return references.fresnel_normal(index), f"Fresnel, n = {index.real:g} + {index.imag:g}i"
    return float(props["absorptivity"]), "material file"


def eagar_tsai(row):
    """Eagar–Tsai's pool for a row: dict of width, depth, length (m), peak (K), the
    absorptivity and the reference temperature of its constant properties."""
    props, _ = material(row["material"])
    t_m, t0 = float(props["melting_point"]), row["T0_K"]
    t_ref = 0.5 * (t0 + t_m)
    k, rho_c = constant_properties(row["material"], t_ref)
    a, a_source = eagar_tsai_absorptivity(row["material"])
    et = references.EagarTsai(a * row["power_W"], k, rho_c, row["spot_radius_m"],
                              row["speed_m_per_s"], t0)
    width, depth, length = et.melt_pool(t_m)
    return {"width": width, "depth": depth, "length": length, "peak": et.peak_temperature(),
            "absorptivity": a, "absorptivity_source": a_source, "t_ref": t_ref, "k": k,
            "rho_c": rho_c, "melting_point": t_m}


def regime(row):
    """conduction D/W < 0.5, transition 0.5 <= D/W < 1, keyhole D/W >= 1, on the measured pool;
    a row without a measured width takes D/(2w) (over the spot's 1/e^2 diameter) instead; a row
    without a measured depth has none."""
    d, w = row["depth_m"], row["width_m"]
    if d is None:
        return "width only"
    ratio = d / w if w else d / (2 * row["spot_radius_m"])
    return "conduction" if ratio < 0.5 else "transition" if ratio < 1 else "keyhole"


# ------------------------------------------------------------------------------------------------
# sinter

def available_options():
    """The new options this build's sinter has (from --help)."""
    text = subprocess.run([apps.app("sinter"), "--help"], capture_output=True, text=True).stdout
    return {name for name in NEW_OPTIONS if re.search(r"--" + re.escape(name) + r"\b", text)}


def variant_options(names, have):
    """The command-line options of a variant, or None when the build lacks one of them."""
    if any(n not in have for n in names):
        return None
    out = []
    for name, (off, on) in NEW_OPTIONS.items():
        if name in have:
            out += [f"--{name}", on if name in names else off]
    return out


# Bare-plate tracks start and end EDGE spot radii inside the plate's edges, as tracks are made
# (the beam switched on over the plate; at the edge the intensity is exp(-2 EDGE^2) = 3e-4 of
# the peak). A beam that sweeps in across the grid's Dirichlet side at keyhole powers drills a
# slot against that side's cold column and reaches the grid's bottom (ORNL P525 and P637.5 did,
# at column 2).
EDGE = 2


def empty_bed(lx, ly, height, path):
    """A bed with a domain and no particles (sinter's bare substrate), made by bedconv from a
    CSV with only its header: how a user would make one."""
    if os.path.exists(path):
        return path
    os.makedirs(os.path.dirname(path), exist_ok=True)
    csv_path = path.replace(".h5", ".csv")
    with open(csv_path, "w") as f:
        f.write("x,y,z,r\n")
    proc = subprocess.run([apps.app("bedconv"), csv_path, path, "--domain",
                           f"0,0,0,{lx!r},{ly!r},{height!r}"], capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"bedconv of an empty CSV exited {proc.returncode}: "
                           f"{proc.stderr.strip()}")
    return path


def stable_dt(row, h):
    """The explicit grid step sinter will take, about: 0.9 rho c_min h^2 / (6 k_max) (its bound
    takes the smallest rho c and the largest conductivity of the run's temperatures)."""
    props, table = material(row["material"])
    rho_c = min(t[1] * t[3] for t in table)
    k = max(t[2] for t in table) * 1.3  # the liquid row and the extrapolation above the table
    return 0.9 * rho_c * h * h / (6 * k)


def substrate(row, et, budget, cost):
    """(lx, ly, depth, h, estimated s) of the bare plate for a row."""
    w = row["spot_radius_m"]
    meas_d = row["depth_m"] or 0.0
    pre = max(0.4e-3, 1.2 * et["length"] + 4 * w)       # start to the plane x = Lx/2
    lx = 2 * (pre + EDGE * w)  # the beam runs from EDGE w inside one side to EDGE w before the other
    ly = max(0.4e-3, 2.5 * et["width"], 8 * w)
    depth = min(1.0e-3, max(0.5e-3, 2 * et["depth"], 1.5 * meas_d))
    for h in GRIDS:
        # even node counts across x and y: the track's line and the plane x = Lx/2 on nodes
        n = [2 * math.ceil(lx / (2 * h)), 2 * math.ceil(ly / (2 * h)), round(depth / h)]
        nodes = (n[0] + 1) * (n[1] + 1) * (n[2] + 1)
        steps = (lx - 2 * EDGE * w) / row["speed_m_per_s"] / stable_dt(row, h)
        est = nodes * steps * cost
        if est <= budget or h == GRIDS[-1]:
            return n[0] * h, n[1] * h, n[2] * h, h, est


def hottest(run_path):
    """Where the run's peak is: 'particle' or the top face's hottest node (x, y offset from the
    track's line, m), from the run file's /melt."""
    import h5py
    import numpy as np
    with h5py.File(run_path, "r") as f:
        top = np.array(f["melt/top"])
        part = np.array(f["melt/particle"]) if "particle" in f["melt"] else np.array([])
        origin = f["substrate"].attrs["origin"]
        spacing = f["substrate"].attrs["spacing"]
    j, i = np.unravel_index(int(np.argmax(top)), top.shape)
    where = {"x": float(origin[0] + i * spacing[0]), "y": float(origin[1] + j * spacing[1]),
             "top_peak": float(top.max())}
    where["on"] = "particle" if part.size and part.max() > top.max() else "top face"
    return where


def run_sinter(row, name, options, et, args, costs):
    """One sinter run of a row in a variant: its pool, peak, where, wall and grid."""
    tag = f"{row['file'].split('-')[0]}-{row['id']}-{name.strip('+')}"
    out = os.path.join(WORK, tag + ".h5")
    common = ["--power", repr(row["power_W"]), "--speed", repr(row["speed_m_per_s"]),
              "--spot", repr(row["spot_radius_m"]), "--threads", "1", "--snapshots", "1",
              "--out", out] + options
    if row["plate"] == "powder":
        try:
            bed = apps.gz2016_bed()  # deposit's [GZ] bed, made once (about a minute)
        except (OSError, subprocess.CalledProcessError) as e:
            return {"error": f"no [GZ] bed: {e}", "grid": {"h": 5e-6, "lx": 1e-3, "ly": 0.5e-3,
                                                             "depth": 0.3e-3, "estimate": None}}
        cmd = [apps.app("sinter"), "--config", apps.GZ2016_SINTER_SCENE, "--bed", bed] + common
        grid = {"h": 5e-6, "lx": 1e-3, "ly": 0.5e-3, "depth": 0.3e-3, "estimate": None}
    else:
        cost = sorted(costs)[len(costs) // 2] if costs else COST_PER_NODE_STEP
        lx, ly, depth, h, est = substrate(row, et, args.budget, cost)
        bed = empty_bed(lx, ly, 50e-6, os.path.join(WORK, "beds", f"bare-{lx:.4g}-{ly:.4g}.h5"))
        t0 = repr(row["T0_K"])
        cmd = [apps.app("sinter"), "--bed", bed, "--material", row["material"],
               "--substrate.depth", repr(depth), "--grid-spacing", repr(h),
               "--environment.temperature", t0, "--environment.initial-temperature", t0] + common
        w = row["spot_radius_m"]
        cmd += ["--laser.start-x", repr(EDGE * w), "--laser.end-x", repr(lx - EDGE * w)]
        grid = {"h": h, "lx": lx, "ly": ly, "depth": depth, "estimate": est}
    try:
        s, wall = apps.run_json(cmd)
    except (RuntimeError, OSError) as e:
        return {"error": str(e).splitlines()[-1][-400:], "grid": grid, "command": cmd}
    if row["plate"] != "powder":
        costs.append(wall / (s["nodes"] * max(s["steps"], 1)))
    m = s["melt_pool"]
    return {"width": m["width"], "depth": m["depth"], "height": m["height"],
            "t_max": s["max_temperature"], "where": hottest(out), "wall": wall,
            "t_max_particles": s.get("max_temperature_particles"),
            "t_max_substrate": s.get("max_temperature_substrate"),
            "evaporated_mass": s.get("evaporated_mass"),
            "depression_depth": s.get("depression_depth"),
            "steps": s["steps"], "nodes": s["nodes"], "absorptance": s["absorptance"],
            "energy_balance_error": s["energy_balance_error"], "grid": grid,
            "options": options}


# ------------------------------------------------------------------------------------------------
# the page

def err(pred, meas):
    """Signed error in % (None without a measurement or a prediction)."""
    if meas is None or pred is None:
        return None
    return 100.0 * (pred - meas) / meas


def fmt_um(x):
    return "–" if x is None else f"{x * 1e6:.0f}"


def fmt_err(e):
    return "–" if e is None else f"{e:+.0f} %"


def mean_abs(values):
    values = [abs(v) for v in values if v is not None]
    return (sum(values) / len(values), len(values)) if values else (None, 0)


def predictions(result):
    """(label, {row id: (width, depth)}) for each model with results: the variants that ran and
    Eagar–Tsai."""
    out = []
    for name in result["variants"]:
        if result["variants"][name] is None:
            continue
        preds = {}
        for row in result["rows"]:
            r = row["sinter"].get(name)
            if r and "error" not in r:
                preds[row["id"] + row["file"]] = (r["width"], r["depth"])
        out.append((f"sinter {name}", preds))
    out.append(("Eagar–Tsai", {row["id"] + row["file"]: (row["et"]["width"], row["et"]["depth"])
                                for row in result["rows"]}))
    return out


def track_table(result):
    ran = [n for n in result["variants"] if result["variants"][n] is not None]
    head = ["track", "P (W)", "v (m/s)", "w (um)", "plate", "regime", "measured W/D (um)"]
    for n in ran:
        head += [f"{n} W/D (um)", f"{n} err W / D"]
    head += ["Eagar–Tsai W/D (um)", "ET err W / D"]
    lines = report.table_head(*head)
    for row in result["rows"]:
        cells = [f"{row['id']} ({row['file'].split('-')[0]})", f"{row['power_W']:g}",
                 f"{row['speed_m_per_s']:g}",
                 f"{row['spot_radius_m'] * 1e6:.1f}" + ("*" if row["spot_assumed"] else ""),
                 row["plate"], row["regime"],
                 f"{fmt_um(row['width_m'])} / {fmt_um(row['depth_m'])}"]
        for n in ran:
            r = row["sinter"].get(n)
            if not r or "error" in r:
                cells += ["not run" if not r else "failed", "–"]
                continue
            cells += [f"{fmt_um(r['width'])} / {fmt_um(r['depth'])}",
                      f"{fmt_err(err(r['width'], row['width_m']))} / "
                      f"{fmt_err(err(r['depth'], row['depth_m']))}"]
        et = row["et"]
        cells += [f"{fmt_um(et['width'])} / {fmt_um(et['depth'])}",
                  f"{fmt_err(err(et['width'], row['width_m']))} / "
                  f"{fmt_err(err(et['depth'], row['depth_m']))}"]
        lines.append(report.table_row(*cells))
    return "\n".join(lines)


REGIMES = ["conduction", "transition", "keyhole", "width only"]


def error_table(result):
    lines = report.table_head("model", *[f"{g}: W / D (n)" for g in REGIMES + ["all"]])
    rows_by_key = {row["id"] + row["file"]: row for row in result["rows"]}
    for label, preds in predictions(result):
        cells = [label]
        for g in REGIMES + ["all"]:
            keys = [k for k, row in rows_by_key.items() if g == "all" or row["regime"] == g]
            we = [err(preds[k][0], rows_by_key[k]["width_m"]) for k in keys if k in preds]
            de = [err(preds[k][1], rows_by_key[k]["depth_m"]) for k in keys if k in preds]
            (mw, nw), (md, nd) = mean_abs(we), mean_abs(de)
            cells.append(f"{'–' if mw is None else f'{mw:.0f} %'} ({nw}) / "
                         f"{'–' if md is None else f'{md:.0f} %'} ({nd})")
        lines.append(report.table_row(*cells))
    return "\n".join(lines)


def run_table(result):
    ran = [n for n in result["variants"] if result["variants"][n] is not None]
    lines = report.table_head("track", "variant", "grid h (um)", "Lx x Ly x depth (mm)", "nodes",
                              "steps", "absorptance", "T_max (K)", "particles / substrate (K)",
                              "where (x, y - y_track; um)", "evaporated (ng)", "ET peak (K)",
                              "wall (s)")
    for row in result["rows"]:
        for n in ran:
            r = row["sinter"].get(n)
            if not r:
                continue
            g = r["grid"]
            size = f"{g['lx'] * 1e3:.2f} x {g['ly'] * 1e3:.2f} x {g['depth'] * 1e3:.2f}"
            if "error" in r:
                lines.append(report.table_row(row["id"], n, f"{g['h'] * 1e6:g}", size, "–", "–",
                                              "–", "failed: " + r["error"].replace("|", "/"),
                                              "–", "–", "–", "–", "–"))
                continue
            wh = r["where"]
            y_track = g["ly"] / 2
            lines.append(report.table_row(
                row["id"], n, f"{g['h'] * 1e6:g}", size, f"{r['nodes']:,}", r["steps"],
                f"{r['absorptance']:.3f}", f"{r['t_max']:.0f}", peaks_text(r),
                f"{wh['on']} ({wh['x'] * 1e6:.0f}, {(wh['y'] - y_track) * 1e6:.0f})",
                "–" if r.get("evaporated_mass") is None else f"{r['evaporated_mass'] * 1e12:.3g}",
                f"{row['et']['peak']:.0f}", f"{r['wall']:.1f}"))
    return "\n".join(lines)


def peaks_text(r):
    """The run's peaks over the particles and the substrate, as the program labels them."""
    if r.get("t_max_substrate") is None:
        return "–"
    part = "–" if not r.get("t_max_particles") else f"{r['t_max_particles']:.0f}"
    return f"{part} / {r['t_max_substrate']:.0f}"


def bounds_table(result):
    """Per variant: the hottest substrate and particle over its runs against T_b + 500 K."""
    ran = [n for n in result["variants"] if result["variants"][n] is not None]
    lines = report.table_head("variant", "runs", "hottest substrate (K)", "hottest particle (K)",
                              "runs above T_b + 500 K")
    for n in ran:
        runs = [(row, row["sinter"][n]) for row in result["rows"]
                if n in row["sinter"] and "error" not in row["sinter"][n]]
        if not runs:
            continue
        t_b = {row["material"]: float(material(row["material"])[0]["boiling_point"]) for row, _ in runs}
        sub = max(r.get("t_max_substrate") or r["t_max"] for _, r in runs)
        part = max((r.get("t_max_particles") or 0) for _, r in runs)
        above = sum(1 for row, r in runs if r["t_max"] > t_b[row["material"]] + 500)
        lines.append(report.table_row(n, len(runs), f"{sub:.0f}", f"{part:.0f}" if part else "–",
                                      above))
    return "\n".join(lines)


def variants_text(result):
    out = []
    for name, _ in VARIANTS:
        opts = result["variants"].get(name)
        if opts is None:
            out.append(f"- {name}: not available in this build")
        else:
            out.append(f"- {name}: ran" + (f" with `{' '.join(opts)}`" if opts else
                                           " (no new options in this build: sinter as it is)"))
    return "\n".join(out)


def plot(result, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = {row["id"] + row["file"]: row for row in result["rows"]}
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.6))
    markers = "osD^vP"
    for n, ((label, preds), marker) in enumerate(zip(predictions(result), markers)):
        colour = "k" if label.startswith("Eagar") else f"C{n}"
        for ax, i, key in ((axes[0], 0, "width_m"), (axes[1], 1, "depth_m")):
            pts = [(rows[k][key] * 1e6, p[i] * 1e6) for k, p in preds.items()
                   if rows[k][key] is not None and p[i] is not None]
            if pts:  # Eagar–Tsai hollow, the sinter variants filled
                ax.scatter(*zip(*pts), marker=marker, label=label, alpha=0.8,
                           facecolors="none" if label.startswith("Eagar") else colour,
                           edgecolors=colour)
    for ax, name in zip(axes, ("width", "depth")):
        lim = max(ax.get_xlim()[1], ax.get_ylim()[1])
        ax.plot([0, lim], [0, lim], "k--", lw=1, label="measured = predicted")
        ax.set_xlim(0, lim)
        ax.set_ylim(0, lim)
        ax.set_xlabel(f"measured {name} (um)")
        ax.set_ylabel(f"predicted {name} (um)")
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
    axes[1].legend(fontsize=8, loc="upper left")
    fig.suptitle("single tracks: measured against predicted melt pools")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


SPOT_FACTORS = (0.6, 0.7, 0.8, 0.9, 1.0)


def spot_table(result):
    """Eagar–Tsai's width / depth of each row with a measured width and depth at fractions of
    its stated spot: how much of a width error an uncertain spot convention can hold."""
    head = report.table_head("track", "measured W/D (um)",
                             *(f"ET at {f:g} w: W/D (um)" for f in SPOT_FACTORS))
    lines = list(head)
    for row in result["rows"]:
        if row["width_m"] is None or row["depth_m"] is None:
            continue
        cells = []
        for f in SPOT_FACTORS:
            et = eagar_tsai(dict(row, spot_radius_m=f * row["spot_radius_m"]))
            cells.append(f"{et['width'] * 1e6:.0f} / {et['depth'] * 1e6:.0f}")
        lines.append(report.table_row(
            f"{row['id']} (w = {row['spot_radius_m'] * 1e6:g} um, {row['speed_m_per_s']:g} m/s)",
            f"{row['width_m'] * 1e6:.0f} / {row['depth_m'] * 1e6:.0f}", *cells))
    return "\n".join(lines)


def write_page(result):
    plot(result, os.path.join(report.RESULTS, "sinter-tracks.png"))
    rows = result["rows"]
    walls = [r["wall"] for row in rows for r in row["sinter"].values() if r and "wall" in r]
    failed = [f"{row['id']} {n}: {r['error']}" for row in rows for n, r in row["sinter"].items()
              if r and "error" in r]
    et316 = next((row["et"] for row in rows if row["material"] == "316L"), None)
    values = {
        "command": "POWDERBED_BUILD=build python3 bench/studies/sinter_tracks.py"
                   + (" --quick" if result["quick"] else ""),
        "quick_note": ("**A --quick smoke run: three tracks only.**\n\n" if result["quick"]
                       else ""),
        "machine": result["machine"],
        "study_wall": f"{result['study_wall']:.0f}",
        "runs": len(walls),
        "run_wall_sum": f"{sum(walls):.0f}",
        "run_wall_max": f"{max(walls):.0f}" if walls else "–",
        "run_wall_median": f"{sorted(walls)[len(walls) // 2]:.0f}" if walls else "–",
        "budget": f"{result['budget']:g}",
        "rows": len(rows),
        "variants": variants_text(result),
        "bounds_table": bounds_table(result),
        "assumed_spot": f"{ASSUMED_SPOT * 1e6:g}",
        "et_absorptivity_316L": f"{et316['absorptivity']:.3f}" if et316 else "–",
        "track_table": track_table(result),
        "error_table": error_table(result),
        "spot_table": spot_table(result),
        "run_table": run_table(result),
        "failures": "\n".join(f"- {f}" for f in failed) if failed else "None.",
    }
    report.write_page("sinter-tracks.md", report.fill_template("sinter-tracks.md.in", values))


# ------------------------------------------------------------------------------------------------

def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help=f"three tracks: {', '.join(QUICK)}")
    parser.add_argument("--from-json", action="store_true",
                        help="rewrite the page from out/studies/sinter-tracks/results.json")
    parser.add_argument("--budget", type=float, default=60.0,
                        help="s of one thread a bare-plate run may take, estimated (default 60)")
    parser.add_argument("--only", help="comma-separated track ids (e.g. N01,P300)")
    args = parser.parse_args()
    if args.from_json:
        with open(RESULTS_JSON) as f:
            write_page(json.load(f))
        return
    os.makedirs(WORK, exist_ok=True)
    start, load = time.perf_counter(), report.load_average()
    have = available_options()
    variants = {name: variant_options(names, have) for name, names in VARIANTS}
    rows = read_rows()
    if args.quick:
        rows = [r for r in rows if r["id"] in QUICK]
    if args.only:
        # The rerun rows replace theirs in the stored study; without it the page would hold them alone.
        if not os.path.exists(RESULTS_JSON):
            sys.exit(f"--only: no stored study at {RESULTS_JSON} to put the rows into (run the whole study first)")
        rows = [r for r in rows if r["id"] in args.only.split(",")]
    costs = []
    for row in rows:
        row["regime"] = regime(row)
        row["et"] = eagar_tsai(row)
        row["sinter"] = {}
        for name, options in variants.items():
            # The width-only rows (IN625) run today's model and the whole one; the single-effect
            # variants run on the rows with depths, where they differ.
            if options is None or (row["depth_m"] is None and name not in ("today", "all")):
                continue
            r = run_sinter(row, name, options, row["et"], args, costs)
            row["sinter"][name] = r
            msg = r.get("error") or (f"W/D {r['width'] * 1e6:.0f}/{r['depth'] * 1e6:.0f} um, "
                                     f"{r['wall']:.1f} s, h {r['grid']['h'] * 1e6:g} um")
            print(f"{row['id']:>10} {name:>13}: {msg}", flush=True)
    result = {"rows": rows, "variants": variants, "quick": args.quick, "budget": args.budget,
              "study_wall": time.perf_counter() - start,
              "machine": report.machine(load, program=apps.app("sinter"))}
    if args.only:  # rerun rows replace theirs in the stored study
        with open(RESULTS_JSON) as f:
            stored = json.load(f)
        rerun = {r["id"]: r for r in rows}
        stored["rows"] = [rerun.pop(r["id"], r) for r in stored["rows"]] + list(rerun.values())
        stored["machine"] += f" Rerun since: {', '.join(r['id'] for r in rows)}, {result['machine']}"
        result = stored
    with open(RESULTS_JSON, "w") as f:
        json.dump(result, f, indent=1)
    write_page(result)


if __name__ == "__main__":
    main()
