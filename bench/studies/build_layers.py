#!/usr/bin/env python3
"""Layers of a part, three by default (issues 17 and 32): `build --config data/scenes/build-316L.ini` on one
thread, and where its time goes (spread against scan, per layer).

Writes docs/results/build-layers.md, or with --dosing D docs/results/build-layers-dosed.md. Run
from anywhere with /usr/bin/python3 after building (POWDERBED_BUILD selects the build folder):
    POWDERBED_BUILD=build python3 bench/studies/build_layers.py [LAYERS] [--dosing D]
        [--from-json build.json]

The scene: per layer the blade spreads data/scenes/spread-blade.ini's 2500-particle supply over
the 2 x 0.5 mm strip (316L 15-45 um, gap 90 um then 45 um layers), the laser scans five hatched
tracks 100 um apart over x 0.8-2.0 mm at 200 W and 1 m/s, turned 67 degrees a layer
(data/scenes/build-316L-scan.ini), and what melted fuses. --dosing D supplies instead D times
each layer's nominal powder (deposit's supply.dosing, as machines dose), from a supply region
twice as long, with the chamber's far wall keeping what the blade pushes past the strip.
A run keeps its report (build.json with the study's own fields) as
out/studies/build-layers[-dosed].json; --from-json rewrites the page from it or from a build.json
of an earlier run (its wall times and load are then that run's).
"""
import argparse
import json
import os
import subprocess
import tempfile
import time

from lib.apps import ROOT, WORK, app, dosed_build_spread, dosed_build_text, dosed_name
from lib.report import load_average, machine, source, write_page

CONFIG = os.path.join(ROOT, "data", "scenes", "build-316L.ini")
SPREAD = os.path.join(ROOT, "data", "scenes", "spread-blade.ini")


def spread_option(name):
    """The blade scene's value of `name` as deposit resolves it (--print-config)."""
    printed = subprocess.run([app("deposit"), "--config", SPREAD, "--print-config"], check=True,
                             capture_output=True, text=True).stdout
    for line in printed.splitlines():
        key, _, value = line.partition("=")
        if key.strip() == name:
            return float(value)
    raise KeyError(f"deposit --print-config of {SPREAD} has no {name}")


def run_build(layers, dosing):
    with tempfile.TemporaryDirectory() as work:
        out = os.path.join(work, "run")
        load = load_average()
        built = source(app("build"))  # what ran, before a later build can replace it
        start = time.perf_counter()
        dosed = ["--spread-args", dosed_build_spread(dosing)] if dosing else []
        subprocess.run([app("build"), "--config", CONFIG, "--layers", str(layers), "--out", out,
                        "--threads", "1", "--progress", "0", *dosed], check=True, capture_output=True)
        wall = time.perf_counter() - start
        with open(os.path.join(out, "build.json")) as f:
            report = json.load(f)
        report["seam_lack_of_fusion"] = [seam_share(out, r["layer"]) for r in report["layers"]]
    report["dosing"] = dosing
    report["source"] = built
    return report, wall, (load, load_average())


def seam_share(out, layer):
    """The share of a layer's scanned columns that lack fusion on the grid's edge rows across y
    (the strip's periodic seam; on a periodic plate the last row is the first's image, never
    counted as scanned): fusion/lack_of_fusion of the layer's scan file, 2 where a scanned
    column's solid top never melted."""
    import h5py  # only here: --from-json pages need no HDF5
    with h5py.File(os.path.join(out, f"layer-{layer:03d}-scan.h5"), "r") as f:
        lack = f["fusion/lack_of_fusion"][:]
    scanned = (lack > 0).sum()
    seam = (lack[0] == 2).sum() + (lack[-1] == 2).sum()
    return float(seam / scanned) if scanned else 0.0


