#!/usr/bin/env python3
"""Geometric (packgen, each approach) and dynamic (deposit) beds of the same PSD in the same box.

The [GZ] deposition scene (data/scenes/gz2016-deposit.ini: 600 316L particles, diameters
N(27, 4.25) um on [10, 50] um, 1 mm x 0.5 mm floor) is settled by deposit at its documented
default softening; packgen places the same 600-particle PSD on the same floor with each approach.
The beds are compared with `bedstat A B ...` (side by side) and its JSON: density of the bottom
30 um, coordination, contacts histogram, phi(z), wall time; and the in-plane pair correlation
g(r) of the centres projected on the floor (bedstat's 3D g(r) needs centres far from every face,
which a one-to-two-particle layer on a floor does not have). Writes
docs/results/geometric-vs-dynamic.md and .png.
Usage: bench/studies/geometric_vs_dynamic.py  (POWDERBED_BUILD = a Release build, default build/)
"""
import argparse
import os
import subprocess
import tempfile

import numpy as np

from lib import report
from lib.apps import ROOT, app, bedstat, read_bed, run_json, scene


def domain_of(path):
    """The domain's lower and upper corners of a bed file."""
    import h5py
    with h5py.File(path, "r") as f:
        return np.array(f["domain"].attrs["lower"]), np.array(f["domain"].attrs["upper"])

SCENE = scene("gz2016-deposit.ini")
PSD = "gauss:mean=27e-6,sd=4.25e-6,min=10e-6,max=50e-6,on=diameter"
COUNT = 600
# packgen's box: the scene's floor, 60 um (about two mean diameters) high, so that the 0/1/2-
# contact rules (no gravity) also make a layer; 3-contact lowest-site grows from the floor.
PACK_DOMAIN = "1e-3,0.5e-3,60e-6"
YOUNG_SCALE = "1e3"  # deposit's documented default softening (docs/results/deposit-accuracy.md)
SEED = "1"


def beds(workdir):
    """(label, path, wall seconds of the run) for every bed."""
    out = []
    for approach in ("0", "1", "2", "3"):
        path = os.path.join(workdir, f"packgen-{approach}.h5")
        summary, _ = run_json([app("packgen"), "--dim", "3", "--domain", PACK_DOMAIN, "--psd", PSD,
                               "--approach", approach, "--count", str(COUNT), "--seed", SEED,
                               "--out", path])
        out.append((f"packgen {approach}-contact", path, summary["wall_time"]))
    path = os.path.join(workdir, "deposit.h5")
    summary, _ = run_json([app("deposit"), "--config", SCENE, "--young-scale", YOUNG_SCALE,
                           "--seed", SEED, "--out", path])
    out.append((f"deposit (young-scale {YOUNG_SCALE})", path, summary["wall_time"]))
    return out


def inplane_rdf(path, r_max=100e-6, bins=40):
    """g(r) of the floor-projected centres: centres at least r_max from the x and y walls count
    neighbours in annuli, normalised by the areal number density (brute force: N is small)."""
    xy = read_bed(path)[0][:, :2]
    lo, hi = (corner[:2] for corner in domain_of(path))
    inner = np.all((xy - lo >= r_max) & (hi - xy >= r_max), axis=1)
    density = len(xy) / np.prod(hi - lo)
    edges = np.linspace(0, r_max, bins + 1)
    counts = np.zeros(bins)
    for c in xy[inner]:
        d = np.hypot(*(xy - c).T)
        counts += np.histogram(d[d > 0], bins=edges)[0]
    shell = np.pi * (edges[1:] ** 2 - edges[:-1] ** 2)
    g = counts / (max(inner.sum(), 1) * density * shell)
    return 0.5 * (edges[1:] + edges[:-1]), g


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    for label, stat, _, rdf in rows:
        hist = stat["contacts_histogram"]
        n = sum(hist)
        axes[0].plot(range(len(hist)), [h / n for h in hist], marker="o", label=label)
        axes[1].plot(rdf[0] * 1e6, rdf[1], label=label)
        prof = stat["density_profile"]
        axes[2].plot(prof["y"], [x * 1e6 for x in prof["x"]], label=label)
    axes[0].set_xlabel("contacts per particle (tol 1e-6)")
    axes[0].set_ylabel("fraction of particles")
    axes[1].set_xlabel("r (µm)")
    axes[1].set_ylabel("in-plane g(r)")
    axes[2].set_xlabel("φ(z)")
    axes[2].set_ylabel("z (µm)")
    axes[2].set_ylim(0, 70)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=90)


