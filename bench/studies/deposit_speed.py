#!/usr/bin/env python3
"""Speed of deposit beside LIGGGHTS 3.8 on the [GZ] scene, in one run (issue 4 "Speed").

Writes docs/results/deposit-speed.md. Run from anywhere with python3 (needs numpy and
h5py) after building deposit, bedconv and bedstat (POWDERBED_BUILD selects the build folder):
    POWDERBED_BUILD=build python3 bench/studies/deposit_speed.py

What is measured (all on this machine, in this one run, one after the other):
1. A settled bed: data/scenes/gz2016-deposit.ini (600 particles, seed 1) dropped and settled with
   --young-scale 1e4 --until-rest; exported with bedconv to a LAMMPS data file, so both codes
   start from the same 600 particles.
2. Head to head: STEPS steps from that bed at full stiffness, E = 193 GPa, with deposit's
   automatic step (0.2 x the Rayleigh step of the smallest particle) for both codes; one thread
   each; the timer is each code's own loop timer (deposit's wall_time, LIGGGHTS's "Loop time"),
   so start-up and file I/O are left out of both; median of REPEATS, the codes interleaved so
   that both see the same machine load. LIGGGHTS runs bench/liggghts/gz2016-speed.liggghts with
   tangential no_history (closest to our sliding friction) and, for reference, history.
3. Scaling: the settled bed tiled 1 x 1, 5 x 2 and 10 x 10 in x and y (600, 6,000, 60,000
   particles; walls only around the whole tiling), SCALING_STEPS steps at E = 193 GPa, 1 thread.
4. The paper's full settle: the scene as it is (t-end 0.1 s) with --young-scale 1e3 (the
   softening used for the [GZ] results, docs/results/deposit-gz2016.md) and --threads 2.
The page's prose is bench/studies/templates/deposit-speed.md.in.
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

import numpy as np

from lib import report
from lib.apps import ROOT, app, read_bed, run_json, scene

SCENE = scene("gz2016-deposit.ini")
PHYSICS = scene("gz2016-bench.ini")
DECK = os.path.join(ROOT, "bench", "liggghts", "gz2016-speed.liggghts")
STEPS = 20000
SCALING_STEPS = 2000
REPEATS = 3
SETTLE_SCALE = 1e4      # softening of the drop that makes the benchmark's starting bed
DEFAULT_SCALE = 1e3     # softening of the full settle (the [GZ] results' default)
TILES = [(1, 1), (5, 2), (10, 10)]


def liggghts_binary():
    for name in ("liggghts", "lmp_auto"):
        path = shutil.which(name)
        if path:
            return path
    sys.exit("LIGGGHTS not found (apt-get install liggghts)")


def run_liggghts(work, data, dt, steps, tangential):
    """Loop seconds and final kinetic energy of one LIGGGHTS run."""
    log = os.path.join(work, f"liggghts-{tangential}.log")
    proc = subprocess.run(
        [liggghts_binary(), "-in", DECK, "-var", "DATA", data, "-var", "DT", repr(dt),
         "-var", "NSTEPS", str(steps), "-var", "TANG", tangential,
         "-var", "OUT", os.path.join(work, f"liggghts-{tangential}.txt"), "-log", log],
        capture_output=True, text=True, cwd=work)
    if proc.returncode != 0:
        raise RuntimeError(f"liggghts exited {proc.returncode}: {proc.stdout[-2000:]}")
    loop = re.search(r"Loop time of ([0-9.eE+-]+) on 1 procs for (\d+) steps with (\d+) atoms",
                     proc.stdout)
    ke = re.findall(rf"^\s*{steps}\s+(\d+)\s+([0-9.eE+-]+)\s*$", proc.stdout, re.M)
    return float(loop.group(1)), int(loop.group(3)), float(ke[-1][1])


def deposit_run(bed, steps, dt, threads, out):
    summary, _ = run_json([app("deposit"), "--config", PHYSICS, "--in", bed, "--seed", "1",
                           "--t-end", repr(steps * dt), "--threads", str(threads), "--out", out])
    assert summary["steps"] == steps, summary
    return summary


def tile_bed(work, src, nx, ny):
    """The settled bed repeated nx x ny times in x, y; returns the HDF5 path."""
    centres, radii = read_bed(src)
    lx, ly, lz = 1e-3, 0.5e-3, 0.35e-3  # the scene's box
    rows = [np.column_stack([centres[:, 0] + ix * lx, centres[:, 1] + iy * ly, centres[:, 2], radii])
            for ix in range(nx) for iy in range(ny)]
    csv = os.path.join(work, f"tiled-{nx}x{ny}.csv")
    np.savetxt(csv, np.vstack(rows), delimiter=",", header="x,y,z,r", comments="", fmt="%.17g")
    h5 = csv[:-4] + ".h5"
    subprocess.run([app("bedconv"), csv, h5, "--domain", f"0,0,0,{nx * lx!r},{ny * ly!r},{lz!r}"],
                   check=True, capture_output=True)
    return h5


def settled_bed(work):
    """The benchmark's starting bed: the [GZ] scene dropped and settled at SETTLE_SCALE, as HDF5
    and, for LIGGGHTS, as a LAMMPS data file; with deposit's summary of the settle and that of a
    probe run from the bed (its automatic step at full stiffness and its particle count)."""
    settled = os.path.join(work, "settled.h5")
    settle, _ = run_json([app("deposit"), "--config", SCENE, "--seed", "1", "--young-scale",
                          repr(SETTLE_SCALE), "--until-rest", "--t-end", "0.1", "--threads", "1",
                          "--out", settled])
    data = os.path.join(work, "settled.data")
    subprocess.run([app("bedconv"), settled, data], check=True, capture_output=True)
    probe, _ = run_json([app("deposit"), "--config", PHYSICS, "--in", settled, "--seed", "1",
                         "--t-end", "1e-12", "--threads", "1", "--out", os.path.join(work, "p.h5")])
    return settled, data, settle, probe


def head_to_head(work, settled, data, dt):
    """REPEATS runs of STEPS steps in deposit and in LIGGGHTS (no_history, history), the codes
    interleaved so that all see the same load: per repeat, deposit's (wall, KE, rebuilds) and
    LIGGGHTS's (loop s, atoms, KE)."""
    ours, lig_nh, lig_h = [], [], []
    for _ in range(REPEATS):
        s = deposit_run(settled, STEPS, dt, 1, os.path.join(work, "ours.h5"))
        ours.append((s["wall_time"], s["kinetic_energy"], s["neighbour_rebuilds"]))
        lig_nh.append(run_liggghts(work, data, dt, STEPS, "no_history"))
        lig_h.append(run_liggghts(work, data, dt, STEPS, "history"))
    return ours, lig_nh, lig_h


