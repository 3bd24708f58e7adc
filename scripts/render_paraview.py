#!/usr/bin/env pvpython
"""Renders a bed, a deposit trajectory or a sinter run (their .xmf sidecars) to PNG with
ParaView, headless, each particle a sphere of its true radius (docs/bed-format.md "Seeing
true radii in ParaView" does the same steps by hand). A time series is drawn at its last step;
colour by temperature when the file has it (sinter), else by radius. An array a run holds on
another of its blocks (a build's scan file: `height` and `lack_of_fusion` on `solid_top`; the
substrate's `temperature` on `top` or `section_y` with --block) is drawn on that block as a
surface; an array no block holds is refused (exit 2, one line naming the arrays there are), never
drawn grey. Run it with pvpython under a virtual X server (ParaView 5.11 of Debian needs a 24-bit
screen):

    xvfb-run -a -s "-screen 0 1280x1024x24" pvpython scripts/render_paraview.py out/sinter.xmf out/sinter-pv.png

Options: --color ARRAY|solid, --block NAME (a run's block to colour), --size W,H (pixels),
--view top|iso, --extent XLO,XHI,YLO,YHI (m; the rectangle a top view shows, default the drawn
block's bounds). It prints one JSON line: the particles' points and cells as ParaView's reader
sees them, the time drawn, the block coloured and the range of its array (a vector's magnitude),
and for a top view the scale in pixels per metre.
"""
import argparse
import json
import sys

from paraview import simple as pv


def arguments():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("xmf", help="the .xmf of a bed, trajectory or sinter run")
    p.add_argument("png", help="the picture to write")
    p.add_argument("--color", help="point array to colour by (default: temperature, else "
                   "radius), or 'solid' for one colour")
    p.add_argument("--block", help="a run's block that holds --color (default: particles when "
                   "they hold it, else the first block that does)")
    p.add_argument("--size", default="1200,800", help="W,H in pixels (default 1200,800)")
    p.add_argument("--view", choices=("top", "iso"), default="iso",
                   help="top: orthographic, looking down z; iso: perspective from above a corner")
    p.add_argument("--extent", help="top view: XLO,XHI,YLO,YHI (m) filling the picture")
    return p.parse_args()


def last_step(reader):
    """Moves the animation to the series' last time; 0 for a single bed (it has none)."""
    times = list(reader.TimestepValues) if reader.TimestepValues else []
    if not times:
        return 0.0
    scene = pv.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = times[-1]
    return times[-1]


def block_names(reader):
    """The reader's top-level blocks: particles, top, section_y for a sinter run; none for a
    bed or a trajectory (one grid)."""
    assembly = reader.GetDataInformation().DataInformation.GetHierarchy()
    if assembly is None:
        return []
    return [assembly.GetNodeName(c) for c in assembly.GetChildNodes(0, False)]


def spheres(source, view, color):
    """Point Gaussian with the sphere shader, each point scaled by its radius and nothing else:
    "Use Scale Function" is on by default and would map the radius range onto [0, 1]."""
    d = pv.Show(source, view)
    d.SetRepresentationType("Point Gaussian")
    d.ShaderPreset = "Sphere"
    d.ScaleByArray = 1
    d.SetScaleArray = ["POINTS", "radius"]
    d.UseScaleFunction = 0
    d.GaussianRadius = 1.0
    colour_by(d, view, color, source)
    return d


# Scalar bar titles with the arrays' units (docs/bed-format.md, docs/build.md).
TITLES = {"temperature": "temperature (K)", "radius": "radius (m)", "velocity": "speed (m/s)",
          "height": "solid top above the plate (m)",
          "lack_of_fusion": "lack_of_fusion (0 not scanned, 1 bonded, 2 lack of fusion)",
          "phase": "phase (0 solid, 1 liquid, 2 gas)"}


def colour_by(display, view, color, source):
    """Colours by a point array (a vector by its magnitude) with Viridis, which has no grey: a
    constant array is drawn in one colour of the map, never in the uncoloured grey."""
    if color == "solid":
        pv.ColorBy(display, None)
        display.AmbientColor = display.DiffuseColor = [0.2, 0.3, 0.7]
        return
    vector = source.PointData[color].GetNumberOfComponents() > 1
    pv.ColorBy(display, ("POINTS", color, "Magnitude") if vector else ("POINTS", color))
    lut = pv.GetColorTransferFunction(color)
    lut.ApplyPreset("Viridis (matplotlib)", True)
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(lut, view)
    bar.Title = TITLES.get(color, color)
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]  # on the white background


def surface(block, view, color):
    """A grid block of a run (top, section_y, solid_top) drawn as a surface coloured by `color`."""
    d = pv.Show(block, view)
    d.SetRepresentationType("Surface")
    colour_by(d, view, color, block)
    return d


