#!/usr/bin/env python3
"""A dosed blade layer (issue 32, point 4): does more supply and a slower blade bring the layer of
data/scenes/spread-blade.ini into the measured 0.38-0.60 band, and what the layer's density is
over its own powder rather than over the gap.

Writes docs/results/spread-dosing.md. Run with /usr/bin/python3 after building deposit and
bedstat (POWDERBED_BUILD selects the build folder):
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
from lib.report import batch_lines, load_average, record_batches, table_head, table_row, write_page
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


def page(runs, scene, batches):
    nominal = scene.nominal_layer()
    x0, x1 = scene.window()

    def rows(key):
        return [r for r in runs if r["key"] == key]

    def span(values, fmt="{:.3f}", sep="-"):
        values = list(values)
        lo, hi = fmt.format(min(values)), fmt.format(max(values))
        return lo if lo == hi else f"{lo}{sep}{hi}"

    def dens(key):
        return span(r["stats"]["density"] for r in rows(key))

    def seeds(key):
        n = len(rows(key))
        return f"{n} seed{'s' if n > 1 else ''}"

    best = max(runs, key=lambda r: r["stats"]["density"])
    lines = [
        "# A dosed blade layer: more supply and a slower blade",
        "",
        f"`POWDERBED_BUILD=build python3 bench/studies/spread_dosing.py` (method in the script's "
        "docstring): one blade layer of `data/scenes/spread-blade.ini` (316L 15-45 µm, 2 mm strip "
        f"0.5 mm across, gap {scene.gap * 1e6:.0f} µm) per row, measured over x "
        f"{x0 * 1e3:.2f}-{x1 * 1e3:.2f} mm as docs/results/spread-density.md measures its rows. "
        "Run one at a time, one thread each, on a 2-core machine shared with other work; the load "
        "column is the 1-min load average when each run started.",
        *batch_lines(batches),
        "",
        "**The supply by volume.** The scene's psd gives D10/D50/D90 = 19/30/45 µm by volume "
        "(bed/include/powderbed/bed/psd.hpp: a d10/d50/d90 lognormal is volume-based unless "
        "`basis=number`), so the particles' number median is ~23 µm and the scene's 2500 "
        f"particles hold {span((r['supply_solid'] for r in rows('scene')), '{:.2e}', ' to ')} m³ of "
        f"solid ({seeds('scene')}). The layer's nominal powder (deposit's `supply.dosing`: "
        f"φ_b (end − start) L_y t at φ_b = {scene.num('supply.bulk-density'):g}, t the "
        f"{scene.gap * 1e6:.0f} µm gap) is {nominal:.2e} m³, so the scene doses "
        f"{span((r['supply_solid'] / nominal for r in rows('scene')), '{:.2f}')} on its gap "
        f"(twice that on the build's {scene.num('recoater.layer-thickness') * 1e6:.0f} µm "
        "layers), where machines dose 1.5-2.",
        "",
        *table_head("row", "seed", "supplied", "supply solid (m³)", "dosing on the gap",
                    "overflow", "layer density", "coverage", "mean top (µm)",
                    "powder-top density", "Sa (µm)", "deposit wall (s)", "load"),
    ]
    for r in runs:
        s = r["stats"]
        lines.append(table_row(
            r["label"], r["seed"], r["supplied"], f"{r['supply_solid']:.2e}",
            f"{r['supply_solid'] / nominal:.2f}", r["overflow"], f"{s['density']:.3f}",
            f"{s['coverage']:.3f}", f"{s['mean_height'] * 1e6:.1f}", f"{top_density(r):.2f}",
            f"{s['sa'] * 1e6:.1f}", f"{r['wall']:.0f}", r["load"][0].split()[0]))
    lines += [
        "",
        "Overflow: the particles the blade pushed past its end (centres in front of its front "
        "face where it stopped), as deposit's overflow counts them; 0 means the supply ran out "
        "before the end of the travel. Layer density: the solid between the plate and the gap over "
        "the window (bedstat `--spread`). Mean top: the mean height of the powder's top surface "
        "over the window, bare plate counted as 0. Powder-top density: the same solid over the "
        "window's area times the mean top, layer density × gap / mean top.",
        "",
        f"**The band.** The scene leaves {dens('scene')} ({seeds('scene')}). At {SLOW} m/s its "
        f"supply leaves {dens('slow')} ({seeds('slow')}) and runs out: overflow "
        f"{span((r['overflow'] for r in rows('slow')), '{:d}')}, coverage "
        f"{span(r['stats']['coverage'] for r in rows('slow'))}. With supply.dosing 1 (a dosing of "
        f"{span((r['supply_solid'] / nominal for r in rows('dosed-slow')), '{:.2f}')} on the gap "
        f"as measured, 2 on a 45 µm layer) at {SLOW} m/s the blade leaves {dens('dosed-slow')} ({seeds('dosed-slow')}, coverage "
        f"{span(r['stats']['coverage'] for r in rows('dosed-slow'))}) and still pushes "
        f"{span((r['overflow_solid'] / r['supply_solid'] for r in rows('dosed-slow')), '{:.0%}')} "
        "of the supply's solid past the strip's end (the scene at 0.1 m/s: "
        f"{span((r['overflow_solid'] / r['supply_solid'] for r in rows('scene')), '{:.0%}')}), so "
        "the powder in front of the blade is not what is short. "
        "docs/results/spread-density.md has the steps between: 0.05 m/s alone, and twice the "
        "supply at 0.05 m/s. The densest layer here, "
        f"{best['stats']['density']:.3f}, is "
        + (f"inside the measured {BAND[0]:.2f}-{BAND[1]:.2f} band."
           if best["stats"]["density"] >= BAND[0] else
           f"{BAND[0] - best['stats']['density']:.2f} short of the measured "
           f"{BAND[0]:.2f}-{BAND[1]:.2f} band: a dose of twice the scene's at a quarter of its "
           "speed does not bring the blade's first layer on a flat plate into it."),
        "",
        "**Why, measured.** Over the gap the layer is sparse because its powder does not reach "
        "the gap's height: the mean height of its top surface is "
        f"{span((r['stats']['mean_height'] * 1e6 for r in rows('scene')), '{:.0f}')} µm for the "
        f"scene (the particles' mean diameter is {MEAN_D * 1e6:.0f} µm by number; "
        f"{span((1 - r['stats']['coverage'] for r in rows('scene')), '{:.0%}')} of the plate "
        f"bare), {span((r['stats']['mean_height'] * 1e6 for r in rows('slow')), '{:.0f}')} µm "
        f"for the scene's supply at {SLOW} m/s and "
        f"{span((r['stats']['mean_height'] * 1e6 for r in rows('dosed-slow')), '{:.0f}')} µm "
        f"dosed at {SLOW} m/s, inside a {scene.gap * 1e6:.0f} µm gap "
        f"({scene.gap / MEAN_D:.1f} mean diameters). Under "
        f"its own top surface the same powder is {span(top_density(r) for r in rows('scene'))} "
        f"dense for the scene, {span(top_density(r) for r in rows('slow'))} and "
        f"{span(top_density(r) for r in rows('dosed-slow'))} for the slow rows (powder-top "
        + ("density): above" if min(map(top_density, runs)) > BAND[1] else "density): against")
        + " the band, but not the band's measure either. It says how the "
        "powder is stacked, not how much of the plate it covers: a lone sphere on the plate "
        "reads 0.80 (the volume under its top surface is 5/3 π r³) whatever the bare plate "
        "around it, so does the square monolayer, and only a layer many particles thick tends "
        "to its bulk packing (random close packing ~0.64). So the gap-based density is low "
        "because the layer is thin: its mean top is "
        f"{span((r['stats']['mean_height'] / MEAN_D for r in runs), '{:.1f}', ' to ')} mean "
        f"diameters against a gap of {scene.gap / MEAN_D:.1f}, with part of the plate bare; at "
        "the dosed rows' powder-top density a "
        f"gap-based {BAND[0]:.2f} would need a mean top of ~"
        f"{BAND[0] * scene.gap / statistics.mean(top_density(r) for r in rows('dosed-slow')) * 1e6:.0f}"
        " µm. The measured band is of layers a blade spreads into a recess over earlier powder "
        "and solid (docs/results/spread-density.md, its last paragraph), not of one layer on a "
        "flat plate under 2 D90; the build's later layers, spread over the powder and the solid "
        "before them (docs/results/build-layers.md), are where the two could meet.",
    ]
    return "\n".join(lines) + "\n"


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
