#!/usr/bin/env python3
"""Why the blade's layer is sparse: one parameter of data/scenes/spread-blade.ini at a time against
the layer density it leaves (issue 32, point 4).

Writes docs/results/spread-density.md (its prose: bench/studies/templates/spread-density.md.in).
Run with /usr/bin/python3 after building deposit and bedstat (POWDERBED_BUILD selects the build
folder):
    POWDERBED_BUILD=build python3 bench/studies/spread_density.py [--work DIR] [--only KEYS]

Each variant is one blade layer, `deposit --config data/scenes/spread-blade.ini --seed S
--threads 1 --out L.h5` with the variant's options, measured as bench/studies/spread_accuracy.py
measures it: `bedstat L.h5 --spread --window X0,X1 --json` (the solid fraction between the plate
and the gap the bed records, over the strip the blade leaves behind it less 10 % at each end).
The variants change one thing from the scene (its header says where each value comes from):
sliding and rolling friction, the blade's speed, the gas drag, the gap, the softening of the
contacts (Young's modulus 1e3 and 1e2 times softer instead of the scene's 1e4), the contacts'
damping ratio (0.3 and 0.6 instead of 0.1: restitution from ~0.7 down to ~0.1), the supply (twice the
particles at the same number density, a dosing twice the scene's), and the tool's shape: a thin
blade (50 µm), a blade whose bottom is a half cylinder (edge radius = half its 200 µm thickness,
no flat face to shear the gap's particles along), and a roller, which is
data/scenes/spread-roller.ini itself (the blade scene with MercuryDPM's roller, its strip moved
0.3-0.4 mm along x to make room for the roller's 0.5 mm radius). The blade rows are measured over
the scene's window; the roller row over its own: from the roller's front at the start (where its
supply begins) to its axis, the lowest point, at the end, less the same 10 % at each end. Measured spread layers of
gas-atomised powders lie at 0.38-0.60 (the values Mahmoodkhani et al. 2019 collect); nothing here
is fitted to that band: the page shows which parameters move the layer towards it and how far.
The runs are kept in --work (default out/studies/spread-density) and a later call reuses them;
the study's rows (and the machine sentence of the call that ran them) are stored there in
results.json. --only KEYS (comma-separated keys of VARIANTS, e.g. thin,round) runs those rows
afresh and puts them into the stored study in place of theirs, the others as stored: the page
still lists every row, with the load of each call. A results.json missing is made from the
runs kept in --work and the page's Machine line (the study before it kept one).
"""
import argparse
import json
import os
import re
import sys

from lib.apps import ROOT, app, bedstat, run_json
from lib.report import (fill_template, load_average, machine, read_page, table_head, table_row,
                        write_page_keeping)
from lib.spread_scene import WINDOW_MARGIN, Scene, read_scene

SCENE = os.path.join(ROOT, "data", "scenes", "spread-blade.ini")
ROLLER = os.path.join(ROOT, "data", "scenes", "spread-roller.ini")
WORK = os.path.join(ROOT, "out", "studies", "spread-density")
SUPPLY_TWICE = ["--supply.count", "5000", "--supply.x1", "1.2e-3"]
# (key for --only, label, scene, deposit options, seeds)
VARIANTS = [
    ("scene", "the scene (μ 0.5, μ_r 0.1, 0.1 m/s, gap 90 µm, drag)", SCENE, [], [1, 2]),
    ("rolling", "rolling friction 0.01", SCENE, ["--material.rolling", "0.01"], [1]),
    ("sliding", "sliding friction 0.3", SCENE, ["--material.friction", "0.3"], [1]),
    ("friction", "μ 0.3 and μ_r 0.01", SCENE,
     ["--material.friction", "0.3", "--material.rolling", "0.01"], [1]),
    ("slow", "blade at 0.05 m/s", SCENE, ["--recoater.speed", "0.05"], [1, 2]),
    ("nodrag", "no gas drag", SCENE, ["--effects.drag", "false"], [1]),
    ("gap135", "gap 135 µm (3 D90)", SCENE, ["--recoater.gap", "135e-6"], [1]),
    ("supply2", "supply twice (5000 over 0.2-1.2 mm)", SCENE, SUPPLY_TWICE, [1]),
    ("supply2-slow", "supply twice, blade at 0.05 m/s", SCENE,
     SUPPLY_TWICE + ["--recoater.speed", "0.05"], [1]),
    ("supply2-gap180", "supply twice, gap 180 µm (4 D90)", SCENE,
     SUPPLY_TWICE + ["--recoater.gap", "180e-6"], [1]),
    ("thin", "blade 50 µm thick (sharp edges)", SCENE, ["--recoater.thickness", "50e-6"], [1]),
    ("round", "blade edge radius 100 µm (200 µm thick: a half-cylinder bottom)", SCENE,
     ["--recoater.edge-radius", "100e-6"], [1, 2]),
    ("round-supply2", "supply twice, blade edge radius 100 µm", SCENE,
     SUPPLY_TWICE + ["--recoater.edge-radius", "100e-6"], [1, 2]),
    ("roller", "roller (spread-roller.ini: R 0.5 mm, ωR = 0.1 m/s counter-rotating)", ROLLER,
     [], [1, 2]),
    ("damping0.3", "damping ratio 0.3 (the scene: 0.1)", SCENE, ["--material.damping", "0.3"], [1]),
    ("damping0.6", "damping ratio 0.6 (the scene: 0.1)", SCENE, ["--material.damping", "0.6"], [1]),
    ("stiff1e3", "Young's modulus softened 1e3 times (the scene: 1e4)", SCENE,
     ["--young-scale", "1e3"], [1]),
    ("stiff1e2", "Young's modulus softened 1e2 times (the scene: 1e4)", SCENE,
     ["--young-scale", "1e2"], [1]),
]


