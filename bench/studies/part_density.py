#!/usr/bin/env python3
"""The part's porosity against measured part densities (issue 32, point 6): `build --map` on
data/scenes/build-316L.ini (316L 15-45 um, 45 um layers, 100 um hatch, five tracks turned 67
degrees a layer) over a power x speed grid, and the measured 316L series of
data/validation/part-density/ beside it, each point with its volumetric energy density
E = P / (v h t).

Writes docs/results/part-density.md, part-density.png and part-density-map.png (build's own
map.png); with --dosing D the build's spreads are dosed D times each layer's nominal powder, as
machines dose (lib.apps.dosed_build_spread), into part-density-dosed.md and its pictures. Run
with /usr/bin/python3 after building (POWDERBED_BUILD selects the build folder):
    POWDERBED_BUILD=build python3 bench/studies/part_density.py [--layers N]
        [--power 100,200,300] [--speed 1,2,4] [--dosing D] [--from-json]
The map runs once into out/studies/part-density[-dosed]/ (about 3 minutes of one core per point
and layer here, undosed); --from-json redraws the page from its map.json.

What is compared, and what is not: the measured series are whole cubes of many layers on other
machines (their spot, hatch and layer given per row), ours a patch of a few layers whose
porosity is the never-molten share of the solid over the patch's core below the top the layer
before the last left, its interior (docs/build.md "Porosity of the part"): a measured density is a
part's interior, and the last layer's top carries a film of captured powder no later scan
remelts (the whole part's porosity, that film included, is in the table too). Energy density
alone does not fix a part's density (the measured series say so too: the same E gives different
densities at different P); the page plots both against it because that is the axis users read,
and says where each crosses 1 % and 10 % porosity.
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import time

from lib.apps import ROOT, WORK, app, dosed_build_spread, dosed_build_text, dosed_name
from lib.report import load_average, machine, source, write_page

CONFIG = os.path.join(ROOT, "data", "scenes", "build-316L.ini")
MEASURED = os.path.join(ROOT, "data", "validation", "part-density")


def read_measured():
    """The measured rows: (source file, E in J/mm^3, porosity, P, v, h, t)."""
    rows = []
    for name in sorted(os.listdir(MEASURED)):
        if not name.endswith(".csv"):
            continue
        with open(os.path.join(MEASURED, name)) as f:
            for r in csv.DictReader(line for line in f if not line.startswith("#")):
                p, v, h, t = (float(r[k]) for k in ("power_W", "speed_m_per_s", "hatch_m", "layer_m"))
                rows.append({"source": name, "energy": p / (v * h * t) * 1e-9,
                             "porosity": float(r["porosity"]), "power": p, "speed": v})
    return rows


def run_map(layers, powers, speeds, dosing):
    out = os.path.join(WORK, dosed_name("part-density", dosing))
    if os.path.exists(out):
        subprocess.run(["rm", "-rf", out], check=True)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    load = load_average()
    built = source(app("build"))  # what ran, before a later build can replace it
    start = time.perf_counter()
    subprocess.run([app("build"), "--config", CONFIG, "--layers", str(layers), "--threads", "1",
                    "--progress", "0", "--map.power", powers, "--map.speed", speeds, "--out", out,
                    *(["--spread-args", dosed_build_spread(dosing)] if dosing else [])],
                   check=True, capture_output=True)
    wall = time.perf_counter() - start
    run = {"wall": wall, "load": [load, load_average()], "layers": layers, "source": built,
           "dosing": dosing, "power": powers, "speed": speeds}
    with open(os.path.join(out, "run.json"), "w") as f:
        json.dump(run, f)
    return run


def crossing(points, level):
    """The energy densities (J/mm^3) between which the porosity passes `level`, going down in E
    from the densest point: the lowest E at or below `level` and the highest above it under it."""
    ordered = sorted(points, key=lambda p: p["energy"])
    dense = [p["energy"] for p in ordered if p["porosity"] < level]
    if not dense:
        return None
    lowest_dense = min(dense)
    porous = [p["energy"] for p in ordered if p["porosity"] >= level and p["energy"] < lowest_dense]
    return (max(porous) if porous else None, lowest_dense)


def plot(ours, measured, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.4, 4.6))
    markers = {}
    for m in measured:
        label = m["source"].replace("part-density-316L-", "measured: ").replace(".csv", "")
        markers.setdefault(label, [])
        markers[label].append(m)
    for (label, rows), marker in zip(markers.items(), ("o", "s", "^", "v")):
        ax.scatter([r["energy"] for r in rows], [max(r["porosity"], 1e-4) for r in rows],
                   marker=marker, facecolors="none", edgecolors="0.4", label=label)
    ax.scatter([p["energy"] for p in ours], [max(p["porosity"], 1e-4) for p in ours], c="tab:red",
               edgecolors="k", s=60, zorder=3, label="build --map (this page)")
    ax.axhline(0.01, color="tab:green", linestyle="dashed", linewidth=1, label="1 % (dense)")
    ax.axhline(0.10, color="tab:orange", linestyle="dotted", linewidth=1, label="10 %")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("energy density P / (v h t) (J/mm³)")
    ax.set_ylabel("porosity (1 − relative density; 1e-4 shown for 0)")
    ax.legend(fontsize=8, loc="upper right")
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def page(data, run, measured):
    ours = [{"energy": p["energy_density"] * 1e-9, **p} for p in data["map"]]
    dosing = run.get("dosing")
    stem = dosed_name("part-density", dosing)
    grid = f" --power {run['power']} --speed {run['speed']}" if "power" in run else ""
    study_option, spread_args = dosed_build_text(dosing)
    lines = [
        "# Part density: build's porosity against measured 316L parts"
        + (f", the spreads dosed {dosing:g}×" if dosing else ""),
        "",
        f"`POWDERBED_BUILD=build python3 bench/studies/part_density.py --layers {run['layers']}{grid}"
        f"{study_option}`: `build --config data/scenes/build-316L.ini --layers {run['layers']} "
        f"--map.power ... --map.speed ...{spread_args}` (docs/build.md \"Process maps\"), one thread; the measured series of "
        "data/validation/part-density/ (their headers give the sources)"
        + (f"; the supply dosed {dosing:g} times each layer's nominal powder, as machines dose "
           "(docs/deposit-spread.md \"supply.dosing\"; the undosed map: part-density.md)."
           if dosing else "; docs/results/part-density-dosed.md runs the spreads dosed as "
           "machines dose."),
        "",
        machine(run["load"][0], run["load"][1], program=app("build"), source_text=run.get("source")),
        "",
        f"The map took {run['wall']:.0f} s for {len(ours)} points of {run['layers']} layers.",
        "",
        "Porosity: of the part's interior, below the top the layer before the last left, as a "
        "measured density is (docs/build.md \"Porosity of the part\"); whole part: to the final "
        "top, with the film of powder the last scan captured there, which no later layer remelts.",
        "",
        "| P (W) | v (m/s) | E (J/mm³) | porosity | whole part | lack of fusion (last layer) "
        "| remelt depth (µm) | pool W / D (µm) | ΔH/h_s (keyhole >) | Tang | layer density | regions "
        "| wall (s) |",
        "|" + "---|" * 13,
    ]
    for p in sorted(ours, key=lambda p: (p["power"], p["speed"])):
        lines.append(
            f"| {p['power']:g} | {p['speed']:g} | {p['energy']:.1f} | {p['porosity']:.2%} | "
            f"{p['whole_porosity']:.2%} | "
            f"{p['lack_of_fusion']:.1%} | {p['remelt_depth_mean'] * 1e6:.1f} | "
            f"{p['mean_track_width'] * 1e6:.0f} / {p['mean_track_depth'] * 1e6:.0f} | "
            f"{p['normalised_enthalpy']:.1f} ({p['keyhole_threshold']:.1f}) | "
            f"{p['tang'] if p['tang'] is not None else float('inf'):.2f} | {p['layer_density']:.3f} | "
            f"{', '.join(p['regions'])} | {p['wall_time']:.0f} |")
    lines += ["", "The map as build draws it (map.png; dashed: the porosity's contours):", "",
              f"![the process map]({stem}-map.png)", "",
              f"![porosity against energy density]({stem}.png)", "",
              "Where the porosity crosses 1 % and 10 % going down in energy density (the highest "
              "E still above the level, and the lowest E below it):", "",
              "| series | 1 % | 10 % |", "|---|---|---|"]
    series = {"build --map": ours}
    for m in measured:
        series.setdefault(m["source"].replace(".csv", ""), []).append(m)
    for name, rows in series.items():
        cells = []
        for level in (0.01, 0.10):
            c = crossing(rows, level)
            cells.append("not reached" if c is None else
                         f"{'—' if c[0] is None else f'{c[0]:.0f}'} → {c[1]:.0f} J/mm³")
        lines.append(f"| {name} | {cells[0]} | {cells[1]} |")
    lines += ["", findings(ours, measured, run["layers"]), ""]
    return "\n".join(lines)


def judged(layers):
    """What a point's interior is, for a part of `layers` layers (2 or more)."""
    if layers == 2:
        return ("A point of 2 layers judges its first as the second left it: its interior is the "
                "layer on the plate, which bonds to dense solid")
    return (f"A point of {layers} layers judges its first {layers - 1} as the last left them: the "
            f"layer on the plate, which bonds to dense solid, is 1/{layers - 1} of its interior")


