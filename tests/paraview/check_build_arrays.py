#!/usr/bin/env python3
"""ctest paraview.build_array.*: every array a build's layer files hold renders in ParaView
(docs/build.md "Files"): scripts/render_paraview.py draws it on the block that holds it, coloured
over its range, never in the grey of an uncoloured array (as `--color lack_of_fusion` once did:
it coloured the particles, which do not hold it).

    check_build_arrays.py layer BUILD_PROGRAM DIR      one layer of tests/data/build-small in DIR
                                                       (the fixture the array tests share)
    check_build_arrays.py render DIR FILE BLOCK ARRAY  renders ARRAY of DIR/FILE (BLOCK: the
                                                       run's block that holds it, - for a bed)
    check_build_arrays.py refuse DIR                   an array no block holds exits 2, one line

Exits 77 (ctest: skipped) with a message when pvpython or xvfb-run is missing.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np
from matplotlib import image

import pvrun

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
RENDER = os.path.join(ROOT, "scripts", "render_paraview.py")
SCENE = os.path.join(ROOT, "tests", "data", "build-small", "build.ini")
# The one array of the small build that is the same everywhere: its powder is mono:d=30e-6.
CONSTANT = {"radius": 15e-6}


def layer(program, folder):
    """One layer of the small build in `folder` (emptied first: build wants a new folder)."""
    shutil.rmtree(folder, ignore_errors=True)
    subprocess.run([program, "--config", SCENE, "--layers", "1", "--out", folder, "--threads", "1",
                    "--progress", "0", "--pictures", "false"], check=True, capture_output=True,
                   timeout=300)


def chromatic(png):
    """The fraction of the picture drawn in colour (channels apart by > 0.15) and how many
    distinct colours that has, left of the colour bar (ParaView puts it in the right 15 % of
    the picture; it is in colour even when the array it names is drawn nowhere). Viridis, the
    map render_paraview.py colours with, is nowhere nearer grey than ~0.3 between channels; an
    uncoloured block is grey, white or a beige of 0.07, shaded: its channels stay together."""
    rgb = image.imread(png)[:, :, :3]
    rgb = rgb[:, : int(0.85 * rgb.shape[1])]
    colour = rgb.max(axis=2) - rgb.min(axis=2) > 0.15
    distinct = len(np.unique((rgb[colour] * 255).astype(np.uint8), axis=0))
    return colour.mean(), distinct


def render(folder, file, block, array):
    with tempfile.TemporaryDirectory() as work:
        png = os.path.join(work, "array.png")
        out = pvrun.pvpython(RENDER, os.path.join(folder, file), png, "--color", array,
                             *([] if block == "-" else ["--block", block]))
        info = json.loads(out.stdout.strip().splitlines()[-1])
        share, distinct = chromatic(png)
    low, high = info["range"]
    print(f"{file} {block} {array}: drawn on {info['block']}, range [{low:g}, {high:g}], "
          f"{share:.2%} of the picture in {distinct} colours")
    assert info["block"] == ("particles" if block == "-" else block), info
    assert math.isfinite(low) and math.isfinite(high), info
    if array in CONSTANT:
        assert low == high == CONSTANT[array], info
    else:  # each of the others varies over the layer (a scan that melted a track)
        assert high > low, info
    # The layer's particles cover 1 to 3 % of the picture, the maps and the section 3 to 8 %
    # (measured: 1.0 to 7.6 % in colour, the spheres' dark rims and the darkest end of Viridis
    # shaded on them not counted); drawn uncoloured, as lack_of_fusion once was, none of it
    # is in colour (measured: 0.0 % left of the bar).
    assert share > 0.003, share
    assert distinct > (1 if array in CONSTANT else 10), distinct


def refuse(folder):
    with tempfile.TemporaryDirectory() as work:
        out = pvrun.pvpython(RENDER, os.path.join(folder, "layer-001-scan.xmf"),
                             os.path.join(work, "none.png"), "--color", "no_such_array",
                             check=False)
        assert not os.path.exists(os.path.join(work, "none.png"))
    lines = [line for line in out.stderr.splitlines() if line.startswith("render_paraview.py:")]
    print(out.returncode, lines)
    assert out.returncode == 2 and len(lines) == 1 and "lack_of_fusion" in lines[0], out.stderr


def main():
    if pvrun.skipped():
        return 77
    mode, args = sys.argv[1], sys.argv[2:]
    {"layer": layer, "render": render, "refuse": refuse}[mode](*args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
