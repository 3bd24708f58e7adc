#!/usr/bin/env python3
"""Process map: a laser power x scan speed grid of single tracks on one powder layer, each
track's mean melt pool (width W, depth D below the solid's top, length L along the track, from
sinter --json "tracks"), with sinter's default melt-pool models (Fresnel optics, evaporation, the
vapour depression with the beam traced into it: docs/sinter.md), and the usual criteria drawn as
regions:

  keyhole          dH/h_s > pi T_b / T_m   (King et al. 2014, J. Mater. Process. Technol. 214:
                                          the normalised enthalpy of sinter --explain), or the
                                          pool itself W / D <= 1.5 (Johnson et al. 2019, Acta
                                          Mater. 176), which the depression model now deepens
  lack of fusion   (h / W)^2 + (t / D_t)^2 > 1  for hatch h and layer t, with D_t = t + D the
                                          pool's depth from the top of the new layer (Tang,
                                          Pistorius & Beuth 2017, Addit. Manuf. 14: neighbouring
                                          elliptic pools no longer overlap down to the layer
                                          below); and wherever the powder melts but the solid
                                          under it does not (D = 0: nothing bonds)
  balling          L / W > pi where the melt does not remelt the solid under it (D = 0)
                                          (Plateau-Rayleigh: a free liquid cylinder longer than
                                          pi times its width breaks up; Yadroitsev et al. 2010,
                                          J. Mater. Process. Technol. 210). A pool that remelts
                                          the solid along its length has pinned contact lines,
                                          which hold a rivulet of contact angle below 90 degrees
                                          against that instability at any length (Davis 1980,
                                          J. Fluid Mech. 98)

Writes docs/results/process-map.md and process-map.png. Run with python3:
    POWDERBED_BUILD=build python3 bench/studies/process_map.py [--bed LAYER.h5] [--small]
The bed defaults to a spread layer (data/scenes/spread-blade.ini, seed 1), made once in
out/studies/. --small runs a 3 x 3 grid for a quick look.
"""
import argparse
import json
import math
import os
import subprocess

from lib import apps, report
from lib.melted import melted_mass

WORK = apps.WORK
SPREAD_SCENE = apps.scene("spread-blade.ini")
SINTER_SCENE = apps.GZ2016_SINTER_SCENE
POWERS = [50, 100, 150, 200, 300]          # W
SPEEDS = [0.25, 0.5, 1.0, 2.0, 3.0]        # m/s
SMALL_POWERS, SMALL_SPEEDS = [100, 200, 300], [0.5, 1.0, 2.0]
HATCH = 100e-6      # m: the hatch the lack-of-fusion criterion is evaluated for
# m: the layer thickness t of the criterion is the plate's drop per layer (recoater.layer-thickness
# of data/scenes/spread-blade.ini), what a machine calls the layer thickness, not the blade gap.
LAYER = 45e-6


def spread_layer():
    """The default bed: one layer spread by the blade scene with seed 1 (a few minutes once)."""
    os.makedirs(WORK, exist_ok=True)
    path = os.path.join(WORK, "process-map-layer.h5")
    if not os.path.exists(path):
        subprocess.run([apps.app("deposit"), "--config", SPREAD_SCENE, "--seed", "1", "--threads", "1",
                        "--out", path], check=True, capture_output=True)
    return path


def track_pool(summary):
    """(W, D, L) in m of the run's one track; sinter's "tracks" list, else its melt_pool."""
    tracks = summary.get("tracks") or []
    if tracks:
        t = tracks[0]
        return t["width"], t["depth"], t.get("length", float("nan"))
    pool = summary["melt_pool"]
    return pool["width"], pool["depth"], float("nan")


def track_of(bed, length):
    """(x0, x1, y) of a track of `length` m centred on the bed's plate: the middle of a spread
    strip, away from the heap at its start and the thin end the blade leaves."""
    import h5py
    with h5py.File(bed, "r") as f:
        lower, upper = f["domain"].attrs["lower"], f["domain"].attrs["upper"]
    cx, cy = 0.5 * (lower[0] + upper[0]), 0.5 * (lower[1] + upper[1])
    return cx - 0.5 * length, cx + 0.5 * length, cy


def run_point(bed, power, speed, track, extra):
    x0, x1, y = track
    options = ["--power", str(power), "--speed", str(speed), "--laser.start-x", repr(x0),
               "--laser.end-x", repr(x1), "--laser.y", repr(y), *extra]
    regime, _ = apps.run_json([apps.app("sinter"), "--config", SINTER_SCENE, "--bed", bed,
                               "--explain", *options])
    point = {"power": power, "speed": speed, "enthalpy": regime["normalised_enthalpy"],
             "keyhole_at": regime["keyhole_threshold"]}
    try:
        summary, wall = apps.sinter(SINTER_SCENE, bed, f"process-map-{power:g}W-{speed:g}ms.h5",
                                    "--snapshots", "1", *options)
    except RuntimeError as error:  # sinter exits 3 when the keyhole drills through the grid
        if "depression reached the substrate's bottom" not in str(error):
            raise
        nan = float("nan")
        return {**point, "width": nan, "depth": nan, "length": nan, "drilled": True,
                "peak_particles": nan, "peak_substrate": nan, "evaporated": nan, "melted": nan,
                "vaporised": 0, "wall": nan}
    width, depth, length = track_pool(summary)
    return {**point, "width": width, "depth": depth, "length": length, "drilled": False,
            "peak_particles": summary["max_temperature_particles"],
            "peak_substrate": summary["max_temperature_substrate"],
            "evaporated": summary["evaporated_mass"], "vaporised": summary["particles_vaporised"],
            "melted": melted_mass(summary["out_path"], x1 - x0), "wall": wall}


