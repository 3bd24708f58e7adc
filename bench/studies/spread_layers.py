#!/usr/bin/env python3
"""Layer after layer: a blade scene spread LAYERS times on itself (issue 16, point 3).

Writes docs/results/spread-layers.md and spread-layers.png (matplotlib, Agg). Run from anywhere
with /usr/bin/python3 (numpy, matplotlib) after building deposit and bedstat (POWDERBED_BUILD
selects the build folder):
    POWDERBED_BUILD=build python3 bench/studies/spread_layers.py [LAYERS] [SEED]
        [--scene data/scenes/spread-blade.ini] [--work DIR]

One run of `deposit --config SCENE --seed SEED --layers LAYERS --threads 1` (default 20 layers
of data/scenes/spread-blade.ini; the 20-layer study uses data/scenes/spread-blade-layers.ini, the
same scene in a taller box and a strip half as wide, see its header): each layer the plate goes
down by recoater.layer-thickness t (45 um), a new supply falls in front of the blade, the blade
spreads it and the excess past its end is removed (recoater.overflow). deposit writes the bed
after each layer, OUT-001.h5 ... OUT-NNN.h5; each is measured with `bedstat --spread`.

The bed keeps the plate's frame (docs/deposit-spread.md): in layer k the tool's bottom is at
H_k = gap + (k - 1) t above the floor. Per layer k, over the window the blade leaves behind it
(bench/studies/spread_peer.py's rule: from the blade's front face at the start to its back face
at the end, less 10 % of that at each end), with --plate and --gap set explicitly:
- slab density: bedstat's density of the new layer's slab, --plate H_(k-1) --gap t (layer 1:
  --plate 0 --gap gap): the solid volume, spheres cut exactly by the slab's planes, in
  [H_(k-1), H_k] over the window, divided by the slab's volume;
- added density: the solid the layer added under the tool, V_k - V_(k-1) with
  V_k = phi(0, H_k) (window area) H_k from bedstat --plate 0 --gap H_k on bed k, divided by the
  window area times t (layer 1: the gap): what weighing the powder a layer adds would give;
- bed density: bedstat's density of the whole bed under the tool, [0, H_k];
- coverage of the new slab, and Sa, Sq of the bed's top surface (bedstat --plate 0 --gap H_k);
- the solid height (solid volume per plate area, bed density x H_k) in each quarter of the
  window along x: whether the supply lasted the whole travel;
and the JSON summary's numbers per layer: particles, supplied, overflow, the quick-look density
by centres under the gap, wall time.

With --work DIR the beds and deposit's JSON are kept there and a later call with the same DIR
measures them without running deposit again; --measure-only measures a stopped run (the layers
whose beds exist, wall times from the beds' file times, the run's start time in DIR/started;
particles from bedstat, no overflow or quick look: those are in deposit's JSON at the run's end).
--reference K runs the same scene a second time with recoater.freeze-depth = 0 (nothing frozen:
every particle integrated every step) for its first K layers, in DIR/unfrozen, measures it the
same way and sets it beside the main run layer by layer, with each run's wall time: what
freezing the powder deep under the tool (docs/deposit-spread.md "Many layers") changes and saves.
Its beds are reused like the main run's.

--resume continues a stopped run from its last bed L-K.h5 (`deposit --in L-K.h5 --layers
LAYERS-K`, the bed's /restart group: with the same build the continued run equals the
uninterrupted one bit for bit, docs/deposit-spread.md "Restarts"); that segment's start time and
JSON are kept as DIR/started-K and DIR/deposit-from-K.json, and the page names each segment's
layers and the commit it ran (DIR/commit, DIR/commit-K when present).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

from lib.apps import ROOT, app, bedstat
from lib.report import RESULTS, load_average, machine, source, write_page_with_discussion
from lib.spread_scene import Scene, shown_path

SCENE = os.path.join(ROOT, "data", "scenes", "spread-blade.ini")


def supply_text(scene):
    """The supply of a layer as the scene gives it: a count of particles, or a dosed volume
    (supply.volume > 0 replaces the count; docs/deposit-spread.md)."""
    volume = float(scene.options["supply.volume"])
    return (f"{volume:.3g} m^3 of powder" if volume > 0
            else f"{scene.options['supply.count']} particles")


def last_bed(work, layers):
    """The number of the last layer bed L-K.h5 in work (0 when there is none)."""
    k = 0
    while k < layers and os.path.exists(os.path.join(work, f"L-{k + 1:03d}.h5")):
        k += 1
    return k


def segments(work):
    """The run's segments as (first layer - 1, suffix): the first run, then each --resume."""
    found = [(0, "")]
    for name in sorted(os.listdir(work)):
        if name.startswith("started-"):
            k = int(name[len("started-"):])
            found.append((k, f"-{k:03d}"))
    return sorted(found)