def window(scene):
    """The x range bedstat measures: the blade scene's Scene.window(), or for a roller from its
    front at the start to its axis (its lowest point) at the end, less the same margin."""
    if scene == SCENE:
        return Scene(SCENE, {}).window()
    o = read_scene(scene)
    lo, hi = float(o["recoater.start"]) + float(o["recoater.radius"]), float(o["recoater.end"])
    margin = WINDOW_MARGIN * (hi - lo)
    return lo + margin, hi - margin


def run_tag(scene, options, seed):
    """The name of a run's files in work (the blade scene's runs keep the names they had)."""
    prefix = "" if scene == SCENE else os.path.splitext(os.path.basename(scene))[0] + "-"
    return prefix + "".join(c if c.isalnum() else "-" for c in "-".join(options) or "scene") + \
        f"-s{seed}"


def one_run(work, key, label, scene, options, seed, fresh=False):
    """{deposit: JSON, stats: bedstat spread JSON, load: [before, after]}, cached in work
    (fresh: run again even when cached)."""
    tag = run_tag(scene, options, seed)
    saved = os.path.join(work, tag + ".json")
    if os.path.exists(saved) and not fresh:
        with open(saved) as f:
            return dict(json.load(f), key=key, label=label)
    bed = os.path.join(work, tag + ".h5")
    before = load_average()
    dep, wall = run_json([app("deposit"), "--config", scene, "--seed", str(seed), "--threads", "1",
                          "--out", bed] + options)
    x0, x1 = window(scene)
    stats = bedstat([bed, "--spread", "--window", f"{x0!r},{x1!r}"])["spread"]
    stats.pop("segregation", None)
    out = {"key": key, "label": label, "seed": seed, "n": dep["n"], "wall": wall, "stats": stats,
           "max_overlap": dep.get("max_overlap"),
           "max_tool_force": [l.get("max_tool_force") for l in dep.get("layers", [])],
           "load": [before, load_average()]}
    os.remove(bed)
    with open(saved, "w") as f:
        json.dump(out, f)
    print(f"{label}, seed {seed}: density {stats['density']:.3f}", file=sys.stderr, flush=True)
    return out


def run_table(runs):
    """One line per run: the layer it left and what it cost."""
    lines = table_head("variant", "seed", "particles left", "layer density", "coverage", "Sa (µm)",
                       "deposit wall (s)", "load")
    for r in runs:
        s = r["stats"]
        lines.append(table_row(r["label"], r["seed"], r["n"], f"{s['density']:.3f}",
                               f"{s['coverage']:.3f}", f"{s['sa'] * 1e6:.1f}", f"{r['wall']:.0f}",
                               r["load"][0].split()[0]))
    return "\n".join(lines)


def span(values):
    """The range of a row's values ("0.149-0.166"), the value itself for one seed."""
    return f"{min(values):.3f}-{max(values):.3f}" if len(values) > 1 else f"{values[0]:.3f}"


def variant_values(runs):
    """Each variant's layer density, coverage and seed count, named after its key (not a word
    character: "_"), for the template to quote."""
    out = {}
    for key, *_ in VARIANTS:
        rows = [r["stats"] for r in runs if r["key"] == key]
        name = re.sub(r"\W", "_", key)
        out[name] = span([s["density"] for s in rows])
        out[f"{name}_coverage"] = span([s["coverage"] for s in rows])
        out[f"{name}_seeds"] = f"{len(rows)} seed{'s' if len(rows) > 1 else ''}"
    return out


def thin_against_scene(thin, spread):
    """How the thin blade's layer differs from the scene's with the same seed (`thin`), against
    the spread of the scene's seeds."""
    text = ("(the same to three digits, " if abs(thin) < 5e-4 else
            f"({abs(thin):.3f} {'more' if thin > 0 else 'less'}, ")
    if abs(thin) <= spread:
        return text + (f"within the seed spread of {spread:.3f}): the 200 µm flat bottom "
                       "dragging the gap's particles along is not what empties the layer. ")
    return text + f"beyond the seed spread of {spread:.3f}). "


