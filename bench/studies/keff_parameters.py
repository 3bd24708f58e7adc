#!/usr/bin/env python3
"""The [KE] parameter studies with keff (docs/physics.md §6, issue 6): bed temperature with and without
radiation, gas-to-solid conductivity ratio, Young's modulus and DEM stiffness, emissivity, bed
height, polydispersity and consolidation, on steel 1 mm beds made as [KE] made theirs. Writes
docs/results/keff-parameters.md and keff-parameters.png. Run with python3 (one thread):
    POWDERBED_BUILD=build python3 bench/studies/keff_parameters.py [--seeds N]
(--seeds N: seeds 1..N of the bed studies, default 3.)

Beds: [KE]'s unconsolidated bed, `deposit --config data/scenes/ke2016-<case>-bed.ini --seed S`
(linear spring-dashpot k_n = 1e5 N/m, insertion from the top of a 10 D cube until full), with
each study's change on the command line. The scene's own beds, the lid-depth consolidated ones
and the stiffness sweep are those of keff_validation.py and keff_softening.py (their caches in
out/studies/keff-validation/ and keff-softening/, made there if missing); the height and size
distribution beds are kept in out/studies/keff-parameters/. keff runs with
data/scenes/ke2016-<case>.ini (contacts with the Hertz correction read from the bed).
"""
import json
import math
import os
import re
import statistics
import sys

import numpy as np

import keff_validation as kv
from common import ROOT, RESULTS, app, bedstat, run_json, summary, write_text
from keff_softening import bed as softened_bed
from keff_validation import core_gradient

WORK = os.path.join(ROOT, "out", "studies", "keff-parameters")
SCENES = os.path.join(ROOT, "data", "scenes")
ENV = dict(os.environ, OMP_NUM_THREADS="1")
SIGMA = 5.670374419e-8  # Stefan–Boltzmann, W/m^2K^4
# Seeds of the bed studies (3, height, polydispersity, consolidation): 1..N with --seeds N
# (default 3).
FULL_SEEDS = 3
SEEDS = list(range(1, FULL_SEEDS + 1))
D = 1.0e-3  # the steel case's diameter (m)
TEMPERATURES = [300, 500, 700, 900, 1100, 1300, 1500]
EMISSIVITIES = [0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.0]
RATIOS = [1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1]  # k_g / k_s
YOUNG = [1, 3, 10, 30, 100, 198, 300, 1000]  # GPa, the same bed read at E
STIFFNESS = [1e3, 1e4, 1e5, 1e6]  # DEM k_n (N/m) of keff_softening.py's beds; [KE] 1e5
HEIGHTS = [1, 2, 3, 5, 7, 10]  # box height H/D, insertion until full
SPREADS = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]  # sigma/D
FULL_SPREAD = 0.5
DEPTHS = [0.0] + kv.DEPTHS  # lid depth below the surface (r): keff_validation's beds
RAYS = 1000


def seeds_text():
    return "seed 1" if len(SEEDS) == 1 else f"seeds 1–{len(SEEDS)}"


def bed_scene(case="steel-1mm"):
    return os.path.join(SCENES, f"ke2016-{case}-bed.ini")


def scene_value(path, section, key):
    """A key of an INI scene (section None: before the first [section])."""
    current = None
    for line in open(path):
        line = line.split("#")[0].strip()
        m = re.match(r"\[(.+)\]", line)
        if m:
            current = m.group(1)
        elif "=" in line and current == section:
            k, v = (x.strip() for x in line.split("=", 1))
            if k == key:
                return float(v)
    raise KeyError(f"{key} in {path}")


def zbs(porosity, kappa, c=1.25):
    """Zehner–Bauer–Schlünder stagnant conductivity k_eff/k_g of a packed bed of spheres, point
    contacts, no radiation, no Smoluchowski effect (Zehner & Schlünder, Chem. Ing. Tech. 42 (1970)
    933; VDI Heat Atlas, section M5): kappa = k_s/k_g, B = C ((1 - eps)/eps)^(10/9), C = 1.25."""
    b = c * ((1 - porosity) / porosity) ** (10 / 9)
    n = 1 - b / kappa
    core = 2 / n * ((1 - 1 / kappa) * b / n ** 2 * math.log(kappa / b) - (b + 1) / 2 - (b - 1) / n)
    root = math.sqrt(1 - porosity)
    return 1 - root + root * core


def pm(values, digits=4):
    """mean ± sd of the seeds, or the value alone for one seed."""
    mean, _, _, sd = summary(values)
    return f"{mean:.{digits}f}" if len(values) == 1 else f"{mean:.{digits}f} ± {sd:.{digits}f}"


def wall_links(bed, lens=0.2):
    """Particles within reach of the hot (top) and cold (bottom) wall: with the wall inside
    their gas lens (gap < lens r), or touching it."""
    import h5py
    with h5py.File(bed, "r") as f:
        z = np.array(f["particles/position"])[:, 2]
        r = np.array(f["particles/radius"])
        lo, hi = f["domain"].attrs["lower"][2], f["domain"].attrs["upper"][2]
    top, bottom = hi - z - r, z - r - lo
    touch = 1e-9 * r
    return (int(np.sum(top < lens * r)), int(np.sum(top <= touch)),
            int(np.sum(bottom < lens * r)), int(np.sum(bottom <= touch)))


def record(path, dep, wall):
    """A bed made elsewhere (keff_validation, keff_softening) with bedstat's summary (kept in
    WORK): dict with path, dep, stat, wall."""
    os.makedirs(WORK, exist_ok=True)
    meta = os.path.join(WORK, os.path.basename(path) + ".bedstat.json")
    if os.path.exists(meta):
        with open(meta) as f:
            stat = json.load(f)
    else:
        stat = bedstat([path], env=ENV)
        with open(meta, "w") as f:
            json.dump(stat, f)
    return {"path": path, "dep": dep, "stat": stat, "wall": wall}


def validation_bed(case, seed, depth=0.0):
    """keff_validation's bed of the case and seed: unconsolidated (depth 0) or with the lid
    lowered to `depth` particle radii below the surface, raised and relaxed."""
    d = next(c[2] for c in kv.CASES if c[0] == case)
    base = os.path.join(kv.WORK, f"{case}-seed{seed}.h5")
    common = [app("deposit"), "--config", kv.bed_scene(case), "--seed", str(seed), "--threads",
              "1"]
    os.makedirs(kv.WORK, exist_ok=True)
    dep, wall = kv.cached_run(base, common)
    if depth == 0:
        return record(base, dep, wall)
    path = os.path.join(kv.WORK, f"{case}-seed{seed}-depth{depth:g}.h5")
    dep, wall = kv.cached_run(path, common + ["--in", base, "--t-end", "1e-4", "--lid.enabled",
                                              "true", "--lid.depth", f"{depth * d / 2:.6g}"])
    return record(path, dep, wall)


