#!/usr/bin/env python3
"""A blade spread in deposit beside LIGGGHTS 3.8 on the same particles (issue 16 point 5).

Writes docs/results/spread-peer.md (a --small run prints its table and writes it under the work
folder instead, leaving the results file alone). Needs deposit, bedconv and bedstat built
(POWDERBED_BUILD selects the build folder) and LIGGGHTS (`liggghts`, Debian package liggghts):
    POWDERBED_BUILD=build python3 bench/studies/spread_peer.py [--scene data/scenes/spread-blade.ini]
    POWDERBED_BUILD=build python3 bench/studies/spread_peer.py --small   (seed 1, shorter travel and waits)

Method, per seed (1, 2, 3; --seeds to choose):
1. The initial particles: deposit with the scene and the seed, but the tool moving 1 nm with no
   delay and no settle (recoater.end = recoater.start + 1e-9, recoater.delay = 0,
   recoater.settle = 0, recoater.overflow = false): the supply as deposit inserts it, before
   anything moves. `bedconv`
   writes it as a LAMMPS data file for LIGGGHTS (atom types raised to 2: the walls' type).
2. deposit spreads the layer with the scene and the seed as given (the same supply: insertion
   depends on the seed only); its JSON gives the loop time, steps, particles and dt. When the
   scene has the gas's Stokes drag on (effects.drag), deposit spreads the layer a second time
   without it ("deposit, no gas"): LIGGGHTS has no drag that grows with the radius (fix viscous
   takes one coefficient per atom type), so the deck runs without gas, and it is this run that
   is set beside LIGGGHTS (same physics); the run with the gas shows what the gas changes.
3. LIGGGHTS runs bench/liggghts/spread-blade.liggghts from the data file with the same dt: the
   blade an STL box (bench/liggghts/blade_stl.py, the scene's thickness, bottom edge at the gap,
   centred on recoater.start, inset across by 1e-3 of the width since LIGGGHTS aborts on a mesh
   vertex on a periodic face) that stands for recoater.delay, moves to recoater.end at
   recoater.speed (fix move/mesh linear) and stands for recoater.settle; Hertz with the scene's
   E and nu (softened by young-scale, particles and walls), the restitution that matches the
   scene's damping ratio, friction with the tangential history spring (no_history when
   deposit's friction.model is sliding, its default), rolling resistance (epsd) when the scene has
   material.rolling > 0; plate, lid and end walls as primitive walls, periodic in y. Loop time from LIGGGHTS's "Loop time" lines (all three runs).
4. Both beds through `bedstat --spread` with the same gap, plate (the domain floor) and window
   (the layer the blade leaves behind it, [start + t/2, end - t/2] for a blade of thickness t
   centred at recoater.start and stopping centred at recoater.end, less 10 % of it at each end;
   --window to set it), the initial particles as the feed.
Reported: time per particle-step of each code and their ratio (LIGGGHTS / deposit on the same
physics: > 1 means deposit is faster), and the layer statistics of the beds side by side, with the
mean and sd over seeds and whether the densities of the two codes agree within the seeds' spread.

Only the blade is supported (a roller needs a rotating cylinder mesh; recoater.tool = roller is
refused), only periodic y, and one layer. Testing without deposit's recoater: --liggghts-only
--initial-bed BED runs step 3 from a bed you give (the domain of the scene) with dt from the
Rayleigh step, e.g. the stand-in scene bench/studies/spread_peer_test.ini.
"""
import argparse
import math
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile

from lib.apps import ROOT, app, option_args, run_json
from lib.spread_scene import Scene, read_scene, shown_path
from lib.report import load_average, machine, write_page

sys.path.insert(0, os.path.join(ROOT, "bench", "liggghts"))
import blade_stl  # noqa: E402

SCENE = os.path.join(ROOT, "data", "scenes", "spread-blade.ini")
DECK = os.path.join(ROOT, "bench", "liggghts", "spread-blade.liggghts")
SEEDS = [1, 2, 3]
PEERED = "deposit, no gas"  # deposit on the deck's physics: the run set beside LIGGGHTS
INSET = 1e-3          # blade inset across, fraction of the width (LIGGGHTS periodic faces)
SMALL_TRAVEL = 0.25   # --small: fraction of the travel beyond the blade's thickness
SMALL_SETTLE = 1e-3   # --small: longest settle (s)
SMALL_DELAY = 2e-3    # --small: longest delay before the blade moves (s)


