#!/usr/bin/env python3
"""A taller heap in front of the blade (issue 32: towards a machine-sized dose): the layer of
data/scenes/spread-blade.ini with a supply heap several times taller, at the scene's blade
speed and at a slower one, measured as docs/results/spread-density.md measures its rows.

Writes its section of docs/results/spread-density.md (between the markers
<!-- spread-heap:begin --> and <!-- spread-heap:end -->; spread_density.py keeps it when it
rewrites the page). Run with /usr/bin/python3 after building deposit and bedstat
(POWDERBED_BUILD selects the build folder):
    POWDERBED_BUILD=build python3 bench/studies/spread_heap.py [--work DIR] [--only KEYS]

spread-shear.md found that only a small heap (~150 µm thick, ~300 µm tall) moves with the
scene's blade: the scene supplies 2500 particles (x 0.2-0.7 mm, 0.5 mm across, 0.7 mm tall,
placed without overlap at a solid fraction of ~0.13) and lets them fall for 10 ms. In a
machine the dose in front of the blade is a heap millimetres tall. The TALL supply here keeps
the scene's x range, its 0.5 mm periodic width and its number density, and is TALL_FACTOR
times taller (so TALL_FACTOR times the particles); the box is raised to hold it and the blade
waits TALL_DELAY before it moves, time for the supply to fall through the gas (a 30 µm sphere
in argon falls at ~0.19 m/s once its ~19 ms relaxation is over). Everything else is the
scene's: the gap (90 µm), the blade, the contact laws, the drag, the travel (0.1 to 2.2 mm)
and so the window of the layer. The rows:

- tall: the tall supply at the scene's blade speed (0.1 m/s), seeds 1 and 2;
- tall-slow: the tall supply at 0.05 m/s, seeds 1 and 2.

Each row is one blade layer, `deposit --config data/scenes/spread-blade.ini --seed S
--threads 1 --out L.h5` with the row's options, measured as spread_density.py measures its
rows: `bedstat L.h5 --spread --window X0,X1 --json`, the window Scene.window() of
lib/spread_scene.py (the blade's front face at the start to its back face at the end, less 10 %
at each end). The heap as posed is the same run stopped as the blade starts to move
(`--recoater.end` 1 µm past the start, `--recoater.settle 0 --recoater.overflow false`, seed 1;
the supply's fall does not depend on the blade's speed): its height is the highest surface of
the 50 µm columns in front of the blade (a column's surface the 95th percentile of its
particles' tops z + r, so that a fine still falling does not count), and its length the extent
along x of the columns whose surface lies above the gap. The runs are kept in --work (default
out/studies/spread-heap) and reused; results.json there keeps each run's load and the machine
sentence of the call that ran it. --only KEYS runs those rows afresh.

The literature table beside the rows is what the cited texts say, as read (LITERATURE below):
no number in it is computed here, and nothing here is fitted to it.
"""
import argparse
import json
import os
import sys

import h5py
import numpy as np

from lib.apps import ROOT, app, memo_json, remove_bed, run_json, spread_layer
from lib.report import (batch_lines, load_average, read_page, record_batches, splice,
                        section_markers, table_head, table_row, write_page)
from lib.spread_scene import Scene, check_rows_keep_window, run_rows

SCENE = os.path.join(ROOT, "data", "scenes", "spread-blade.ini")
WORK = os.path.join(ROOT, "out", "studies", "spread-heap")
PAGE = "spread-density.md"
SECTION = "spread-heap"
TALL_FACTOR = 4          # the supply's height and count over the scene's
TALL_DELAY = 40e-3       # s before the blade moves (the scene: 10 ms for a 0.7 mm supply)
COLUMN = 50e-6           # m, the columns the heap's height and length are read over


def tall_options(scene):
    """The deposit options of the tall supply: the scene's supply region TALL_FACTOR times
    taller with TALL_FACTOR times the particles, the box raised by as much."""
    o = scene.options
    height = float(o["supply.height"]) * TALL_FACTOR
    count = int(o["supply.count"]) * TALL_FACTOR
    lz = scene.lz + height - float(o["supply.height"])
    return ["--domain", f"{scene.lx!r},{scene.ly!r},{lz!r}", "--supply.height", f"{height!r}",
            "--supply.count", str(count), "--recoater.delay", f"{TALL_DELAY!r}"]


