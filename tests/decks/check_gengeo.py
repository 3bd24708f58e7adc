#!/usr/bin/env python3
"""ctest decks.gengeo: a packing GenGeo writes (python3-gengeo's MNTable3D.write, LSMGeometry
1.2) reads into a bed: every particle, its radius to GenGeo's printed digits, GenGeo's ids, the
bounding box as the domain. Exits 77 (ctest: skipped) without python3-gengeo.

usage: check_gengeo.py APPS_DIR"""
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

try:
    from gengeo import BoxWithPlanes3D, InsertGenerator3D, MNTable3D, Plane, Vector3
except ImportError:
    print("skipped: no gengeo module (Debian package python3-gengeo)")
    sys.exit(77)

L, RMIN, RMAX = 2e-4, 1e-5, 2e-5


def main():
    work = tempfile.mkdtemp(prefix="powderbed_gengeo_")
    try:
        lo, hi = Vector3(0, 0, 0), Vector3(L, L, L)
        box = BoxWithPlanes3D(lo, hi)
        for normal in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):
            box.addPlane(Plane(lo, Vector3(*normal)))
            box.addPlane(Plane(hi, Vector3(*(-c for c in normal))))
        table = MNTable3D(lo, hi, 2.5 * RMAX, 1)
        InsertGenerator3D(RMIN, RMAX, 300, 1000, 1e-6).generatePacking(box, table, 0, 1)
        geo = os.path.join(work, "pack.geo")
        table.write(geo, 1)
        lines = open(geo).read().splitlines()
        start = lines.index("Simple") + 2
        rows = [l.split() for l in lines[start:lines.index("EndParticles")]]
        assert int(lines[start - 1]) == len(rows) > 50, "GenGeo wrote a packing"
        out = os.path.join(work, "pack.h5")
        p = subprocess.run([os.path.join(APPS, "bedconv"), geo, out], capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
        with h5py.File(out, "r") as f:
            radius, ids = f["particles/radius"][()], f["particles/id"][()]
            assert np.array_equal(ids, [int(r[4]) for r in rows]), "GenGeo's ids"
            # The file's own digits, parsed exactly.
            assert np.array_equal(radius, [float(r[3]) for r in rows]), "radii"
            assert np.array_equal(f["domain"].attrs["upper"], [L, L, L]), "bounding box"
        # GenGeo's InsertGenerator3D keeps radii in [RMIN, RMAX] (to its 10 printed digits).
        assert radius.min() >= RMIN * (1 - 1e-9) and radius.max() <= RMAX * (1 + 1e-9)
        print(f"gengeo: {len(rows)} particles read, radii {radius.min():.3g}..{radius.max():.3g} m")
        return 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    APPS = sys.argv[1]
    sys.exit(main())
