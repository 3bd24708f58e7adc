#!/usr/bin/env python3
"""A dosed blade layer (issue 32, point 4): does more supply and a slower blade bring the layer of
data/scenes/spread-blade.ini into the measured 0.38-0.60 band, and what the layer's density is
over its own powder rather than over the gap.

Writes docs/results/spread-dosing.md (its prose: bench/studies/templates/spread-dosing.md.in).
Run with /usr/bin/python3 after building deposit and bedstat (POWDERBED_BUILD selects the build
folder):
    POWDERBED_BUILD=build python3 bench/studies/spread_dosing.py [--work DIR] [--only KEYS]

The supply. The scene's psd gives D10/D50/D90 = 19/30/45 um by volume (psd.hpp: the default
basis of a d10/d50/d90 lognormal), so the particles' number median is ~23 um and the scene's 2500
particles hold ~2.3e-11 m^3 of solid. The dosing factor is deposit's (supply.dosing,
docs/deposit-spread.md): the supply's solid over phi_b (recoater.end - recoater.start) L_y t with
phi_b = supply.bulk-density (0.5) and t the gap (90 um), Scene.nominal_layer() of
lib/spread_scene.py; each row's is measured on its own supply (the solid of every particle in the
bed, overflow included). The scene's supply is a dosing of ~0.5 on its 90 um gap (~1.0 on a 45 um
layer of the build); machines dose 1.5-2.

The rows, each one blade layer `deposit --config data/scenes/spread-blade.ini --seed S --threads
1 --recoater.overflow false --out L.h5` with the row's options:
- scene: the scene as it is (0.1 m/s), seeds 1 and 2 (the control);
- dosed-slow: supply.dosing 1 (the supply region x 0.2-1.2 mm instead of 0.7 mm, to hold it at the
  scene's height: a dosing of 2 on a 45 um layer) and the blade at 0.025 m/s, seeds 1 and 2;
- slow: the scene's supply, the blade at 0.025 m/s, seed 1 (what the speed does alone).
recoater.overflow false keeps the powder the blade pushed past its end in the bed (the overflow
is removed after the layer, so the layer is the same): it is counted here as the particles
whose centres lie in front of the blade's front face where it stopped, as deposit's overflow is.
Each layer is measured as docs/results/spread-density.md measures its rows: `bedstat L.h5
--spread --window X0,X1 --json`, the window Scene.window() (the blade's front face at the start to
its back face at the end, less 10 % at each end). The layer density there is the solid between
the plate and the gap over the window; the powder-top density is the same solid over the window's
area times the mean height of the powder's top surface (bedstat's mean_height, bare plate
counted as 0): the layer's solid fraction under its own surface, the height a profilometer
would read. For the square monolayer of equal spheres resting on the plate it is 0.80 (phi =
pi/6 at a gap of 2r, mean height 5 pi r / 12; docs/spread-layer.md). The runs are kept in --work
(default out/studies/spread-dosing) and reused; results.json there keeps each run's load and the
machine sentence of the call that ran it. --only KEYS runs those rows afresh. Run one at a time,
one thread each (a spread of the dosed-slow rows takes ~5 min of one core).
"""
import argparse
import os
import statistics
import sys

from lib.apps import ROOT, app, memo_json, read_bed, remove_bed, spread_layer
from lib.report import (batch_lines, fill_template, load_average, record_batches, table_head,
                        table_row, write_page)
from lib.spread_scene import Scene, check_rows_keep_window, run_rows, solid_volume