def page(report, wall, load):
    rows = report["layers"]
    spread = sum(r["spread_wall_time"] for r in rows)
    added = ", ".join(f"{r['layer_density'] * r['recoater_clearance'] * 1e6:.0f}" for r in rows)
    clearance = ", ".join(f"{r['recoater_clearance'] * 1e6:.0f}" for r in rows)
    scan = sum(r["scan_wall_time"] for r in rows)
    dosing = report.get("dosing")
    study_option, spread_args = dosed_build_text(dosing)
    lines = [
        f"# A part layer after layer: {len(rows)} layers of 316L"
        + (f", dosed {dosing:g}×" if dosing else ""),
        "",
        f"`POWDERBED_BUILD=build python3 bench/studies/build_layers.py {len(rows)}{study_option}`: "
        f"`build --config data/scenes/build-316L.ini --layers {len(rows)} --threads 1{spread_args}` "
        "(docs/build.md): each layer the blade spreads "
        + (f"{dosing:g} times the layer's nominal powder" if dosing else "2500 particles")
        + " of 316L 15–45 µm over the "
        "2 × 0.5 mm strip (data/scenes/spread-blade.ini), five tracks 100 µm apart at 200 W and "
        "1 m/s scan x 0.8–2.0 mm, turned 67° a layer (data/scenes/build-316L-scan.ini, 10 µm "
        "grid), and what melted fuses.",
        "",
        machine(load[0], load[1], program=app("build"), source_text=report.get("source")),
        "",
        f"**Whole run: {wall:.0f} s** (the goals: three layers in under 10 minutes, issue 17; "
        "ten in under 20 minutes, issue 32, there on a 1 × 1 mm patch); "
        f"the spreads {spread:.0f} s, the scans {scan:.0f} s, the rest (files) "
        f"{max(0.0, wall - spread - scan):.0f} s.",
        "",
        "| layer | particles spread | supplied | overflow | spread steps | neighbour rebuilds "
        "| asleep (mean) | spread (s) | settle (ms) | at rest | scan (s) | layer density | fused | captured | balled | vaporised | fused fraction "
        "| lack of fusion | remelt depth mean / min (µm) | mean track width / depth (µm) "
        "| absorptance | part porosity (interior) | solid top max (µm) | recoater clearance (µm) | mass error |",
        "|" + "---|" * 25,
    ]
    for r in rows:
        lines.append(
            f"| {r['layer']} | {r['particles_spread']} | {r['supplied']} | {r['overflow']} | "
            f"{r['spread_steps']} | {r['neighbour_rebuilds']} | {asleep(r)} | {r['spread_wall_time']:.0f} | "
            f"{r['spread_settle_time'] * 1e3:.1f} | {'yes' if r['spread_at_rest'] else 'no'} | "
            f"{r['scan_wall_time']:.0f} | {r['layer_density']:.3f} | {r['fused']} | "
            f"{r['captured']} | {r['balled']} | {r['vaporised']} | {r['fused_fraction']:.2f} | "
            f"{r['lack_of_fusion']:.3f} | {r['remelt_depth_mean'] * 1e6:.1f} / "
            f"{r['remelt_depth_min'] * 1e6:.1f} | {r['mean_track_width'] * 1e6:.0f} / "
            f"{r['mean_track_depth'] * 1e6:.0f} | {r['absorptance']:.3f} | "
            f"{r['part_porosity']:.2%} ({r['interior_porosity']:.2%}) | {r['solid_top_max'] * 1e6:.0f} | "
            f"{r['recoater_clearance'] * 1e6:.0f} | {r['mass_error']:.1e} |")
    lines += [
        "",
        "Where the time goes: the spread is the granular loop of docs/deposit-spread.md on one "
        "thread (its steps are set by the softened Rayleigh step, 1.7e-7 s; its cost by the "
        "particles in the box, which grow with the powder each layer leaves, and by the "
        "neighbour-list rebuilds while the supply falls); the scan is sinter's explicit solver "
        "on 261 × 51 × 31 nodes (and the planes over the plate the part grows into) with the "
        "ray-traced beam.",
        "",
        "Asleep: the particles that slept through the spread, on average over its steps (at rest "
        "under the tool: docs/deposit-spread.md \"Sleeping powder\"); the rest were integrated "
        "at every step.",
        "",
        "Settle: how long the layer settled on after the blade stopped, until the powder behind "
        f"it was slower than {spread_option('rest.speed') * 1e3:g} mm/s for "
        f"{spread_option('rest.window') * 1e3:g} ms (at rest) or the scene's cap of "
        f"{spread_option('recoater.rest-cap') * 1e3:g} ms passed "
        "(data/scenes/spread-blade.ini, docs/deposit-spread.md \"Settling to rest\").",
        "",
        "Layer density is the solid fraction of the powder over the scanned columns between the "
        "solid's top and the tool's bottom; lack of fusion the area fraction of the scanned "
        "columns whose solid top stayed below T_m, the remelt depth how far the melt went into "
        "the solid under the layer, from its top at the layer's start (docs/build.md). Fused: melted and bonded to "
        "molten solid, directly or through molten neighbours (docs/sinter.md \"Fusion\"). "
        "Captured: powder the grown solid overlapped by more than 5 % of its radius, fused with "
        "it. Balled: melted on solid that did not melt, left in the bed as a ball. Part "
        "porosity: the never-molten share of the solid over the columns every layer so far "
        "scanned, after that layer, and of its interior, below the top the layer before left "
        "(docs/build.md \"Porosity of the part\").",
        "",
        supply_text(dosing),
        "",
        "The clearance over the solid (the tool's bottom over the solid's highest point: "
        f"{clearance} um here): a layer adds about layer density x clearance of solid "
        f"({added} um here) while the plate goes down 45 um. Where that is less than 45 um the "
        "solid's mean top falls behind the plate, and over many layers the powder over it tends "
        "to t / phi, the layer thickness over the layer density: with a spread layer as sparse "
        "as 0.1-0.2 (docs/results/spread-density.md) several hundred um for the beam to melt "
        "through before it reaches the solid under it. The tracks' beads stand above that mean "
        "(solid top max), so the clearance over them can shrink while the mean falls behind.",
        "",
    ]
    seam = report.get("seam_lack_of_fusion")
    if seam:
        shares = ", ".join(f"{x:.3f}" for x in seam)
        lines += [
            "Where the lack of fusion lies: the seam's row of nodes (y = 0, where the strip is "
            "periodic) lacks fusion in this share of the scanned area, per layer: "
            f"{shares}, of the lack of fusion above. The plate under the strip is periodic "
            "across y (substrate.periodic = y, docs/sinter.md \"Geometry\"), so that row is a row "
            "like any other; with Dirichlet sides at T0 it never melted (0.020, 0.019, 0.021 "
            "of the scanned area at commit 84de7c4, most of the lack of fusion).",
            "",
        ]
    return "\n".join(lines)