def run_deposit(scene, layers, seed, work, measure_only, resume, options=()):
    """deposit's JSON summaries of the run's segments (deposit.json, deposit-from-K.json), running
    the first (or, with resume, a continuation from the last bed) unless its JSON exists; a
    segment that did not finish (or, with measure_only, was not run here) has none."""
    summaries = []
    for k, suffix in segments(work):
        saved = os.path.join(work, "deposit.json" if k == 0 else f"deposit-from{suffix}.json")
        if os.path.exists(saved):
            with open(saved) as f:
                summaries.append(json.load(f))
    done = last_bed(work, layers)
    if measure_only or done == layers or (not resume and os.path.exists(os.path.join(work, "deposit.err"))):
        return summaries
    cmd = [app("deposit"), "--config", scene.path, "--seed", str(seed), "--threads", "1",
           "--out", os.path.join(work, "L.h5"), "--json", *options]
    err_name, saved = "deposit.err", os.path.join(work, "deposit.json")
    if resume and done > 0:
        with open(os.path.join(work, f"started-{done:03d}"), "w") as f:
            f.write(repr(time.time()))
        with open(os.path.join(work, f"source-{done:03d}"), "w") as f:
            f.write(source(app("deposit")))
        cmd += ["--in", os.path.join(work, f"L-{done:03d}.h5"), "--layers", str(layers - done)]
        err_name, saved = f"deposit-from-{done:03d}.err", os.path.join(work, f"deposit-from-{done:03d}.json")
    else:
        cmd += ["--layers", str(layers)]
    with open(os.path.join(work, err_name), "w") as err:
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=err, text=True)
    if proc.returncode != 0:
        print(f"spread_layers: deposit exited {proc.returncode} (see {work}/{err_name}); "
              "measuring the layers it wrote", file=sys.stderr)
        return summaries
    with open(saved, "w") as f:
        f.write(proc.stdout)
    return summaries + [json.loads(proc.stdout)]


def spread_stats(bed, plate, gap, window):
    """bedstat's spread object of the bed, with the bed's particle count added as "n_bed"."""
    entry = bedstat([bed, "--spread", "--plate", repr(plate), "--gap", repr(gap),
                     "--window", f"{window[0]!r},{window[1]!r}"])
    return dict(entry["spread"], n_bed=entry["n"])


def run_segments(work, rows):
    """One sentence per segment of the run: its layers and the source it ran (DIR/source[-K])."""
    last = rows[-1]["layer"]
    bounds = segments(work) + [(last, None)]
    parts = []
    for (k, suffix), (end, _) in zip(bounds, bounds[1:]):
        path = os.path.join(work, "source" + suffix)
        ran = open(path).read().strip() if os.path.exists(path) else "source not recorded"
        how = "the first run" if k == 0 else f"continued with --resume from L-{k:03d}.h5"
        span = f"layers {k + 1}–{end}" if end > k + 1 else f"layer {k + 1}"
        parts.append(f"{span}: {how} ({ran})")
    return "; ".join(parts)


