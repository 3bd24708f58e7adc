#!/usr/bin/env python3
"""Reproduces the 2D study of Luberto & de Payrebrune with packgen (their ranges:
lib/references.py LP_2D).

--samples per paper case (seeds 1..N; the paper: 100) on the 4.0 x 4.0 um square with the raster
collision grid of spacing h = 0.015 um and packgen's 2D defaults; the diameter reading of the Gauss
window with --alt-samples; then one-at-a-time sensitivity runs (--sens-samples seeds each) over
tries, directions, max-failures and retire-after. Coordination is counted on the written beds at
absolute surface gaps of order h (docs/physics.md §3). Writes docs/results/packgen-2d-study.md (its
prose: bench/studies/templates/packgen-2d-study.md.in) and .png.
Usage: POWDERBED_BUILD=build bench/studies/packgen_2d_study.py [--samples N] [--alt-samples N]
       [--sens-samples N]
"""
import argparse
import math
import os
import sys
import tempfile

from lib import references, report
from lib.apps import app, coordination_at_gaps, read_bed, run_json
from lib.report import summary

H = 0.015e-6          # raster spacing of the paper
DOMAIN = "4e-6,4e-6"
MONO = "mono:r=0.075e-6"
GAUSS_RADIUS = "gauss:mean=0.075e-6,sd=0.0375e-6,min=0.015e-6,max=0.15e-6,on=radius"
# The paper's text also calls the window a diameter window: radii in [0.0075, 0.075] um.
GAUSS_DIAMETER_WINDOW = "gauss:mean=0.075e-6,sd=0.0375e-6,min=0.0075e-6,max=0.075e-6,on=radius"
# Contacts in a raster bed: surface gap d - ri - rj <= g with g of order h (docs/physics.md §3). The table
# shows g = h, sqrt(2) h (the diagonal of a grid cell) and 2 h; "strict" is packgen's tol 1e-6.
GAPS = [("h", 1.0), ("√2 h", math.sqrt(2)), ("2 h", 2.0)]
SCAN = [0.1 * k for k in range(31)]  # g / h for the tolerance scan, 0 .. 3 h

PAPER = references.LP_2D  # particles, density, coordination ranges [LP] report
CASES = [  # label, psd, approach, paper key, samples option
    ("mono r = 0.075 µm, 0-contact", MONO, 0, ("mono", 0), "samples"),
    ("mono r = 0.075 µm, 1-contact", MONO, 1, ("mono", 1), "samples"),
    ("Gauss (window on radius), 0-contact", GAUSS_RADIUS, 0, ("gauss", 0), "samples"),
    ("Gauss (window on radius), 1-contact", GAUSS_RADIUS, 1, ("gauss", 1), "samples"),
    ("Gauss (window on diameter), 0-contact", GAUSS_DIAMETER_WINDOW, 0, ("gauss", 0),
     "alt_samples"),
    ("Gauss (window on diameter), 1-contact", GAUSS_DIAMETER_WINDOW, 1, ("gauss", 1),
     "alt_samples"),
]
# One-at-a-time changes from the defaults (tries 1000, directions 10 in 2D, max-failures 100,
# retire-after 32): (case index, extra packgen options, seeds = sens_samples or this number).
SENSITIVITY = [
    (1, ["--directions", "6"], None), (1, ["--directions", "8"], None),
    (1, ["--directions", "12"], None), (1, ["--directions", "16"], None),
    (1, ["--directions", "32"], None),
    (1, ["--retire-after", "8"], None), (1, ["--retire-after", "0"], None),
    (1, ["--directions", "16", "--retire-after", "0"], None),
    (1, ["--tries", "100"], None), (1, ["--max-failures", "10"], None),
    (1, ["--max-failures", "1000"], None),
    (0, ["--max-failures", "1"], None), (0, ["--max-failures", "10"], None),
    (0, ["--tries", "100"], None), (0, ["--max-failures", "1000"], None),
    (2, ["--max-failures", "1"], None), (2, ["--max-failures", "10"], None),
    (2, ["--tries", "10", "--max-failures", "10"], None),
    (3, ["--retire-after", "8"], None), (3, ["--directions", "16"], None),
    (3, ["--retire-after", "0"], 2),  # never retiring: ~30 s per bed, so 2 seeds
]


def run_one(psd, approach, seed, extra, workdir):
    out = os.path.join(workdir, "bed.h5")
    pack, _ = run_json([app("packgen"), "--dim", "2", "--domain", DOMAIN, "--psd", psd,
                        "--approach", str(approach), "--collision", "raster",
                        "--raster-spacing", str(H), "--seed", str(seed), "--out", out] + extra)
    centres, radii = read_bed(out)
    z_scan = coordination_at_gaps(centres, radii, [g * H for g in SCAN])
    for f in (out, out[:-3] + ".xmf"):
        if os.path.exists(f):
            os.remove(f)
    return {"n": pack["n"], "density": pack["density"], "z_strict": pack["coordination"],
            "z_scan": z_scan, "overlap": pack["max_relative_overlap"], "wall": pack["wall_time"]}