SCENE = os.path.join(ROOT, "data", "scenes", "spread-blade.ini")
WORK = os.path.join(ROOT, "out", "studies", "spread-dosing")
PAGE = "spread-dosing.md"
BAND = (0.38, 0.60)           # measured spread layers (spread-density.md)
# the psd's number-mean diameter (its truncated lognormal; the supplies drawn: 24.1-24.3 um)
MEAN_D = 24.2e-6
SLOW = "0.025"                # m/s, a quarter of the scene's blade speed
DOSED = ["--supply.count", "0", "--supply.dosing", "1", "--supply.x1", "1.2e-3"]
# (key, label, deposit options, seeds); seed 1 of every row runs first
ROWS = [
    ("scene", "the scene (2500 particles, 0.1 m/s)", [], [1, 2]),
    ("dosed-slow", f"supply.dosing 1 (x 0.2-1.2 mm), blade at {SLOW} m/s",
     DOSED + ["--recoater.speed", SLOW], [1, 2]),
    ("slow", f"the scene's supply, blade at {SLOW} m/s", ["--recoater.speed", SLOW], [1]),
]


def tag(key, seed):
    return f"{key}-s{seed}"


def layer_run(work, key, label, options, seed, scene, fresh):
    """One row's run and its measures, cached in work as TAG.json (fresh: run again)."""
    def make():
        bed = os.path.join(work, tag(key, seed) + ".h5")
        before = load_average()
        dep, wall, stats = spread_layer(SCENE, seed, ["--recoater.overflow", "false"] + options, bed,
                                        scene.window())
        centres, radii = read_bed(bed)
        remove_bed(bed)
        front = scene.end + scene.thickness / 2  # the blade's front face where it stopped
        over = [r for c, r in zip(centres, radii) if c[0] > front]
        print(f"{label}, seed {seed}: density {stats['density']:.3f}", file=sys.stderr, flush=True)
        return {"seed": seed, "options": options, "n": dep["n"], "lost": dep["lost"],
                "supplied": dep["layers"][0]["supplied"], "supply_solid": solid_volume(radii),
                "overflow": len(over), "overflow_solid": solid_volume(over), "wall": wall,
                "stats": stats, "load": [before, load_average()]}
    out = memo_json(os.path.join(work, tag(key, seed) + ".json"), fresh, make)
    return dict(out, key=key, label=label)


def top_density(r):
    """The layer's solid over the window's area times the powder's mean top height."""
    s = r["stats"]
    return s["density"] * s["gap"] / s["mean_height"]


def span(values, fmt="{:.3f}", sep="-"):
    """The range of `values` as text in `fmt`, one number when both ends read the same."""
    values = list(values)
    lo, hi = fmt.format(min(values)), fmt.format(max(values))
    return lo if lo == hi else f"{lo}{sep}{hi}"


def row_values(name, rows, nominal):
    """The template's numbers of one row's runs, each named `name`_what (the template quotes
    some of them for each row)."""
    n = len(rows)
    return {f"{name}_seeds": f"{n} seed{'s' if n > 1 else ''}",
            f"{name}_density": span(r["stats"]["density"] for r in rows),
            f"{name}_coverage": span(r["stats"]["coverage"] for r in rows),
            f"{name}_bare": span((1 - r["stats"]["coverage"] for r in rows), "{:.0%}"),
            f"{name}_solid": span((r["supply_solid"] for r in rows), "{:.2e}", " to "),
            f"{name}_dosing": span((r["supply_solid"] / nominal for r in rows), "{:.2f}"),
            f"{name}_overflow": span((r["overflow"] for r in rows), "{:d}"),
            f"{name}_overflow_share": span((r["overflow_solid"] / r["supply_solid"] for r in rows),
                                           "{:.0%}"),
            f"{name}_top": span((r["stats"]["mean_height"] * 1e6 for r in rows), "{:.0f}"),
            f"{name}_top_density": span(top_density(r) for r in rows)}