def keff_scene(case="steel-1mm"):
    return os.path.join(SCENES, f"ke2016-{case}.ini")


def k_air(t):
    """The [KE] air conductivity of docs/physics.md §6 (W/mK, 175–1900 K)."""
    return 6.566e-12 * t ** 3 - 3.386e-8 * t ** 2 + 9.426e-5 * t + 7.505e-4


def radiation_number(t, d):
    """sigma T^3 D / k_g(T), [KE]'s measure of radiation against gas conduction."""
    return SIGMA * t ** 3 * d / k_air(t)


def crossing(d, target=0.5):
    """The temperature where sigma T^3 D / k_g(T) = target (bisection; it rises with T)."""
    lo, hi = 175.0, 1900.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if radiation_number(mid, d) < target else (lo, mid)
    return 0.5 * (lo + hi)


def deposit(name, seed, *extra, case="steel-1mm"):
    """A bed of the case's deposit scene with `extra` options (cached with its --json summary and
    bedstat's): dict with path, dep, stat, wall."""
    os.makedirs(WORK, exist_ok=True)
    path = os.path.join(WORK, f"{name}-seed{seed}.h5")
    meta = path + ".json"
    if os.path.exists(path) and os.path.exists(meta):
        with open(meta) as f:
            return json.load(f)
    dep, wall = run_json([app("deposit"), "--config", bed_scene(case), "--seed", str(seed),
                          "--threads", "1", "--out", path, *extra], env=ENV)
    stat = bedstat([path], env=ENV)
    bed = {"path": path, "dep": dep, "stat": stat, "wall": wall}
    with open(meta, "w") as f:
        json.dump(bed, f)
    print(f"deposit {name} seed {seed}: {wall:.1f} s, core density {dep['core_density']}",
          flush=True)
    return bed


def keff(bed, *extra, case="steel-1mm", core=True):
    """keff's --json summary on the bed (the case's keff scene), plus k_core (the core-gradient
    conductivity of keff_validation.core_gradient) when the bed is tall enough to have a core
    more than 2 D from both walls."""
    out = os.path.join(WORK, "keff-temperatures.h5")
    s, _ = run_json([app("keff"), "--config", keff_scene(case), "--bed", bed["path"], *extra,
                     "--out", out], env=ENV)
    if core:
        s["k_core"] = core_gradient(out, s)
    return s


def base_bed(seed=1):
    return validation_bed("steel-1mm", seed)


# ------------------------------------------------------------------------------------------------
# 1. Bed temperature, radiation off and on

def temperature_study():
    """k_eff at T (walls T ± 0.5 K), air k_g(T) per gas link, radiation off and on at eps 0.5 and
    0.9 (particles and walls), on the seed-1 steel 1 mm and 3.2 mm beds; the temperatures of the
    list plus the one where sigma T^3 D / k_g = 0.5."""
    rows = []
    for case, d in (("steel-1mm", 1.0e-3), ("steel-3.2mm", 3.2e-3)):
        bed = validation_bed(case, 1)
        t_star = crossing(d)
        for t in sorted(TEMPERATURES + [round(t_star, 1)]):
            base = ["--temperature", f"{t}", "--gas.model", "air", "--rays", str(RAYS)]
            runs = {"off": keff(bed, *base, case=case, core=False)}
            for eps in (0.5, 0.9):
                runs[eps] = keff(bed, *base, "--effects.radiation", "true",
                                 "--radiation.emissivity", f"{eps}",
                                 "--radiation.wall-emissivity", f"{eps}", case=case, core=False)
            rows.append({"case": case, "d": d, "t": t, "star": t == round(t_star, 1),
                         "number": radiation_number(t, d), "runs": runs})
            print(f"T {case} {t}: {runs['off']['k_eff']:.4f} {runs[0.5]['k_eff']:.4f} "
                  f"{runs[0.9]['k_eff']:.4f}", flush=True)
    return rows


# ------------------------------------------------------------------------------------------------
# 2. Gas-to-solid conductivity ratio

def ratio_study():
    """k_s = k_g / ratio on the seed-1 bed, contact + gas at 300 K (k_g 0.026 W/mK constant),
    against ZBS at the bed's core porosity."""
    bed = base_bed()
    k_g = scene_value(keff_scene(), "gas", "conductivity")
    eps_core = 1 - bed["dep"]["core_density"]
    rows = []
    for ratio in RATIOS:
        k_s = k_g / ratio
        s = keff(bed, "--solid.conductivity", f"{k_s:.6g}")
        rows.append({"ratio": ratio, "k_s": k_s, "k_g": k_g, "run": s,
                     "zbs": zbs(eps_core, 1 / ratio)})
    return eps_core, rows


# ------------------------------------------------------------------------------------------------
# 3. Young's modulus

def young_study():
    """(a) The seed-1 bed read as a material of modulus E (`--contact.young`: the Hertz
    correction k_n δ_s = (4/3) E* √R* δ_h^{3/2} at E, the packing the same). (b) The beds of
    keff_softening.py, deposited at k_n = 1e3 ... 1e6 N/m (seed 1), read with the Hertz
    correction at their own k_n and with the geometric contact radius."""
    bed = base_bed()
    e_nom = scene_value(bed_scene(), "material", "young") / 1e9
    k_bed = scene_value(bed_scene(), "contact", "stiffness")
    same = [(e, keff(bed, "--contact.young", f"{e * 1e9:.6g}")) for e in YOUNG]
    beds = []
    for k_n in STIFFNESS:
        for seed in SEEDS:
            if seed == 1:  # keff_softening.py's bed
                b = record(*softened_bed("steel-1mm", k_n))
            elif k_n == k_bed:
                b = base_bed(seed)
            else:
                b = deposit(f"steel-1mm-kn{k_n:g}", seed, "--contact.stiffness", f"{k_n:g}")
            beds.append({"k_n": k_n, "seed": seed, "bed": b, "hertz": keff(b),
                         "geometric": keff(b, "--contact.hertz-correction", "false")})
    return e_nom, k_bed, same, beds


# ------------------------------------------------------------------------------------------------
# 4. Emissivity

def emissivity_study():
    """k_eff and the radiation share at 1000 and 1500 K (air k_g, seed-1 bed) against the
    particles' emissivity, with the walls at the same emissivity and at the scene's 0.5 (the pair
    formula of docs/physics.md §6), and with both at ε in the radiosity model (the grey enclosure)."""
    bed = base_bed()
    wall_scene = scene_value(keff_scene(), "radiation", "wall-emissivity")
    rows = []
    for t in (1000, 1500):
        base = ["--temperature", f"{t}", "--gas.model", "air", "--rays", str(RAYS)]
        off = keff(bed, *base, core=False)
        for eps in EMISSIVITIES:
            both = keff(bed, *base, "--effects.radiation", "true", "--radiation.emissivity",
                        f"{eps}", "--radiation.wall-emissivity", f"{eps}", core=False)
            alone = keff(bed, *base, "--effects.radiation", "true", "--radiation.emissivity",
                         f"{eps}", "--radiation.wall-emissivity", f"{wall_scene}", core=False)
            radiosity = keff(bed, *base, "--effects.radiation", "true", "--radiation.model",
                             "radiosity", "--radiation.emissivity", f"{eps}",
                             "--radiation.wall-emissivity", f"{eps}", core=False)
            rows.append({"t": t, "eps": eps, "off": off, "both": both, "alone": alone,
                         "radiosity": radiosity})
    return wall_scene, rows