def asleep(row):
    """The particles asleep through a layer's spread, on average (build.json's spread_asleep;
    "–" in a report from before build gave it)."""
    return f"{row['spread_asleep']:.0f}" if "spread_asleep" in row else "–"


def supply_text(dosing):
    """What the page says of the supply: the scene's 2500 particles, or a dose."""
    if dosing:
        return (f"The supply: dosed {dosing:g}× (deposit's `supply.dosing`: d phi_b L W t of solid "
                "a layer, phi_b = 0.5, L the blade's 2.1 mm travel, W the 0.5 mm strip, t the "
                "first layer's 90 um gap and then 45 um; docs/deposit-spread.md), as machines dose "
                "1.5-2, placed in x 0.2-0.9 mm; the box's far wall keeps what the blade pushes "
                "past the strip (`recoater.chamber`), as a machine's chamber wall does.")
    return ("The supply: 2500 particles a layer. The scene's psd gives D10/D50/D90 by volume "
            "(bed/include/powderbed/bed/psd.hpp), so their number median is ~23 um and they hold "
            "~2.3e-11 m^3 of solid (2.34e-11 expected from the psd as sampled; deposit's first "
            "supply holds 2.40e-11 with seed 1, 2.30e-11 with seed 2): a dosing factor of ~0.5 on "
            "the first layer's 90 um gap and ~1.0 on the 45 um layers after it, at a dosed bulk "
            "density of 0.5 (deposit's `supply.dosing`: d phi_b L W t; docs/deposit-spread.md), "
            "where machines dose 1.5-2 (`--dosing 2` runs the build dosed: "
            "docs/results/build-layers-dosed.md).")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("layers", nargs="?", type=int, default=3)
    parser.add_argument("--dosing", type=float, help="dose D times each layer's nominal powder")
    parser.add_argument("--from-json", help="a build.json of an earlier run, with --wall and --load")
    parser.add_argument("--wall", type=float, help="with --from-json: the run's wall time, s")
    parser.add_argument("--load", help="with --from-json: the load averages before,after (as "
                        "recorded; default: the report's own, else unknown)")
    args = parser.parse_args()
    if args.from_json:
        with open(args.from_json) as f:
            report = json.load(f)
        wall = args.wall if args.wall else report["wall_time"]
        load = tuple(args.load.split(",")) if args.load else tuple(report.get("load", ("unknown",) * 2))
    else:
        report, wall, load = run_build(args.layers, args.dosing)
        report["wall_time"], report["load"] = wall, list(load)
        kept = os.path.join(WORK, dosed_name("build-layers", args.dosing) + ".json")
        os.makedirs(WORK, exist_ok=True)
        with open(kept, "w") as f:
            json.dump(report, f)
        print(f"the run's report, for --from-json: {kept}")
    print(write_page(dosed_name("build-layers", report.get("dosing")) + ".md", page(report, wall, load)))


if __name__ == "__main__":
    main()