def tang_sum(p, hatch, layer):
    """(h/W)^2 + (t/D_t)^2 with D_t = t + D, the depth from the new layer's top (inf: no bond)."""
    w, d = p["width"], p["depth"]
    return (hatch / w) ** 2 + (layer / (layer + d)) ** 2 if w > 0 and d > 0 else float("inf")


def classify(p, hatch, layer):
    """The regions a point falls in (a point may be in several), or 'fused' when in none."""
    w, d, length = p["width"], p["depth"], p["length"]
    if p.get("drilled"):  # the keyhole went through the substrate grid (sinter's exit 3)
        return ["keyhole"]
    if not w > 0:
        return ["no melt"]
    regions = []
    if p["enthalpy"] > p["keyhole_at"] or (d > 0 and w / d <= 1.5):
        regions.append("keyhole")
    if tang_sum(p, hatch, layer) > 1:  # D = 0: the powder melts but nothing bonds below
        regions.append("lack of fusion")
    if not d > 0 and math.isfinite(length) and length / w > math.pi:
        regions.append("balling")
    return regions or ["fused"]


def plot(points, hatch, layer, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    colours = {"fused": "tab:green", "lack of fusion": "tab:orange", "keyhole": "tab:red",
               "balling": "tab:purple", "no melt": "tab:gray"}
    fig, ax = plt.subplots(figsize=(7.6, 4.8))
    for p in points:
        regions = classify(p, hatch, layer)
        ax.scatter(p["speed"], p["power"], s=160, c=colours[regions[0]], edgecolors="k", zorder=3)
        if len(regions) > 1:  # a second region as a ring
            ax.scatter(p["speed"], p["power"], s=320, facecolors="none",
                       edgecolors=colours[regions[1]], linewidths=2.5, zorder=2)
        if p["width"] > 0:
            ax.annotate(f"{p['width'] * 1e6:.0f}/{p['depth'] * 1e6:.0f}", (p["speed"], p["power"]),
                        textcoords="offset points", xytext=(0, 11), ha="center", fontsize=7)
    for name, colour in colours.items():
        ax.scatter([], [], c=colour, edgecolors="k", label=name)
    ax.set_xlabel("scan speed (m/s)")
    ax.set_ylabel("laser power (W)")
    ax.set_title(f"single tracks, W/D in um; hatch {hatch * 1e6:.0f} um, layer {layer * 1e6:.0f} um")
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.02, 0.5))
    ax.set_xscale("log")
    speeds = sorted({p["speed"] for p in points})
    ax.set_xticks(speeds, [f"{v:g}" for v in speeds])
    ax.minorticks_off()
    ax.margins(0.12)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def percent(part, whole):
    return f"{100 * part / whole:.2f} %" if whole > 0 else "–"


