#!/usr/bin/env python3
"""ctest scripts.plot_height_map: bedstat --spread --height-map, then scripts/plot_height_map.py.

A square monolayer of equal spheres covers the left half of a strip and leaves the right half
bare: the PNG must show the bare plate in grey over the right half of the map and a covered
fraction pi/4 on the left (bare between the spheres 1 - pi/4 = 0.215). Skips (exit 77) without
matplotlib. Usage: check_plot_height_map.py BEDSTAT
"""
import math
import os
import subprocess
import sys
import tempfile

try:
    import matplotlib.image as mpimg
    import numpy as np
except ImportError as err:
    print(f"skipped: {err}")
    sys.exit(77)

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(ROOT, "scripts", "plot_height_map.py")


def main():
    bedstat = sys.argv[1]
    r, n = 10e-6, 8
    length, width = 4 * r * n, 2 * r * n  # spheres over x < length / 2 only
    with tempfile.TemporaryDirectory() as work:
        bed = os.path.join(work, "half.csv")
        with open(bed, "w") as f:
            f.write("x,y,z,r\n")
            for j in range(n):
                for i in range(n):
                    f.write(f"{2 * r * (i + 0.5)!r},{2 * r * (j + 0.5)!r},{r!r},{r!r}\n")
        csv = os.path.join(work, "map.csv")
        png = os.path.join(work, "map.png")
        subprocess.run([bedstat, bed, "--domain", f"0,0,0,{length!r},{width!r},{4 * r!r}", "--spread",
                        "--gap", repr(2 * r), "--raster", repr(r / 10), "--height-map", csv],
                       check=True, capture_output=True)
        subprocess.run([sys.executable, SCRIPT, csv, png], check=True, capture_output=True)
        image = mpimg.imread(png)[:, :, :3]
        grey = np.all(np.abs(image - 0.6) < 1.5 / 255, axis=2)
        # The map is where grey is dense (the bare right half spans every row of it, and the left
        # edge runs between the spheres); antialiased text has a few grey pixels elsewhere.
        per_row, per_col = grey.sum(axis=1), grey.sum(axis=0)
        rows = np.nonzero(per_row > 0.2 * per_row.max())[0]
        cols = np.nonzero(per_col > 0.2 * per_col.max())[0]
        top, bottom, left, right = rows.min(), rows.max(), cols.min(), cols.max()
        map_grey = grey[top:bottom + 1, left:right + 1]
        half = map_grey.shape[1] // 2
        bare_left = map_grey[:, :half].mean()
        bare_right = map_grey[:, half + 1:].mean()
        expected_left = 1 - math.pi / 4
        print(f"bare fraction: left {bare_left:.3f} (expected {expected_left:.3f}), right {bare_right:.3f} "
              f"(expected 1); map {right - left + 1} x {bottom - top + 1} px")
        # Pixels straddling a disk edge are antialiased neither grey nor a map colour, and a
        # 10 in wide figure gives each sphere ~ 70 px of diameter: the edge band is ~ 3 % of the
        # area; 0.05 absolute.
        ok = abs(bare_left - expected_left) < 0.05 and bare_right > 0.95
        # The map is twice as wide as it is tall (x along the image, y up).
        ok = ok and abs((right - left + 1) / (bottom - top + 1) - 2) < 0.05
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