def segment_starts(work):
    """{layers done before the segment: its start time} for every segment of the run."""
    starts = {}
    for k, suffix in segments(work):
        with open(os.path.join(work, "started" + suffix)) as f:
            starts[k] = float(f.read())
    return starts


def measure(scene, work, layers, window, summaries):
    t = float(scene.options["recoater.layer-thickness"])
    rows, prev_solid, prev_time = [], 0.0, None
    starts = segment_starts(work)
    by_layer = {s["layer"]: s for summary in summaries for s in summary["layers"]}
    area = None
    for k in range(1, layers + 1):
        bed = os.path.join(work, f"L-{k:03d}.h5")
        if not os.path.exists(bed):
            break
        top = scene.gap + (k - 1) * t
        low = 0.0 if k == 1 else top - t
        slab = spread_stats(bed, low, top - low, window)
        whole = spread_stats(bed, 0.0, top, window)
        area = (window[1] - window[0]) * scene.ly
        solid = whole["density"] * area * top
        row = {"layer": k, "top": top, "slab_density": slab["density"],
               "added_density": (solid - prev_solid) / (area * (top - low)),
               "bed_density": whole["density"], "coverage": slab["coverage"],
               "sa": whole["sa"], "sq": whole["sq"], "mean_height": whole["mean_height"],
               "slab_particles": slab["particles"], "n": whole["n_bed"]}
        prev_solid = solid
        # the solid height (solid volume per plate area) in each quarter of the window: how even
        # the bed is along the travel
        edges = [window[0] + q * (window[1] - window[0]) / 4 for q in range(5)]
        row["quarters"] = [spread_stats(bed, 0.0, top, (edges[q], edges[q + 1]))["density"] * top
                           for q in range(4)]
        mtime = os.path.getmtime(bed)
        row["wall_file"] = mtime - (starts[k - 1] if k - 1 in starts else prev_time)
        prev_time = mtime
        if k in by_layer:
            s = by_layer[k]
            row.update(n=s["n"], supplied=s["supplied"], overflow=s["overflow"],
                       quick=s["density_under_gap"], wall=s["wall_time"], steps=s["steps"],
                       frozen=s.get("frozen", 0))
        rows.append(row)
    return rows