def main():
    argparse.ArgumentParser(description=__doc__,
                            formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    load = report.load_average()
    with tempfile.TemporaryDirectory() as workdir:
        made = beds(workdir)
        rows = []
        for label, path, wall in made:
            lo, hi = domain_of(path)
            bins = max(4, round((hi[2] - lo[2]) / 5e-6))  # phi(z) in 5 um layers
            stat = bedstat([path, "--layer", "0,30e-6", "--profile", str(bins)])
            rows.append((label, stat, wall, inplane_rdf(path)))
        table = subprocess.run([app("bedstat")] + [p for _, p, _ in made] + ["--layer", "0,30e-6"],
                               capture_output=True, text=True, check=True).stdout
    plot(rows, os.path.join(report.RESULTS, "geometric-vs-dynamic.png"))
    lines = [
        "# Geometric and dynamic beds of the same powder",
        "",
        "Regenerate: `python3 bench/studies/geometric_vs_dynamic.py` (Release build in `build/`).",
        "",
        report.machine(load),
        "",
        f"PSD `{PSD}`, {COUNT} particles, seed {SEED}. deposit: `{os.path.relpath(SCENE, ROOT)}` "
        f"(1 × 0.5 mm floor, dropped from 0.2–0.3 mm, 0.1 s) with `--young-scale {YOUNG_SCALE}`. "
        f"packgen: `--count {COUNT}` in a {PACK_DOMAIN.replace(',', ' × ')} m box (the same floor; "
        "60 µm high so the rules without gravity also make a layer), each approach "
        "(3 = lowest-site-first growth from the floor, the 3D default).",
        "",
        "| bed | density 0–30 µm | box density | Z (tol 1e-6) | Z (tol 1e-2) | rattlers | wall contacts | "
        "max overlap | wall time (s) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for label, s, wall, _ in rows:
        lines.append(f"| {label} | {s['layer_density']:.3f} | {s['box_density']:.3f} | {s['coordination']:.2f} "
                     f"| {s['coordination_by_tol']['0.01']:.2f} | {s['rattlers']} | {s['wall_contacts']} "
                     f"| {s['max_overlap']:.1e} | {wall:.2f} |")
    geo, dyn = rows[3], rows[-1]
    lines += [
        "",
        f"The 3-contact (lowest-site) packgen layer has {geo[1]['layer_density']:.3f} in the bottom 30 µm "
        f"against deposit's {dyn[1]['layer_density']:.3f} ([GZ]: ≈ 0.45) in {geo[2]:.2f} s instead of "
        f"{dyn[2]:.0f} s; the 0/1/2-contact rules, without gravity, spread the same 600 particles "
        "through the box and leave the floor layer at half that density. The beds differ in their "
        "contacts: the settled bed rests mostly on the floor (many particles touch only the floor: "
        "rattlers among particles), while the geometric growth makes every particle touch three "
        "partners (particles, floor or walls).",
        "",
        "Box density is over the box each bed was made in (packgen 60 µm high, deposit 0.35 mm), so",
        "only the layer density compares like with like.",
        "",
        "`bedstat` side by side (beds in the order of the table):",
        "",
        "```",
        table.rstrip(),
        "```",
        "",
        "![contacts, in-plane g(r), phi(z)](geometric-vs-dynamic.png)",
        "",
    ]
    print(report.write_page("geometric-vs-dynamic.md", "\n".join(lines)))


if __name__ == "__main__":
    main()
