#!/usr/bin/env python3
"""ctest bench.spread_peer_liggghts: the LIGGGHTS side of bench/studies/spread_peer.py end to end.

A heap of 448 spheres (4 layers, tops up to 135 um) stands in front of the blade of the stand-in
scene bench/studies/spread_peer_test.ini (gap 90 um); `spread_peer.py --small --liggghts-only`
spreads it with LIGGGHTS and measures the layer with bedstat --spread. Checks: the run ends with
every particle (nothing lost through the plate, the blade or the periodic faces), the layer
behind the blade has powder (density > 0) and nothing above the blade's bottom edge beyond a
contact overlap (tops <= 1.1 x gap: the heap was 1.5 x gap tall there). Skips (exit 77) without
LIGGGHTS. Usage: check_spread_peer.py BUILD_DIR
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENE = os.path.join(ROOT, "bench", "studies", "spread_peer_test.ini")
GAP = 90e-6


def heap_csv(path):
    """4 layers of 8 x 14 spheres, radii 12 and 16 um alternating, at x 0.27-0.51 mm."""
    rows = []
    for k in range(4):
        for j in range(14):
            for i in range(8):
                r = 12e-6 if (i + j + k) % 2 else 16e-6
                rows.append((0.27e-3 + 34e-6 * i, (j + 0.5) * 0.5e-3 / 14, 17e-6 + 34e-6 * k, r))
    with open(path, "w") as f:
        f.write("x,y,z,r\n")
        for row in rows:
            f.write(",".join(repr(v) for v in row) + "\n")
    return len(rows)


def dump_particles(path):
    text = open(path).read().split("ITEM: ATOMS")[-1].splitlines()
    columns = text[0].split()
    return [dict(zip(columns, map(float, line.split()))) for line in text[1:] if line.strip()]


def main():
    build = sys.argv[1]
    if not (shutil.which("liggghts") or shutil.which("lmp_auto")):
        print("skipped: LIGGGHTS not installed (apt-get install liggghts)")
        sys.exit(77)
    with tempfile.TemporaryDirectory() as work:
        csv = os.path.join(work, "heap.csv")
        n = heap_csv(csv)
        heap = os.path.join(work, "heap.h5")
        subprocess.run([os.path.join(build, "apps", "bedconv"), csv, heap, "--domain",
                        "0,0,0,1.2e-3,0.5e-3,0.5e-3"], check=True, capture_output=True)
        env = dict(os.environ, POWDERBED_BUILD=build)
        proc = subprocess.run([sys.executable, os.path.join(ROOT, "bench", "studies", "spread_peer.py"),
                               "--scene", SCENE, "--small", "--liggghts-only", "--initial-bed", heap],
                              capture_output=True, text=True, env=env)
        print(proc.stdout[-3000:], proc.stderr[-2000:])
        if proc.returncode != 0:
            sys.exit(1)
        # | seed | code | particles | steps | loop time | ns per particle-step | CPU ns per
        # particle-step | layer density | ...: the density is the eighth column.
        row = re.search(r"^\| 1 \| LIGGGHTS \| (\d+) \| \d+ \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \| ([0-9.]+) \|",
                        proc.stdout, re.M)
        window = re.search(r"over x in \[([0-9.]+), ([0-9.]+)\] mm", proc.stdout)
        folder = re.search(r"work folder (\S+)", proc.stdout)
        try:
            atoms, density = int(row.group(1)), float(row.group(2))
            x0, x1 = float(window.group(1)) * 1e-3, float(window.group(2)) * 1e-3
            particles = dump_particles(os.path.join(folder.group(1), "liggghts-1.dump"))
        finally:
            if folder:
                shutil.rmtree(folder.group(1), ignore_errors=True)
        tops = [p["z"] + p["radius"] for p in particles if x0 <= p["x"] <= x1]
        print(f"particles {atoms} of {n}, layer density {density}, {len(tops)} in the window, "
              f"highest top {max(tops) * 1e6:.1f} um (gap {GAP * 1e6:.0f} um)")
        ok = atoms == n and len(particles) == n and density > 0 and tops and max(tops) <= 1.1 * GAP
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
