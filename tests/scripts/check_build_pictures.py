#!/usr/bin/env python3
"""ctest scripts.build_pictures: build's pictures of each layer (docs/build.md "Pictures").

Two layers of the small build of tests/data/build-small: each layer's three PNGs (top, fusion,
height) exist, are PNGs of a plausible size, are named in build.json and left no temporary; the
top view shows fused particles in the fused colour when the layer fused some, the fusion map
bonded columns in the bonded colour. `--pictures false` writes none. A copy of the program with no
plotter beside it, and one whose plotter lacks matplotlib, print one warning line for the whole
build, exit 0 and list no pictures. Skips (exit 77) without matplotlib.
Usage: check_build_pictures.py BUILD_PROGRAM
"""
import glob
import json
import os
import shutil
import stat
import struct
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
SCENE = os.path.join(ROOT, "tests", "data", "build-small", "build.ini")
KINDS = ("top", "fusion", "height", "section")
SIGNATURE = b"\x89PNG\r\n\x1a\n"
# The colours plot_build_layer.py draws fused particles and bonded columns in.
FUSED, BONDED = (0xe6, 0x55, 0x0d), (0x31, 0xa3, 0x54)


def build(program, out, *extra, layers=2):
    run = subprocess.run([program, "--config", SCENE, "--layers", str(layers), "--out", out,
                          "--threads", "1", "--progress", "0", *extra],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    with open(os.path.join(out, "build.json")) as f:
        return json.load(f), run.stderr


def png_size(path):
    """(width, height) from the PNG's IHDR chunk, after checking the signature."""
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == SIGNATURE, f"{path}: not a PNG (signature {head[:8]!r})"
    assert head[12:16] == b"IHDR", f"{path}: no IHDR chunk first"
    return struct.unpack(">II", head[16:24])


def pixels_of(path, colour):
    """How many pixels of the picture are `colour` (within 2/255 a channel: PNG is lossless)."""
    rgb = mpimg.imread(path)[:, :, :3]
    return int(np.sum(np.all(np.abs(rgb - np.array(colour) / 255) < 2 / 255, axis=2)))


def check_pictures(program, work):
    out = os.path.join(work, "on")
    report, stderr = build(program, out)
    assert "warning: no pictures" not in stderr, stderr
    for layer in report["layers"]:
        n = layer["layer"]
        expected = {kind: f"layer-{n:03d}-{kind}.png" for kind in KINDS}
        assert layer["pictures"] == expected, layer["pictures"]
        for kind, name in expected.items():
            path = os.path.join(out, name)
            size = os.path.getsize(path)
            width, height = png_size(path)
            print(f"layer {n} {kind}: {width} x {height} pixels, {size} bytes")
            # 10 in wide at 120 dpi, cropped to what is drawn (bbox "tight"): ~1100 pixels;
            # the strip is 5 times as long as wide, so not less than 200 pixels high. A
            # picture with its axes, labels and legend compresses to tens of kB, an empty one
            # to a few.
            assert 800 <= width <= 2000 and 200 <= height <= 1500, (name, width, height)
            assert size > 10_000, (name, size)
        fused = pixels_of(os.path.join(out, expected["top"]), FUSED)
        bonded = pixels_of(os.path.join(out, expected["fusion"]), BONDED)
        print(f"layer {n}: {fused} pixels of fused particles ({layer['fused']} fused), "
              f"{bonded} of bonded columns")
        # Each fused particle is a disk of ~19 pixels across (30 um at ~0.6 pixel/um).
        assert (fused > 50 * layer["fused"]) if layer["fused"] else fused < 10, (fused, layer)
        assert bonded > 100, bonded
    assert not glob.glob(os.path.join(out, "*.tmp.*")), os.listdir(out)

    report, _ = build(program, os.path.join(work, "off"), "--pictures", "false", layers=1)
    assert report["layers"][0]["pictures"] == {}, report["layers"][0]
    assert not glob.glob(os.path.join(work, "off", "*.png")), os.listdir(os.path.join(work, "off"))


def check_warnings(program, work):
    """The program copied to work/bin: first no plotter beside it, then one whose matplotlib
    fails to import (a package of that name on its PYTHONPATH that raises ImportError)."""
    os.makedirs(os.path.join(work, "bin"))
    copy = os.path.join(work, "bin", "build")
    shutil.copy2(program, copy)
    fake = os.path.join(work, "fake", "matplotlib")
    os.makedirs(fake)
    with open(os.path.join(fake, "__init__.py"), "w") as f:
        f.write("raise ImportError(\"No module named 'matplotlib'\")\n")
    plotter = os.path.join(work, "scripts", "plot_build_layer")
    for case in ("no plotter", "no matplotlib"):
        if case == "no matplotlib":
            os.makedirs(os.path.dirname(plotter))
            with open(plotter, "w") as f:
                f.write(f"#!/bin/sh\nPYTHONPATH={os.path.dirname(fake)} exec {sys.executable} "
                        f"{os.path.join(ROOT, 'scripts', 'plot_build_layer.py')} \"$@\"\n")
            os.chmod(plotter, os.stat(plotter).st_mode | stat.S_IXUSR)
        out = os.path.join(work, case.replace(" ", "-"))
        report, stderr = build(copy, out)
        warnings = [line for line in stderr.splitlines() if "warning: no pictures" in line]
        print(f"{case}: {warnings}")
        assert len(warnings) == 1, stderr[-2000:]
        assert ("matplotlib" in warnings[0]) if case == "no matplotlib" else "plotter" in warnings[0]
        assert all(layer["pictures"] == {} for layer in report["layers"]), report["layers"]
        assert len(report["layers"]) == 2 and not glob.glob(os.path.join(out, "*.png"))


def main():
    with tempfile.TemporaryDirectory() as work:
        check_pictures(sys.argv[1], work)
        check_warnings(sys.argv[1], work)
    return 0


if __name__ == "__main__":
    sys.exit(main())