def table(points, hatch, layer):
    rows = ["| P (W) | v (m/s) | E = P/(v h t) (J/mm^3) | dH/h_s | W (um) | D (um) | L (um) | W/D | "
            "L/W | (h/W)^2+(t/D_t)^2 | regions | peak T particles / substrate (K) | evaporated (ng) "
            "| evaporated / melted | vaporised | wall (s) |", "|" + "---|" * 16]
    for p in points:
        w, d, length = p["width"], p["depth"], p["length"]
        ok = w > 0 and d > 0
        energy = p["power"] / (p["speed"] * hatch * layer) * 1e-9
        rows.append(
            f"| {p['power']:g} | {p['speed']:g} | {energy:.0f} | {p['enthalpy']:.1f} "
            f"(keyhole > {p['keyhole_at']:.1f}) | {w * 1e6:.1f} | {d * 1e6:.1f} | "
            f"{length * 1e6:.0f} | {w / d if ok else float('nan'):.2f} | "
            f"{length / w if w > 0 else float('nan'):.2f} | {tang_sum(p, hatch, layer):.2f} | "
            f"{', '.join(classify(p, hatch, layer))}"
            f"{' (drilled through the grid: sinter exit 3)' if p.get('drilled') else ''} | "
            f"{p['peak_particles']:.0f} / "
            f"{p['peak_substrate']:.0f} | {p['evaporated'] * 1e12:.3g} | "
            f"{percent(p['evaporated'], p['melted'])} | {p['vaporised']} | "
            f"{p['wall']:.1f} |")
    return "\n".join(rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bed", help="the powder layer (default: a spread-blade layer, seed 1)")
    parser.add_argument("--small", action="store_true", help="a 3 x 3 grid")
    parser.add_argument("--hatch", type=float, default=HATCH)
    parser.add_argument("--layer", type=float, default=LAYER)
    parser.add_argument("--from-json", action="store_true",
                        help="redraw from out/studies/process-map.json instead of running sinter")
    parser.add_argument("--track-length", type=float, default=0.6e-3,
                        help="m, centred on the bed (default 0.6 mm)")
    parser.add_argument("--sinter-args", default="--grid-spacing 1e-5",
                        help="extra sinter options (default: the 10 um grid, within 1.6 um of "
                             "the 2.5 um grid's depth at a tenth of the 5 um grid's time: "
                             "docs/results/sinter-accuracy.md)")
    args = parser.parse_args()
    bed = args.bed or spread_layer()
    saved = os.path.join(WORK, "process-map.json")
    if args.from_json:
        with open(saved) as f:
            stored = json.load(f)
        # Points stored before the machine was recorded with them are a bare list.
        points, machine = ((stored, "Machine: not recorded with these points.")
                           if isinstance(stored, list) else (stored["points"], stored["machine"]))
    else:
        load = report.load_average()
        powers, speeds = (SMALL_POWERS, SMALL_SPEEDS) if args.small else (POWERS, SPEEDS)
        extra = args.sinter_args.split()
        track = track_of(bed, args.track_length)
        points = [run_point(bed, p, v, track, extra) for p in powers for v in speeds]
        machine = report.machine(load)
        with open(saved, "w") as f:
            json.dump({"points": points, "machine": machine}, f, indent=1)
    plot(points, args.hatch, args.layer, os.path.join(report.RESULTS, "process-map.png"))
    bed_name = (os.path.relpath(bed, apps.ROOT) if bed.startswith(apps.ROOT)
                else os.path.basename(bed))
    text = f"""# Process map: power x speed on one powder layer

Regenerate: `POWDERBED_BUILD=build python3 bench/studies/process_map.py` (script docstring:
the criteria and their sources). Bed: `{bed_name}`; scene `data/scenes/gz2016-sinter.ini`
(316L, absorptivity and spot of [GZ]) with `--power` and `--speed` per point
{('and `' + args.sinter_args + '`') if args.sinter_args else ''}; one track of
{args.track_length * 1e3:g} mm along x through the bed's centre per run, one thread.
{machine}

W: the melt's width across the track (powder and solid); D: its depth below the solid's top
(the plate here); L: the longest stretch of the track's centre line molten at once (at most the
track's {args.track_length * 1e6:.0f} um); E: the volumetric energy density P/(v h t) machines are
set by. Criteria (the script's docstring gives the sources): keyhole when King's normalised
enthalpy dH/h_s passes pi T_b/T_m or the pool's W/D <= 1.5; lack of fusion when
(h/W)^2 + (t/D_t)^2 > 1 with hatch h = {args.hatch * 1e6:.0f} um, layer thickness
t = {args.layer * 1e6:.0f} um (the plate's drop per layer) and D_t = t + D, the pool's depth from
the top of the new layer as Tang et al. take it, and wherever the powder melts but the solid under
it does not (D = 0); balling where such an unbonded melt is longer than pi times its width
(a pool that remelts the solid along its length is pinned there and does not break up). The tracks run with sinter's default melt-pool models
(Fresnel optics, evaporation, the vapour depression with the beam traced into it), so peak
temperatures stay near the depression temperature instead of running away; keyhole porosity is
not modelled (the depression does not collapse into pores). A point whose depression drilled
through the substrate grid (sinter's exit 3, "deeper than the grid") is a keyhole by any measure
and is marked so, without a pool. A particle's ceiling is its own depression temperature T_d(r),
where the recoil balances 2 gamma / r (3731 K for the 15 um fines of this layer's PSD, above the
plate's 3178 K); the particles stay well below it because once molten they join the pool or a
molten neighbour (docs/sinter.md, wetting) on a bed spread to rest (docs/deposit-spread.md
"Settling to rest": powder still in the air touches nothing and boils). Evaporated / melted: the
mass evaporated over what melted, the particles that reached T_m and the substrate's molten
section at x = Lx/2 times the track's length (bench/studies/lib/melted.py); measured evaporative
losses in LPBF are well under 1 % of the melt.

The map's points are single tracks on the first layer; the hatch enters only through h in the
criterion, not through the heat one track leaves for the next (sinter's `--scan.hatch` runs that).
Tang's criterion asks the elliptic pools of neighbouring tracks to overlap down to the layer
below, which is stricter than bonding alone: a point it calls lack of fusion may still bond along
each track's centre.

![process map](process-map.png)

{table(points, args.hatch, args.layer)}
"""
    report.write_page("process-map.md", text)


if __name__ == "__main__":
    main()
