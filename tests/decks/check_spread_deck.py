#!/usr/bin/env python3
"""ctest decks.spread_liggghts and decks.spread_lammps (issue 34 item 7): a layer spread by
LIGGGHTS or LAMMPS (the ENGINE) against deposit's.

The scene tests/data/spread-liggghts/spread.ini (600 spheres, one blade layer at a 90 um gap).
1. deposit spreads it for seeds 1, 2, 3 (its own engine);
2. `deposit --seed 1 --export-deck ENGINE` writes the deck of the same spread (the same supply,
   laws and time step), which the engine runs serially and on 2 MPI ranks (mpirun
   --allow-run-as-root --oversubscribe -np 2);
3. every bed through `bedstat --spread` (gap 90 um, window x 0.25-1.05 mm: the layer the blade
   left, less its ends).
Asserted for each engine run: layer density, coverage and Sa within 3 sigma of deposit's mean
over the three seeds, sigma = the larger of deposit's seed-to-seed sd measured over seeds 1-10
(docs/results/spread-liggghts.md: density 0.0057, coverage 0.020, Sa 0.63 um) and the sd of this
test's three seeds. Both engines are deterministic here (deposit bit for bit; the engine for a given
binary and rank count), so the test passes or fails the same way every time; 3 sigma is what
separates a run from the same distribution (a single run differs from a three-seed mean with
sd sigma sqrt(4/3), so a 3 sigma bound is 2.6 of those sds) from a different law. Also checked:
no particle lost (the dump's atoms plus those delete_atoms took as the overflow are the supply),
the deck's steps equal deposit's.
Exits 77 (ctest: skipped) with a message without the engine's program or mpirun.
Usage: check_spread_deck.py BUILD_APPS_DIR liggghts|lammps
"""
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENE = os.path.join(ROOT, "tests", "data", "spread-liggghts", "spread.ini")
GAP = 90e-6
WINDOW = "0.25e-3,1.05e-3"
SEEDS = [1, 2, 3]
# deposit's seed-to-seed sd over seeds 1-10 of SCENE (docs/results/spread-liggghts.md)
SIGMA = {"density": 0.0057, "coverage": 0.020, "sa": 0.63e-6}
KEYS = ("density", "coverage", "sa")
SUPPLY = 600  # supply.count of SCENE
# each engine's program, its name in messages and the Debian package that has it
ENGINES = {"liggghts": ("liggghts", "LIGGGHTS", "liggghts"), "lammps": ("lmp", "LAMMPS", "lammps")}


def run(args, cwd=None):
    proc = subprocess.run(args, capture_output=True, text=True, cwd=cwd)
    if proc.returncode != 0:
        sys.exit(f"FAIL: {' '.join(args)} exited {proc.returncode}:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    return proc


def engine_run(work, apps, engine, ranks):
    """The seed-1 deck in its own folder, run on `ranks` ranks; returns (dump, steps, seconds)."""
    program, name, _ = ENGINES[engine]
    folder = os.path.join(work, f"{engine}-{ranks}")
    os.mkdir(folder)
    run([os.path.join(apps, "deposit"), "--config", SCENE, "--seed", "1", "--out",
         os.path.join(folder, "L.h5"), "--export-deck", engine])
    cmd = [program, "-in", f"in.L.{engine}", "-log", "log.txt"]
    if ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
    out = run(cmd, cwd=folder).stdout
    loops = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps", out)
    if "ERROR" in out:
        sys.exit(f"FAIL: {name} on {ranks} rank(s) printed an error:\n{out[-2000:]}")
    dump = os.path.join(folder, f"L.{engine}.layer-1.lammpstrj")
    with open(dump) as f:
        kept = int(re.search(r"ITEM: NUMBER OF ATOMS\s+(\d+)", f.read()).group(1))
    deleted = sum(int(n) for n in re.findall(r"Deleted (\d+) atoms", out))
    if kept + deleted != SUPPLY:
        sys.exit(f"FAIL: {name} on {ranks} rank(s) kept {kept} and removed {deleted} of {SUPPLY}: lost some")
    return (dump, sum(int(s) for _, s in loops),
            sum(float(t) for t, _ in loops))


def layer_stats(apps, beds):
    out = run([os.path.join(apps, "bedstat"), *beds, "--spread", "--gap", repr(GAP), "--window", WINDOW,
               "--json"]).stdout
    return [b["spread"] for b in json.loads(out)["beds"]]


def main():
    apps, engine = sys.argv[1], sys.argv[2]
    program, name, package = ENGINES[engine]
    missing = [p for p in (program, "mpirun") if not shutil.which(p)]
    if missing:
        print(f"skipped: {', '.join(missing)} not installed (apt-get install {package} openmpi-bin)")
        sys.exit(77)
    with tempfile.TemporaryDirectory() as work:
        beds, steps = [], []
        for seed in SEEDS:
            bed = os.path.join(work, f"deposit-{seed}.h5")
            summary = json.loads(run([os.path.join(apps, "deposit"), "--config", SCENE, "--seed", str(seed),
                                      "--out", bed, "--json", "--thermo", "0"]).stdout)
            if summary["lost"] != 0:
                sys.exit(f"FAIL: deposit seed {seed} lost {summary['lost']} particles")
            beds.append(bed)
            steps.append(summary["steps"])
        dumps = [engine_run(work, apps, engine, ranks) for ranks in (1, 2)]
        stats = layer_stats(apps, beds + [d for d, _, _ in dumps])
        ok = True
        for (dump, n_steps, seconds), ranks in zip(dumps, (1, 2)):
            print(f"{name} on {ranks} rank(s): {n_steps} steps (deposit seed 1: {steps[0]}), loop time {seconds:.1f} s")
            if n_steps != steps[0]:
                print(f"  FAIL: steps differ from deposit's")
                ok = False
        dep, lig = stats[:len(SEEDS)], stats[len(SEEDS):]
        for key in KEYS:
            values = [s[key] for s in dep]
            mean, sd = statistics.mean(values), statistics.stdev(values)
            sigma = max(SIGMA[key], sd)
            for s, ranks in zip(lig, (1, 2)):
                diff = s[key] - mean
                good = abs(diff) <= 3 * sigma
                ok &= good
                print(f"{key}: deposit seeds {SEEDS} {', '.join(f'{v:.4g}' for v in values)} (mean {mean:.4g}, sd {sd:.2g}); "
                      f"{name} {ranks} rank(s) {s[key]:.4g}: {diff / sigma:+.2f} sigma (sigma {sigma:.2g}) "
                      f"{'ok' if good else 'FAIL: beyond 3 sigma'}")
        if lig[0]["particles"] != lig[1]["particles"]:
            print(f"note: the 2-rank layer has {lig[1]['particles']} particles, the serial {lig[0]['particles']}")
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