# ------------------------------------------------------------------------------------------------
# 5. Bed height

def height_study():
    """Boxes of 10 x 10 x H D filled by the scene's insertion (until full, top cropped at the
    highest particle top), seed 1: k_eff at 300 K, and at 1000 K with radiation (eps 0.5,
    air)."""
    rows = []
    for h in HEIGHTS:
        for seed in SEEDS:
            b = base_bed(seed) if h == 10 else deposit(
                f"steel-1mm-H{h}", seed, "--domain", f"{10 * D:g},{10 * D:g},{h * D:g}")
            cold = keff(b, core=False)
            hot = keff(b, "--temperature", "1000", "--gas.model", "air", "--effects.radiation",
                       "true", "--rays", str(RAYS), core=False)
            rows.append({"h": h, "seed": seed, "bed": b, "cold": cold, "hot": hot})
    return rows


# ------------------------------------------------------------------------------------------------
# 6. Polydispersity

def psd_spec(spread):
    """Gaussian on the diameter, mean D, sd spread D, truncated symmetrically at the mean
    ± min(2 sd, 0.75 D) (the mean stays D; the smallest sphere 0.25 D keeps the DEM step at a
    quarter of the monodisperse one). Returns (spec, count): the count gives the solid volume
    of the scene's pool of 1,400 spheres of D (the insertion stops when the box is full)."""
    if spread == 0:
        return f"mono:d={D:g}", 1400
    from scipy.stats import truncnorm
    sd = spread * D
    half = min(2 * sd, 0.75 * D)
    dist = truncnorm(-half / sd, half / sd, loc=D, scale=sd)
    count = round(1400 * D ** 3 / dist.moment(3))
    return (f"gauss:mean={D:g},sd={sd:.6g},min={D - half:.6g},max={D + half:.6g}", count)


def psd_study():
    rows = []
    for spread in SPREADS:
        spec, count = psd_spec(spread)
        for seed in SEEDS:
            b = (base_bed(seed) if spread == 0 else
                 deposit(f"steel-1mm-psd{spread:g}", seed, "--psd", spec, "--count", str(count)))
            rows.append({"spread": spread, "spec": spec, "count": count, "seed": seed, "bed": b,
                         "run": keff(b)})
    return rows


# ------------------------------------------------------------------------------------------------
# 7. Consolidation

def consolidation_study():
    """[KE]'s consolidation: keff_validation's beds, the lid lowered to 0.25-1 r below the
    surface of the unconsolidated bed, held, raised and relaxed; seed 1."""
    rows = []
    for depth in DEPTHS:
        for seed in SEEDS:
            b = validation_bed("steel-1mm", seed, depth)
            rows.append({"p": depth, "seed": seed, "bed": b, "run": keff(b)})
    return rows


# ------------------------------------------------------------------------------------------------
# Report

def groups(rows, key):
    out = {}
    for r in rows:
        out.setdefault(r[key], []).append(r)
    return out


def bed_panel(a, rows, key, xlabel, title, log_x):
    """k_eff of each bed (dots) and the means of k_eff and k_core over the seeds (lines) against
    the study's setting `key`, the mean core porosity on the right axis."""
    g = groups(rows, key)
    a.plot([r[key] for r in rows], [r["run"]["k_eff"] for r in rows], "o", color="C0", alpha=0.4)
    a.plot(list(g), [statistics.mean(r["run"]["k_eff"] for r in v) for v in g.values()],
           "-", color="C0", label="k_eff")
    a.plot(list(g), [statistics.mean(r["run"]["k_core"] for r in v) for v in g.values()],
           "--", color="C0", label="k_core")
    if log_x:
        a.set_xscale("log")
    a.set_xlabel(xlabel)
    a.set_ylabel("k (W/mK)")
    a.set_title(title)
    b = a.twinx()
    b.plot(list(g), [statistics.mean(1 - r["bed"]["dep"]["core_density"] for r in v)
                     for v in g.values()], "s:", color="C3", label="core porosity (right)")
    b.set_ylabel("core porosity")
    h1, l1 = a.get_legend_handles_labels()
    h2, l2 = b.get_legend_handles_labels()
    a.legend(h1 + h2, l1 + l2, fontsize=7)


