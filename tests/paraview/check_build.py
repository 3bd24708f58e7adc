#!/usr/bin/env python3
"""ctest paraview.build: ParaView opens a build's layer file (docs/build.md): one layer of the
small build of tests/data/build-small, then pvpython's XDMF reader on layer-001-scan.xmf must
find its five blocks (particles, top, section_y, solid_top, part) and the solid top's arrays
height (>= 0, raised where the track fused powder) and lack_of_fusion (0 not scanned, 1 bonded,
2 lack of fusion), and the part's cell arrays solid_fraction and never_molten_fraction (within
[0, 1], some solid). Exits 77 (ctest: skipped) with a message when pvpython or xvfb-run is missing.
Usage: check_build.py BUILD_PROGRAM"""
import json
import os
import subprocess
import sys
import tempfile

import pvrun

SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "build-small")
READ = """
import json, sys
from paraview.simple import XDMFReader
from paraview import servermanager as sm
r = XDMFReader(FileNames=[sys.argv[1]])
r.UpdatePipeline(r.TimestepValues[-1] if r.TimestepValues else 0)
data = sm.Fetch(r)
print(json.dumps({"blocks": data.GetNumberOfBlocks(),
                  "arrays": {k: list(r.PointData[k].GetRange()) for k in r.PointData.keys()},
                  "cells": {k: list(r.CellData[k].GetRange()) for k in r.CellData.keys()}}))
"""


def main():
    if pvrun.skipped():
        return 77
    with tempfile.TemporaryDirectory() as work:
        out = os.path.join(work, "run")
        subprocess.run([sys.argv[1], "--config", os.path.join(SCENES, "build.ini"), "--layers", "1",
                        "--out", out, "--threads", "1"], check=True, capture_output=True)
        script = os.path.join(work, "read.py")
        with open(script, "w") as f:
            f.write(READ)
        run = pvrun.pvpython(script, os.path.join(out, "layer-001-scan.xmf"))
        info = json.loads(run.stdout.strip().splitlines()[-1])
    print(info)
    assert info["blocks"] == 5, info
    arrays = info["arrays"]
    assert arrays["height"][0] >= 0 and arrays["height"][1] > 0, arrays
    assert arrays["lack_of_fusion"][0] == 0 and arrays["lack_of_fusion"][1] in (1, 2), arrays
    cells = info["cells"]
    assert 0 <= cells["solid_fraction"][0] and 0 < cells["solid_fraction"][1] <= 1 + 1e-12, cells
    assert 0 <= cells["never_molten_fraction"][0] <= cells["never_molten_fraction"][1] <= 1 + 1e-12, cells
    return 0


if __name__ == "__main__":
    sys.exit(main())