def array_range(source, color):
    """The range of the drawn array (a vector's magnitude: component -1); None for 'solid'."""
    if color == "solid":
        return None
    return list(source.PointData[color].GetRange(-1))


def substrate(reader, view, color):
    """The substrate's top face of a sinter run under the particles, coloured as they are."""
    top = pv.ExtractBlock(Input=reader, Selectors=["/Root/top"])
    d = pv.Show(top, view)
    d.SetRepresentationType("Surface")
    if color == "temperature":
        pv.ColorBy(d, ("POINTS", "temperature"))


def block_arrays(reader, names, time):
    """{block: (its source, [its point arrays])} of a run's blocks at `time`."""
    found = {}
    for name in names:
        block = pv.ExtractBlock(Input=reader, Selectors=["/Root/" + name])
        block.UpdatePipeline(time)
        found[name] = (block, [a.GetName() for a in block.PointData])
    return found


def pick_block(blocks, color, asked):
    """The block to colour: --block, else the particles when they hold `color`, else the first
    block that does. Exits 2 with one line when the array is on none of them."""
    holders = [n for n, (_, arrays) in blocks.items() if color == "solid" or color in arrays]
    if asked:
        if asked not in blocks:
            fail(f"--block {asked}: no such block (accepted: {', '.join(blocks)})")
        if asked not in holders:
            fail(f"--color {color}: not on block {asked} (accepted: {listing(blocks)})")
        return asked
    if not holders:
        fail(f"--color {color}: no such point array (accepted: {listing(blocks)})")
    return "particles" if "particles" in holders else holders[0]


def listing(blocks):
    return "; ".join(f"{n}: {', '.join(arrays)}" for n, (_, arrays) in blocks.items())


def fail(message):
    sys.stderr.write(f"render_paraview.py: {message}\n")
    sys.exit(2)


def camera(view, source, how, extent, size):
    """Top: orthographic down -z showing `extent` (or the particles' bounds); returns pixels
    per metre. Iso: ParaView's reset camera from above a corner; returns None."""
    x0, x1, y0, y1, z0, z1 = source.GetDataInformation().GetBounds()
    if how == "iso":
        # A section (section_y: one y) is seen from in front of it, never edge-on.
        dy = y1 - y0 if y1 - y0 > 1e-6 * (x1 - x0) else x1 - x0
        view.CameraPosition = [x0 - (x1 - x0), y0 - dy, z1 + (x1 - x0)]
        view.CameraFocalPoint = [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2]
        view.CameraViewUp = [0, 0, 1]
        view.ResetCamera()
        return None
    if extent:
        x0, x1, y0, y1 = extent
    else:  # the bounds of the centres, widened by the largest radius (a grid block: none)
        r = source.PointData["radius"].GetRange()[1] if "radius" in source.PointData.keys() else 0
        x0, x1, y0, y1 = x0 - r, x1 + r, y0 - r, y1 + r
    width, height = size
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2]
    view.CameraPosition = [(x0 + x1) / 2, (y0 + y1) / 2, z1 + 10 * (x1 - x0 + y1 - y0)]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelScale = max((y1 - y0) / 2, (x1 - x0) / 2 * height / width)
    return height / (2 * view.CameraParallelScale)


def main():
    args = arguments()
    size = [int(v) for v in args.size.split(",")]
    # ParaView's "XDMF Reader" keeps the grids' names as block names (the Xdmf3 readers of
    # 5.11 merge a sinter run's three grids into one unnamed multipiece).
    reader = pv.XDMFReader(FileNames=[args.xmf])
    time = last_step(reader)
    reader.UpdatePipeline(time)
    names = block_names(reader)
    # A bed or trajectory is one grid, the particles; a run has named blocks.
    blocks = block_arrays(reader, names, time) if "particles" in names else {
        "particles": (reader, [a.GetName() for a in reader.PointData])}
    particles = blocks["particles"][0]
    color = args.color or ("temperature" if "temperature" in blocks["particles"][1] else "radius")
    drawn = pick_block(blocks, color, args.block)
    source = blocks[drawn][0]
    view = pv.GetActiveViewOrCreate("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    view.UseColorPaletteForBackground = 0
    if drawn == "particles":
        spheres(source, view, color)
        if "top" in blocks:
            substrate(reader, view, color)
    else:  # a map of the run's grid: the particles would hide it
        surface(source, view, color)
    pv.Render(view)  # the first render resets the camera: set ours after it
    scale = camera(view, source, args.view,
                   [float(v) for v in args.extent.split(",")] if args.extent else None, size)
    pv.Render(view)
    pv.SaveScreenshot(args.png, view, ImageResolution=size)
    info = particles.GetDataInformation()
    print(json.dumps({"points": info.GetNumberOfPoints(), "cells": info.GetNumberOfCells(),
                      "time": time, "color": color, "pixels_per_metre": scale, "blocks": names,
                      "block": drawn, "range": array_range(source, color)}))


if __name__ == "__main__":
    main()