def scaling_runs(work, settled, dt):
    """Per tiling (particles, median wall of REPEATS, rebuilds) on one thread, and the largest
    tiling's walls on two threads."""
    scaling = []
    for nx, ny in TILES:
        bed = tile_bed(work, settled, nx, ny)
        times = []
        for _ in range(REPEATS):
            s = deposit_run(bed, SCALING_STEPS, dt, 1, os.path.join(work, "scaled.h5"))
            times.append(s["wall_time"])
        scaling.append((s["n"], statistics.median(times), s["neighbour_rebuilds"]))
    big = tile_bed(work, settled, *TILES[-1])
    two = [deposit_run(big, SCALING_STEPS, dt, 2, os.path.join(work, "scaled2.h5"))["wall_time"]
           for _ in range(REPEATS)]
    return scaling, two


def speed_table(n, runs):
    """The head-to-head table of `runs` (head_to_head's three lists): each code's median loop
    time, rates, ratio to deposit and the last run's kinetic energy."""
    ours, lig_nh, lig_h = runs
    t_ours = statistics.median(r[0] for r in ours)
    lines = report.table_head("code", "loop time (s)", "particle-steps/s", "ns per particle-step",
                              "ratio deposit / code", "final KE (J)")
    for label, code_runs, ke in (
            ("deposit (Verlet, Hertz + damping + sliding friction + drag + walls)", ours, 1),
            ("LIGGGHTS 3.8, tangential no_history", lig_nh, 2),
            ("LIGGGHTS 3.8, tangential history (the peer deck's)", lig_h, 2)):
        t = statistics.median(r[0] for r in code_runs)
        lines.append(report.table_row(
            label, f"{t:.3f}", f"{n * STEPS / t:.3g}", f"{t / (n * STEPS) * 1e9:.1f}",
            "1" if code_runs is ours else f"{t / t_ours:.2f}", f"{code_runs[-1][ke]:.3g}"))
    return "\n".join(lines)


