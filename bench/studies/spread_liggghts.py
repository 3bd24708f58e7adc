#!/usr/bin/env python3
"""Throughput of a blade spread in deposit and in LIGGGHTS on 1 and 2 ranks (issue 34 item 7).

Prints the Markdown table of docs/results/spread-liggghts.md (the page's prose is written by
hand around it). Needs deposit built (POWDERBED_BUILD selects the build folder), `liggghts` and
`mpirun`:
    python3 bench/studies/spread_liggghts.py [--scene S.ini] [--repeats 3] [--ranks 1,2] [--no-gas]

Per repeat, one after the other on the same seed (1): deposit spreads the scene (its JSON's
particle_steps_per_s: the particles each step moved over the loop's wall time); `deposit
--export-deck liggghts` writes the same spread's deck, which LIGGGHTS runs on each rank count
(particle-steps = the sum over its runs of steps x atoms, over the sum of their "Loop time"s).
The median over repeats is reported with the load average before and after.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import tempfile

from lib.apps import ROOT, app
from lib.report import load_average, machine

SCENE = os.path.join(ROOT, "tests", "data", "spread-liggghts", "spread.ini")


def deposit(scene, work, extra):
    out = subprocess.run([app("deposit"), "--config", scene, "--seed", "1", "--out",
                          os.path.join(work, "d.h5"), "--json", "--thermo", "0", *extra],
                         capture_output=True, text=True, check=True).stdout
    s = json.loads(out)
    return s["particle_steps_per_s"], s["n"], s["steps"]


def liggghts(scene, work, ranks, extra):
    folder = tempfile.mkdtemp(dir=work)
    subprocess.run([app("deposit"), "--config", scene, "--seed", "1", "--out", os.path.join(folder, "L.h5"),
                    "--export-deck", "liggghts", *extra], capture_output=True, check=True)
    cmd = ["liggghts", "-in", "in.L.liggghts", "-log", "log.txt"]
    if ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
    out = subprocess.run(cmd, capture_output=True, text=True, check=True, cwd=folder).stdout
    loops = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", out)
    seconds = sum(float(t) for t, _, _ in loops)
    return sum(int(s) * int(n) for _, s, n in loops) / seconds, sum(int(s) for _, s, _ in loops)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default=SCENE)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--ranks", default="1,2")
    p.add_argument("--no-gas", action="store_true", help="--effects.drag false for both")
    a = p.parse_args()
    extra = ["--effects.drag", "false"] if a.no_gas else []
    ranks = [int(r) for r in a.ranks.split(",")]
    before = load_average()
    rates = {"deposit": []}
    rates.update({f"LIGGGHTS, {r} rank(s)": [] for r in ranks})
    with tempfile.TemporaryDirectory() as work:
        for _ in range(a.repeats):
            rate, n, steps = deposit(a.scene, work, extra)
            rates["deposit"].append(rate)
            for r in ranks:
                rates[f"LIGGGHTS, {r} rank(s)"].append(liggghts(a.scene, work, r, extra)[0])
    after = load_average()
    base = statistics.median(rates["deposit"])
    print(f"Scene {os.path.relpath(a.scene, ROOT)}{' without gas' if a.no_gas else ''}: deposit kept {n} "
          f"particles after {steps} steps. {machine(before, after)}\n")
    print("| engine | particle-steps/s (median) | runs | time per particle-step (ns) | deposit / engine |")
    print("|---|---|---|---|---|")
    for name, values in rates.items():
        m = statistics.median(values)
        print(f"| {name} | {m:.3g} | {', '.join(f'{v:.3g}' for v in values)} | {1e9 / m:.0f} | {base / m:.2f} |")


if __name__ == "__main__":
    main()
