#!/usr/bin/env python3
"""Layer after layer: the blade scene spread LAYERS times on itself (issue 16, point 3).

Writes docs/results/spread-layers.md (and spread-layers.png when matplotlib is installed). Run
from anywhere with python3 after building deposit (POWDERBED_BUILD selects the build folder):
    POWDERBED_BUILD=build python3 bench/studies/spread_layers.py [LAYERS] [SEED]

One run of `deposit --config data/scenes/spread-blade.ini --layers LAYERS` (default 20): each
layer the plate goes down by recoater.layer-thickness (45 um), a new supply of 2500 particles
falls in front of the blade, the blade spreads it and the excess past its end is removed
(recoater.overflow). The table lists, per layer, the JSON summary's numbers: particles in the
bed, the solid fraction by centres under the tool's lowest point between the supply's back and
the tool's end (the whole bed under the gap, so it mixes the new layer with the ones below:
a quick look, bedstat measures a layer), the tool's largest and mean x force, and wall time.
"""
import os
import sys
import tempfile

from common import ROOT, app, run_json, write_text

SCENE = os.path.join(ROOT, "data", "scenes", "spread-blade.ini")


def main():
    layers = int(sys.argv[1]) if len(sys.argv) > 1 else 20
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    with tempfile.TemporaryDirectory() as work:
        out, wall = run_json([app("deposit"), "--config", SCENE, "--seed", str(seed),
                              "--layers", str(layers), "--out", os.path.join(work, "L.h5")])
    rows = out["layers"]
    lines = [
        "# Spreading layer after layer (blade scene)",
        "",
        f"`python3 bench/studies/spread_layers.py {layers} {seed}`: data/scenes/spread-blade.ini "
        f"(316L 15–45 µm, gap 90 µm, 0.1 m/s, layer thickness 45 µm, young-scale "
        f"{out['young_scale']:g}), {layers} layers, seed {seed}, one thread; {wall:.0f} s wall "
        f"for the whole run, {out['steps']} steps of {out['dt']:.3g} s.",
        "",
        "The density is the JSON summary's quick look: the solid fraction of the centres under "
        "the tool's lowest point between the supply's back and the tool's end, i.e. the whole "
        "bed under the gap (new layer and the ones below).",
        "",
        "| layer | particles | supplied | overflow | density under the gap | max tool force (N) "
        "| mean tool x force (N) | wall (s) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(f"| {r['layer']} | {r['n']} | {r['supplied']} | {r['overflow']} | "
                     f"{r['density_under_gap']:.3f} | {r['max_tool_force']:.3g} | "
                     f"{r['mean_tool_force_x']:.3g} | {r['wall_time']:.0f} |")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5, 3.2))
        ax.plot([r["layer"] for r in rows], [r["density_under_gap"] for r in rows], "o-")
        ax.set_xlabel("layer")
        ax.set_ylabel("solid fraction under the gap")
        fig.tight_layout()
        fig.savefig(os.path.join(ROOT, "docs", "results", "spread-layers.png"), dpi=120)
        lines += ["", "![density over layers](spread-layers.png)"]
    except ImportError:
        lines += ["", "(no plot: python3-matplotlib is not installed where this ran)"]
    print(write_text("spread-layers.md", "\n".join(lines) + "\n"))


if __name__ == "__main__":
    main()
