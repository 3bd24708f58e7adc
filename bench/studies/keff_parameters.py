#!/usr/bin/env python3
"""The [KE] parameter studies with keff (SPEC.md §6, issue 6): bed temperature with and without
radiation, gas-to-solid conductivity ratio, Young's modulus, emissivity, bed height,
polydispersity and consolidation, on steel 1 mm beds. Writes docs/results/keff-parameters.md and
keff-parameters.png. Run with /usr/bin/python3 (one thread):
    POWDERBED_BUILD=build /usr/bin/python3 bench/studies/keff_parameters.py

Beds come from `deposit --config data/scenes/ke2016-steel-1mm-held-lid-bed.ini --seed S` with the study's
changes on the command line (lid kept as keff's hot wall) and are kept in
out/studies/keff-parameters/ (about fifteen minutes of one core the first time; a bed that is
there is reused). keff runs with data/scenes/ke2016-steel-1mm.ini (contacts read with the Hertz
correction at the bed's softening).
"""
import json
import os
import statistics

from common import ROOT, RESULTS, app, run_json, summary, write_text
from keff_validation import core_gradient, pm, scene_value, wall_links, zbs

WORK = os.path.join(ROOT, "out", "studies", "keff-parameters")
SCENES = os.path.join(ROOT, "data", "scenes")
ENV = dict(os.environ, OMP_NUM_THREADS="1")
SIGMA = 5.670374419e-8  # Stefan–Boltzmann, W/m^2K^4
SEEDS = [1, 2, 3]
D = 1.0e-3  # the steel case's diameter (m)
TEMPERATURES = [300, 500, 700, 900, 1100, 1300, 1500]
EMISSIVITIES = [0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.0]
RATIOS = [1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1]  # k_g / k_s
YOUNG = [1, 3, 10, 30, 100, 198, 300, 1000]  # GPa, the same bed read at E
BED_SCALES = [10, 100, 1000, 10000]  # young-scale of re-deposited beds
HEIGHTS = [1, 2, 3, 5, 7, 10]  # H/D
SPREADS = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]  # sigma/D
PRESSURES = [1e2, 1e3, 3e3, 1e4, 3e4, 1e5]  # lid pressure, Pa (the scene: 1e4)
RAYS = 1000


def bed_scene(case="steel-1mm"):
    return os.path.join(SCENES, f"ke2016-{case}-held-lid-bed.ini")


def keff_scene(case="steel-1mm"):
    return os.path.join(SCENES, f"ke2016-{case}.ini")


def k_air(t):
    """The [KE] air conductivity of SPEC §6 (W/mK, 175–1900 K)."""
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
    stat, _ = run_json([app("bedstat"), path], env=ENV)
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
        s.update(core_gradient(out, s))
    return s


def base_bed(seed=1):
    return deposit("steel-1mm", seed)


# ------------------------------------------------------------------------------------------------
# 1. Bed temperature, radiation off and on

def temperature_study():
    """k_eff at T (walls T ± 0.5 K), air k_g(T) per gas link, radiation off and on at eps 0.5 and
    0.9 (particles and walls), on the seed-1 steel 1 mm and 3.2 mm beds; the temperatures of the
    list plus the one where sigma T^3 D / k_g = 0.5."""
    rows = []
    for case, d in (("steel-1mm", 1.0e-3), ("steel-3.2mm", 3.2e-3)):
        bed = deposit(case, 1, case=case)
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
    """(a) The seed-1 bed read as a material of modulus E: the bed settled at E_nom / S_bed, and
    under the same forces a Hertz contact at E has the overlap delta_s (E_nom / (S_bed E))^(2/3),
    which is keff's reading at young-scale S_bed E / E_nom. (b) Beds deposited at young-scale S
    (E_nom / S in the DEM), read with the Hertz correction at their own S and with the geometric
    contact radius."""
    bed = base_bed()
    e_nom = scene_value(bed_scene(), "material", "young") / 1e9
    s_bed = scene_value(bed_scene(), None, "young-scale")
    same = [(e, keff(bed, "--contact.young-scale", f"{s_bed * e / e_nom:.6g}")) for e in YOUNG]
    beds = []
    for scale in BED_SCALES:
        for seed in SEEDS:
            b = (base_bed(seed) if scale == s_bed else
                 deposit(f"steel-1mm-S{scale:g}", seed, "--young-scale", f"{scale:g}"))
            hertz = keff(b, "--contact.young-scale", f"{scale:g}")
            geometric = keff(b, "--contact.hertz-correction", "false")
            beds.append({"scale": scale, "seed": seed, "bed": b, "hertz": hertz,
                         "geometric": geometric})
    return e_nom, s_bed, same, beds


