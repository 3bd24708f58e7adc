#!/usr/bin/env python3
"""Before and after: two build binaries run in alternation on one layer of a part.

    POWDERBED_BUILD=build python3 bench/studies/build_ab.py OLD_BUILD NEW_BUILD \
        --old-label eecb474 --new-label 9b5b7ba [--rounds 2] [--layer K] --title "..." \
        --page build-ab.md

The case: layer K (default 2) of data/scenes/build-316L.ini (spread over the fused solid of the
layers before it, then scanned), one thread, continued from the file of layer K - 1 the new
binary writes once (`build --in LAYER-K-1 --layers 1`). Per binary the page gives the median
[min, max] over the rounds of the layer's spread and scan wall times (build.json), the ratio
new / old of the medians, the 1-min load average around each run, and whether the two layers are
the same: the spread's and the fused layer's particles compared as deposit_ab.py compares beds.
Alternating the two puts both under the same load. Build the old binary in a clone (`git clone
-q . /tmp/old && git -C /tmp/old checkout COMMIT`, then `cmake --build /tmp/old/build --target
build_app`).
"""
import json
import os
import shutil
import subprocess

from deposit_ab import ab_arguments, ab_row, compare, write_ab_page
from lib import apps
from lib.apps import scene
from lib.report import load_average

WORK = os.path.join(apps.WORK, "build-ab")
FIRST = os.path.join(WORK, "first")


def build(binary, out, *args):
    """build's report (build.json) of one run into the new folder `out`, with the 1-min load before it."""
    load = float(load_average().split()[0])
    shutil.rmtree(out, ignore_errors=True)
    subprocess.run([binary, "--config", scene("build-316L.ini"), "--threads", "1", "--progress", "0",
                    "--out", out, *args], check=True, capture_output=True)
    with open(os.path.join(out, "build.json")) as f:
        report = json.load(f)
    report["load"] = load
    return report


def main():
    p = ab_arguments(__doc__.splitlines()[0])
    p.add_argument("--layer", type=int, default=2, help="the layer timed (>= 2)")
    a = p.parse_args()
    if a.layer < 2:
        p.error("--layer: the layer timed continues from the one before it (accepted: 2 or more)")
    os.makedirs(WORK, exist_ok=True)
    before = load_average()
    build(a.new, FIRST, "--layers", str(a.layer - 1))
    start = os.path.join(FIRST, f"layer-{a.layer - 1:03d}.h5")
    times = {(tag, stage): [] for tag in ("old", "new") for stage in ("spread", "scan")}
    loads = []
    for _ in range(a.rounds):
        for tag, binary in (("old", a.old), ("new", a.new)):
            report = build(binary, os.path.join(WORK, tag), "--in", start, "--layers", "1")
            times[(tag, "spread")].append(report["layers"][-1]["spread_wall_time"])
            times[(tag, "scan")].append(report["layers"][-1]["scan_wall_time"])
            loads.append(report["load"])
    rows = [ab_row(f"layer {a.layer}, {stage}", times[("old", key)], times[("new", key)], loads,
                   compare(*(os.path.join(WORK, t, file) for t in ("old", "new"))))
            for stage, key, file in (("spread", "spread", f"layer-{a.layer:03d}-spread.h5"),
                                     ("scan and fusion", "scan", f"layer-{a.layer:03d}.h5"))]
    write_ab_page(a, "build", f": layer {a.layer} of data/scenes/build-316L.ini, continued from its layer "
                  f"{a.layer - 1}",
                  before, "Wall time (s) from build.json: median [min, max] over the rounds.", "stage",
                  "particles", rows)

if __name__ == "__main__":
    main()