def liggghts_binary():
    for name in ("liggghts", "lmp_auto"):
        path = shutil.which(name)
        if path:
            return path
    sys.exit("spread_peer: LIGGGHTS not found (apt-get install liggghts; scripts/setup.sh)")


def small_overrides(scene_path):
    """--small: the blade's thickness plus SMALL_TRAVEL of the travel (so that it leaves a layer
    behind it), at most SMALL_DELAY before it moves (the supply may still be falling: a check of
    the pipeline, not a result) and at most SMALL_SETTLE after."""
    o = read_scene(scene_path)
    start, end = float(o["recoater.start"]), float(o["recoater.end"])
    thickness = float(o["recoater.thickness"])
    delay = min(float(o["recoater.delay"]), SMALL_DELAY)
    settle = min(float(o["recoater.settle"]), SMALL_SETTLE)
    small_end = min(end, start + thickness + SMALL_TRAVEL * (end - start))
    return {"recoater.end": repr(small_end), "recoater.delay": repr(delay),
            "recoater.settle": repr(settle)}


def initial_particles(work, scene_path, seed, overrides):
    """The supply as deposit inserts it for `seed` (step 1 of the method)."""
    path = os.path.join(work, f"initial-{seed}.h5")
    first = dict(overrides)
    start = float(Scene(scene_path, overrides).start)
    # overflow off: the tool has not moved, so the whole supply lies past its end
    first.update({"recoater.end": repr(start + 1e-9), "recoater.delay": "0", "recoater.settle": "0",
                  "recoater.overflow": "false"})
    run_json([app("deposit"), "--config", scene_path, "--seed", str(seed), "--out", path,
              *option_args(first)])
    return path