def scaling_table(scaling):
    """Per tiling: the loop time, the rates and the cost against the untiled bed's."""
    ns = [t / (c * SCALING_STEPS) * 1e9 for c, t, _ in scaling]
    lines = report.table_head("particles", "loop time (s)", "particle-steps/s",
                              "ns per particle-step", "/ 600-particle cost", "rebuilds")
    for (count, t, rebuilds), cost in zip(scaling, ns):
        lines.append(report.table_row(count, f"{t:.3f}", f"{count * SCALING_STEPS / t:.3g}",
                                      f"{cost:.1f}", f"{cost / ns[0]:.2f}", rebuilds))
    return "\n".join(lines)


def page(m):
    """The page: templates/deposit-speed.md.in filled with main()'s measurements `m`."""
    ours, lig_nh, lig_h = m["runs"]
    t_ours, t_nh, t_h = (statistics.median(r[0] for r in runs) for runs in m["runs"])
    scaling, two = m["scaling"], m["two"]
    ns = [t / (c * SCALING_STEPS) * 1e9 for c, t, _ in scaling]
    t2 = statistics.median(two)
    # more runnable jobs than cores: each OpenMP barrier waits for a descheduled thread
    busy = max(float(load.split()[0]) for load in m["loads"]) > os.cpu_count()
    settle, full = m["settle"], m["full"]
    return report.fill_template("deposit-speed.md.in", {
        "machine": report.machine(*m["loads"]),
        "settle_scale": f"{SETTLE_SCALE:g}", "settle_steps": settle["steps"],
        "settle_wall": f"{settle['wall_time']:.1f}", "settle_lost": settle["lost"],
        "steps": STEPS, "dt": f"{m['probe']['dt']:.4g}", "repeats": REPEATS,
        "speed_table": speed_table(m["probe"]["n"], m["runs"]),
        "runs_ours": ", ".join(f"{r[0]:.3f}" for r in ours),
        "runs_no_history": ", ".join(f"{r[0]:.3f}" for r in lig_nh),
        "runs_history": ", ".join(f"{r[0]:.3f}" for r in lig_h),
        "rebuilds": ours[-1][2],
        "best_no_history": f"{min(r[0] for r in lig_nh) / min(r[0] for r in ours):.2f}",
        "best_history": f"{min(r[0] for r in lig_h) / min(r[0] for r in ours):.2f}",
        "target": "met" if t_nh / t_ours >= 2 and t_h / t_ours >= 2 else "NOT met",
        "ratio_no_history": f"{t_nh / t_ours:.2f}", "ratio_history": f"{t_h / t_ours:.2f}",
        "scaling_steps": SCALING_STEPS, "scaling_table": scaling_table(scaling),
        "cost_spread": f"{max(ns) / min(ns):.2f}", "largest": scaling[-1][0],
        "two_threads": f"{t2:.3f}", "speed_up": f"{scaling[-1][1] / t2:.2f}",
        "load_note": (" (with more runnable jobs than cores, each OpenMP barrier waits for a "
                      "descheduled thread, so this figure measures the load more than the code)."
                      if busy else "."),
        "default_scale": f"{DEFAULT_SCALE:g}", "full_steps": full["steps"],
        "full_dt": f"{full['dt']:.4g}", "full_time": f"{full['sim_time']:.3g}",
        "full_wall": f"{full['wall_time']:.1f}", "full_process": f"{m['full_process']:.1f}",
        "full_rate": f"{full['particle_steps_per_s']:.3g}", "full_lost": full["lost"],
        "full_rebuilds": full["neighbour_rebuilds"]})


def main():
    argparse.ArgumentParser(description=__doc__,
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    work = tempfile.mkdtemp(prefix="deposit-speed-")
    load_before = report.load_average()
    settled, data, settle, probe = settled_bed(work)
    runs = head_to_head(work, settled, data, probe["dt"])
    scaling, two = scaling_runs(work, settled, probe["dt"])
    full, full_process = run_json([app("deposit"), "--config", SCENE, "--seed", "1",
                                   "--young-scale", repr(DEFAULT_SCALE), "--threads", "2",
                                   "--out", os.path.join(work, "full.h5")])
    measured = {"settle": settle, "probe": probe, "runs": runs, "scaling": scaling, "two": two,
                "full": full, "full_process": full_process,
                "loads": (load_before, report.load_average())}
    # speed_targets.py's section stays (it regenerates it on its own).
    report.write_page_keeping("deposit-speed.md", page(measured), ["paper-protocol"])
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
