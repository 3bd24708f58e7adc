#!/usr/bin/env python3
"""Accuracy costs time: softening and step against the spread layer (issue 16, point 6).

Writes docs/results/spread-accuracy.md and spread-accuracy.png (matplotlib, Agg). Run with
/usr/bin/python3 after building deposit and bedstat (POWDERBED_BUILD selects the build folder):
    POWDERBED_BUILD=build python3 bench/studies/spread_accuracy.py [--scene data/scenes/spread-blade.ini]
        [--work DIR] [--quick]

One blade layer of the scene (`deposit --config SCENE --seed S --threads 1 --out L.h5 --json`),
one run at a time, for these settings:
- --young-scale 1e5, 1e4 (the scene's), 1e3 at each one's default step (0.2 x the Rayleigh step
  of the smallest particle at the softened modulus: dt goes as young-scale^(1/2), so 1e3 takes
  sqrt(10) x the steps of 1e4);
- at young-scale 1e4, --dt 0.5 x the default step (read from the 1e4 run's JSON "dt");
- seeds: 1, 2, 3 at the 1e4 default (the seed spread), 1 and 2 for the other settings (the supply
  is placed from the seed alone, so runs of one seed start from the same particles; the spread is
  chaotic, though, so the paired differences still carry trajectory divergence of the order of
  the seed spread).
Each bed is measured with `bedstat L.h5 --spread --window X0,X1 --json` (the gap the bed records,
the plate at the floor; the window of bench/studies/spread_peer.py: the layer the blade leaves
behind it, less 10 % of its length at each end): layer density, coverage, Sa, Sq. Reported with
deposit's steps, loop wall time, the process's wall time, the largest overlap at the end
(relative to the smaller radius) and the load average around each run.

--quick runs seed 1 only. With --work DIR each run's deposit and bedstat JSON are kept in DIR and a
later call reuses them (a run is repeated only when its JSON is missing).
"""
import argparse
import json
import os
import statistics
import sys
import tempfile

from lib.apps import ROOT, app, bedstat, run_json
from lib.report import RESULTS, machine, write_page_with_discussion
from lib.spread_scene import Scene, shown_path

SCENE = os.path.join(ROOT, "data", "scenes", "spread-blade.ini")
# (label, young-scale, factor on the 1e4 default dt or None for the setting's own default, seeds)
SETTINGS = [
    ("1e4", 1e4, None, [1, 2, 3]),
    ("1e5", 1e5, None, [1, 2]),
    ("1e4, dt/2", 1e4, 0.5, [1, 2]),
    ("1e3", 1e3, None, [1, 2]),
]
REFERENCE = "1e3"     # the stiffest setting


def one_run(scene, work, label, young_scale, dt, seed):
    """{deposit: JSON, wall: s, stats: bedstat spread, load: [before, after]}, cached in work."""
    tag = f"ys{young_scale:g}-dt{'default' if dt is None else format(dt, '.4g')}-s{seed}"
    saved = os.path.join(work, tag + ".json")
    if os.path.exists(saved):
        with open(saved) as f:
            return json.load(f)
    bed = os.path.join(work, tag + ".h5")
    cmd = [app("deposit"), "--config", scene.path, "--seed", str(seed), "--threads", "1",
           "--young-scale", repr(young_scale), "--out", bed]
    if dt is not None:
        cmd += ["--dt", repr(dt)]
    print(f"spread_accuracy: {label}, seed {seed}: {' '.join(cmd[1:])}", file=sys.stderr, flush=True)
    load_before = os.getloadavg()[0]
    summary, wall = run_json(cmd)
    load_after = os.getloadavg()[0]
    window = scene.window()
    stats = bedstat([bed, "--spread", "--window", f"{window[0]!r},{window[1]!r}"])["spread"]
    stats.pop("segregation", None)
    result = {"label": label, "young_scale": young_scale, "dt_arg": dt, "seed": seed,
              "deposit": {k: summary[k] for k in ("n", "steps", "dt", "dt_stable", "wall_time",
                                                  "particle_steps_per_s", "max_overlap", "young_scale")},
              "overflow": summary["layers"][-1]["overflow"],
              "wall": wall, "stats": stats, "load": [load_before, load_after]}
    with open(saved, "w") as f:
        json.dump(result, f, indent=1)
    os.remove(bed)          # the bed is measured; keep the work folder small
    return result


def mean_sd(values):
    return statistics.mean(values), (statistics.stdev(values) if len(values) > 1 else 0.0)