def plot(temps, ratio, young, emis, heights, psd, cons):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(3, 3, figsize=(16, 13))
    a = ax[0, 0]
    for n, (case, rows) in enumerate(groups(temps, "case").items()):
        t = [r["t"] for r in rows]
        for style, key, name in (("-", "off", "no radiation"), ("--", 0.5, "ε 0.5"),
                                 (":", 0.9, "ε 0.9")):
            a.plot(t, [r["runs"][key]["k_eff"] for r in rows], style + "o", color=f"C{n}",
                   ms=3, label=f"{case}, {name}")
        a.axvline(crossing(rows[0]["d"]), color=f"C{n}", lw=0.8, alpha=0.5)
    a.set_xlabel("bed temperature T (K)")
    a.set_ylabel("k_eff (W/mK)")
    a.set_title("1. temperature (air k_g(T)); lines: σT³D/k_g = 0.5")
    a.legend(fontsize=7)
    a = ax[0, 1]
    for n, (case, rows) in enumerate(groups(temps, "case").items()):
        for marker, key in (("o", 0.5), ("s", 0.9)):
            a.plot([r["number"] for r in rows], [r["runs"][key]["share"]["radiation"]
                                                 for r in rows], marker + "-", color=f"C{n}",
                   ms=4, label=f"{case}, ε {key}")
    a.axvline(0.5, color="k", lw=0.8)
    a.set_xscale("log")
    a.set_xlabel("σT³D / k_g(T)")
    a.set_ylabel("radiation share of the heat flow")
    a.set_title("1. radiation share against [KE]'s number")
    a.legend(fontsize=7)
    a = ax[0, 2]
    eps_core, rows = ratio
    x = [r["ratio"] for r in rows]
    a.plot(x, [r["run"]["k_eff"] / r["k_g"] for r in rows], "o-", label="keff: k_eff / k_g")
    a.plot(x, [r["run"]["k_core"] / r["k_g"] for r in rows], "s--", label="keff: k_core / k_g")
    a.plot(x, [r["zbs"] for r in rows], "k:", label=f"ZBS (ε = {eps_core:.3f})")
    a.set_xscale("log")
    a.set_yscale("log")
    a.set_xlabel("k_g / k_s")
    a.set_ylabel("k_eff / k_g")
    a.set_title("2. gas-to-solid ratio (300 K, contact + gas)")
    b = a.twinx()
    b.plot(x, [r["run"]["share"]["contact"] for r in rows], "^-", color="C3", ms=4,
           label="contact share (right)")
    b.set_ylabel("contact share")
    b.set_ylim(0, 1)
    h1, l1 = a.get_legend_handles_labels()
    h2, l2 = b.get_legend_handles_labels()
    a.legend(h1 + h2, l1 + l2, fontsize=7, loc="lower left")
    a = ax[1, 0]
    e_nom, k_bed, same, beds = young
    a.plot([e for e, _ in same], [s["k_eff"] for _, s in same], "o-", label="k_eff")
    a.plot([e for e, _ in same], [s["k_core"] for _, s in same], "s--", label="k_core")
    a.axvline(e_nom, color="k", lw=0.8)
    a.set_xscale("log")
    a.set_xlabel("Young's modulus E read (GPa)")
    a.set_ylabel("k (W/mK)")
    a.set_title("3a. the same bed read at E (Hertz correction, 300 K)")
    a.legend(fontsize=7)
    a = ax[1, 1]
    g = groups(beds, "k_n")
    for key, marker, n, name in (("hertz", "o", 0, "Hertz correction at the bed's k_n"),
                                 ("geometric", "v", 2, "geometric a")):
        a.plot([r["k_n"] for r in beds], [r[key]["k_eff"] for r in beds], marker,
               color=f"C{n}", alpha=0.4)
        a.plot(list(g), [statistics.mean(r[key]["k_eff"] for r in v) for v in g.values()],
               "-", color=f"C{n}", label=f"k_eff, {name}")
        a.plot(list(g), [statistics.mean(r[key]["k_core"] for r in v) for v in g.values()],
               "--", color=f"C{n}", alpha=0.6, label=f"k_core, {name}")
    a.set_xscale("log")
    a.set_yscale("log")
    a.set_xlabel("DEM stiffness k_n (N/m) of the deposit ([KE]: 1e5)")
    a.set_ylabel("k (W/mK)")
    a.set_title(f"3b. beds deposited at k_n ({seeds_text()}, line: mean)")
    a.legend(fontsize=7)
    a = ax[1, 2]
    for n, (t, rows) in enumerate(groups(emis[1], "t").items()):
        eps = [r["eps"] for r in rows]
        a.plot(eps, [r["both"]["k_eff"] for r in rows], "o-", color=f"C{n}",
               label=f"{t} K, particles and walls")
        a.plot(eps, [r["alone"]["k_eff"] for r in rows], "s--", color=f"C{n}",
               label=f"{t} K, particles (walls 0.5)")
        a.plot(eps, [r["radiosity"]["k_eff"] for r in rows], "^-.", color=f"C{n}",
               label=f"{t} K, both, radiosity model")
        a.axhline(rows[0]["off"]["k_eff"], color=f"C{n}", lw=0.8, ls=":")
    a.set_xlabel("emissivity ε")
    a.set_ylabel("k_eff (W/mK)")
    a.set_title("4. emissivity (dotted: radiation off)")
    a.legend(fontsize=7)
    a = ax[2, 0]
    ref_cold = statistics.mean(r["cold"]["k_eff"] for r in heights if r["h"] == 10)
    ref_hot = statistics.mean(r["hot"]["k_eff"] for r in heights if r["h"] == 10)
    for key, ref, n, name in (("cold", ref_cold, 0, "300 K"),
                              ("hot", ref_hot, 1, "1000 K, radiation ε 0.5")):
        g = groups(heights, "h")
        a.plot([r["bed"]["dep"]["domain_top"] / D for r in heights],
               [r[key]["k_eff"] / ref for r in heights], "o", color=f"C{n}", alpha=0.4)
        a.plot([statistics.mean(r["bed"]["dep"]["domain_top"] / D for r in rows)
                for rows in g.values()],
               [statistics.mean(r[key]["k_eff"] for r in rows) / ref for rows in g.values()],
               "-", color=f"C{n}", label=name)
    a.set_xlabel("bed height H / D (floor to the highest particle top)")
    a.set_ylabel("k_eff / k_eff(10 D)")
    a.set_title(f"5. bed height ({seeds_text()}, line: mean)")
    a.legend(fontsize=7)
    bed_panel(ax[2, 1], psd, "spread", "σ / D (Gaussian on the diameter, nominal)",
              "6. polydispersity (same solid volume)", log_x=False)
    bed_panel(ax[2, 2], cons, "p", "lid depth below the surface (r; 0: unconsolidated)",
              f"7. consolidation ({seeds_text()}, line: mean)", log_x=False)
    fig.tight_layout()
    fig.savefig(os.path.join(RESULTS, "keff-parameters.png"), dpi=110)


def report(temps, ratio, young, emis, heights, psd, cons):
    L = [
        "# keff parameter studies ([KE])",
        "",
        "Generated by `bench/studies/keff_parameters.py`; regenerate with",
        "",
        "    POWDERBED_BUILD=build python3 bench/studies/keff_parameters.py"
        + ("" if len(SEEDS) == FULL_SEEDS else f" --seeds {len(SEEDS)}"),
        "",
        "(one thread). Beds: [KE]'s unconsolidated bed, `deposit --config "
        "data/scenes/ke2016-steel-1mm-bed.ini --seed S` (monodisperse steel spheres of 1 mm "
        "inserted from the top of a 10 D cube with a downward velocity until it is full, the "
        "linear spring–dashpot contact of [KE]'s MFiX-DEM runs, k_n = 1e5 N/m, settled; written "
        "with the top at the highest particle top, keff's hot wall) with each study's change on "
        "the command line; the scene's own beds and the consolidated ones are those of "
        "docs/results/keff-validation.md (bench/studies/keff_validation.py), the stiffness sweep "
        "those of keff_softening.py (docs/results/keff-accuracy.md). keff: `keff --config "
        "data/scenes/ke2016-steel-1mm.ini --bed BED` (k_s 28.555, k_g 0.026 W/mK, contacts with "
        "the Hertz correction read from the bed, k_n δ_s = (4/3) E* √R* δ_h^{3/2}; larger-lens "
        "gas region, walls at 305 / 295 K) with the study's options. k_eff is wall to wall; "
        "k_core the bed's core conductivity (heat flux over the mean temperature gradient of "
        "the particles more than 2 D from both walls, keff_validation.core_gradient), which on "
        "these beds is several times k_eff: the hot wall at the highest particle top touches "
        "few particles (keff-validation.md). Shares: each path's part of Σ G ΔT² "
        "(docs/keff.md).",
        "",
        "" + ("" if len(SEEDS) >= FULL_SEEDS and SPREADS[-1] >= FULL_SPREAD else
           "**Cut for compute time:** "
           + "; ".join(([f"{seeds_text()} in the bed studies, where the held-lid page had "
                         "seeds 1–3"] if len(SEEDS) < FULL_SEEDS else [])
                       + ([f"polydispersity to σ/D {SPREADS[-1]:g} (was 0.5: the smallest "
                           "sphere sets the DEM step)"] if SPREADS[-1] < FULL_SPREAD else []))
           + ". ")
        + "**Changed with the protocol (issue 13):** the DEM's softness is now the linear law's k_n, so "
        "3b sweeps k_n (keff_softening.py's beds for seed 1) where it swept the Hertz "
        "young-scale; consolidation is [KE]'s lid depth (0.25–1 r, the validation beds) in "
        "place of the held lid's pressure sweep. Single-case studies (1, 2, 3a, 4) are on the "
        "seed-1 bed. The seed-to-seed spread of the scene's bed (8 beds) is in "
        "keff-validation.md (Bed generation).",
        "",
        "**Published values.** docs/physics.md §6 records what [KE] found qualitatively (radiation matters "
        "above σT³D/k_g ≈ 0.5; thin beds lose up to half the conductivity; the other studies are "
        "named without results) and no k_eff values of [KE]'s studies, so nothing here is "
        "compared with a published number; where [KE] state a trend it is set beside ours.",
        "",
    ]
    L += temperature_section(temps)
    L += ratio_section(*ratio)
    L += young_section(*young)
    L += emissivity_section(*emis)
    L += height_section(heights)
    L += psd_section(psd)
    L += consolidation_section(cons)
    L += ["![the seven studies](keff-parameters.png)", ""]
    return "\n".join(L)