# ------------------------------------------------------------------------------------------------
# 4. Emissivity

def emissivity_study():
    """k_eff and the radiation share at 1000 and 1500 K (air k_g, seed-1 bed) against the
    particles' emissivity, with the walls at the same emissivity and at the scene's 0.5 (SPEC's
    pair formula), and with both at ε in the radiosity model (the grey enclosure)."""
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
    """Beds of 110 H/D spheres in the same 10 x 10 D box (lid kept, 1e4 Pa), seeds 1-3: k_eff at
    300 K, and at 1000 K with radiation (eps 0.5, air)."""
    rows = []
    for h in HEIGHTS:
        for seed in SEEDS:
            b = base_bed(seed) if h == 10 else deposit(f"steel-1mm-H{h}", seed, "--count",
                                                       str(110 * h))
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
    of 1,100 spheres of D."""
    if spread == 0:
        return f"mono:d={D:g}", 1100
    from scipy.stats import truncnorm
    sd = spread * D
    half = min(2 * sd, 0.75 * D)
    dist = truncnorm(-half / sd, half / sd, loc=D, scale=sd)
    count = round(1100 * D ** 3 / dist.moment(3))
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
    """Lid pressures 1e2 (about a fifth of the bed's weight per area: the lid only touches)
    to 1e5 Pa, lid kept, seeds 1-3."""
    rows = []
    for p in PRESSURES:
        for seed in SEEDS:
            b = (base_bed(seed) if p == 1e4 else
                 deposit(f"steel-1mm-P{p:g}", seed, "--lid.pressure", f"{p:g}"))
            rows.append({"p": p, "seed": seed, "bed": b, "run": keff(b)})
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
    e_nom, s_bed, same, beds = young
    a.plot([e for e, _ in same], [s["k_eff"] for _, s in same], "o-", label="k_eff")
    a.plot([e for e, _ in same], [s["k_core"] for _, s in same], "s--", label="k_core")
    a.axvline(e_nom, color="k", lw=0.8)
    a.set_xscale("log")
    a.set_xlabel("Young's modulus E read (GPa)")
    a.set_ylabel("k (W/mK)")
    a.set_title("3a. the same bed read at E (Hertz a, 300 K)")
    a.legend(fontsize=7)
    a = ax[1, 1]
    g = groups(beds, "scale")
    for key, marker, n, name in (("hertz", "o", 0, "Hertz a at the bed's S"),
                                 ("geometric", "v", 2, "geometric a")):
        a.plot([r["scale"] for r in beds], [r[key]["k_eff"] for r in beds], marker,
               color=f"C{n}", alpha=0.4)
        a.plot(list(g), [statistics.mean(r[key]["k_eff"] for r in rows) for rows in g.values()],
               "-", color=f"C{n}", label=name)
    a.set_xscale("log")
    a.set_yscale("log")
    a.set_xlabel("deposit young-scale S (DEM modulus 198 GPa / S)")
    a.set_ylabel("k_eff (W/mK)")
    a.set_title("3b. beds deposited softened (seeds 1-3, line: mean)")
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
    a.set_xlabel("bed height H / D (floor to lid; 110, 220, ... 1100 spheres)")
    a.set_ylabel("k_eff / k_eff(10 D)")
    a.set_title("5. bed height (seeds 1-3, line: mean)")
    a.legend(fontsize=7)
    bed_panel(ax[2, 1], psd, "spread", "σ / D (Gaussian on the diameter, nominal)",
              "6. polydispersity (same solid volume)", log_x=False)
    bed_panel(ax[2, 2], cons, "p", "lid pressure (Pa)", "7. consolidation (seeds 1-3, line: mean)",
              log_x=True)
    fig.tight_layout()
    fig.savefig(os.path.join(RESULTS, "keff-parameters.png"), dpi=110)


def report(temps, ratio, young, emis, heights, psd, cons):
    L = [
        "# keff parameter studies ([KE])",
        "",
        "Generated by `bench/studies/keff_parameters.py`; regenerate with",
        "",
        "    POWDERBED_BUILD=build /usr/bin/python3 bench/studies/keff_parameters.py",
        "",
        "(one thread; the beds are cached in out/studies/keff-parameters/, about fifteen minutes "
        "of one core the first time). Beds: `deposit --config data/scenes/ke2016-steel-1mm-held-lid-bed.ini "
        "--seed S` (1,100 monodisperse steel spheres of 1 mm in a box of 10 × 10 D, settled, "
        "pressed by the lid at 1e4 Pa, which stays as the bed's top face: keff's hot wall; "
        "docs/deposit-lid.md) with each study's change on the command line. keff: `keff --config "
        "data/scenes/ke2016-steel-1mm.ini --bed BED` (k_s 28.555, k_g 0.026 W/mK, contacts read "
        "with the Hertz correction at the bed's softening S = 1e3, larger-lens gas region, walls "
        "at 305 / 295 K) with the study's options. k_core is the bed's core conductivity (heat "
        "flux over the mean temperature gradient of the particles more than 2 D from both walls, "
        "keff_validation.core_gradient). Shares: each path's part of Σ G ΔT² (docs/keff.md). "
        "Seed 1 unless the table gives seeds 1–3; the seed-to-seed sd of k_eff on the scene's "
        "bed is in section 7.",
        "",
        "**Published values.** SPEC.md §6 records what [KE] found qualitatively (radiation matters "
        "above σT³D/k_g ≈ 0.5; thin beds lose up to half the conductivity; the other studies are "
        "named without results) and no k_eff values of [KE]'s studies, so nothing here is "
        "compared with a published number; where SPEC states a trend it is set beside ours.",
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
        "`--temperature T` (walls at T ± 0.5 K), `--gas.model air` (SPEC §6 k_g(T) at each gas "
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
        "for 1 mm, 300 → 1500 K). [KE] (SPEC §6): radiation matters above σT³D/k_g ≈ 0.5; "
        "ours agrees: below 0.5 radiation adds at most ~20 % (2–5 % at 300 K, near the seed "
        "spread), above it it grows fast (k_eff doubles at σT³D/k_g ≈ 2–3). The number does not "
        "collapse the two sizes onto one curve (panel 2): at the same σT³D/k_g the 3.2 mm bed "
        "has the smaller radiation share, its contacts (pressed by a lid scaled with ρD) "
        "carrying more of the heat than the 1 mm bed's.",
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
        "conductance 2 k_s a, so at k_g/k_s ≥ 1e-2 k_eff/k_g stops at the gas network's own "
        f"value (~{hi['run']['k_eff'] / hi['k_g']:.1f}) while ZBS, which conducts through the "
        f"solid in series, falls to {hi['zbs']:.1f}: the model (SPEC §6 as written) does not "
        "hold for poorly conducting solids (k_core / ZBS "
        f"{hi['run']['k_core'] / hi['k_g'] / hi['zbs']:.2f} at 0.1). For metals in air "
        "(k_g/k_s ≈ 1e-4–1e-3) it is within ZBS's range (k_core / ZBS "
        f"{lo['run']['k_core'] / lo['k_g'] / lo['zbs']:.2f}–"
        f"{rows[2]['run']['k_core'] / rows[2]['k_g'] / rows[2]['zbs']:.2f}), and there the ratio "
        "acts through the contact path. [KE] studied the ratio (SPEC §6) without a stated result "
        "to compare with.",
        "",
    ]
    return L


def lid_columns(rows):
    """Lid travel (D) and the lid's mean force over the second half of the hold over its target,
    mean ± sd."""
    return (f"{pm([r['bed']['dep']['lid']['travel'] / D for r in rows], 2)} | "
            + pm([held(r) for r in rows], 3))


def held(row):
    """The lid's mean force over the second half of the hold, over its target."""
    lid = row["bed"]["dep"]["lid"]
    return lid["hold_late_force"] / lid["target_force"]


def young_section(e_nom, s_bed, same, beds):
    ref = next(s for e, s in same if e == round(e_nom))
    L = [
        "## 3. Young's modulus",
        "",
        f"(a) The seed-1 bed (deposited at E_nom / S_bed, E_nom = {e_nom:g} GPa, "
        f"S_bed = {s_bed:g}) read as a material of modulus E: under the bed's forces a Hertz "
        "contact at E has the overlap δ_s (E_nom / (S_bed E))^(2/3), which is keff's Hertz "
        "reading at `--contact.young-scale` S_bed E / E_nom (the pure contact-area effect, "
        "a ∝ E^(-1/3); the packing is the same). 300 K, contact + gas.",
        "",
        "| E (GPa) | young-scale read | k_eff (W/mK) | vs E_nom | k_core (W/mK) | contact share |",
        "|---|---|---|---|---|---|",
    ]
    for e, s in same:
        L.append(f"| {e:g} | {s_bed * e / e_nom:.4g} | {s['k_eff']:.4f} | "
                 f"{(s['k_eff'] / ref['k_eff'] - 1) * 100:+.1f} % | {s['k_core']:.4f} | "
                 f"{s['share']['contact']:.3f} |")
    L += [
        "",
        "(b) Beds deposited at young-scale S (the DEM runs with E_nom / S, particles and walls; "
        "lid at 1e4 Pa, seeds 1–3), read with the Hertz correction at their own S (the contacts "
        "of the real steel) and with the geometric radius of the soft overlap (what a softened "
        "bed gives without the correction).",
        "",
        "| S | DEM E (GPa) | lid travel (D) | lid force in the hold / target | "
        "max overlap / r | core porosity | Z (bedstat) | k_eff, Hertz a | "
        "k_eff, geometric a | geometric / Hertz | contact share, Hertz / geometric | "
        "deposit wall (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for scale, rows in groups(beds, "scale").items():
        h = [r["hertz"]["k_eff"] for r in rows]
        g = [r["geometric"]["k_eff"] for r in rows]
        L.append(
            f"| {scale:g} | {e_nom / scale:.3g} | {lid_columns(rows)} | "
            f"{statistics.mean(r['bed']['dep']['max_overlap_m'] for r in rows) / (D / 2):.4f} | "
            f"{pm([1 - r['bed']['dep']['core_density'] for r in rows], 3)} | "
            f"{pm([r['bed']['stat']['coordination'] for r in rows], 2)} | {pm(h)} | {pm(g)} | "
            f"{statistics.mean(g) / statistics.mean(h):.2f} | "
            f"{statistics.mean(r['hertz']['share']['contact'] for r in rows):.3f} / "
            f"{statistics.mean(r['geometric']['share']['contact'] for r in rows):.3f} | "
            f"{statistics.median(r['bed']['wall'] for r in rows):.0f} |")
    lo, hi = same[0], same[-1]
    by = groups(beds, "scale")
    hz = {s: statistics.mean(r["hertz"]["k_eff"] for r in rows) for s, rows in by.items()}
    gm = {s: statistics.mean(r["geometric"]["k_eff"] for r in rows) for s, rows in by.items()}
    left = {s: statistics.mean(held(r) for r in rows) for s, rows in by.items()}
    L += [
        "",
        f"**Findings.** (a) From E = {lo[0]:g} to {hi[0]:g} GPa the same packing's k_eff falls "
        f"from {lo[1]['k_eff']:.4f} to {hi[1]['k_eff']:.4f} W/mK "
        f"({(lo[1]['k_eff'] / hi[1]['k_eff'] - 1) * 100:.0f} % more at the soft end), the contact "
        f"share from {lo[1]['share']['contact']:.2f} to {hi[1]['share']['contact']:.2f}: "
        "only the contact path depends on E (a ∝ E^(-1/3)) and it carries a minority of the heat "
        f"at 300 K. (b) With the Hertz correction the beds softened {BED_SCALES[0]:g}–"
        f"{BED_SCALES[-1]:g} times give "
        + ", ".join(f"{hz[s]:.4f}" for s in BED_SCALES)
        + " W/mK (S = " + ", ".join(f"{s:g}" for s in BED_SCALES) + "): far outside the seed "
        "spread, because the softening changes the packing itself: the lid holds the same "
        "pressure (its mean force over the hold's second half is "
        + ", ".join(f"{left[s] * 100:.0f} %" for s in BED_SCALES)
        + " of the target), but the softer beds let it travel further and pack denser (core "
        "porosity and Z in the table). So the Hertz correction of the contact radius does not "
        "make k_eff independent of S; against the scenes' S = 1e3, "
        + ", ".join(f"S = {s:g} gives {(hz[s] / hz[1000] - 1) * 100:+.0f} %"
                    for s in BED_SCALES if s < 1000)
        + ". Read with the geometric radius they "
        "give "
        + ", ".join(f"{gm[s]:.4f}" for s in BED_SCALES)
        + " W/mK, i.e. " + ", ".join(f"{gm[s] / hz[s]:.1f}×" for s in BED_SCALES)
        + " the corrected value: softening without the correction inflates the contacts by "
        "√2 S^(1/3) and k_eff with them. [KE] studied E (SPEC §6) without a stated result; the "
        "correction is SPEC's prescription for softened beds.",
        "",
    ]
    return L


def emissivity_section(wall_scene, rows):
    L = [
        "## 4. Emissivity",
        "",
        f"Seed-1 bed at 1000 and 1500 K (walls T ± 0.5 K), air k_g(T), {RAYS} rays (the same "
        "view factors for every ε: `radiation.seed` 1). 'Particles and walls': both at ε; "
        f"'particles': walls at the scene's {wall_scene:g}. SPEC's pair formula, and the "
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
        "**Findings.** " + ". ".join(find) + ". SPEC's pair formula 1/G = (1−ε)/(εA_i) + "
        "1/(A_i F_ij) + (1−ε)/(εA_j) adds each sphere's whole surface resistance to every one of "
        "its ~10 links, but with F_ij ≈ 0.1 the space term 1/(A F_ij) dominates until ε is "
        "small, and a wall's surface resistance is charged over each particle's area rather "
        "than the wall's (docs/keff.md). In the grey enclosure a sphere's ε acts only where it "
        "trades heat between conduction and radiation, and the walls' ε over their whole area. "
        "[KE] studied ε 0.1–1 (SPEC §6) without a stated result to compare with.",
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
        "110 H/D spheres (the scene's 1,100 at 10 D) in the same 10 × 10 D box, lid at 1e4 Pa "
        "kept, seeds 1–3. k_eff at 300 K (scene) and at 1000 K with radiation (ε 0.5, air "
        f"k_g(T), {RAYS} rays). H is keff's wall-to-wall distance (floor to lid).",
        "",
        "| H/D nominal | particles | H/D (floor to lid) | box porosity | k_eff 300 K (W/mK) | "
        "/ k_eff(10 D) | contact share | k_eff 1000 K, radiation | / k_eff(10 D) | "
        "radiation share |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for h, rs in g.items():
        c = [r["cold"]["k_eff"] for r in rs]
        w = [r["hot"]["k_eff"] for r in rs]
        L.append(
            f"| {h} | {rs[0]['cold']['particles']} | "
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
        + ". The wall layers (porosity near a flat wall is higher, and each wall adds a contact "
        "resistance in series) weigh more in a thin bed; with radiation, which crosses the open "
        "wall layers, the thin beds keep "
        + ("more" if rel_hot[HEIGHTS[0]] > rel[HEIGHTS[0]] else "less")
        + ". [KE] (SPEC §6): thin beds lose up to half the conductivity; ours keep "
        f"{rel[2] * 100:.0f} % at 2 D and {rel[1] * 100:.0f} % at nominal 1 D (whose 110 "
        "spheres do not fit in one layer: see its H/D and porosity in the table).",
        "",
    ]
    return L


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
        "0.75 mm) (so the mean stays 1 mm; σ/D 0.4 and 0.5 are cut at 0.25–1.75 mm and their "
        "sampled sd is below the nominal σ), the count chosen for the solid volume of 1,100 "
        "spheres of 1 mm; lid at 1e4 Pa kept, seeds 1–3. Sampled σ/D: bedstat's radius sd over "
        "its mean.",
        "",
        "| σ/D nominal | --psd | particles | sampled σ/D | core porosity | box porosity | "
        "Z (bedstat) | k_eff (W/mK) | k_core (W/mK) | contact share | deposit wall (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for spread, rs in g.items():
        L.append(
            f"| {spread:g} | `{rs[0]['spec']}` | {rs[0]['count']} | "
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
    sd0 = statistics.stdev(r["run"]["k_eff"] for r in g[0.0]) / k[0.0]
    L += [
        "",
        f"**Findings.** From σ/D 0 to 0.5 the core porosity goes {por[0.0]:.3f} → {por[0.5]:.3f}, "
        f"Z {z[0.0]:.2f} → {z[0.5]:.2f}, k_eff {k[0.0]:.4f} → {k[0.5]:.4f} W/mK "
        f"({(k[0.5] / k[0.0] - 1) * 100:+.0f} %; seed sd at σ = 0: {sd0 * 100:.0f} %), while "
        f"k_core stays at {kc[0.0]:.3f}–{max(kc.values()):.3f} W/mK within its seed spread: the "
        "core packs as densely, with fewer contacts per particle, and the loss in k_eff comes "
        "from the wall layers (box porosity up by "
        f"{box_porosity(g[0.5]) - box_porosity(g[0.0]):.3f}). "
        "[KE] studied σ/D up to 0.5 (SPEC §6) without a stated result to compare with.",
        "",
    ]
    return L


def consolidation_section(rows):
    g = groups(rows, "p")
    L = [
        "## 7. Consolidation",
        "",
        "Lid pressure 1e2 Pa (about a fifth of the bed's own weight per area, ~470 Pa: the lid "
        "only touches the bed) to 1e5 Pa (the scene: 1e4), lid kept, seeds 1–3. Travel: how far "
        "the lid went down from the highest particle top; the force in the hold: its mean over "
        "the hold's second half, over the target (the lid holds the pressure, following the "
        "creeping bed; docs/deposit-lid.md). Touching: overlapping "
        "the wall (keff_validation.wall_links). Max overlap: deposit's, over r.",
        "",
        "| lid pressure (Pa) | lid travel (D) | lid force in the hold / target | particles "
        "touching the lid / the floor | core porosity | box porosity | Z (bedstat) | "
        "max overlap / r | k_eff (W/mK) | per seed | k_core (W/mK) | contact share |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for p, rs in g.items():
        k = [r["run"]["k_eff"] for r in rs]
        L.append(
            f"| {p:g} | {lid_columns(rs)} | "
            f"{statistics.mean(wall_links(r['bed']['path'])[1] for r in rs):.0f} / "
            f"{statistics.mean(wall_links(r['bed']['path'])[3] for r in rs):.0f} | "
            f"{pm([1 - r['bed']['dep']['core_density'] for r in rs], 3)} | "
            f"{pm([1 - r['bed']['stat']['box_density'] for r in rs], 3)} | "
            f"{pm([r['bed']['stat']['coordination'] for r in rs], 2)} | "
            f"{statistics.mean(r['bed']['dep']['max_overlap_m'] for r in rs) / (D / 2):.4f} | "
            f"{pm(k)} | {' / '.join(f'{v:.4f}' for v in k)} | "
            f"{pm([r['run']['k_core'] for r in rs])} | "
            f"{statistics.mean(r['run']['share']['contact'] for r in rs):.3f} |")
    means = {p: statistics.mean(r["run"]["k_eff"] for r in rs) for p, rs in g.items()}
    scene = [r["run"]["k_eff"] for r in g[1e4]]
    allk = [r["run"]["k_eff"] for r in rows]
    mean, lo, hi, sd = summary(allk)
    band = [r["run"]["k_eff"] for r in rows if 3e3 <= r["p"] <= 3e4]
    bmean, blo, bhi, bsd = summary(band)
    cores = [r["run"]["k_core"] for r in rows]
    cmean, _, _, csd = summary(cores)
    L += [
        "",
        "**Findings.** k_eff (mean of the seeds) goes "
        + " → ".join(f"{means[p]:.4f}" for p in PRESSURES)
        + " W/mK from 1e2 to 1e5 Pa. Seed spread at the scene's 1e4 Pa: "
        f"{pm(scene)} W/mK ({statistics.stdev(scene) / statistics.mean(scene) * 100:.1f} %). "
        "Consolidation spread (the issue's uncertainty source): over all "
        f"{len(PRESSURES)} settings × 3 seeds k_eff = {mean:.4f} ± {sd:.4f} W/mK "
        f"({sd / mean * 100:.0f} %, range {lo:.4f}–{hi:.4f}), k_core = {cmean:.4f} ± {csd:.4f} "
        f"({csd / cmean * 100:.0f} %); over the half decade either side of the scene "
        f"(3e3–3e4 Pa, 9 beds) k_eff = {bmean:.4f} ± {bsd:.4f} W/mK ({bsd / bmean * 100:.0f} %, "
        f"range {blo:.4f}–{bhi:.4f}). Below ~1e3 Pa (the bed's own weight is ~470 Pa) the lid "
        "touches few particles (table) and k_eff falls to a fraction of k_core: the hot-wall "
        "contact, not the bed, sets it, as with the released lid of "
        "docs/results/keff-validation.md. "
        f"At {PRESSURES[-1]:g} Pa the softened (S = 1e3) bed is pressed to core porosity "
        f"{statistics.mean(1 - r['bed']['dep']['core_density'] for r in g[PRESSURES[-1]]):.3f} "
        "(random close packing of rigid spheres: 0.36): its overlaps are those of 0.2 GPa "
        "spheres, so a setting that dense is outside what the softened DEM represents. "
        "[KE] consolidate by lowering a lid and releasing it (SPEC §6); here the lid stays "
        "(docs/deposit-lid.md), so the stress it left is still on the bed.",
        "",
    ]
    return L


def main():
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