def variants(scene):
    """(key, label, deposit options, seeds) of the rows."""
    tall = tall_options(scene)
    return [
        ("tall", f"supply {TALL_FACTOR}x as tall, blade at {scene.speed:g} m/s", tall, [1, 2]),
        ("tall-slow", f"supply {TALL_FACTOR}x as tall, blade at 0.05 m/s",
         tall + ["--recoater.speed", "0.05"], [1, 2]),
    ]


def tag(key, seed):
    return f"{key}-s{seed}"


def layer_run(work, key, label, options, seed, window, fresh):
    """{key, label, seed, n, supplied, wall, stats, load}: one layer and its bedstat --spread,
    cached in work."""
    def make():
        bed = os.path.join(work, tag(key, seed) + ".h5")
        before = load_average()
        dep, wall, stats = spread_layer(SCENE, seed, options, bed, window)
        remove_bed(bed)
        layer = dep["layers"][0]
        print(f"{label}, seed {seed}: density {stats['density']:.3f} ({wall:.0f} s)", file=sys.stderr,
              flush=True)
        return {"seed": seed, "n": dep["n"], "wall": wall, "supplied": layer.get("supplied"),
                "steps": layer.get("steps"), "overflow": layer.get("overflow"), "lost": layer.get("lost"),
                "max_tool_force": layer.get("max_tool_force"), "stats": stats,
                "load": [before, load_average()]}
    out = memo_json(os.path.join(work, tag(key, seed) + ".json"), fresh, make)
    return dict(out, key=key, label=label)