def page(runs, batches):
    """The page: templates/spread-density.md.in filled with every row's runs."""
    scene = [r["stats"]["density"] for r in runs if r["key"] == "scene"]
    seed1 = {r["key"]: r["stats"]["density"] for r in runs if r["seed"] == 1}
    best = max(runs, key=lambda r: r["stats"]["density"])
    density = best["stats"]["density"]

    def lift(key):  # a row's density less the scene's, its seeds against the scene's
        rows = [r["stats"]["density"] for r in runs if r["key"] == key]
        return f"{min(rows) - max(scene):+.3f} to {max(rows) - min(scene):+.3f}"
    overlap = max(r.get("max_overlap") or 0 for r in runs if r["key"] in ("round", "round-supply2"))
    return fill_template("spread-density.md.in", {
        **variant_values(runs),
        "machine": "\n".join(machine_lines(batches)),
        "table": run_table(runs),
        "scene_range": f"{min(scene):.3f}-{max(scene):.3f}", "scene_count": len(scene),
        "best": f"{density:.3f}", "best_label": best["label"],
        "best_against_band": "inside" if density >= 0.38 else "below",
        "best_short": f"{0.38 - density:.2f}",
        "thin_seed1": f"{seed1['thin']:.3f}", "scene_seed1": f"{seed1['scene']:.3f}",
        "thin_against_scene": thin_against_scene(seed1["thin"] - seed1["scene"],
                                                 max(scene) - min(scene)),
        "round_lift": lift("round"), "roller_lift": lift("roller"),
        "overlap": f"{overlap * 100:.1f}"})


def machine_lines(batches):
    """The Machine sentence of each call that ran rows of the page, the later ones naming them."""
    lines = [batches[0]["machine"]]
    for b in batches[1:]:
        text = b["machine"][len("Machine: "):] if b["machine"].startswith("Machine: ") else b["machine"]
        lines.append(f"Rows {', '.join(b['keys'])} run later, machine: {text}")
    return [line + "  " if i < len(lines) - 1 else line for i, line in enumerate(lines)]


def stored_study(work, path, skip):
    """The stored study (results.json), or one made from the runs kept in work (all but the
    keys in skip) and the page's Machine line, for a work folder from before results.json."""
    if os.path.exists(path):
        with open(path) as f:
            return json.load(f)
    runs = []
    for key, label, scene, options, seeds in VARIANTS:
        for seed in seeds:
            if key not in skip and os.path.exists(os.path.join(work, run_tag(scene, options, seed)
                                                               + ".json")):
                runs.append(one_run(work, key, label, scene, options, seed))
    line = [l for l in read_page("spread-density.md").splitlines() if l.startswith("Machine: ")]
    keys = list(dict.fromkeys(r["key"] for r in runs))
    return {"runs": runs, "batches": [{"keys": keys, "machine": line[0].rstrip() if line else
                                       "Machine: not recorded."}] if runs else []}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--work", default=WORK,
                        help="keep the runs and results.json here (reused by a later call; "
                             "default out/studies/spread-density)")
    parser.add_argument("--only", help="comma-separated keys of the rows to run afresh "
                        f"({', '.join(v[0] for v in VARIANTS)})")
    args = parser.parse_args()
    work = args.work
    os.makedirs(work, exist_ok=True)
    results = os.path.join(work, "results.json")
    only = args.only.split(",") if args.only else None
    unknown = [k for k in only or [] if k not in [v[0] for v in VARIANTS]]
    if unknown:
        sys.exit(f"spread_density: --only {','.join(unknown)}: no such row "
                 f"(accepted: {', '.join(v[0] for v in VARIANTS)})")
    stored = stored_study(work, results, only) if only else {"runs": [], "batches": []}
    load = [load_average(), None]
    ran = [one_run(work, key, label, scene, options, seed, fresh=only is not None)
           for key, label, scene, options, seeds in VARIANTS if only is None or key in only
           for seed in seeds]
    load[1] = load_average()
    batch = {"keys": list(dict.fromkeys(r["key"] for r in ran)),
             "machine": machine(load[0], load[1], program=app("deposit"))}
    # Every row of VARIANTS, in its order: the rows run now, the others as stored.
    have = {(r["key"], r["seed"]): r for r in stored["runs"]}
    have.update({(r["key"], r["seed"]): r for r in ran})
    missing = [f"{key} seed {seed}" for key, _, _, _, seeds in VARIANTS for seed in seeds
               if (key, seed) not in have]
    if missing:
        sys.exit(f"spread_density: no stored run for {', '.join(missing)} (run them: --only "
                 f"{','.join(dict.fromkeys(m.split()[0] for m in missing))}, or the whole study)")
    runs = [have[(key, seed)] for key, _, _, _, seeds in VARIANTS for seed in seeds]
    batches = [dict(b, keys=[k for k in b["keys"] if k not in batch["keys"]])
               for b in stored["batches"]]
    batches = [b for b in batches if b["keys"]] + [batch]
    with open(results, "w") as f:
        json.dump({"runs": runs, "batches": batches}, f, indent=1)
    # The section bench/studies/spread_heap.py keeps in this page stays as it is.
    print(write_page_keeping("spread-density.md", page(runs, batches), ["spread-heap"]))


if __name__ == "__main__":
    main()