def run_case(psd, approach, samples, workdir, extra=()):
    return [run_one(psd, approach, s, list(extra), workdir) for s in range(1, samples + 1)]


def z_at(rows, g_over_h):
    k = min(range(len(SCAN)), key=lambda i: abs(SCAN[i] - g_over_h))
    return [r["z_scan"][k] for r in rows]


def col(rows, key):
    return [r[key] for r in rows]


def fmt(values, digits):
    mean, lo, hi, sd = summary(values)
    return f"{mean:.{digits}f} ({lo:.{digits}f}–{hi:.{digits}f}, sd {sd:.{digits}f})"


def mean(values):
    return summary(values)[0]


def mark(values, rng):
    return "" if rng[0] <= mean(values) <= rng[1] else " ✗"


def gap_window(rows, rng):
    """The gaps g/h of the scan at which the mean Z lies in the paper's range ('none' if no g)."""
    inside = [g for k, g in enumerate(SCAN) if rng[0] <= mean([r["z_scan"][k] for r in rows])
              <= rng[1]]
    return f"{min(inside):.1f}–{max(inside):.1f}" if inside else "none"


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(results), 3, figsize=(12, 2.5 * len(results)))
    for row, (case, rows) in enumerate(results):
        pn, pd, pz = PAPER[case[3]]
        for column, (values, label, rng) in enumerate([
                ([(col(rows, "n"), None)], "particles", pn),
                ([(col(rows, "density"), None)], "density", pd),
                ([(z_at(rows, 1.0), "gap ≤ h"), (z_at(rows, 2.0), "gap ≤ 2h")], "Z", pz)]):
            ax = axes[row][column]
            for v, name in values:
                ax.hist(v, bins=20, alpha=0.6, label=name)
            ax.axvspan(rng[0], rng[1], color="tab:orange", alpha=0.25, label="paper range")
            ax.set_xlabel(label)
            if column == 0:
                ax.set_title(f"{case[0]} ({len(rows)} samples)", loc="left", fontsize=9)
            if column == 2:
                ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=80)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--samples", type=int, default=100)
    parser.add_argument("--alt-samples", type=int, default=20)
    parser.add_argument("--sens-samples", type=int, default=10)
    args = parser.parse_args()
    load = report.load_average()
    results, sens = [], []
    with tempfile.TemporaryDirectory() as workdir:
        for case in CASES:
            print(f"{case[0]} ...", file=sys.stderr, flush=True)
            results.append((case, run_case(case[1], case[2], getattr(args, case[4]), workdir)))
        for index, extra, seeds in SENSITIVITY:
            case = CASES[index]
            print(f"{case[0]} {' '.join(extra)} ...", file=sys.stderr, flush=True)
            sens.append((index, extra, run_case(case[1], case[2], seeds or args.sens_samples,
                                                workdir, extra)))
    plot(results, os.path.join(report.RESULTS, "packgen-2d-study.png"))
    path = report.write_page("packgen-2d-study.md", page(results, sens, args, report.machine(load)))
    print(path)


def case_table(results):
    """Per paper case: our samples' particles, density and Z against the paper's ranges."""
    lines = report.table_head("case", "particles", "paper", "density", "paper", "Z gap ≤ h",
                              "Z gap ≤ √2 h", "Z gap ≤ 2 h", "Z strict (tol 1e-6)", "paper Z",
                              "gap g/h giving paper Z", "wall time s")
    for case, rows in results:
        pn, pd, pz = PAPER[case[3]]
        zs = " | ".join(fmt(z_at(rows, g), 2) + mark(z_at(rows, g), pz) for _, g in GAPS)
        lines.append(
            f"| {case[0]} | {fmt(col(rows, 'n'), 0)}{mark(col(rows, 'n'), pn)} | {pn[0]}–{pn[1]} "
            f"| {fmt(col(rows, 'density'), 3)}{mark(col(rows, 'density'), pd)} | {pd[0]}–{pd[1]} "
            f"| {zs} | {fmt(col(rows, 'z_strict'), 2)} | {pz[0]}–{pz[1]} "
            f"| {gap_window(rows, pz)} | {mean(col(rows, 'wall')):.3f} |")
    return "\n".join(lines)


