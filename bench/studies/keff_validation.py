#!/usr/bin/env python3
"""The five validation cases of Kumar Yadav & Eshraghi [KE] 2016 with keff, on beds made as they
made theirs and between the walls as they set them: two opposite side walls of the filled box
(keff --axis x, the scenes' axis), contact radius the geometric intersection circle at the
Hertz-corrected overlap (MFiX's, which [KE] ran) and, side by side, the Hertz circle; radiation
on. Per bed: k_eff wall to wall and k_core (the flux over the core's mean gradient), both as the
program reports them (--json), the profile's R², each wall's share of the drop; the
unconsolidated bed and consolidated ones (the top wall lowered L particle radii below the
bed's surface, held, raised, relaxed), their mean and standard deviation (the consolidation
uncertainty), the input uncertainty over [KE]'s ranges of k_s, k_g and E by a second-order
polynomial chaos on a Smolyak sparse grid, the total; the same beds with the hot wall at the
bed's top (--axis z, the former set-up); the contacts before and after consolidation. Writes
docs/results/keff-validation.md. Run with python3:
    POWDERBED_BUILD=build python3 bench/studies/keff_validation.py [--seeds N] [--depths L,..]
        [--bed-seeds M]

--seeds N: the consolidation/PCE study on seeds 1..N (default 1). --depths: the lid depths in
particle radii (default [KE]'s four, 0.25,0.5,0.75,1: about 40 minutes of one core per seed
for the beds, the copper ones most). --bed-seeds M: the bed-generation study, steel 1 mm
unconsolidated, seeds 1..M (default 8, [KE]'s count; ~160 s of one core per bed). keff results
are kept (results.json, bed-seeds.json) and reused for beds that are there.

Beds: `deposit --config data/scenes/ke2016-<case>-bed.ini --seed S` (unconsolidated), then
`deposit --config ... --in BED --t-end 1e-4 --lid.enabled true --lid.depth L` for each depth;
kept in out/studies/keff-validation/. keff: data/scenes/ke2016-<case>.ini.
The page's prose is bench/studies/templates/keff-validation.md.in.
"""
import argparse
import json
import math
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from lib import apps, pce, references, report

# [KE]'s cases (Table 2 ranges, Table 3 porosity) and lid depths (particle radii).
CASES = references.KE2016_CASES
KE_DEPTHS = references.KE2016_LID_DEPTHS
DEPTHS = list(KE_DEPTHS)  # --depths


def beds(case, seed):
    """The unconsolidated bed and the consolidated ones of `seed`: [(label, depth/r, path,
    deposit summary, wall s)] (lib/apps.py ke2016_bed: kept in out/studies/keff-validation/)."""
    out = [("unconsolidated", 0.0, *apps.ke2016_bed(case, seed))]
    for depth in DEPTHS:
        out.append((f"lid {depth:g} r", depth, *apps.ke2016_bed(case, seed, depth)))
    return out


def make_all(seeds):
    """Every case's beds, two processes at a time (the copper cases are the long ones)."""
    jobs = [(c[0], c[2], seed) for seed in seeds for c in CASES]
    jobs.sort(key=lambda j: j[1])  # smallest particles (longest runs) first
    with ThreadPoolExecutor(max_workers=2) as pool:
        return dict(zip(jobs, pool.map(lambda j: beds(j[0], j[2]), jobs)))


def box_porosity(path):
    """1 - solid volume / box volume, the box's top at the bed's top (the highest particle top:
    the written beds are cropped there)."""
    import h5py
    with h5py.File(path, "r") as f:
        r = np.array(f["particles/radius"])
        lo, hi = f["domain"].attrs["lower"], f["domain"].attrs["upper"]
    return 1 - (4 / 3 * math.pi * np.sum(r ** 3)) / np.prod(np.array(hi) - np.array(lo))