def findings(ours, measured, layers):
    """What the page shows, in its own numbers: the standard point, a quarter of its energy
    density, the densest point, where the dense window starts against the measured series', and
    the layer density behind it (each point built `layers` layers)."""
    def at(power, speed):
        return next((p for p in ours if p["power"] == power and p["speed"] == speed), None)
    text = []
    standard, quarter = at(200, 1), at(200, 4)
    if standard:
        text.append(f"At 200 W, 1 m/s ({standard['energy']:.0f} J/mm³, the standard 316L point) "
                    f"the part's porosity is {standard['porosity']:.1%} (a dense part's bar: under 1 %"
                    f"{': met' if standard['porosity'] < 0.01 else ': not met'})")
    if quarter:
        text.append(f"at a quarter of that energy density (200 W, 4 m/s, {quarter['energy']:.0f} J/mm³) "
                    f"{quarter['porosity']:.1%} (the lack-of-fusion bar: over 10 %"
                    f"{': met' if quarter['porosity'] > 0.1 else ': not met'})")
    densest = min(ours, key=lambda p: p["porosity"])
    density = [p["layer_density"] for p in ours]
    ours_dense = crossing(ours, 0.01)
    theirs = {}
    for m in measured:
        theirs.setdefault(m["source"].replace(".csv", ""), []).append(m)
    starts = [c[1] for c in (crossing(rows, 0.01) for rows in theirs.values()) if c]
    if ours_dense is None:
        window = "the dense window (under 1 %) is not reached on this grid"
    else:
        side = ("below both" if ours_dense[1] < min(starts) else
                "above both" if ours_dense[1] > max(starts) else "between") if starts else "—"
        window = (f"the dense window (under 1 %) starts at {ours_dense[1]:.0f} J/mm³ on this grid, "
                  f"{side} of the measured series' ({', '.join(f'{e:.0f}' for e in starts)} J/mm³)")
    text.append(f"the densest point is {densest['power']:g} W, {densest['speed']:g} m/s "
                f"({densest['energy']:.0f} J/mm³, {densest['porosity']:.1%}). The porosity rises as "
                f"the energy density falls, as the measured series' does; {window}. "
                + (f"At the standard point the whole part, its top's film of captured powder "
                   f"included, holds {standard['whole_porosity']:.1%}: the porosity of a part "
                   f"{layers} layers thick is mostly its top. " if standard else "")
                + "The spread layers the scans "
                f"met held {min(density):.3f}-{max(density):.3f} of solid where measured spread layers "
                "hold 0.38-0.60 (docs/results/spread-density.md): a layer brings a fraction of the "
                "metal a machine's layer does, so a melt that would leave a machine's layer unbonded "
                "still goes through this one to the layer below (docs/results/build-layers-dosed.md "
                "builds with the supply dosed as machines dose). " + judged(layers))
    return "; ".join(text[:2]) + ("; " if len(text) > 2 else "") + text[-1] + "."


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--layers", type=int, default=2)
    parser.add_argument("--power", default="100,200,300")
    parser.add_argument("--speed", default="1,2,4")
    parser.add_argument("--dosing", type=float, help="dose D times each layer's nominal powder")
    parser.add_argument("--from-json", action="store_true")
    args = parser.parse_args()
    stem = dosed_name("part-density", args.dosing)
    out = os.path.join(WORK, stem)
    if args.from_json:
        with open(os.path.join(out, "run.json")) as f:
            run = json.load(f)
    else:
        run = run_map(args.layers, args.power, args.speed, args.dosing)
    with open(os.path.join(out, "map.json")) as f:
        data = json.load(f)
    measured = read_measured()
    ours = [{"energy": p["energy_density"] * 1e-9, "porosity": p["porosity"]} for p in data["map"]]
    results = os.path.join(ROOT, "docs", "results")
    plot(ours, measured, os.path.join(results, f"{stem}.png"))
    shutil.copyfile(os.path.join(out, "map.png"), os.path.join(results, f"{stem}-map.png"))
    write_page(f"{stem}.md", page(data, run, measured))


if __name__ == "__main__":
    main()