def sensitivity_table(results, sens, sens_samples):
    """Per case of the paper's settings: its defaults (the first `sens_samples` seeds) and each
    one-at-a-time change, mean over the seeds."""
    lines = report.table_head("case", "change", "seeds", "particles", "density", "Z gap ≤ h",
                              "Z gap ≤ 2 h", "wall time s")

    def sens_line(label, change, rows):
        return (f"| {label} | {change} | {len(rows)} | {mean(col(rows, 'n')):.0f} "
                f"| {mean(col(rows, 'density')):.3f} | {mean(z_at(rows, 1.0)):.2f} "
                f"| {mean(z_at(rows, 2.0)):.2f} | {mean(col(rows, 'wall')):.3f} |")
    for index in range(4):
        base = results[index][1][:sens_samples]
        lines.append(sens_line(CASES[index][0], "defaults", base))
        for i, extra, rows in sens:
            if i == index:
                lines.append(sens_line(CASES[index][0], "`" + " ".join(extra) + "`", rows))
    return "\n".join(lines)


def page(results, sens, args, machine):
    """The page: templates/packgen-2d-study.md.in with the tables and the findings."""
    return report.fill_template("packgen-2d-study.md.in", {
        "samples": args.samples, "alt_samples": args.alt_samples,
        "sens_samples": args.sens_samples, "machine": machine,
        "case_table": case_table(results),
        "sensitivity_table": sensitivity_table(results, sens, args.sens_samples),
        **why_values(results, sens)})


def where(value, rng):
    return "inside" if rng[0] <= value <= rng[1] else "outside"


def common_gap(results):
    """One sentence: the gaps g/h (if any) at which every case's mean Z is in its paper range."""
    ok = [g for k, g in enumerate(SCAN)
          if all(PAPER[c[3]][2][0] <= mean([r["z_scan"][k] for r in rows]) <= PAPER[c[3]][2][1]
                 for c, rows in results)]
    if ok:
        return f"Every case is met at g/h = {min(ok):.1f}–{max(ok):.1f}."
    return ("These intervals have no common gap, so no single tolerance reproduces every case: "
            "our 0-contact beds need a smaller gap than our 1-contact beds.")


def find(sens, index, extra):
    for i, e, rows in sens:
        if i == index and e == extra:
            return rows
    raise KeyError(extra)


def why_values(results, sens):
    """The numbers of the findings (the page's "Why the numbers differ"), all from this run."""
    rows = [r for _, r in results]

    def d(rs):  # the samples' mean density
        return f"{mean(col(rs, 'density')):.3f}"

    def n(rs):  # the samples' mean particle count
        return f"{mean(col(rs, 'n')):.0f}"
    k_scan = [(k, mean(col(find(sens, 1, ["--directions", str(k)]), "density")))
              for k in (6, 8, 12, 16, 32)]
    k_scan.insert(2, (10, mean(col(rows[1], "density"))))
    m0_mf = [(m, find(sens, 0, ["--max-failures", str(m)])) for m in (1, 10)]
    m0_mf += [(100, rows[0]), (1000, find(sens, 0, ["--max-failures", "1000"]))]
    g0_first = find(sens, 2, ["--max-failures", "1"])
    g0_early = find(sens, 2, ["--tries", "10", "--max-failures", "10"])
    g1_never = find(sens, 3, ["--retire-after", "0"])
    return {
        "k_scan": ", ".join(f"K = {k}: φ = {v:.3f}" for k, v in k_scan),
        "k_met": ", ".join(str(k) for k, v in k_scan if 0.62 <= v <= 0.64) or "none",
        "phi_mono_never16": d(find(sens, 1, ["--directions", "16", "--retire-after", "0"])),
        "phi_mono_never": d(find(sens, 1, ["--retire-after", "0"])),
        "phi_mono_retire8": d(find(sens, 1, ["--retire-after", "8"])),
        "stop_scan": ", ".join(f"M = {m}: φ = {d(rs)}" for m, rs in m0_mf),
        "phi_gauss0": d(rows[2]), "n_gauss0": n(rows[2]),
        "n_gauss_first": n(g0_first), "phi_gauss_first": d(g0_first),
        "n_gauss_early": n(g0_early), "phi_gauss_early": d(g0_early),
        "gauss_early_where": where(mean(col(g0_early, "density")), (0.42, 0.52)),
        "n_gauss1": n(rows[3]), "phi_gauss1": d(rows[3]),
        "n_gauss_never": n(g1_never), "phi_gauss_never": d(g1_never),
        "seeds_gauss_never": len(g1_never), "wall_gauss_never": f"{mean(col(g1_never, 'wall')):.0f}",
        "n_diameter0": n(rows[4]), "n_diameter1": n(rows[5]),
        "diameter_over_upper": f"{mean(col(rows[5], 'n')) / 575:.1f}",
        "radius_over_lower": f"{mean(col(rows[3], 'n')) / 525:.2f}",
        "z_strict": f"{mean(col(rows[1], 'z_strict')):.2f}",
        "gap_windows": "; ".join(f"{case[0]}: {gap_window(r, PAPER[case[3]][2])}"
                                 for (case, r) in results[:4]),
        "common_gap": common_gap(results[:4]),
    }


if __name__ == "__main__":
    main()