def run_table(runs, nominal):
    """One line per run: its supply, its overflow and the layer it left."""
    lines = table_head("row", "seed", "supplied", "supply solid (m³)", "dosing on the gap",
                       "overflow", "layer density", "coverage", "mean top (µm)",
                       "powder-top density", "Sa (µm)", "deposit wall (s)", "load")
    for r in runs:
        s = r["stats"]
        lines.append(table_row(
            r["label"], r["seed"], r["supplied"], f"{r['supply_solid']:.2e}",
            f"{r['supply_solid'] / nominal:.2f}", r["overflow"], f"{s['density']:.3f}",
            f"{s['coverage']:.3f}", f"{s['mean_height'] * 1e6:.1f}", f"{top_density(r):.2f}",
            f"{s['sa'] * 1e6:.1f}", f"{r['wall']:.0f}", r["load"][0].split()[0]))
    return "\n".join(lines)


def against_band(best):
    """Where the densest layer's density `best` lies against the measured band."""
    if best >= BAND[0]:
        return f"inside the measured {BAND[0]:.2f}-{BAND[1]:.2f} band."
    return (f"{BAND[0] - best:.2f} short of the measured {BAND[0]:.2f}-{BAND[1]:.2f} band: a "
            "dose of twice the scene's at a quarter of its speed does not bring the blade's "
            "first layer on a flat plate into it.")


def page(runs, scene, batches):
    """The page: templates/spread-dosing.md.in filled with the runs of every row."""
    nominal = scene.nominal_layer()
    x0, x1 = scene.window()
    best = max(r["stats"]["density"] for r in runs)
    dosed = [r for r in runs if r["key"] == "dosed-slow"]
    values = {
        "machine": "\n".join(batch_lines(batches)),
        "gap": f"{scene.gap * 1e6:.0f}", "x0": f"{x0 * 1e3:.2f}", "x1": f"{x1 * 1e3:.2f}",
        "bulk_density": f"{scene.num('supply.bulk-density'):g}", "nominal": f"{nominal:.2e}",
        "layer": f"{scene.num('recoater.layer-thickness') * 1e6:.0f}", "slow": SLOW,
        "table": run_table(runs, nominal),
        "best": f"{best:.3f}", "against_band": against_band(best),
        "mean_d": f"{MEAN_D * 1e6:.0f}", "gap_diameters": f"{scene.gap / MEAN_D:.1f}",
        "top_against_band": "above" if min(map(top_density, runs)) > BAND[1] else "against",
        "top_diameters": span((r["stats"]["mean_height"] / MEAN_D for r in runs), "{:.1f}",
                              " to "),
        "band_low": f"{BAND[0]:.2f}",
        # the mean top that would give the band's low end at the dosed rows' powder-top density
        "top_needed": f"{BAND[0] * scene.gap / statistics.mean(map(top_density, dosed)) * 1e6:.0f}",
    }
    for name, key in (("scene", "scene"), ("slow", "slow"), ("dosed", "dosed-slow")):
        values.update(row_values(name, [r for r in runs if r["key"] == key], nominal))
    return fill_template("spread-dosing.md.in", values)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--work", default=WORK)
    parser.add_argument("--only", help="comma-separated keys of the rows to run afresh "
                        f"({', '.join(r[0] for r in ROWS)})")
    args = parser.parse_args()
    only = args.only.split(",") if args.only else []
    unknown = [k for k in only if k not in [r[0] for r in ROWS]]
    if unknown:
        sys.exit(f"spread_dosing: --only {','.join(unknown)}: no such row "
                 f"(accepted: {', '.join(r[0] for r in ROWS)})")
    os.makedirs(args.work, exist_ok=True)
    scene = Scene(SCENE, {})
    check_rows_keep_window("spread_dosing", SCENE, ROWS)
    path = os.path.join(args.work, "results.json")
    ran = [key for key, _, _, seeds in ROWS
           if key in only or any(not os.path.exists(os.path.join(args.work, tag(key, s) + ".json"))
                                 for s in seeds)]
    before = load_average()
    runs = run_rows(ROWS, lambda key, label, options, seed:
                    layer_run(args.work, key, label, options, seed, scene, key in only))
    batches = record_batches(path, ran, before, app("deposit"))
    print(write_page(PAGE, page(runs, scene, batches)))


if __name__ == "__main__":
    main()
