#!/usr/bin/env pvpython
"""Renders a bed, a deposit trajectory or a sinter run (their .xmf sidecars) to PNG with
ParaView, headless, each particle a sphere of its true radius (docs/bed-format.md "Seeing
true radii in ParaView" does the same steps by hand). A time series is drawn at its last step;
colour by temperature when the file has it (sinter), else by radius. Run it with pvpython under
a virtual X server (ParaView 5.11 of Debian needs a 24-bit screen):

    xvfb-run -a -s "-screen 0 1280x1024x24" pvpython scripts/render_paraview.py out/sinter.xmf out/sinter-pv.png

Options: --color ARRAY|solid, --size W,H (pixels), --view top|iso, --extent XLO,XHI,YLO,YHI (m; the
rectangle a top view shows, default the particles' bounds). It prints one JSON line: the
particles' points and cells as ParaView's reader sees them, the time drawn, and for a top view
the scale in pixels per metre.
"""
import argparse
import json

from paraview import simple as pv


def arguments():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("xmf", help="the .xmf of a bed, trajectory or sinter run")
    p.add_argument("png", help="the picture to write")
    p.add_argument("--color", help="point array to colour by (default: temperature, else "
                   "radius), or 'solid' for one colour")
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
    colour_by(d, view, color)
    return d


def colour_by(display, view, color):
    if color == "solid":
        pv.ColorBy(display, None)
        display.AmbientColor = display.DiffuseColor = [0.2, 0.3, 0.7]
        return
    pv.ColorBy(display, ("POINTS", color))
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(pv.GetColorTransferFunction(color), view)
    bar.Title = {"temperature": "temperature (K)", "radius": "radius (m)"}.get(color, color)
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]  # on the white background


def substrate(reader, view, color):
    """The substrate's top face of a sinter run, coloured as the particles."""
    top = pv.ExtractBlock(Input=reader, Selectors=["/Root/top"])
    d = pv.Show(top, view)
    d.SetRepresentationType("Surface")
    if color == "temperature":
        pv.ColorBy(d, ("POINTS", "temperature"))


def camera(view, source, how, extent, size):
    """Top: orthographic down -z showing `extent` (or the particles' bounds); returns pixels
    per metre. Iso: ParaView's reset camera from above a corner; returns None."""
    x0, x1, y0, y1, z0, z1 = source.GetDataInformation().GetBounds()
    if how == "iso":
        view.CameraPosition = [x0 - (x1 - x0), y0 - (y1 - y0), z1 + (x1 - x0)]
        view.CameraFocalPoint = [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2]
        view.CameraViewUp = [0, 0, 1]
        view.ResetCamera()
        return None
    if extent:
        x0, x1, y0, y1 = extent
    else:  # the bounds of the centres, widened by the largest radius
        r = source.PointData["radius"].GetRange()[1]
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
    is_run = "particles" in block_names(reader)
    source = pv.ExtractBlock(Input=reader, Selectors=["/Root/particles"]) if is_run else reader
    source.UpdatePipeline(time)
    arrays = [a.GetName() for a in source.PointData]
    color = args.color or ("temperature" if "temperature" in arrays else "radius")
    view = pv.GetActiveViewOrCreate("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    view.UseColorPaletteForBackground = 0
    spheres(source, view, color)
    if is_run:
        substrate(reader, view, color)
    pv.Render(view)  # the first render resets the camera: set ours after it
    scale = camera(view, source, args.view,
                   [float(v) for v in args.extent.split(",")] if args.extent else None, size)
    pv.Render(view)
    pv.SaveScreenshot(args.png, view, ImageResolution=size)
    info = source.GetDataInformation()
    print(json.dumps({"points": info.GetNumberOfPoints(), "cells": info.GetNumberOfCells(),
                      "time": time, "color": color, "pixels_per_metre": scale,
                      "blocks": block_names(reader)}))


if __name__ == "__main__":
    main()