def child_cpu():
    """CPU seconds (user + system) of the finished child processes so far: a run's own CPU time
    is the difference around it, which a second job on the machine inflates far less than the
    wall time (it still shares the caches)."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def deposit_spread(work, scene_path, seed, overrides, tag):
    path = os.path.join(work, f"deposit-{tag}-{seed}.h5")
    cpu = child_cpu()
    s, _ = run_json([app("deposit"), "--config", scene_path, "--seed", str(seed), "--threads", "1",
                     "--out", path, *option_args(overrides)])
    cpu = child_cpu() - cpu
    steps = s["steps"]
    n = s["n"] if "n" in s else s["layers"][-1]["n"]
    per = 1.0 / s["particle_steps_per_s"] if s.get("particle_steps_per_s") else s["wall_time"] / (n * steps)
    particle_steps = s["particle_steps_per_s"] * s["wall_time"]
    return {"bed": path, "loop": s["wall_time"], "steps": steps, "n": n, "per_step": per,
            "cpu_per_step": cpu / particle_steps,
            "dt": s["dt"], "lost": s.get("lost", 0)}


def rayleigh_dt(scene, r_min):
    """0.2 x the Rayleigh step of the smallest particle at the softened E (deposit's default)."""
    shear = scene.young / scene.young_scale / (2 * (1 + scene.poisson))
    return 0.2 * math.pi * r_min * math.sqrt(scene.density / shear) / (0.1631 * scene.poisson + 0.8766)


def bed_radii(path):
    """Radii of a bed through bedstat (no h5py needed): min and max from its JSON."""
    out, _ = run_json([app("bedstat"), path])
    radius = out["beds"][0]["radius"]
    return radius["min"], radius["max"]


def liggghts_spread(work, scene, initial, seed, dt):
    """Step 3 of the method: returns the dump, loop time, particle-steps and steps."""
    data = os.path.join(work, f"initial-{seed}.data")
    subprocess.run([app("bedconv"), initial, data, "--density", repr(scene.density)], check=True,
                   capture_output=True)
    with open(data) as f:
        text = f.read()
    text, count = re.subn(r"^(\s*)1 atom types", r"\g<1>2 atom types", text, count=1, flags=re.M)
    if count != 1:
        sys.exit(f"spread_peer: {data}: no '1 atom types' line to raise to 2")
    with open(data, "w") as f:
        f.write(text)
    half = scene.thickness / 2
    if scene.start - half < 0 or scene.end + half > scene.lx:
        sys.exit(f"spread_peer: the blade [{scene.start - half}, {scene.end + half}] m leaves the box "
                 f"[0, {scene.lx}] m (LIGGGHTS loses mesh elements outside the domain)")
    stl = os.path.join(work, "blade.stl")
    lo, hi = blade_stl.blade(scene.start + half, scene.thickness, scene.gap, scene.lz * (1 - 1e-3),
                             0.0, scene.ly, INSET)
    blade_stl.write_stl(stl, blade_stl.box_triangles(lo, hi))
    r_min, r_max = bed_radii(initial)
    dump = os.path.join(work, f"liggghts-{seed}.dump")
    nmove = round((scene.end - scene.start) / scene.speed / dt)
    variables = {
        "DATA": data, "STL": stl, "OUT": dump, "DT": repr(dt),
        "E": repr(scene.young / scene.young_scale), "NU": repr(scene.poisson),
        "EW": repr(scene.wall_young / scene.young_scale), "NUW": repr(scene.wall_poisson),
        "REST": repr(scene.restitution()), "MU": repr(scene.friction), "TANG": scene.tangential,
        "ROLL": "epsd" if scene.rolling > 0 else "off", "MUR": repr(scene.rolling),
        "RDAMP": repr(scene.damping), "G": repr(scene.gravity), "V": repr(scene.speed),
        "NDELAY": str(round(scene.delay / dt)), "NMOVE": str(nmove),
        "NSETTLE": str(round(scene.settle / dt)), "SKIN": repr(0.2 * r_max),
        "THERMO": str(max(1, nmove // 10)),
    }
    args = [liggghts_binary(), "-in", DECK, "-log", os.path.join(work, f"liggghts-{seed}.log")]
    for key, value in variables.items():
        args += ["-var", key, value]
    cpu = child_cpu()
    proc = subprocess.run(args, capture_output=True, text=True, cwd=work)
    cpu = child_cpu() - cpu
    if proc.returncode != 0 or not os.path.exists(dump):
        sys.exit(f"spread_peer: liggghts exited {proc.returncode}:\n{proc.stdout[-3000:]}{proc.stderr[-2000:]}")
    loops = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", proc.stdout)
    loop = sum(float(t) for t, _, _ in loops)
    particle_steps = sum(int(s) * int(n) for _, s, n in loops)
    steps = sum(int(s) for _, s, _ in loops)
    atoms = int(loops[-1][2]) if loops else 0
    return {"bed": dump, "loop": loop, "steps": steps, "n": atoms,
            "per_step": loop / particle_steps if particle_steps else float("nan"),
            "cpu_per_step": cpu / particle_steps if particle_steps else float("nan"), "dt": dt}


def layer_stats(beds, scene, window, feed):
    """bedstat --spread of the beds side by side: one 'spread' dict per bed, in order."""
    out, _ = run_json([app("bedstat"), *beds, "--spread", "--gap", repr(scene.gap),
                       "--window", f"{window[0]!r},{window[1]!r}", "--feed", feed])
    return [b["spread"] for b in out["beds"]]


STAT_ROWS = [("density", "layer density", "{:.4f}"), ("coverage", "coverage", "{:.4f}"),
             ("sa", "Sa (um)", "um"), ("sq", "Sq (um)", "um"), ("particles", "layer particles", "{:d}")]


def fmt(value, style):
    if style == "um":
        return f"{value * 1e6:.2f}"
    return style.format(value)


def mean_sd(values):
    return statistics.mean(values), (statistics.stdev(values) if len(values) > 1 else 0.0)


def report(scene, args, window, runs, load_before):
    """The Markdown of the study from runs = [(seed, {code: (timing, stats)})]."""
    codes = [c for c in ("deposit", PEERED, "LIGGGHTS") if c in runs[0][1]]
    lines = [
        "# Blade spread: deposit beside LIGGGHTS (issue 16 point 5)",
        "",
        f"Generated by `bench/studies/spread_peer.py{' --small' if args.small else ''}` (method in its "
        f"docstring) on `{shown_path(scene.path)}`: blade {scene.thickness * 1e6:.0f} um thick, "
        f"gap {scene.gap * 1e6:.0f} um, {scene.speed * 1e3:.0f} mm/s from x = {scene.start * 1e3:.3f} to "
        f"{scene.end * 1e3:.3f} mm, strip {scene.lx * 1e3:g} x {scene.ly * 1e3:g} mm periodic in y, "
        f"E / young-scale = {scene.young / scene.young_scale:.3g} Pa, friction {scene.friction:g}, "
        f"rolling {scene.rolling:g}, restitution for LIGGGHTS {scene.restitution():.5f}, LIGGGHTS "
        f"tangential {scene.tangential}. "
        f"Layer statistics over x in [{window[0] * 1e3:.3f}, {window[1] * 1e3:.3f}] mm, plate at the floor, "
        f"feed = the initial particles. One thread each, one run after the other (the ratio is of runs "
        f"under the same load). {machine(load_before)}",
        "",
        "*deposit* is the scene as it is, with the argon's Stokes drag; *deposit, no gas* the same "
        "spread without it, the physics of the LIGGGHTS deck (LIGGGHTS has no drag that grows with "
        "the radius), and the run the two codes are compared on. Left as they differ: deposit's "
        "rolling spring k_r = 2.25 mu_r^2 R*^2 k_n takes the Hertz contact's tangent stiffness "
        "2 E* sqrt(R* delta), LIGGGHTS's epsd its secant 4/3 E* sqrt(R* delta) (so deposit's "
        "spring is 1.5 times stiffer, the same cap mu_r R* F_n); deposit's tangential spring "
        "stores a force turned with the contact (length kept), LIGGGHTS's a displacement "
        "projected onto the tangent plane.",
        "",
        "| seed | code | particles | steps | loop time (s) | ns per particle-step | CPU ns per particle-step | "
        + " | ".join(label for _, label, _ in STAT_ROWS) + " | slope d(d)/dx | KS D | KS p |",
        "|---" * (10 + len(STAT_ROWS)) + "|",
    ]
    for seed, by_code in runs:
        for code in codes:
            t, s = by_code[code]
            ks = s.get("psd_ks", {})
            lines.append(f"| {seed} | {code} | {t['n']} | {t['steps']} | {t['loop']:.2f} | "
                         f"{t['per_step'] * 1e9:.1f} | {t['cpu_per_step'] * 1e9:.1f} | "
                         + " | ".join(fmt(s[key], style) for key, _, style in STAT_ROWS)
                         + f" | {s['segregation']['slope']:.3g} | {ks.get('d', float('nan')):.4f} | "
                         f"{ks.get('p', float('nan')):.3g} |")
    lines += ["", "## Over seeds (mean ± sd)", ""]
    lines.append("| statistic | " + " | ".join(codes) + " |")
    lines.append("|---" * (1 + len(codes)) + "|")
    for key, label, style in STAT_ROWS[:-1]:
        cells = []
        for code in codes:
            m, sd = mean_sd([by[code][1][key] for _, by in runs])
            cells.append(f"{fmt(m, style)} ± {fmt(sd, style)}")
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    for key, label in (("per_step", "ns per particle-step"), ("cpu_per_step", "CPU ns per particle-step")):
        cells = []
        for code in codes:
            m, sd = mean_sd([by[code][0][key] * 1e9 for _, by in runs])
            cells.append(f"{m:.1f} ± {sd:.1f}")
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    if PEERED in codes and "LIGGGHTS" in codes:
        ratios = [by["LIGGGHTS"][0]["per_step"] / by[PEERED][0]["per_step"] for _, by in runs]
        cpu_ratios = [by["LIGGGHTS"][0]["cpu_per_step"] / by[PEERED][0]["cpu_per_step"] for _, by in runs]
        dep = [by[PEERED][1]["density"] for _, by in runs]
        lig = [by["LIGGGHTS"][1]["density"] for _, by in runs]
        spread = max(mean_sd(dep)[1], mean_sd(lig)[1])
        diff = abs(statistics.mean(dep) - statistics.mean(lig))
        lines += [
            "",
            "Throughput: LIGGGHTS / deposit (no gas) time per particle-step = "
            + ", ".join(f"{r:.2f}" for r in ratios) + f" (seeds {', '.join(str(s) for s, _ in runs)}); "
            f"mean {statistics.mean(ratios):.2f}; in CPU time (the process's user + system time: "
            "what a second job on the machine inflates far less) "
            + ", ".join(f"{r:.2f}" for r in cpu_ratios) + f", mean {statistics.mean(cpu_ratios):.2f}. "
            f"Goal (issue 16): >= 2: {'met' if min(ratios) >= 2 else 'NOT met'} in loop time, "
            f"{'met' if min(cpu_ratios) >= 2 else 'NOT met'} in CPU time.",
            "",
            f"Layer density: deposit (no gas) {statistics.mean(dep):.4f}, LIGGGHTS {statistics.mean(lig):.4f}, "
            f"difference {diff:.4f}"
            + ((f" against the larger seed sd {spread:.4f}: "
                + ("within the seed spread." if diff <= spread else "NOT within the seed spread."))
               if len(runs) > 1 else " (one seed: no seed spread to compare it with)."),
        ]
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default=SCENE, help="deposit scene of a blade spread")
    parser.add_argument("--seeds", default=None, help="comma-separated seeds (default 1,2,3; --small: 1)")
    parser.add_argument("--small", action="store_true", help="seed 1, a quarter of the travel: a quick check")
    parser.add_argument("--window", default=None, help="X0,X1 (m) of the layer statistics")
    parser.add_argument("--liggghts-only", action="store_true", help="skip deposit (needs --initial-bed)")
    parser.add_argument("--initial-bed", default=None, help="start LIGGGHTS from this bed (testing)")
    parser.add_argument("--keep", action="store_true", help="keep the work folder")
    args = parser.parse_args()
    if not os.path.exists(args.scene):
        sys.exit(f"spread_peer: scene {args.scene} not found (accepted: a deposit blade-spread scene)")
    if args.liggghts_only != (args.initial_bed is not None):
        sys.exit("spread_peer: --liggghts-only and --initial-bed go together")
    seeds = [int(s) for s in args.seeds.split(",")] if args.seeds else ([1] if args.small else SEEDS)
    overrides = small_overrides(args.scene) if args.small else {}
    # LIGGGHTS settles for the fixed recoater.settle; deposit settles the same time.
    overrides["recoater.until-rest"] = "false"
    scene = Scene(args.scene, overrides)
    window = tuple(float(v) for v in args.window.split(",")) if args.window else scene.window()
    work = tempfile.mkdtemp(prefix="spread-peer-")
    load_before = load_average()
    runs = []
    for seed in seeds:
        by_code = {}
        if args.liggghts_only:
            initial = args.initial_bed
            dt = rayleigh_dt(scene, bed_radii(initial)[0])
        else:
            initial = initial_particles(work, args.scene, seed, overrides)
            if scene.drag:
                by_code["deposit"] = deposit_spread(work, args.scene, seed, overrides, "gas")
            dep = deposit_spread(work, args.scene, seed, {**overrides, "effects.drag": "false"},
                                 "no-gas")
            by_code[PEERED] = dep
            dt = dep["dt"]
        by_code["LIGGGHTS"] = liggghts_spread(work, scene, initial, seed, dt)
        codes = list(by_code)
        stats = layer_stats([by_code[c]["bed"] for c in codes], scene, window, initial)
        runs.append((seed, {c: (by_code[c], s) for c, s in zip(codes, stats)}))
        print(f"spread_peer: seed {seed} done", file=sys.stderr)
    text = report(scene, args, window, runs, load_before)
    if args.small or args.liggghts_only:
        path = os.path.join(work, "spread-peer-small.md")
        with open(path, "w") as f:
            f.write(text)
        print(text)
        print(f"spread_peer: wrote {path} (docs/results/spread-peer.md is written by a full run)")
    else:
        print(f"spread_peer: wrote {write_page('spread-peer.md', text)}")
    if args.keep or args.small or args.liggghts_only:
        print(f"spread_peer: work folder {work}")
    else:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
