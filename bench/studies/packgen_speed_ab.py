#!/usr/bin/env python3
"""Before/after of packgen's densest 3D rule, two binaries run in alternation on one machine.

    python3 bench/studies/packgen_speed_ab.py OLD_PACKGEN NEW_PACKGEN [--rounds 3] [--counts 1e4,1e5,1e6]

Per N (monodisperse r = 0.5, `--approach 3 --site-order lowest`, the cube of packgen_speed.py's
scaling, seed 1) the old and the new binary run one after the other, ROUNDS times; printed per
binary: the median [min, max] of packgen's placement `wall_time` and of the process's user CPU
(placement + --json statistics + writing the bed), the load average before and after, and
whether the two beds' positions and radii are the same bit for bit. Alternating the two puts both
under the same load (a shared 2-core machine moves single runs by ±10 %).
"""
import argparse
import json
import math
import os
import resource
import statistics
import subprocess
import tempfile

import h5py
import numpy as np


def run(binary, n, out):
    side = math.ceil((n * (4.0 / 3.0) * math.pi * 0.5 ** 3 / 0.6 * 1.25) ** (1.0 / 3.0))
    args = [binary, "--dim", "3", "--domain", f"{side},{side},{side}", "--psd", "mono:r=0.5",
            "--approach", "3", "--site-order", "lowest", "--count", str(n), "--seed", "1",
            "--progress", "0", "--json", "--out", out]
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    s = json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)
    return s["wall_time"], resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - before, s


def same_bed(a, b):
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        return all(np.array_equal(fa["particles"][k][...].view(np.uint64),
                                  fb["particles"][k][...].view(np.uint64))
                   for k in ("position", "radius"))


def fmt(v):
    return f"{statistics.median(v):.3f} [{min(v):.3f}, {max(v):.3f}]"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--counts", default="1e4,1e5,1e6")
    a = p.parse_args()
    print("| N | build | placement wall (s), median [range] | process user CPU (s), median [range] | "
          "load before / after | beds bit-identical | Z |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in (int(float(c)) for c in a.counts.split(",")):
            load0 = os.getloadavg()[0]
            t = {"old": [], "new": []}
            u = {"old": [], "new": []}
            z = {}
            for _ in range(a.rounds):
                for label in ("old", "new"):
                    wall, user, s = run(getattr(a, label), n, os.path.join(tmp, f"{label}.h5"))
                    t[label].append(wall)
                    u[label].append(user)
                    z[label] = s["coordination"]
            same = same_bed(os.path.join(tmp, "old.h5"), os.path.join(tmp, "new.h5"))
            load1 = os.getloadavg()[0]
            for label in ("old", "new"):
                print(f"| {n:,} | {label} | {fmt(t[label])} | {fmt(u[label])} | {load0:.2f} / {load1:.2f} | "
                      f"{'yes' if same else 'NO'} | {z[label]:.4f} |", flush=True)


if __name__ == "__main__":
    main()