def plot(rows, reference, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    k = [r["layer"] for r in rows]
    kr = [r["layer"] for r in reference]
    fig, (ax, ax2, ax3) = plt.subplots(1, 3, figsize=(12.5, 3.6))
    ax.plot(k, [r["added_density"] for r in rows], "o-", label="added by the layer (mass)")
    ax.plot(k, [r["slab_density"] for r in rows], "s--", label="new layer's slab")
    ax.plot(k, [r["bed_density"] for r in rows], "^:", label="whole bed under the tool")
    ax2.plot(k, [r["top"] * 1e6 for r in rows], "k-", label="tool bottom H_k")
    ax2.plot(k, [r["mean_height"] * 1e6 for r in rows], "o-", label="mean surface height")
    ax3.plot(k, [r.get("wall", r["wall_file"]) for r in rows], "o-", label="frozen below the depth")
    if reference:
        ax.plot(kr, [r["added_density"] for r in reference], "o", mfc="none", color="C3",
                label="added, nothing frozen")
        ax.plot(kr, [r["bed_density"] for r in reference], "^", mfc="none", color="C4",
                label="bed, nothing frozen")
        ax2.plot(kr, [r["mean_height"] * 1e6 for r in reference], "o", mfc="none", color="C3",
                 label="surface, nothing frozen")
        ax3.plot(kr, [r.get("wall", r["wall_file"]) for r in reference], "s--", color="C3",
                 label="nothing frozen")
    ax.set_ylabel("solid fraction")
    ax2.set_ylabel("height above the plate (µm)")
    ax3.set_ylabel("wall time of the layer (s, one core)")
    for a in (ax, ax2, ax3):
        a.set_xlabel("layer")
        a.set_xticks(k if len(k) <= 12 else k[::2])
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def prepare(work):
    """The work folder, with the run's start time, source and load noted on its first use; returns
    the load average noted then."""
    os.makedirs(work, exist_ok=True)
    if not os.path.exists(os.path.join(work, "started")):
        with open(os.path.join(work, "started"), "w") as f:
            f.write(repr(time.time()))
        with open(os.path.join(work, "source"), "w") as f:
            f.write(source(app("deposit")))
        with open(os.path.join(work, "load-before"), "w") as f:
            f.write(load_average())
    with open(os.path.join(work, "load-before")) as f:
        return f.read().strip()


def layer_table(rows):
    """The main table: one row per layer."""
    lines = ["| layer | H_k (µm) | particles | frozen | overflow | added | slab | bed | quick look | h̄ (µm) "
             "| H_k − h̄ (µm) | slab coverage | Sa (µm) | Sq (µm) | solid height by quarter of the window "
             "(µm) | wall (s) |",
             "|---" * 16 + "|"]
    for r in rows:
        lines.append(
            f"| {r['layer']} | {r['top'] * 1e6:.0f} | {r['n']} | {r.get('frozen', '–')} | {r.get('overflow', '–')} | "
            f"{r['added_density']:.3f} | {r['slab_density']:.3f} | {r['bed_density']:.3f} | "
            + (f"{r['quick']:.3f}" if "quick" in r else "–")
            + f" | {r['mean_height'] * 1e6:.1f} | {(r['top'] - r['mean_height']) * 1e6:.1f}"
            f" | {r['coverage']:.3f} | {r['sa'] * 1e6:.1f} | {r['sq'] * 1e6:.1f} | "
            + " / ".join(f"{h * 1e6:.0f}" for h in r["quarters"]) + " | "
            f"{r.get('wall', r['wall_file']):.0f} |")
    return lines


def comparison_table(rows, reference, runs):
    """The main run beside the reference (nothing frozen), layer by layer."""
    if not reference:
        return []
    lines = ["", f"## Frozen against nothing frozen (layers 1–{reference[-1]['layer']})", "",
             f"The same scene and seed with recoater.freeze-depth = 0 (every particle integrated every "
             f"step): {runs}. Each cell is *frozen / nothing frozen*.", "",
             "| layer | particles frozen | added | bed | h̄ (µm) | slab coverage | Sa (µm) | wall (s) |",
             "|---" * 8 + "|"]
    for r, q in zip(rows, reference):
        wall = (r.get("wall", r["wall_file"]), q.get("wall", q["wall_file"]))
        lines.append(
            f"| {r['layer']} | {r.get('frozen', '–')} of {r['n']} | {r['added_density']:.3f} / {q['added_density']:.3f} | "
            f"{r['bed_density']:.3f} / {q['bed_density']:.3f} | {r['mean_height'] * 1e6:.1f} / "
            f"{q['mean_height'] * 1e6:.1f} | {r['coverage']:.3f} / {q['coverage']:.3f} | "
            f"{r['sa'] * 1e6:.1f} / {q['sa'] * 1e6:.1f} | {wall[0]:.0f} / {wall[1]:.0f} |")
    return lines


def header(args, scene, rows, summaries, runs, load_before):
    t = float(scene.options["recoater.layer-thickness"])
    window = scene.window()
    cmd = f"python3 bench/studies/spread_layers.py {args.layers} {args.seed}"
    if os.path.abspath(args.scene) != SCENE:
        cmd += f" --scene {shown_path(args.scene)}"
    if args.reference:
        cmd += f" --reference {args.reference}"
    total = sum(r.get("wall", r["wall_file"]) for r in rows)
    depth = float(scene.options["recoater.freeze-depth"])
    return [
        "# Spreading layer after layer (blade scene)",
        "",
        f"`{cmd}` (method in the script's docstring): `{shown_path(args.scene)}`, strip "
        f"{scene.lx * 1e3:g} x {scene.ly * 1e3:g} mm periodic in y, box {scene.lz * 1e3:g} mm tall, "
        f"gap {scene.gap * 1e6:.0f} um, {scene.speed * 1e3:.0f} mm/s, layer thickness {t * 1e6:.0f} um, "
        f"supply {supply_text(scene)} a layer, young-scale "
        f"{scene.young_scale:g}, powder more than {depth * 1e6:.0f} um below the tool frozen; "
        f"{len(rows)} of {args.layers} layers, seed {args.seed}, one thread; "
        f"{total:.0f} s of wall time in all"
        + (f", {sum(r['steps'] for r in rows)} steps of {summaries[0]['dt']:.3g} s."
           if all("steps" in r for r in rows) else "."),
        f"Segments: {runs}.",
        machine(load_before),
        "",
        f"Window x in [{window[0] * 1e3:.3f}, {window[1] * 1e3:.3f}] mm. In layer k the tool's bottom "
        f"is at H_k = gap + (k − 1) t. *Frozen*: the particles frozen through the layer. *Added*: the solid "
        "the layer added under the tool over the "
        "window, divided by the window area × t (layer 1: × the gap). *Slab*: bedstat's density of "
        "[H_(k−1), H_k] (spheres cut exactly). *Bed*: bedstat's density of [0, H_k]. Surface: bedstat's "
        "mean height h̄ of the bed's top over the plate, the tool's bottom H_k − h̄ above it, coverage "
        "of the new slab, Sa and Sq of the top surface. Solid height: solid volume per plate area in each "
        "quarter of the window along x (from the start). *Quick look*: deposit's JSON, by centres under the gap, "
        "between the supply's back and the tool's end.",
        "",
    ]


def run_and_measure(args, scene, work, layers, options=()):
    """The run in `work` (run or reused) and its rows; its load average before and segments."""
    load_before = prepare(work)
    summaries = run_deposit(scene, layers, args.seed, work, args.measure_only, args.resume, options)
    rows = measure(scene, work, layers, scene.window(), summaries)
    return rows, summaries, load_before, run_segments(work, rows) if rows else ""


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("layers", nargs="?", type=int, default=20)
    parser.add_argument("seed", nargs="?", type=int, default=1)
    parser.add_argument("--scene", default=SCENE)
    parser.add_argument("--work", default=None, help="keep the beds here (and reuse them)")
    parser.add_argument("--measure-only", action="store_true",
                        help="with --work: measure the beds there, do not run deposit (a stopped run)")
    parser.add_argument("--resume", action="store_true",
                        help="with --work: continue a stopped run from its last layer bed")
    parser.add_argument("--reference", type=int, default=0,
                        help="also run the first K layers with nothing frozen, side by side")
    args = parser.parse_args()
    scene = Scene(os.path.abspath(args.scene), {})
    with tempfile.TemporaryDirectory() as tmp:
        work = os.path.abspath(args.work) if args.work else tmp
        rows, summaries, load_before, runs = run_and_measure(args, scene, work, args.layers)
        reference, ref_runs = [], ""
        if args.reference:
            reference, _, _, ref_runs = run_and_measure(args, scene, os.path.join(work, "unfrozen"),
                                                        args.reference, ["--recoater.freeze-depth", "0"])
    if not rows:
        sys.exit("spread_layers: no layer bed was written")
    lines = header(args, scene, rows, summaries, runs, load_before) + layer_table(rows)
    lines += comparison_table(rows, reference, ref_runs)
    plot(rows, reference, os.path.join(RESULTS, "spread-layers.png"))
    lines += ["", "![density over layers; the same with nothing frozen; wall time per layer](spread-layers.png)"]
    if args.work:
        with open(os.path.join(work, "spread-layers-rows.json"), "w") as f:
            json.dump({"rows": rows, "reference": reference}, f, indent=1)
    print(write_page_with_discussion("spread-layers.md", "\n".join(lines)))


if __name__ == "__main__":
    main()