def heap_shape(path, scene):
    """The heap in front of the blade in a bed file: {height, top, length, moving} — height (m)
    the highest surface of the COLUMN-wide columns in front of the blade's front face, a
    column's surface the 95th percentile of its particles' tops (z + r), so that a fine still
    falling onto the heap does not count; top (m) the highest particle top there; length (m)
    the extent along x, from the face on, of the columns whose surface lies above the gap;
    moving the share of the particles faster than 1 cm/s (the heap still settling)."""
    with h5py.File(path, "r") as f:
        p, r = f["particles/position"][:], f["particles/radius"][:]
        v = f["particles/velocity"][:]
        front = f["restart"].attrs["tool_x"] + scene.thickness / 2
    ahead = p[:, 0] >= front
    top = p[ahead, 2] + r[ahead]
    col = ((p[ahead, 0] - front) // COLUMN).astype(int)
    surface = np.array([np.percentile(top[col == c], 95) if np.any(col == c) else 0.0
                        for c in range(col.max() + 1)])
    above = np.nonzero(surface > scene.gap)[0]
    return {"height": float(surface.max()), "top": float(top.max()),
            "length": float((above.max() + 1) * COLUMN) if above.size else 0.0,
            "moving": float(np.mean(np.linalg.norm(v, axis=1) > 0.01))}


def heap_run(work, options, scene, fresh):
    """The tall supply as the blade starts to move (seed 1): heap_shape's numbers, n, wall,
    load."""
    saved = os.path.join(work, "heap-s1.json")
    if os.path.exists(saved) and not fresh:
        with open(saved) as f:
            return json.load(f)
    bed = os.path.join(work, "heap-s1.h5")
    before = load_average()
    dep, wall = run_json([app("deposit"), "--config", SCENE, "--seed", "1", "--threads", "1",
                          "--out", bed] + options +
                         ["--recoater.end", f"{scene.start + 1e-6!r}", "--recoater.settle", "0",
                          "--recoater.overflow", "false"])
    out = dict(heap_shape(bed, scene), n=dep["n"], wall=wall, load=[before, load_average()])
    remove_bed(bed)
    with open(saved, "w") as f:
        json.dump(out, f)
    return out


# What published blade-spreading DEM studies report for the layer's solid fraction, as read
# (docs/results/spread-density.md prints it). Each row: study (authors, title, journal, year),
# gap/D, blade speed, heap, the density reported, whether it is over the whole layer or local,
# and what was read (where each number is). "not found": not in what could be read.
# The abstract of arXiv:2306.06013: "high packing fraction (between 50 %-60 % in a single layer)".
ROLLER_2023 = (0.50, 0.60)
LITERATURE = [
    ("Haeri, Wang, Ghita, Sun, \"Discrete element simulation and experimental study of powder "
     "spreading process in additive manufacturing\", Powder Technol. 306 (2017) 45-54",
     "not found", "varied (values not found)", "not found",
     "no number found; the bed's solid volume fraction falls as the spreader's translational "
     "velocity or the rods' aspect ratio rises, and a roller gives a denser bed than a blade",
     "\"solid volume fraction\" of the bed (over what, not found)",
     "the abstract (Edinburgh Research Explorer page)"),
    ("Haeri, \"Optimisation of blade type spreaders for powder bed preparation in Additive "
     "Manufacturing using DEM simulations\", Powder Technol. 321 (2017) 94-104",
     "not found", "not found", "not found",
     "no number found; the blade's profile (a super-ellipse) is optimised for the lowest void "
     "fraction of the bed, rod-shaped grains", "the bed's void fraction (over what, not found)",
     "the abstract (fdocuments.in copy of the article's first page)"),
    ("Nan et al., \"Jamming during particle spreading "
     "in additive manufacturing\", Powder Technol. 338 (2018) 253",
     "gap in multiples of D90 by number (values not found)", "not found", "not found",
     "no density found; empty patches (jamming) grow more frequent and longer as the gap "
     "narrows, and the arches' collapse bursts particles behind the blade",
     "empty patches over the work surface (a coverage, not a density)",
     "the abstract (scite.ai author page of S. Nadimi); volume and page from a reference list "
     "(ouci.dntb.gov.ua)"),
    ("Meier, Weissbach, Weinberg, Wall, Hart, \"Critical influences of particle size and "
     "adhesion on the powder layer uniformity in metal additive manufacturing\", "
     "arXiv:1804.06822v2 (2018; the journal version not read)",
     "several nominal layer thicknesses (values not found)", "varied (values not found)",
     "not found",
     "no number found; fine (mean 17 µm), cohesive Ti-6Al-4V gives low, strongly varying "
     "packing fractions", "the spatial mean and standard deviation of a packing-fraction field",
     "the abstract (readkong.com, dokumen.tips copies of the preprint)"),
    ("Mahmoodkhani, Ali, Imani Shahabad, Rani Kasinathan, Esmaeilizadeh, Keshavarzkermani, "
     "Marzbanrad, Toyserkani, \"On the measurement of effective powder layer thickness in laser "
     "powder-bed fusion additive manufacturing of metals\", Prog. Addit. Manuf. 4 (2019) "
     "109-116", "an experiment, not DEM: nominal layer 20 µm, 17-4 PH", "not found",
     "not found",
     "no density found; the effective layer thickness on the solid was over 100 µm",
     "not a density", "the abstract (rd.springer.com)"),
    ("Chen et al., \"Powder-spreading mechanisms in powder-bed-based additive manufacturing: "
     "experiments and computational modeling\", Acta Mater. 179 (2019) 158",
     "not found", "not found", "not found", "not found", "not found",
     "only its entry in a reference list (ouci.dntb.gov.ua)"),
    ("Chen et al. 2017 (the spreading DEM study the issue names)", "not found", "not found",
     "not found", "not found", "not found", "nothing: no copy found"),
    ("Fouda, Bayly, \"A DEM study of powder spreading in additive layer manufacturing\", "
     "Granular Matter 22 (2020), doi 10.1007/s10035-019-0971-x",
     "gap 100-300 µm, Ti-6Al-4V (D not found)", "not found", "a heap in front of the blade "
     "(size not found)", "not found", "not found",
     "the introduction (springerprofessional.de) and a summary (3dprint.com): EDEM, Hertz-Mindlin"),
    ("Dai, Chan, Vastola, Zhang, \"Discrete element simulation of powder layer spreading by "
     "blade sliding: packing factor, mechanism, and optimization\", Comput. Part. Mech. (2024), "
     "doi 10.1007/s40571-024-00808-w", "not found",
     "swept; recommends a threshold of 0.15 m/s for a high packing quality",
     "a poured heap, which the layer inherits its size and shape distribution from",
     "no number found", "not found", "the abstract (oar.a-star.edu.sg)"),
    ("\"Novel simulation-inspired roller spreading strategies for fine and highly cohesive "
     "metal powders\", arXiv:2306.06013 (2023; Meier's group, DEM-FEM)",
     "not found", "not found", "not found",
     f"{ROLLER_2023[0]:.2f}-{ROLLER_2023[1]:.2f} \"in a single layer\" for a counter-rotating "
     "or oscillating roller and "
     "Ti-6Al-4V 0-20 µm: a roller, not a blade", "\"packing fraction ... in a single layer\" "
     "(over what, not found)", "the abstract (ar5iv.labs.arxiv.org)"),
]


def section(scene, runs, heap, batches, above):
    """The page's section: the rows, how they were run, the literature table, the reading
    (`above`: the rows of the page's table above it)."""
    begin, end = section_markers(SECTION)
    scene_rows = scene_rows_from_page(above)
    roller = [r for r in above if r["label"].startswith("roller")]
    if not (roller and any(r["label"].startswith("the scene") for r in scene_rows)):
        sys.exit(f"spread_heap: docs/results/{PAGE} has no rows of the scene or the roller to "
                 "compare with (run bench/studies/spread_density.py first)")
    tall = [r for r in runs if r["key"] == "tall"]
    slow = [r for r in runs if r["key"] == "tall-slow"]
    lines = [
        begin,
        "## A taller heap (issue 32: towards a machine-sized dose)",
        "",
        f"`POWDERBED_BUILD=build python3 bench/studies/spread_heap.py` (method in the script's "
        f"docstring): the blade scene with its supply {TALL_FACTOR} times as tall "
        f"({float(scene.options['supply.height']) * TALL_FACTOR * 1e3:.1f} mm instead of "
        f"{float(scene.options['supply.height']) * 1e3:.1f} mm over the same x 0.2-0.7 mm and "
        f"the same 0.5 mm periodic width, {int(scene.options['supply.count']) * TALL_FACTOR} "
        f"particles instead of {scene.options['supply.count']}, the box raised to hold it, the "
        f"blade waiting {TALL_DELAY * 1e3:.0f} ms instead of {scene.delay * 1e3:.0f} ms), "
        "everything else the scene's (gap 90 µm, the window of the rows above); one thread, "
        "one run at a time, on the shared 2-core machine. The command of each row is `deposit "
        "--config data/scenes/spread-blade.ini --seed S --threads 1 --out L.h5` with "
        f"`{' '.join(tall_options(scene))}` (and `--recoater.speed 0.05` for the slow rows), "
        "then `bedstat L.h5 --spread --window X0,X1`. The speeds: the scene's 0.1 m/s (its "
        "header: as the spreading studies of MercuryDPM and of Lethe, Gaboriault et al. 2025) "
        "and half of it; Dai et al. 2024 (table below) recommend \"a threshold sliding rate of "
        "0.15 m/s\" for a high packing quality; what speed machines' recoaters run at was not "
        "found in what could be read. The "
        "width stays the scene's 0.5 mm (each run under 20 min on one thread).",
        *batch_lines(batches),
        "",
        f"The heap as posed (the same run stopped as the blade starts, seed 1, "
        f"{heap['n']} particles, {heap['wall']:.0f} s at load {heap['load'][0].split()[0]}): "
        f"{heap['height'] * 1e3:.2f} mm tall (the highest surface of the 50 µm columns in "
        f"front of the blade, a column's surface the 95th percentile of its particles' tops; the "
        f"highest top, a fine still falling: {heap['top'] * 1e3:.2f} mm), standing above the "
        f"gap over {heap['length'] * 1e3:.2f} mm in front of the blade's face; "
        f"{heap['moving']:.0%} of the particles still moved faster than 1 cm/s.",
        "",
        *table_head("variant", "seed", "supplied", "particles left", "layer density",
                    "coverage", "Sa (µm)", "deposit wall (s)", "load"),
    ]
    for r in scene_rows + runs:
        s = r["stats"]
        lines.append(table_row(r["label"], r["seed"], r.get("supplied", "–"), r["n"],
                               f"{s['density']:.3f}", f"{s['coverage']:.3f}",
                               f"{s['sa'] * 1e6:.1f}", f"{r['wall']:.0f}",
                               r["load"][0].split()[0]))
    lines += ["", "The load is the 1-min load average when each run started; the rows of the "
              "scene are the table's above, repeated for comparison."]
    if LITERATURE:
        lines += ["", "### What published spreading studies report (as read)", "",
                  *table_head("study", "gap / D", "blade speed", "heap", "layer density reported",
                              "over the whole layer or local", "where it was read"),
                  *[table_row(*row) for row in LITERATURE]]
    lines += ["", *reading(runs, tall, slow, above, heap), end]
    return "\n".join(lines)


def reading(runs, tall, slow, above, heap):
    """The paragraphs on what the rows and the literature say (values from the runs and from
    the rows of the table above)."""
    def values(rows):
        return [r["stats"]["density"] for r in rows]

    def mean(rows):
        return sum(values(rows)) / len(rows)

    def span(rows):
        v = values(rows)
        return f"{min(v):.3f}-{max(v):.3f}" if len(v) > 1 else f"{v[0]:.3f}"

    def seeds(rows):
        return f"{len(rows)} seed{'s' if len(rows) > 1 else ''}"

    def rows_of(start):
        return [r for r in above if r["label"].startswith(start)]

    scene, small_slow = rows_of("the scene ("), rows_of("blade at 0.05 m/s")
    long, long_slow = rows_of("supply twice (5000"), rows_of("supply twice, blade at 0.05")
    roller = rows_of("roller")
    best = max(values(runs))
    long_as_much = (min(values(long)) >= min(values(tall)) and
                    min(values(long_slow)) >= min(values(slow)))
    left = [r["overflow"] / r["supplied"] for r in runs]
    return [
        f"**The taller heap.** A supply {TALL_FACTOR} times as tall slumps into a heap "
        f"{heap['height'] * 1e3:.2f} mm high and {heap['length'] * 1e3:.1f} mm long in front of "
        f"the blade when it starts ({heap['moving']:.0%} of the particles still moving), not the "
        "0.6-1 mm the issue asks of a machine's dose (the heap that moves with the scene's blade: "
        "~0.3 mm tall, spread-shear.md). A heap's height at a fixed slope grows as the square root "
        f"of its volume, so 1 mm would take ~{(1e-3 / heap['height']) ** 2:.0f} times this "
        f"supply, ~{round((1e-3 / heap['height']) ** 2 * heap['n'], -3):,.0f} particles at this "
        "width, and "
        "a longer fall: not run here (at the wall times below, well over 20 min a layer). Most "
        f"of the supply stays in front of the blade ({min(left):.0%}-{max(left):.0%} of it is "
        "pushed past the strip's end into the overflow), so the blade pushes a heap of about "
        f"that size over the whole window. It leaves {span(tall)} at the scene's 0.1 m/s "
        f"({seeds(tall)}) against the scene's {span(scene)} ({mean(tall) - mean(scene):+.3f} on "
        f"the means), and {span(slow)} at 0.05 m/s ({seeds(slow)}; "
        f"{mean(slow) - mean(tall):+.3f} on the tall heap at 0.1 m/s, "
        f"{mean(slow) - mean(small_slow):+.3f} on the scene's heap at 0.05 m/s, "
        f"{span(small_slow)})."
        " The table above's supply twice, laid over twice the length at the scene's height "
        f"(half the powder of the tall supply), left {span(long)} at 0.1 m/s and "
        f"{span(long_slow)} at 0.05 m/s ({seeds(long_slow)} each)"
        + (": as much as the tall heap or more, so the heap's height is not what adds to the "
           "layer" if long_as_much else ", less than the tall heap")
        + f". The tall heap adds {mean(tall) - mean(scene):+.2f} to the scene's layer, the slower "
        f"blade {mean(slow) - mean(tall):+.2f} more, and "
        "every row stays " + ("inside" if best >= 0.38 else "below") + " the measured "
        "0.38-0.60 band" + ("" if best >= 0.38 else f", the densest {0.38 - best:.2f} short of it")
        + ": four times the powder in front of the blade, pushed at 0.1 or 0.05 m/s, does not "
        "make the blade's layer on a flat plate as dense as measured layers"
        + (", and since the longer heap of half the powder did as well, a taller heap is not "
           "the lever." if long_as_much else "."),
        "",
        "**The literature.** In what could be read (abstracts, introductions and reference "
        "lists: the table says which), no blade-spreading DEM study gives a number for the "
        "layer's solid fraction at a gap of a few D90, so the table cannot say whether a blade "
        "layer of "
        f"{min(values(scene)):.2f}-{max(values(runs + long_slow)):.2f} on a flat plate is low "
        "for DEM; \"not found\" there means not in "
        "what was read, not that the paper has no such number. The one number found is a "
        f"roller's: {ROLLER_2023[0]:.2f}-{ROLLER_2023[1]:.2f} in a single layer for a "
        "counter-rotating or oscillating roller on a fine, cohesive Ti-6Al-4V, against the roller "
        f"rows above at {span(roller)} (the blade's {span(scene)}); a roller leaves more than a "
        f"blade in both, but that study's roller leaves {ROLLER_2023[0] / max(values(roller)):.1f}"
        f"-{ROLLER_2023[1] / min(values(roller)):.1f} times ours, with another powder, roller and "
        "kinematics. The trends that were read agree with the rows: a faster spreader leaves a "
        "looser bed (Haeri et al. 2017; here 0.05 m/s against 0.1 m/s), a narrow gap in D90 "
        "multiples leaves empty patches (Nan et al. 2018; here a coverage below 1 at 2 D90), and "
        "the layer inherits the heap it is spread from (Dai et al. 2024). The 0.38-0.60 band "
        "is of measured layers; spread_density.py attributes it to Mahmoodkhani et al. 2019, "
        "whose abstract (as read) gives an effective layer thickness (over 100 µm for a nominal "
        "20 µm), not a density.",
    ]


def page_rows(text):
    """The rows of the page's table above (spread_density.py's), parsed back for the comparison:
    [{label, seed, n, stats, wall, load}]."""
    rows = []
    for line in text.split(section_markers(SECTION)[0])[0].splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 8 and cells[1].isdigit():
            rows.append({"label": cells[0], "seed": int(cells[1]), "n": int(cells[2]),
                         "stats": {"density": float(cells[3]), "coverage": float(cells[4]),
                                   "sa": float(cells[5]) * 1e-6},
                         "wall": float(cells[6]), "load": [cells[7]]})
    return rows


def scene_rows_from_page(rows):
    """The scene's rows and its blade at 0.05 m/s, named as the table above's."""
    return [dict(r, label=r["label"] + " (the table above)") for r in rows
            if r["label"].startswith("the scene (") or r["label"] == "blade at 0.05 m/s"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--work", default=WORK)
    parser.add_argument("--only", help="comma-separated keys of the rows to run afresh "
                        "(tall, tall-slow, heap)")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    only = args.only.split(",") if args.only else []
    scene = Scene(SCENE, {})
    window = scene.window()
    rows = variants(scene)
    path = os.path.join(args.work, "results.json")
    before = load_average()
    ran = [k for k in ["heap"] + [r[0] for r in rows]
           if k in only or not os.path.exists(os.path.join(args.work, tag(k, 1) + ".json"))]
    check_rows_keep_window("spread_heap", SCENE, rows)
    runs = run_rows(rows, lambda key, label, options, seed:
                    layer_run(args.work, key, label, options, seed, window, key in only))
    heap = heap_run(args.work, tall_options(scene), scene, "heap" in only)
    batches = record_batches(path, ran, before, app("deposit"))
    text = read_page(PAGE)
    block = section(scene, runs, heap, batches, page_rows(text))
    print(write_page(PAGE, splice(text, SECTION, block)))


if __name__ == "__main__":
    main()