def contacts(case, path):
    """The contacts of the bed's core (both centres over 2 D from every face, the top included):
    Z = 2 contacts / core particles, the overlaps' median, and the geometric contact radius at
    the Hertz-corrected overlap (the scenes' circle: k_n δ = (4/3) E* √R* δ_h^{3/2}, a² = 2 R* δ_h
    − δ_h²/2 for equal spheres) as quantiles over a/r; near contacts: gaps in (0, 0.01 D], which
    the gas lens's l_min-bounded integrand weighs most."""
    from scipy.spatial import cKDTree
    x, r = apps.read_bed(path)
    import h5py
    with h5py.File(path, "r") as f:
        lo, hi = np.array(f["domain"].attrs["lower"]), np.array(f["domain"].attrs["upper"])
    d = 2 * r.max()
    dem = apps.resolved_options("deposit", ["--config", apps.ke2016_bed_scene(case)])
    e, nu = float(dem["material.young"]), float(dem["material.poisson"])
    k_n = float(dem["contact.stiffness"])
    e_star = e / (2 * (1 - nu * nu))
    inside = np.all((x > lo + 2 * d) & (x < hi - 2 * d), axis=1)
    pairs = cKDTree(x).query_pairs(d * 1.02, output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    gap = np.linalg.norm(x[i] - x[j], axis=1) - r[i] - r[j]
    core = inside[i] & inside[j]
    n_core = int(np.count_nonzero(inside))
    touching = core & (gap < 0)
    delta = -gap[touching]
    r_star = r[i][touching] * r[j][touching] / (r[i][touching] + r[j][touching])
    delta_h = (3 * k_n * delta / (4 * e_star * np.sqrt(r_star))) ** (2 / 3)
    a = np.sqrt(2 * r_star * delta_h - delta_h ** 2 / 2) / r[i][touching]
    q = np.quantile(a, [0.1, 0.5, 0.9]) if len(a) else [0, 0, 0]
    # The fabric: ⟨n_k²⟩ of the contact normals weighted by a (1/3 each when isotropic), what
    # the contact path's conductance along axis k goes with.
    n = (x[j] - x[i])[touching]
    n /= np.linalg.norm(n, axis=1)[:, None]
    fabric = (a[:, None] * n ** 2).sum(axis=0) / max(a.sum(), 1e-300)
    near = core & (gap >= 0) & (gap <= 0.01 * d)
    return {"z": 2 * int(np.count_nonzero(touching)) / max(n_core, 1),
            "near": 2 * int(np.count_nonzero(near)) / max(n_core, 1),
            "overlap_median": float(np.median(delta)) if len(delta) else 0.0,
            "a10": float(q[0]), "a50": float(q[1]), "a90": float(q[2]),
            "sum_a": float(np.sum(a)) / max(n_core, 1),
            "fabric": [float(f) for f in fabric]}


def run_row(s):
    """What the page takes from one keff --json summary."""
    return {"k_eff": s["k_eff"], "k_core": s["k_core"], "r2": s["profile_r_squared"],
            "drop_hot": s["wall_drop_hot"], "drop_cold": s["wall_drop_cold"],
            "contact": s["share"]["contact"], "gas": s["share"]["gas"],
            "radiation": s["share"]["radiation"], "rattlers": s["rattlers"],
            "wall_time": s["wall_time"]}


def measure(case, ranges, bed_list, cached=None):
    """Per bed: the nominal keff run (the scene: side walls, geometric circle, radiation), the
    Hertz circle, the top wall (--axis z), the y walls, radiation off, and the PCE over the
    input ranges. `cached`: the rows of an earlier run on the same beds (results.json),
    returned as they are."""
    if cached is not None and [r["label"] for r in cached] == [b[0] for b in bed_list]:
        return cached
    grid = pce.smolyak_grid()
    rows = []
    for label, depth, path, dep, wall in bed_list:
        runs = {
            "nominal": apps.ke2016_keff(case, path),
            "hertz": apps.ke2016_keff(case, path, "--contact.radius", "hertz", tag="hertz"),
            "top": apps.ke2016_keff(case, path, "--axis", "z", tag="z"),
            "y": apps.ke2016_keff(case, path, "--axis", "y", tag="y"),
            "dark": apps.ke2016_keff(case, path, "--effects.radiation", "false", tag="dark"),
        }

        def at(job):
            k, point = job
            k_s, k_g, e = (lo + (x + 1) / 2 * (hi - lo) for x, (lo, hi) in zip(point, ranges))
            s = apps.ke2016_keff(case, path, "--solid.conductivity", f"{k_s:.8g}",
                                 "--gas.conductivity", f"{k_g:.8g}", "--contact.young",
                                 f"{e * 1e9:.8g}", tag=f"pce{k}")
            return s["k_eff"], s["k_core"]
        with ThreadPoolExecutor(max_workers=2) as pool:
            values = list(pool.map(at, enumerate(p for p, _ in grid)))
        mean, sd, sobol = pce.pce([v[0] for v in values], grid)
        _, sd_core, _ = pce.pce([v[1] for v in values], grid)
        row = {"label": label, "depth": depth, "n": dep["n"], "wall": wall,
               "core_porosity": 1 - dep["core_density"], "box_porosity": box_porosity(path),
               "lid_force": dep.get("lid", {}).get("max_force", 0.0),
               "pce_mean": mean, "pce_sd": sd, "pce_sd_core": sd_core, "sobol": sobol,
               "contacts": contacts(case, path)}
        row.update({key: run_row(s) for key, s in runs.items()})
        rows.append(row)
    return rows


def pm(mean, sd, digits=3):
    return f"{mean:.{digits}g} ± {sd:.2g}"


def sd_of(a):
    return float(np.std(a, ddof=1)) if len(a) > 1 else 0.0


def case_summary(rows, run="nominal"):
    k = np.array([r[run]["k_eff"] for r in rows])
    kc = np.array([r[run]["k_core"] for r in rows])
    por = np.array([r["core_porosity"] for r in rows])
    return {"k": k.mean(), "k_sd": sd_of(k), "kc": kc.mean(), "kc_sd": sd_of(kc),
            "s_in": float(np.mean([r["pce_sd"] for r in rows])),
            "s_in_core": float(np.mean([r["pce_sd_core"] for r in rows])),
            "por": por.mean(), "por_sd": sd_of(por),
            "n_min": min(r["n"] for r in rows), "n_max": max(r["n"] for r in rows),
            "r2": min(r[run]["r2"] for r in rows),
            "drop": max(max(r[run]["drop_hot"], r[run]["drop_cold"]) for r in rows),
            "ratio": float(np.mean(k / kc)),
            "contact": float(np.mean([r[run]["contact"] for r in rows])),
            "radiation": float(np.mean([r[run]["radiation"] for r in rows])),
            "sobol": np.mean([r["sobol"] for r in rows], axis=0)}


def ke_value(case):
    v = references.KE2016_KEFF.get(case)
    return f"{v[0]:.3g} ± {v[1]:.2g}" if v else "not transcribed"


def depths_note():
    """The sentence the intro adds when the lid depths are not [KE]'s four ("" when they are)."""
    if DEPTHS == KE_DEPTHS:
        return ""
    n_beds = 1 + len(DEPTHS)
    return (f"; {n_beds} beds per case, not [KE]'s five (their depths "
            + ", ".join(f"{d:g}" for d in KE_DEPTHS) + " r): the four lid beds of the copper "
            "cases alone take about 40 minutes of one core here, and the study had to fit a "
            "two-core machine shared with other work, so the consolidation σ below is the "
            f"standard deviation of {n_beds} beds and carries a large sampling error")


def each_bed(results, seeds):
    """(the case's name in a table, the bed's row) for every bed, case by case; the seed is
    named only when there are several."""
    for case, label, *_ in CASES:
        for seed in seeds:
            for r in results[(case, seed)]:
                yield f"{label}{'' if len(seeds) == 1 else f', seed {seed}'}", r


def summary_table(sums):
    """Per case (case_summary of its beds): k_eff with each uncertainty, k_core, the profile."""
    lines = report.table_head("case", "particles", "core porosity", "[KE] Table 3 porosity",
                              "k_eff (W/mK) ± consolidation", "input σ", "total σ",
                              "k_core (W/mK) ± consolidation", "k_eff / k_core", "R² (lowest)",
                              "wall drop (largest)", "[KE] k_eff", "contact / radiation share",
                              "Sobol k_s / k_g / E")
    for case, label, *_, table3 in CASES:
        s = sums[case]
        lines.append(report.table_row(
            label, f"{s['n_min']}–{s['n_max']}", f"{s['por']:.3f} ± {s['por_sd']:.3f}",
            f"{table3[0]:.3f} ± {table3[1]:.3f}", pm(s["k"], s["k_sd"]), f"{s['s_in']:.2g}",
            f"{math.hypot(s['s_in'], s['k_sd']):.2g}", pm(s["kc"], s["kc_sd"]),
            f"{s['ratio']:.3f}", f"{s['r2']:.4f}", f"{100 * s['drop']:.1f} %", ke_value(case),
            f"{100 * s['contact']:.1f} % / {100 * s['radiation']:.1f} %",
            " / ".join(f"{x:.2f}" for x in s["sobol"])))
    return "\n".join(lines)


def hertz_table(results, seeds):
    """Per case: the geometric contact circle (the scenes') beside the Hertz one."""
    lines = report.table_head("case", "k_eff geometric (W/mK)", "k_eff Hertz (W/mK)",
                              "geometric / Hertz", "k_core geometric", "k_core Hertz",
                              "contact share geometric / Hertz")
    for case, label, *_ in CASES:
        rows = [r for seed in seeds for r in results[(case, seed)]]
        g, h = case_summary(rows), case_summary(rows, "hertz")
        lines.append(report.table_row(
            label, pm(g["k"], g["k_sd"]), pm(h["k"], h["k_sd"]), f"{g['k'] / h['k']:.3f}",
            pm(g["kc"], g["kc_sd"]), pm(h["kc"], h["kc_sd"]),
            f"{100 * g['contact']:.1f} % / {100 * h['contact']:.1f} %"))
    return "\n".join(lines)


def bed_table(results, seeds):
    """Every bed's nominal run, its Hertz k, its PCE σ and how it was made."""
    lines = report.table_head("case", "bed", "particles", "core porosity", "box porosity",
                              "k_eff (W/mK)", "k_core (W/mK)", "k_eff / k_core", "R²",
                              "drop hot / cold", "k_eff Hertz", "k_core Hertz", "contact share",
                              "radiation share", "rattlers", "input σ (PCE)",
                              "largest lid force (N)", "deposit wall time (s)")
    for name, r in each_bed(results, seeds):
        n = r["nominal"]
        lines.append(report.table_row(
            name, r["label"], r["n"], f"{r['core_porosity']:.3f}", f"{r['box_porosity']:.3f}",
            f"{n['k_eff']:.4g}", f"{n['k_core']:.4g}", f"{n['k_eff'] / n['k_core']:.3f}",
            f"{n['r2']:.4f}", f"{100 * n['drop_hot']:.1f} / {100 * n['drop_cold']:.1f} %",
            f"{r['hertz']['k_eff']:.4g}", f"{r['hertz']['k_core']:.4g}",
            f"{100 * n['contact']:.1f} %", f"{100 * n['radiation']:.2f} %",
            n["rattlers"], f"{r['pce_sd']:.2g}", f"{r['lid_force']:.3g}", f"{r['wall']:.0f}"))
    return "\n".join(lines)


def top_table(results, seeds):
    """Every bed between its top and its floor (--axis z) and between its y walls, beside x."""
    lines = report.table_head("case", "bed", "k_eff z (W/mK)", "k_core z", "k_eff / k_core z",
                              "drop at the top wall", "R² z", "k_eff y", "k_core y",
                              "k_eff x (the scenes')", "k_core x")
    for name, r in each_bed(results, seeds):
        t, y, n = r["top"], r["y"], r["nominal"]
        lines.append(report.table_row(
            name, r["label"], f"{t['k_eff']:.4g}", f"{t['k_core']:.4g}",
            f"{t['k_eff'] / t['k_core']:.2f}", f"{100 * t['drop_hot']:.0f} %", f"{t['r2']:.3f}",
            f"{y['k_eff']:.4g}", f"{y['k_core']:.4g}", f"{n['k_eff']:.4g}", f"{n['k_core']:.4g}"))
    return "\n".join(lines)


def contacts_table(results, seeds):
    """Every bed's core contacts (contacts()) and k_core along each axis."""
    lines = report.table_head("case", "bed", "core porosity", "Z", "median overlap (m)",
                              "a/r 10 / 50 / 90 %", "Σa/r per particle", "fabric x / y / z",
                              "near contacts per particle", "k_core x", "k_core y", "k_core z",
                              "gas share x")
    for name, r in each_bed(results, seeds):
        c = r["contacts"]
        lines.append(report.table_row(
            name, r["label"], f"{r['core_porosity']:.3f}", f"{c['z']:.2f}",
            f"{c['overlap_median']:.3g}", f"{c['a10']:.4f} / {c['a50']:.4f} / {c['a90']:.4f}",
            f"{c['sum_a']:.4f}", " / ".join(f"{f:.3f}" for f in c["fabric"]), f"{c['near']:.2f}",
            f"{r['nominal']['k_core']:.4g}", f"{r['y']['k_core']:.4g}",
            f"{r['top']['k_core']:.4g}", f"{100 * r['nominal']['gas']:.1f} %"))
    return "\n".join(lines)


def page(results, seeds, machine, seed_rows, other):
    """The page: templates/keff-validation.md.in filled with the tables and findings of
    `results` ({(case, seed): measure()'s rows}) and the bed-seed study (`seed_rows`, `other`:
    bed_seed_section's)."""
    sums = {c[0]: case_summary([r for seed in seeds for r in results[(c[0], seed)]])
            for c in CASES}
    values = {
        "seeds": f"Seed{'s' if len(seeds) > 1 else ''} {', '.join(map(str, seeds))}",
        "depths": ", ".join(f"{d:g}" for d in DEPTHS),
        "depths_note": depths_note(),
        "machine": machine,
        "summary_table": summary_table(sums),
        "hertz_table": hertz_table(results, seeds),
        "bed_table": bed_table(results, seeds),
        "top_table": top_table(results, seeds),
        "contacts_table": contacts_table(results, seeds),
        "findings": "\n".join(findings(results, seeds, sums)),
        "consolidation": consolidation_paragraph(results, seeds),
        "bed_seeds": "\n".join(bed_seed_section(seed_rows, other)),
    }
    return report.fill_template("keff-validation.md.in", values)


def consolidation_paragraph(results, seeds):
    """Why consolidation lowered k_core on the former page (measured along z) though the bed
    got denser: the contacts before and after, and k_core along each axis."""
    loose = [r for c in CASES for seed in seeds for r in results[(c[0], seed)] if r["depth"] == 0]
    dense = [r for c in CASES for seed in seeds for r in results[(c[0], seed)] if r["depth"] > 0]
    rng = lambda v: f"{min(v):.3f}–{max(v):.3f}"
    per_case = []
    for c, label, *_ in CASES:
        a = [r for seed in seeds for r in results[(c, seed)] if r["depth"] == 0]
        b = [r for seed in seeds for r in results[(c, seed)] if r["depth"] > 0]
        m = lambda rows, f: float(np.mean([f(r) for r in rows]))
        per_case.append(
            f"{label} z {m(a, lambda r: r['top']['k_core']):.3g} → "
            f"{m(b, lambda r: r['top']['k_core']):.3g}, x {m(a, lambda r: r['nominal']['k_core']):.3g}"
            f" → {m(b, lambda r: r['nominal']['k_core']):.3g}, y "
            f"{m(a, lambda r: r['y']['k_core']):.3g} → {m(b, lambda r: r['y']['k_core']):.3g}")
    growth = [np.mean([r["contacts"]["a50"] for seed in seeds for r in results[(c[0], seed)]
                       if r["depth"] > 0]) /
              np.mean([r["contacts"]["a50"] for seed in seeds for r in results[(c[0], seed)]
                       if r["depth"] == 0]) - 1 for c in CASES]
    return (
        "**Consolidation, explained.** The former page measured k_core along z, the lid's "
        "direction, and found it a few per cent lower after consolidation though the bed got "
        "denser. The contacts say why. Poured under gravity alone, the bed carries its weight "
        "down: the contact normals, weighted by their radius, lean to z (⟨n_z²⟩ = "
        f"{rng([r['contacts']['fabric'][2] for r in loose])}, 1/3 when isotropic). The lid "
        "presses, is raised, and the bed relaxes: the vertical contacts unload with it while "
        "the horizontal ones keep their load (a horizontal stress locked in by friction, as in "
        "an unloaded soil; the stresses themselves were not measured), and the fabric turns "
        f"over (⟨n_z²⟩ = {rng([r['contacts']['fabric'][2] for r in dense])}, ⟨n_x²⟩ "
        f"{rng([r['contacts']['fabric'][0] for r in loose])} → "
        f"{rng([r['contacts']['fabric'][0] for r in dense])}). The number of contacts barely "
        f"changes (Z {rng([r['contacts']['z'] for r in loose])} → "
        f"{rng([r['contacts']['z'] for r in dense])}), the median contact radius grows by "
        f"{100 * min(growth):.0f}–{100 * max(growth):.0f} %, and the near contacts, where the "
        "gas lens conducts most, multiply (per particle "
        f"{rng([r['contacts']['near'] for r in loose])} → "
        f"{rng([r['contacts']['near'] for r in dense])}). k_core (W/mK, unconsolidated → mean "
        "of the lid beds) along each axis: " + "; ".join(per_case) + ". So consolidation does "
        "not make the bed conduct worse: it makes it anisotropic, and the former set-up "
        "measured it along the direction its contacts turned away from. The scenes' walls are "
        "now the x faces, across which the consolidated bed's contacts lie.")


def findings(results, seeds, sums):
    out = []
    every = [r for c in CASES for seed in seeds for r in results[(c[0], seed)]]
    ratio = [r["nominal"]["k_eff"] / r["nominal"]["k_core"] for r in every]
    r2 = [r["nominal"]["r2"] for r in every]
    drop = [max(r["nominal"]["drop_hot"], r["nominal"]["drop_cold"]) for r in every]
    top = [r["top"]["k_eff"] / r["top"]["k_core"] for r in every]
    top_drop = [r["top"]["drop_hot"] for r in every]
    out.append(
        f"- **Side walls.** Between the two x faces k_eff / k_core = {min(ratio):.3f}–"
        f"{max(ratio):.3f} over the {len(every)} beds, the profile's R² {min(r2):.4f}–"
        f"{max(r2):.4f}, and neither wall takes more than {100 * max(drop):.1f} % of ΔT: the "
        "profile is the near-straight line [KE] describe, and the wall-to-wall k_eff is the "
        "bed's own. With the hot wall at the bed's top (`--axis z`, the former set-up) "
        f"k_eff / k_core = {min(top):.2f}–{max(top):.2f} and the top wall takes "
        f"{100 * min(top_drop):.0f}–{100 * max(top_drop):.0f} % of ΔT: that wall touches "
        "about one particle of the rough top. The former explanation of the low wall-to-wall "
        "value (MFiX's continuum gas phase) was wrong: [KE] neglected heat transfer to the gas "
        "phase; the set-up was.")
    geo_h = [r["nominal"]["k_eff"] / r["hertz"]["k_eff"] for r in every]
    out.append(
        "- **Contact circle.** The geometric circle (MFiX's) over the Hertz one raises k_eff by "
        + "; ".join(f"{label} {100 * (np.mean([r['nominal']['k_eff'] / r['hertz']['k_eff'] for seed in seeds for r in results[(c, seed)]]) - 1):+.1f} %"
                    for c, label, *_ in CASES)
        + f" (range {min(geo_h):.3f}–{max(geo_h):.3f}): more where the contacts carry more "
        "(copper, where k_s/k_g ~ 1.5e4), little where the gas lens dominates (steel).")
    dark = [r["nominal"]["k_eff"] / r["dark"]["k_eff"] - 1 for r in every]
    t_on = [r["nominal"]["wall_time"] for r in every]
    t_off = [r["dark"]["wall_time"] for r in every]
    out.append(
        f"- **Radiation** at 295–305 K adds {100 * min(dark):.2f}–{100 * max(dark):.2f} % to "
        f"k_eff (share {100 * min(r['nominal']['radiation'] for r in every):.2f}–"
        f"{100 * max(r['nominal']['radiation'] for r in every):.2f} %). It costs the view "
        f"factors and Newton: keff's wall time (network and solve) {np.mean(t_on):.3f} s with it, "
        f"{np.mean(t_off):.3f} s without (means over the beds; 100 rays per particle; "
        "a process start and the bed's reading come on top of both). The rays "
        "are cosine-weighted (diffuse emission); [KE] describe uniform hemisphere directions, "
        "which keff does not offer (docs/keff.md).")
    loose = {c: [r for seed in seeds for r in results[(c, seed)] if r["depth"] == 0]
             for c, *_ in CASES}
    dense = {c: [r for seed in seeds for r in results[(c, seed)] if r["depth"] > 0]
             for c, *_ in CASES}
    out.append(
        "- **Porosity against [KE] Table 3.** Unconsolidated beds (core porosity, and its "
        "difference from [KE]'s mean in their σ): "
        + "; ".join(f"{label} {np.mean([r['core_porosity'] for r in loose[c]]):.3f} "
                    f"({(np.mean([r['core_porosity'] for r in loose[c]]) - t3[0]) / t3[1]:+.1f})"
                    for c, label, *_, t3 in CASES)
        + ". Consolidated: " + "; ".join(
            f"{label} {min(r['core_porosity'] for r in dense[c]):.3f}"
            + (f"–{max(r['core_porosity'] for r in dense[c]):.3f}" if len(dense[c]) > 1 else "")
            for c, label, *_ in CASES)
        + ". Our beds are 1–3 of [KE]'s σ denser than theirs unconsolidated and denser still "
        "after the lid; [KE]'s beds per case agree within ±0.01. Particle counts: "
        + "; ".join(f"{label} {sums[c]['n_min']}"
                    + (f"–{sums[c]['n_max']}" if sums[c]['n_max'] != sums[c]['n_min'] else "")
                    for c, label, *_ in CASES)
        + " ([KE] 1,039–1,095).")
    dom = []
    for c, label, *_ in CASES:
        s = sums[c]
        dom.append(f"{label} {'input' if s['s_in'] > s['k_sd'] else 'consolidation'} "
                   f"({s['s_in']:.2g} vs {s['k_sd']:.2g})")
    out.append("- **Which uncertainty dominates k_eff** (input σ vs consolidation σ): "
               + "; ".join(dom) + ".")
    trend = []
    for c, label, *_ in CASES:
        rows = results[(c, seeds[0])]
        a, b = rows[0], rows[-1]
        trend.append(
            f"{label}: Z {a['contacts']['z']:.2f} → {b['contacts']['z']:.2f}, median a/r "
            f"{a['contacts']['a50']:.4f} → {b['contacts']['a50']:.4f}, near contacts "
            f"{a['contacts']['near']:.2f} → {b['contacts']['near']:.2f}; k_core x "
            f"{a['nominal']['k_core']:.3g} → {b['nominal']['k_core']:.3g}, z "
            f"{a['top']['k_core']:.3g} → {b['top']['k_core']:.3g} W/mK")
    out.append("- **Consolidation** (unconsolidated → the last lid bed, seed "
               f"{seeds[0]}; contacts in the core): " + "; ".join(trend) + ". See the "
               "paragraph after this list.")
    return out


# Bed generation ([KE]: eight beds of steel 1 mm from different random insertions, k_eff
# sd 0.002 W/mK, neglected beside the other sources).
BED_SEED_CASE = "steel-1mm"
BED_SEEDS = references.KE2016_BED_SEEDS
KE_BED_SD = references.KE2016_BED_SD  # W/mK


def bed_seed_study(n):
    """The unconsolidated bed of BED_SEED_CASE for seeds 1..n (the same beds as beds(), two at a
    time) and the nominal keff on each: [{seed, n, core_porosity, box_porosity, k_eff, k_core,
    contact, wall}]. keff results kept in bed-seeds.json."""
    cache_path = apps.KE2016_BED_SEEDS
    cache = {}
    if os.path.exists(cache_path):
        with open(cache_path) as f:
            cache = json.load(f)

    def one(seed):
        path, s, wall = apps.ke2016_bed(BED_SEED_CASE, seed)
        if str(seed) in cache:
            return cache[str(seed)]
        k = apps.ke2016_keff(BED_SEED_CASE, path)
        row = {"seed": seed, "n": s["n"], "core_porosity": 1 - s["core_density"],
               "box_porosity": box_porosity(path), "k_eff": k["k_eff"], "k_core": k["k_core"],
               "contact": k["share"]["contact"], "wall": wall}
        print(f"bed seed {seed}: k_eff {row['k_eff']:.4g} k_core {row['k_core']:.4g}",
              flush=True)
        return row

    with ThreadPoolExecutor(max_workers=2) as pool:
        rows = list(pool.map(one, range(1, n + 1)))
    cache.update({str(r["seed"]): r for r in rows})
    with open(cache_path, "w") as f:
        json.dump(cache, f)
    return rows


def bed_seed_section(rows, other):
    """The lines of the page's bed-generation section under its heading: the seeds' beds
    (bed_seed_study's `rows`) and their σ beside the other uncertainties of that case (`other`,
    its case_summary)."""
    sd = lambda a: float(np.std(a, ddof=1))
    k = [r["k_eff"] for r in rows]
    kc = [r["k_core"] for r in rows]
    por = [r["core_porosity"] for r in rows]
    n = len(rows)
    label = next(c[1] for c in CASES if c[0] == BED_SEED_CASE)
    lines = [
        f"[KE] made {BED_SEEDS} beds of steel 1 mm from different random insertions and found a "
        f"k_eff standard deviation of {KE_BED_SD} W/mK, which they neglected. Here: the "
        f"unconsolidated {label} bed of `data/scenes/ke2016-{BED_SEED_CASE}-bed.ini` for seeds "
        f"1–{n} (`--seed S`, nothing else changed), nominal keff scene, no input sampling."
        + ("" if n >= BED_SEEDS else
           f" {n} seeds, not [KE]'s {BED_SEEDS}: compute time (each bed is ~160 s of one core); "
           f"a σ from {n} samples is itself uncertain by about ±{100 / math.sqrt(2 * (n - 1)):.0f} %."),
        "",
        "| seed | particles | core porosity | box porosity | k_eff (W/mK) | k_core (W/mK) | "
        "k_eff / k_core | contact share | deposit wall time (s) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(f"| {r['seed']} | {r['n']} | {r['core_porosity']:.3f} | "
                     f"{r['box_porosity']:.3f} | {r['k_eff']:.4g} | {r['k_core']:.4g} | "
                     f"{r['k_eff'] / r['k_core']:.2f} | {100 * r['contact']:.1f} % | "
                     f"{r['wall']:.0f} |")
    lines += [
        f"| **mean ± σ** | {np.mean([r['n'] for r in rows]):.0f} | "
        f"{np.mean(por):.3f} ± {sd(por):.3f} | "
        f"{np.mean([r['box_porosity'] for r in rows]):.3f} ± "
        f"{sd([r['box_porosity'] for r in rows]):.3f} | "
        f"{np.mean(k):.4f} ± {sd(k):.4f} | {np.mean(kc):.4f} ± {sd(kc):.4f} | | | |",
        "",
        f"Bed-generation σ over {n} seeds: k_eff {sd(k):.4f} W/mK "
        f"({100 * sd(k) / np.mean(k):.0f} % of its mean), k_core {sd(kc):.4f} W/mK "
        f"({100 * sd(kc) / np.mean(kc):.1f} %), against [KE]'s {KE_BED_SD} W/mK "
        f"(k_eff: {sd(k) / KE_BED_SD:.1f}×, k_core: {sd(kc) / KE_BED_SD:.1f}× theirs). "
        "Between the side walls k_eff and k_core scatter alike over the seeds: both are the "
        "bed's. Beside the other sources of "
        f"{label} (first table, seed 1): k_eff consolidation σ {other['k_sd']:.2g} and input σ "
        f"{other['s_in']:.2g}; k_core consolidation σ {other['kc_sd']:.2g} and input σ "
        f"{other['s_in_core']:.2g} W/mK. Not in the totals of the first table (as [KE]).",
    ]
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seeds", type=int, default=1,
                        help="the consolidation/PCE study on seeds 1..N (default 1)")
    parser.add_argument("--bed-seeds", type=int, default=BED_SEEDS,
                        help=f"the bed-generation study on seeds 1..M (default {BED_SEEDS})")
    parser.add_argument("--depths", default=",".join(f"{d:g}" for d in KE_DEPTHS),
                        help="lid depths in particle radii, comma-separated (default [KE]'s "
                             + ",".join(f"{d:g}" for d in KE_DEPTHS) + ")")
    args = parser.parse_args()
    DEPTHS[:] = [float(x) for x in args.depths.split(",")]
    seeds = list(range(1, args.seeds + 1))
    load = report.load_average()
    seed_rows = bed_seed_study(args.bed_seeds)
    made = make_all(seeds)
    earlier = {}
    if os.path.exists(apps.KE2016_RESULTS):
        with open(apps.KE2016_RESULTS) as f:
            earlier = json.load(f)
    results = {}
    for case, label, d, ks, kg, e, _ in CASES:
        for seed in seeds:
            results[(case, seed)] = measure(case, (ks, kg, e), made[(case, d, seed)],
                                            earlier.get(f"{case}:{seed}"))
            r = results[(case, seed)]
            print(label, seed, " ".join(f"{x['nominal']['k_eff']:.4g}/{x['nominal']['k_core']:.4g}"
                                        for x in r), flush=True)
    with open(apps.KE2016_RESULTS, "w") as f:
        json.dump({f"{c}:{s}": v for (c, s), v in results.items()}, f)
    # The machine sentence of the run that measured: a rerun on kept results (measure()
    # returns the cached rows themselves) must not report its own load and commit as theirs.
    machine_path = os.path.join(apps.KE2016_WORK, "results-machine.json")
    fresh = any(v is not earlier.get(f"{c}:{s}") for (c, s), v in results.items())
    if fresh or not os.path.exists(machine_path):
        machine = report.machine(load)
        with open(machine_path, "w") as f:
            json.dump({"machine": machine}, f)
    else:
        with open(machine_path) as f:
            machine = json.load(f)["machine"]
    other = case_summary([r for seed in seeds for r in results[(BED_SEED_CASE, seed)]])
    print(report.write_page("keff-validation.md", page(results, seeds, machine, seed_rows, other)))


if __name__ == "__main__":
    main()