def temperature_section(temps):
    L = [
        "## 1. Bed temperature, with and without radiation",
        "",
        "`--temperature T` (walls at T ± 0.5 K), `--gas.model air` (docs/physics.md §6 k_g(T) at each gas "
        f"link), radiation off and on (`--effects.radiation true --rays {RAYS}`, particles and "
        "walls at ε 0.5 or 0.9), seed-1 beds of steel 1 mm and steel 3.2 mm (its own scenes). "
        "In bold: the temperature where σT³D/k_g(T) = 0.5.",
        "",
        "| bed | T (K) | k_g(T) (W/mK) | σT³D/k_g | k_eff, no radiation | contact / gas share | "
        "k_eff, ε 0.5 | radiation adds | radiation share | k_eff, ε 0.9 | radiation adds | "
        "radiation share |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in temps:
        off, e5, e9 = r["runs"]["off"], r["runs"][0.5], r["runs"][0.9]
        t = f"**{r['t']:g}**" if r["star"] else f"{r['t']:g}"
        L.append(f"| {r['case']} | {t} | {k_air(r['t']):.4f} | {r['number']:.3f} | "
               f"{off['k_eff']:.4f} | {off['share']['contact']:.3f} / {off['share']['gas']:.3f} | "
               f"{e5['k_eff']:.4f} | {(e5['k_eff'] / off['k_eff'] - 1) * 100:+.1f} % | "
               f"{e5['share']['radiation']:.3f} | {e9['k_eff']:.4f} | "
               f"{(e9['k_eff'] / off['k_eff'] - 1) * 100:+.1f} % | "
               f"{e9['share']['radiation']:.3f} |")
    find = []
    for case, rows in groups(temps, "case").items():
        star = next(r for r in rows if r["star"])
        hot = rows[-1]
        off, e5 = star["runs"]["off"], star["runs"][0.5]
        find.append(
            f"{case}: σT³D/k_g = 0.5 at {star['t']:.0f} K, where radiation (ε 0.5) adds "
            f"{(e5['k_eff'] / off['k_eff'] - 1) * 100:.0f} % (share "
            f"{e5['share']['radiation']:.2f}); at {hot['t']:g} K it adds "
            f"{(hot['runs'][0.5]['k_eff'] / hot['runs']['off']['k_eff'] - 1) * 100:.0f} % "
            f"(ε 0.5) and {(hot['runs'][0.9]['k_eff'] / hot['runs']['off']['k_eff'] - 1) * 100:.0f}"
            f" % (ε 0.9)")
    cold = [rows[0] for rows in groups(temps, "case").values()]
    hottest = groups(temps, "case")["steel-1mm"][-1]
    L += [
        "",
        "**Findings.** " + "; ".join(find) + ". At 300 K radiation adds "
        + " and ".join(f"{(r['runs'][0.5]['k_eff'] / r['runs']['off']['k_eff'] - 1) * 100:.1f} %"
                       for r in cold)
        + " (1 mm, 3.2 mm). Without radiation k_eff rises with T through k_g(T) alone "
        f"({cold[0]['runs']['off']['k_eff']:.3f} → {hottest['runs']['off']['k_eff']:.3f} W/mK "
        "for 1 mm, 300 → 1500 K). Below σT³D/k_g = 0.5 radiation (ε 0.5) adds at most "
        + " and ".join(f"{max((r['runs'][0.5]['k_eff'] / r['runs']['off']['k_eff'] - 1) * 100 for r in rows if r['number'] < 0.5):.0f} %"
                       for rows in groups(temps, "case").values())
        + " (1 mm, 3.2 mm). [KE] (docs/physics.md §6): radiation matters above σT³D/k_g ≈ 0.5. These are "
        "wall-to-wall values on unconsolidated beds, whose hot wall touches few particles; "
        "radiation also crosses that open top layer, so its share here includes the wall "
        "layer's.",
        "",
    ]
    return L


def ratio_section(eps_core, rows):
    L = [
        "## 2. Gas-to-solid conductivity ratio",
        "",
        f"Seed-1 bed, 300 K, contact + gas, k_g = {rows[0]['k_g']:g} W/mK, k_s = k_g / ratio. "
        "ZBS: Zehner–Bauer–Schlünder (point contacts, no radiation; keff_validation.zbs) at the "
        f"bed's core porosity {eps_core:.3f}.",
        "",
        "| k_g / k_s | k_s (W/mK) | k_eff (W/mK) | k_eff / k_g | k_core / k_g | ZBS k/k_g | "
        "k_core / ZBS | contact share | gas share |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        s = r["run"]
        L.append(f"| {r['ratio']:g} | {r['k_s']:.4g} | {s['k_eff']:.4f} | "
                 f"{s['k_eff'] / r['k_g']:.2f} | {s['k_core'] / r['k_g']:.2f} | {r['zbs']:.2f} | "
                 f"{s['k_core'] / r['k_g'] / r['zbs']:.2f} | {s['share']['contact']:.3f} | "
                 f"{s['share']['gas']:.3f} |")
    lo, hi = rows[0], rows[-1]
    cross = [(a, b) for a, b in zip(rows, rows[1:])
             if a["run"]["share"]["contact"] >= 0.5 > b["run"]["share"]["contact"]]
    L += [
        "",
        f"**Findings.** From k_g/k_s = {hi['ratio']:g} to {lo['ratio']:g} k_eff/k_g rises from "
        f"{hi['run']['k_eff'] / hi['k_g']:.2f} to {lo['run']['k_eff'] / lo['k_g']:.2f} "
        f"(ZBS {hi['zbs']:.2f} to {lo['zbs']:.2f}); the contact share from "
        f"{hi['run']['share']['contact']:.3f} to {lo['run']['share']['contact']:.3f}"
        + (f", passing one half between k_g/k_s = {cross[0][0]['ratio']:g} and "
           f"{cross[0][1]['ratio']:g}" if cross else "")
        + ". keff's particles are isothermal and k_s enters only through the contact "
        "conductance 2 k_s a, while ZBS conducts through the solid in series; k_core / ZBS is "
        f"{hi['run']['k_core'] / hi['k_g'] / hi['zbs']:.2f} at k_g/k_s = {hi['ratio']:g} and "
        f"{lo['run']['k_core'] / lo['k_g'] / lo['zbs']:.2f} at {lo['ratio']:g}. k_eff here is "
        f"{lo['run']['k_eff'] / lo['run']['k_core']:.2f}–"
        f"{hi['run']['k_eff'] / hi['run']['k_core']:.2f} of k_core: the unconsolidated bed's "
        "hot-wall layer. [KE] studied the ratio (docs/physics.md §6) without a stated result "
        "to compare with.",
        "",
    ]
    return L


def young_section(e_nom, k_bed, same, beds):
    ref = next(s for e, s in same if e == round(e_nom))
    L = [
        "## 3. Young's modulus and the DEM stiffness",
        "",
        f"(a) The seed-1 bed (deposited with the linear law at k_n = {k_bed:g} N/m; E_nom = "
        f"{e_nom:g} GPa in its record) read as a material of modulus E (`--contact.young`): the "
        "Hertz correction k_n δ_s = (4/3) E* √R* δ_h^{3/2} gives the overlap of a Hertz contact "
        "at E under the bed's forces, so a ∝ E^(-1/3) at the same packing. 300 K, contact + gas.",
        "",
        "| E (GPa) | k_eff (W/mK) | vs E_nom | k_core (W/mK) | vs E_nom | contact share |",
        "|---|---|---|---|---|---|",
    ]
    for e, s in same:
        L.append(f"| {e:g} | {s['k_eff']:.4f} | {(s['k_eff'] / ref['k_eff'] - 1) * 100:+.1f} % | "
                 f"{s['k_core']:.4f} | {(s['k_core'] / ref['k_core'] - 1) * 100:+.1f} % | "
                 f"{s['share']['contact']:.3f} |")
    L += [
        "",
        "(b) The beds of keff_softening.py: the scene's bed deposited at k_n = "
        + ", ".join(f"{k:g}" for k in STIFFNESS) + f" N/m ({seeds_text()}), read with the Hertz "
        "correction at their own k_n (the contacts of the real steel) and with the geometric "
        "radius of the soft overlap (what a soft bed gives without the correction).",
        "",
        "| k_n (N/m) | max overlap / r | core porosity | Z (bedstat) | k_eff, Hertz | "
        "k_eff, geometric | geometric / Hertz | k_core, Hertz | k_core, geometric | "
        "contact share, Hertz / geometric | deposit wall (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    by = groups(beds, "k_n")
    for k_n, rs in by.items():
        h = [r["hertz"]["k_eff"] for r in rs]
        g = [r["geometric"]["k_eff"] for r in rs]
        L.append(
            f"| {k_n:g} | "
            f"{statistics.mean(r['bed']['dep']['max_overlap_m'] for r in rs) / (D / 2):.2e} | "
            f"{pm([1 - r['bed']['dep']['core_density'] for r in rs], 3)} | "
            f"{pm([r['bed']['stat']['coordination'] for r in rs], 2)} | {pm(h)} | {pm(g)} | "
            f"{statistics.mean(g) / statistics.mean(h):.2f} | "
            f"{pm([r['hertz']['k_core'] for r in rs])} | "
            f"{pm([r['geometric']['k_core'] for r in rs])} | "
            f"{statistics.mean(r['hertz']['share']['contact'] for r in rs):.3f} / "
            f"{statistics.mean(r['geometric']['share']['contact'] for r in rs):.3f} | "
            f"{statistics.median(r['bed']['wall'] for r in rs):.0f} |")
    lo, hi = same[0], same[-1]
    hc = [statistics.mean(r["hertz"]["k_core"] for r in rs) for rs in by.values()]
    gc = [statistics.mean(r["geometric"]["k_core"] for r in rs) for rs in by.values()]
    L += [
        "",
        f"**Findings.** (a) From E = {lo[0]:g} to {hi[0]:g} GPa the same packing's k_eff goes "
        f"from {lo[1]['k_eff']:.4f} to {hi[1]['k_eff']:.4f} W/mK and k_core from "
        f"{lo[1]['k_core']:.4f} to {hi[1]['k_core']:.4f} "
        f"({(lo[1]['k_core'] / hi[1]['k_core'] - 1) * 100:.0f} % more at the soft end), the "
        f"contact share from {lo[1]['share']['contact']:.2f} to {hi[1]['share']['contact']:.2f}: "
        "only the contact path depends on E. (b) With the Hertz correction k_core over k_n = "
        f"{STIFFNESS[0]:g}–{STIFFNESS[-1]:g} N/m is "
        + ", ".join(f"{v:.4f}" for v in hc)
        + f" W/mK (spread {(max(hc) - min(hc)) / statistics.mean(hc) * 100:.0f} % of the mean); "
        "with the geometric radius "
        + ", ".join(f"{v:.4f}" for v in gc)
        + " W/mK: without the correction the contacts grow as the DEM softens. [KE] studied E "
        "(docs/physics.md §6) without a stated result to compare with.",
        "",
    ]
    return L


def emissivity_section(wall_scene, rows):
    L = [
        "## 4. Emissivity",
        "",
        f"Seed-1 bed at 1000 and 1500 K (walls T ± 0.5 K), air k_g(T), {RAYS} rays (the same "
        "view factors for every ε: `radiation.seed` 1). 'Particles and walls': both at ε; "
        f"'particles': walls at the scene's {wall_scene:g}. The pair formula of docs/physics.md §6, and the "
        "radiosity model (`--radiation.model radiosity`: the grey enclosure, one radiosity node "
        "per surface, docs/keff.md) with particles and walls at ε.",
        "",
        "| T (K) | ε | k_eff, particles and walls | radiation share | k_eff, particles | "
        "radiation share | k_eff, radiosity model | radiation share | k_eff, radiation off |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        L.append(f"| {r['t']} | {r['eps']:g} | {r['both']['k_eff']:.4f} | "
                 f"{r['both']['share']['radiation']:.3f} | {r['alone']['k_eff']:.4f} | "
                 f"{r['alone']['share']['radiation']:.3f} | {r['radiosity']['k_eff']:.4f} | "
                 f"{r['radiosity']['share']['radiation']:.3f} | {r['off']['k_eff']:.4f} |")
    find = []
    for t, g in groups(rows, "t").items():
        lo, hi = g[0], g[-1]
        find.append(
            f"At {t} K, ε {lo['eps']:g} → {hi['eps']:g} raises k_eff by "
            f"{(hi['both']['k_eff'] / lo['both']['k_eff'] - 1) * 100:.0f} % with the walls "
            f"(radiation share {lo['both']['share']['radiation']:.2f} → "
            f"{hi['both']['share']['radiation']:.2f}) and by "
            f"{(hi['alone']['k_eff'] / lo['alone']['k_eff'] - 1) * 100:.0f} % for the particles "
            "alone; in the radiosity model by "
            f"{(hi['radiosity']['k_eff'] / lo['radiosity']['k_eff'] - 1) * 100:.0f} % (radiation "
            f"share {lo['radiosity']['share']['radiation']:.2f} → "
            f"{hi['radiosity']['share']['radiation']:.2f})")
    L += [
        "",
        "**Findings.** " + ". ".join(find) + ". The pair formula of docs/physics.md §6 1/G = (1−ε)/(εA_i) + "
        "1/(A_i F_ij) + (1−ε)/(εA_j) adds each sphere's whole surface resistance to every one of "
        "its ~10 links, but with F_ij ≈ 0.1 the space term 1/(A F_ij) dominates until ε is "
        "small, and a wall's surface resistance is charged over each particle's area rather "
        "than the wall's (docs/keff.md). In the grey enclosure a sphere's ε acts only where it "
        "trades heat between conduction and radiation, and the walls' ε over their whole area. "
        "[KE] studied ε 0.1–1 (docs/physics.md §6) without a stated result to compare with.",
        "",
    ]
    return L


def height_section(rows):
    g = groups(rows, "h")
    ref_cold = statistics.mean(r["cold"]["k_eff"] for r in g[10])
    ref_hot = statistics.mean(r["hot"]["k_eff"] for r in g[10])
    L = [
        "## 5. Bed height",
        "",
        "A 10 × 10 × H D box filled by the scene's insertion until full (`--domain "
        f"0.01,0.01,H`), unconsolidated, {seeds_text()}. k_eff at 300 K (scene) and at 1000 K with "
        f"radiation (ε 0.5, air k_g(T), {RAYS} rays). H/D (measured) is keff's wall-to-wall "
        "distance, floor to the highest particle top.",
        "",
        "| H/D nominal | particles | H/D (floor to the hot wall) | box porosity | k_eff 300 K (W/mK) | "
        "/ k_eff(10 D) | contact share | k_eff 1000 K, radiation | / k_eff(10 D) | "
        "radiation share |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for h, rs in g.items():
        c = [r["cold"]["k_eff"] for r in rs]
        w = [r["hot"]["k_eff"] for r in rs]
        L.append(
            f"| {h} | {statistics.mean(r['cold']['particles'] for r in rs):.0f} | "
            f"{pm([r['bed']['dep']['domain_top'] / D for r in rs], 2)} | "
            f"{pm([1 - r['bed']['stat']['box_density'] for r in rs], 3)} | {pm(c)} | "
            f"{statistics.mean(c) / ref_cold:.2f} | "
            f"{statistics.mean(r['cold']['share']['contact'] for r in rs):.3f} | {pm(w)} | "
            f"{statistics.mean(w) / ref_hot:.2f} | "
            f"{statistics.mean(r['hot']['share']['radiation'] for r in rs):.3f} |")
    rel = {h: statistics.mean(r["cold"]["k_eff"] for r in rs) / ref_cold for h, rs in g.items()}
    rel_hot = {h: statistics.mean(r["hot"]["k_eff"] for r in rs) / ref_hot
               for h, rs in g.items()}
    L += [
        "",
        "**Findings.** Relative to the 10 D bed, k_eff at 300 K is "
        + ", ".join(f"{rel[h]:.2f}" for h in HEIGHTS[:-1])
        + " at H/D = " + ", ".join(f"{h}" for h in HEIGHTS[:-1])
        + "; at 1000 K with radiation " + ", ".join(f"{rel_hot[h]:.2f}" for h in HEIGHTS[:-1])
        + f" ({seeds_text()}). The 300 K k_eff of an unconsolidated bed is set by the few "
        "particles under the hot wall at the highest particle top: on the 10 D bed its "
        f"seed-to-seed σ is {seed_spread()} of its mean (keff-validation.md, Bed generation), "
        "so the ratios between 2 and 10 D carry that scatter; with radiation, which crosses "
        "the open top layer, they are smoother. At 1 D the insertion stops with "
        f"{statistics.mean(r['cold']['particles'] for r in g[1]):.0f} spheres, an incomplete "
        "monolayer whose spheres each reach both walls, so its k_eff is not that of a thin "
        "bed. [KE] (docs/physics.md §6): thin beds lose up to half the conductivity; ours, relative to "
        f"10 D: {rel[2]:.2f} at 2 D and {rel[3]:.2f} at 3 D at 300 K, {rel_hot[2]:.2f} and "
        f"{rel_hot[3]:.2f} at 1000 K with radiation.",
        "",
    ]
    return L


def seed_spread():
    """The relative sd of k_eff over keff_validation's bed-generation seeds (bed-seeds.json), as
    text, or 'not measured' when that study has not run."""
    path = os.path.join(kv.WORK, "bed-seeds.json")
    if not os.path.exists(path):
        return "not measured"
    with open(path) as f:
        k = [r["k_eff"] for r in json.load(f).values()]
    return (f"{statistics.stdev(k) / statistics.mean(k) * 100:.0f} % ({len(k)} seeds)"
            if len(k) > 1 else "not measured")


def rel_sd(bed):
    """The sampled sd of the radius over its mean (bedstat)."""
    return bed["stat"]["radius"]["sd"] / bed["stat"]["radius"]["mean"]


def box_porosity(rows):
    return statistics.mean(1 - r["bed"]["stat"]["box_density"] for r in rows)


def psd_section(rows):
    g = groups(rows, "spread")
    L = [
        "## 6. Polydispersity",
        "",
        "Gaussian on the diameter, mean 1 mm, sd σ, truncated symmetrically at 1 mm ± min(2σ, "
        "0.75 mm) (so the mean stays 1 mm), the pool chosen for the solid volume of the scene's "
        f"1,400 spheres of 1 mm (the insertion stops when the box is full); unconsolidated, "
        f"{seeds_text()}"
        + (f"; σ/D up to {SPREADS[-1]:g} only (compute time). " if SPREADS[-1] < FULL_SPREAD else
           "; σ/D 0.4 and 0.5 are cut at 0.25–1.75 mm, so their sampled sd is below the nominal "
           "σ. ")
        + "Sampled σ/D: bedstat's radius sd over its mean.",
        "",
        "| σ/D nominal | --psd | pool / particles in the bed | sampled σ/D | core porosity | box porosity | "
        "Z (bedstat) | k_eff (W/mK) | k_core (W/mK) | contact share | deposit wall (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for spread, rs in g.items():
        L.append(
            f"| {spread:g} | `{rs[0]['spec']}` | {rs[0]['count']} / "
            f"{statistics.mean(r['bed']['dep']['n'] for r in rs):.0f} | "
            f"{statistics.mean(rel_sd(r['bed']) for r in rs):.3f} | "
            f"{pm([1 - r['bed']['dep']['core_density'] for r in rs], 3)} | "
            f"{pm([1 - r['bed']['stat']['box_density'] for r in rs], 3)} | "
            f"{pm([r['bed']['stat']['coordination'] for r in rs], 2)} | "
            f"{pm([r['run']['k_eff'] for r in rs])} | {pm([r['run']['k_core'] for r in rs])} | "
            f"{statistics.mean(r['run']['share']['contact'] for r in rs):.3f} | "
            f"{statistics.median(r['bed']['wall'] for r in rs):.0f} |")
    k = {s: statistics.mean(r["run"]["k_eff"] for r in rs) for s, rs in g.items()}
    por = {s: statistics.mean(1 - r["bed"]["dep"]["core_density"] for r in rs)
           for s, rs in g.items()}
    z = {s: statistics.mean(r["bed"]["stat"]["coordination"] for r in rs) for s, rs in g.items()}
    kc = {s: statistics.mean(r["run"]["k_core"] for r in rs) for s, rs in g.items()}
    top = SPREADS[-1]
    L += [
        "",
        f"**Findings.** From σ/D 0 to {top:g} the core porosity goes {por[0.0]:.3f} → "
        f"{por[top]:.3f}, Z {z[0.0]:.2f} → {z[top]:.2f}, k_eff {k[0.0]:.4f} → {k[top]:.4f} W/mK "
        f"({(k[top] / k[0.0] - 1) * 100:+.0f} %), k_core {kc[0.0]:.4f} → {kc[top]:.4f} W/mK "
        f"({(kc[top] / kc[0.0] - 1) * 100:+.0f} %); box porosity "
        f"{box_porosity(g[top]) - box_porosity(g[0.0]):+.3f}. The seed-to-seed σ of "
        f"k_eff on the monodisperse bed is {seed_spread()} of its mean (keff-validation.md, "
        "Bed generation): read a trend in k_eff against it. [KE] studied σ/D up "
        "to 0.5 (docs/physics.md §6) without a stated result to compare with.",
        "",
    ]
    return L


def consolidation_section(rows):
    g = groups(rows, "p")
    L = [
        "## 7. Consolidation",
        "",
        "[KE]'s consolidation: the unconsolidated bed with the top wall lowered to 0.25, 0.5, "
        "0.75 and 1 particle radius below its surface (the 90th percentile of the particle "
        "tops), held, raised back at its speed and relaxed (`--lid.enabled true --lid.depth L`, "
        f"docs/deposit-lid.md), the beds of keff-validation.md ({seeds_text()}); keff's hot wall at the "
        "highest particle top of the relaxed bed. Lid force: the largest during the press. "
        "Within reach of the hot wall / touching it: particles with the wall inside their gas "
        "lens (0.2 r) / overlapping it (wall_links); the same for the floor.",
        "",
        "| lid depth (r) | lid travel (D) | largest lid force (N) | hot wall: in lens / touching "
        "| floor: in lens / touching | core porosity | box porosity | Z (bedstat) | "
        "k_eff (W/mK) | k_core (W/mK) | k_eff / k_core | contact share |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for p, rs in g.items():
        lid = [r["bed"]["dep"].get("lid", {}) for r in rs]
        links = [wall_links(r["bed"]["path"]) for r in rs]
        L.append(
            f"| {p:g} | {statistics.mean(x.get('travel', 0.0) for x in lid) / D:.2f} | "
            f"{statistics.mean(x.get('max_force', 0.0) for x in lid):.3g} | "
            f"{statistics.mean(x[0] for x in links):.0f} / {statistics.mean(x[1] for x in links):.0f} | "
            f"{statistics.mean(x[2] for x in links):.0f} / {statistics.mean(x[3] for x in links):.0f} | "
            f"{pm([1 - r['bed']['dep']['core_density'] for r in rs], 3)} | "
            f"{pm([1 - r['bed']['stat']['box_density'] for r in rs], 3)} | "
            f"{pm([r['bed']['stat']['coordination'] for r in rs], 2)} | "
            f"{pm([r['run']['k_eff'] for r in rs])} | {pm([r['run']['k_core'] for r in rs])} | "
            f"{statistics.mean(r['run']['k_eff'] / r['run']['k_core'] for r in rs):.2f} | "
            f"{statistics.mean(r['run']['share']['contact'] for r in rs):.3f} |")
    k = {p: statistics.mean(r["run"]["k_eff"] for r in rs) for p, rs in g.items()}
    kc = {p: statistics.mean(r["run"]["k_core"] for r in rs) for p, rs in g.items()}
    allk = [r["run"]["k_eff"] for r in rows]
    allc = [r["run"]["k_core"] for r in rows]
    mean, lo, hi, sd = summary(allk)
    cmean, clo, chi, csd = summary(allc)
    L += [
        "",
        "**Findings.** k_eff goes " + " → ".join(f"{k[p]:.4f}" for p in DEPTHS)
        + " W/mK and k_core " + " → ".join(f"{kc[p]:.4f}" for p in DEPTHS)
        + f" W/mK from the unconsolidated bed to the lid at {DEPTHS[-1]:g} r. Over the "
        f"{len(rows)} beds (the consolidation uncertainty of [KE]) k_eff = {mean:.4f} ± "
        f"{sd:.4f} W/mK ({sd / mean * 100:.0f} %, range {lo:.4f}–{hi:.4f}), k_core = "
        f"{cmean:.4f} ± {csd:.4f} ({csd / cmean * 100:.0f} %). The press flattens the top, so "
        "more particles reach the hot wall and k_eff jumps from the unconsolidated bed to any "
        "depth; k_core, the bed's own, moves by a few per cent.",
        "",
    ]
    return L


def main():
    global SEEDS
    if "--seeds" in sys.argv:
        SEEDS = list(range(1, int(sys.argv[sys.argv.index("--seeds") + 1]) + 1))
    temps = temperature_study()
    ratio = ratio_study()
    young = young_study()
    emis = emissivity_study()
    heights = height_study()
    psd = psd_study()
    cons = consolidation_study()
    plot(temps, ratio, young, emis, heights, psd, cons)
    print(write_text("keff-parameters.md", report(temps, ratio, young, emis, heights, psd, cons)))


if __name__ == "__main__":
    main()