def plot(groups, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(8, 3.3))
    for ax, key, name in ((axes[0], "density", "layer density"), (axes[1], "coverage", "coverage")):
        for label, runs in groups:
            walls = [r["deposit"]["wall_time"] for r in runs]
            vals = [r["stats"][key] for r in runs]
            line = ax.plot(walls, vals, "o", alpha=0.5)[0]
            ax.errorbar([statistics.mean(walls)], [statistics.mean(vals)],
                        yerr=[statistics.stdev(vals)] if len(vals) > 1 else None,
                        fmt="s", color=line.get_color(), capsize=3, label=label)
        ax.set_xscale("log")
        ax.set_xlabel("wall time of the spread (s, one thread)")
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8, title="young-scale", title_fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scene", default=SCENE)
    parser.add_argument("--work", default=None, help="keep each run's JSON here (and reuse it)")
    parser.add_argument("--quick", action="store_true", help="seed 1 only")
    args = parser.parse_args()
    scene = Scene(os.path.abspath(args.scene), {})
    with tempfile.TemporaryDirectory() as tmp:
        work = os.path.abspath(args.work) if args.work else tmp
        os.makedirs(work, exist_ok=True)
        base_dt = None
        groups = []
        for label, ys, factor, seeds in SETTINGS:
            runs = []
            for seed in (seeds[:1] if args.quick else seeds):
                dt = None if factor is None else factor * base_dt
                r = one_run(scene, work, label, ys, dt, seed)
                if label == "1e4" and base_dt is None:
                    base_dt = r["deposit"]["dt"]
                runs.append(r)
            groups.append((label, runs))
    write_study_page(scene, args, groups, base_dt)


def write_study_page(scene, args, groups, base_dt):
    window = scene.window()
    loads = [r["load"] for _, runs in groups for r in runs]
    first_load, last_load = loads[0][0], loads[-1][1]
    rows = [
        "# Spread accuracy: softening and step against the layer (issue 16 point 6)",
        "",
        f"`python3 bench/studies/spread_accuracy.py{' --quick' if args.quick else ''}` (method in the "
        f"script's docstring) on `{shown_path(args.scene)}`: one blade layer, strip {scene.lx * 1e3:g} x "
        f"{scene.ly * 1e3:g} mm periodic in y, gap {scene.gap * 1e6:.0f} µm, "
        f"{scene.speed * 1e3:.0f} mm/s, E = {scene.young:.3g} Pa divided by the young-scale; the "
        f"1e4 default step is {base_dt:.4g} s. One thread, one run at a time under `nice -n 10`. Layer "
        f"statistics by `bedstat --spread` over x in [{window[0] * 1e3:.3f}, {window[1] * 1e3:.3f}] mm, "
        "plate at the floor, the gap the bed records.",
        machine(f"{first_load:.2f} (1 min)", f"{last_load:.2f} (1 min)", program=app("deposit"))
        + " The 1-min load average before and after each run is in the table "
        "(wall times are comparable only between runs at similar load).",
        "",
        "| young-scale | seed | dt (s) | steps | loop wall (s) | process wall (s) | load before/after "
        "| particles left | max overlap (r) | layer density | coverage | Sa (µm) | Sq (µm) |",
        "|---" * 13 + "|",
    ]
    for label, runs in groups:
        for r in runs:
            d, s = r["deposit"], r["stats"]
            rows.append(
                f"| {label} | {r['seed']} | {d['dt']:.4g} | {d['steps']} | {d['wall_time']:.1f} | "
                f"{r['wall']:.1f} | {r['load'][0]:.2f} / {r['load'][1]:.2f} | {d['n']} | "
                f"{d['max_overlap']:.4f} | {s['density']:.4f} | {s['coverage']:.4f} | "
                f"{s['sa'] * 1e6:.2f} | {s['sq'] * 1e6:.2f} |")
    rows += [
        "",
        "## Mean ± sd over the seeds, and the paired difference from the stiffest setting",
        "",
        f"Δ: the mean over the seeds both settings ran of (setting − {REFERENCE}), seed by seed. Runs of "
        "one seed start from the same supply, but the spread is chaotic (a change of dt alone moves "
        "the layer by as much as a change of seed), so Δ is not the setting's bias alone: compare it "
        "with the seed spread (sd).",
        "",
        "| young-scale | seeds | mean loop wall (s) | steps | layer density | Δ density | coverage "
        "| Δ coverage | Sa (µm) | Sq (µm) |",
        "|---" * 10 + "|",
    ]
    ref = {r["seed"]: r for r in dict(groups)[REFERENCE]}
    for label, runs in groups:
        def ms(key, scale=1.0):
            m, sd = mean_sd([r["stats"][key] * scale for r in runs])
            return m, sd

        def delta(key):
            diffs = [r["stats"][key] - ref[r["seed"]]["stats"][key] for r in runs if r["seed"] in ref]
            return statistics.mean(diffs) if diffs else float("nan")
        dm, dsd = ms("density")
        cm, csd = ms("coverage")
        am, asd = ms("sa", 1e6)
        qm, qsd = ms("sq", 1e6)
        wall = statistics.mean(r["deposit"]["wall_time"] for r in runs)
        rows.append(
            f"| {label} | {','.join(str(r['seed']) for r in runs)} | {wall:.1f} | "
            f"{runs[0]['deposit']['steps']} | {dm:.4f} ± {dsd:.4f} | {delta('density'):+.4f} | "
            f"{cm:.4f} ± {csd:.4f} | {delta('coverage'):+.4f} | {am:.2f} ± {asd:.2f} | "
            f"{qm:.2f} ± {qsd:.2f} |")
    plot(groups, os.path.join(RESULTS, "spread-accuracy.png"))
    rows += ["", "![layer density and coverage against wall time](spread-accuracy.png)", ""]
    print(write_page_with_discussion("spread-accuracy.md", "\n".join(rows)))


if __name__ == "__main__":
    main()
