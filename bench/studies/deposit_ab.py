#!/usr/bin/env python3
"""Before and after: two deposit binaries run in alternation on the same scenes.

    POWDERBED_BUILD=build python3 bench/studies/deposit_ab.py OLD_DEPOSIT NEW_DEPOSIT \
        --old-label d29b46f --new-label c784a63 [--rounds 2] [--cases A,B] --title "..." \
        --page deposit-subnormals.md

Cases (one thread each, seed 1; --cases picks some by their number, 1-based): [GZ]'s own
protocol at full stiffness (E = 193 GPa, dt = 2e-8 s, 0.1 s; issue 37's "under 90 s" target),
one blade layer of data/scenes/spread-blade.ini, the [GZ] drop with the scene's defaults, and
the [GZ] drop stopped at 0.02 s and pressed by the lid 5 um into its surface (held 1 ms, then
released and relaxed up to 5 ms). Per
case and binary the page gives the median [min, max] of deposit's own `wall_time` over the rounds,
the ratio new / old of the medians, the 1-min load average around each run, and whether the two
beds are the same: positions and radii bit for bit, velocities to the largest difference.
Alternating the two puts both under the same load (single runs on a shared 2-core machine move
by ±10 %). Build the old binary in a worktree (`git worktree add ../old COMMIT`, then
`cmake --build ... --target deposit_app`).
"""
import argparse
import json
import os
import statistics
import subprocess

import h5py
import numpy as np

from lib import apps
from lib.apps import scene
from lib.report import load_average, machine, table_head, table_row, write_page_with_discussion

WORK = os.path.join(apps.WORK, "deposit-ab")
CASES = {
    "[GZ] protocol, full stiffness": ["--config", scene("gz2016-deposit.ini"), "--young-scale", "1",
                                      "--dt", "2e-8", "--unsafe-dt", "--t-end", "0.1"],
    "spread-blade.ini, one layer": ["--config", scene("spread-blade.ini")],
    "[GZ] drop, the scene's defaults": ["--config", scene("gz2016-deposit.ini")],
    "[GZ] drop to 0.02 s, then the lid 5 um deep": [
        "--config", scene("gz2016-deposit.ini"), "--t-end", "0.02", "--lid.enabled", "true",
        "--lid.depth", "5e-6", "--lid.hold", "1e-3", "--lid.relax", "5e-3"],
}


def run(binary, case, out):
    """deposit's JSON summary of `case`, with the 1-min load before the run."""
    load = float(load_average().split()[0])
    args = [binary, *CASES[case], "--seed", "1", "--threads", "1", "--thermo", "0", "--out", out, "--json"]
    summary = json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)
    summary["load"] = load
    return summary


def compare(a, b):
    """'same' / the largest velocity difference / 'positions differ' between two beds."""
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        pa, pb = fa["particles"], fb["particles"]
        if not all(np.array_equal(pa[k][...], pb[k][...]) for k in ("position", "radius")):
            return "positions differ"
        dv = np.max(np.abs(pa["velocity"][...] - pb["velocity"][...]))
        return "same bit for bit" if dv == 0 else f"positions same; velocities within {dv:.1e} m/s"


def spread(values):
    return f"{statistics.median(values):.1f} [{min(values):.1f}, {max(values):.1f}]"


def ab_arguments(description, title_default=None):
    """The options every A/B study takes: the two binaries, their labels, the rounds, the page
    and what changed (its heading)."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--old-label", required=True)
    p.add_argument("--new-label", required=True)
    p.add_argument("--rounds", type=int, default=2)
    p.add_argument("--page", required=True)
    p.add_argument("--title", default=title_default, required=title_default is None,
                   help="what changed between the binaries (the page's heading)")
    return p


def ab_row(name, old, new, loads, same):
    """A row of an A/B table: the old and new times (median [min, max]), their ratio, the load
    range and what compare() said of the two results."""
    ratio = statistics.median(new) / statistics.median(old)
    return table_row(name, spread(old), spread(new), f"{ratio:.2f}", f"{min(loads):.2f}-{max(loads):.2f}", same)


def write_ab_page(a, program, what_ran, before, timing, first, last, rows):
    """The A/B page of `program` (deposit, build): heading, how it was run, the machine, the
    table, and the discussion kept below it."""
    write_page_with_discussion(a.page, "\n".join([
        f"# {program} before and after: {a.title}",
        "",
        f"Written by `bench/studies/{program}_ab.py` ({a.rounds} rounds, the two binaries "
        f"alternating, one thread each){what_ran}. {machine(before, load_average())} Old: "
        f"{a.old_label}; new: {a.new_label}.",
        "",
        timing,
        "",
        *table_head(first, f"old {a.old_label} (s)", f"new {a.new_label} (s)", "new / old",
                    "load (1 min)", last),
        *rows,
    ]))


def main():
    p = ab_arguments(__doc__.splitlines()[0], "subnormal numbers flushed to zero")
    p.add_argument("--cases", help="comma-separated case numbers (1-based); default: all")
    a = p.parse_args()
    names = list(CASES)
    cases = [names[int(k) - 1] for k in a.cases.split(",")] if a.cases else names
    os.makedirs(WORK, exist_ok=True)
    before = load_average()
    rows = []
    for case in cases:
        times = {"old": [], "new": []}
        loads = []
        for k in range(a.rounds):
            for tag, binary in (("old", a.old), ("new", a.new)):
                s = run(binary, case, os.path.join(WORK, f"{tag}.h5"))
                times[tag].append(s["wall_time"])
                loads.append(s["load"])
        rows.append(ab_row(case, times["old"], times["new"], loads,
                           compare(*(os.path.join(WORK, f"{t}.h5") for t in ("old", "new")))))
    write_ab_page(a, "deposit", "", before, "Wall time is deposit's own `wall_time` (s): median "
                  "[min, max] over the rounds.", "case", "beds", rows)

if __name__ == "__main__":
    main()
