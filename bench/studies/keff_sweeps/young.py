"""3. Young's modulus and the DEM stiffness: (a) the seed-1 steel 1 mm bed read as a material of
modulus E (the Hertz correction at E, the packing the same); (b) the bed deposited at DEM
stiffness k_n = 1e3 ... 1e6 N/m, read with the Hertz correction at its own k_n and with the
geometric contact radius."""
import statistics

from lib import apps, report

from .shared import D, base_bed, deposit, groups, keff, pm, record, seeds_text

YOUNG = [1, 3, 10, 30, 100, 198, 300, 1000]  # GPa, the same bed read at E
STIFFNESS = [1e3, 1e4, 1e5, 1e6]  # DEM k_n (N/m) of keff_softening.py's beds; [KE] 1e5


def run(seeds):
    """(a) The seed-1 bed read as a material of modulus E (`--contact.young`: the Hertz
    correction k_n δ_s = (4/3) E* √R* δ_h^{3/2} at E, the packing the same). (b) The beds of
    keff_softening.py, deposited at k_n = 1e3 ... 1e6 N/m (seed 1), read with the Hertz
    correction at their own k_n and with the geometric contact radius."""
    bed = base_bed()
    dem = apps.resolved_options("deposit", ["--config", apps.ke2016_bed_scene("steel-1mm")])
    e_nom = float(dem["material.young"]) / 1e9
    k_bed = float(dem["contact.stiffness"])
    same = [(e, keff(bed, "--contact.young", f"{e * 1e9:.6g}")) for e in YOUNG]
    beds = []
    for k_n in STIFFNESS:
        for seed in seeds:
            if seed == 1:  # keff_softening.py's bed
                b = record(*apps.ke2016_soft_bed("steel-1mm", k_n))
            elif k_n == k_bed:
                b = base_bed(seed)
            else:
                b = deposit(f"steel-1mm-kn{k_n:g}", seed, "--contact.stiffness", f"{k_n:g}")
            beds.append({"k_n": k_n, "seed": seed, "bed": b, "hertz": keff(b),
                         "geometric": keff(b, "--contact.hertz-correction", "false")})
    return e_nom, k_bed, same, beds


def panel(a, b, young, seeds):
    """k_eff and k_core against the E read (a) and against the deposit's k_n (b)."""
    e_nom, k_bed, same, beds = young
    a.plot([e for e, _ in same], [s["k_eff"] for _, s in same], "o-", label="k_eff")
    a.plot([e for e, _ in same], [s["k_core"] for _, s in same], "s--", label="k_core")
    a.axvline(e_nom, color="k", lw=0.8)
    a.set_xscale("log")
    a.set_xlabel("Young's modulus E read (GPa)")
    a.set_ylabel("k (W/mK)")
    a.set_title("3a. the same bed read at E (Hertz correction, 300 K)")
    a.legend(fontsize=7)
    g = groups(beds, "k_n")
    for key, marker, n, name in (("hertz", "o", 0, "Hertz correction at the bed's k_n"),
                                 ("geometric", "v", 2, "geometric a")):
        b.plot([r["k_n"] for r in beds], [r[key]["k_eff"] for r in beds], marker,
               color=f"C{n}", alpha=0.4)
        b.plot(list(g), [statistics.mean(r[key]["k_eff"] for r in v) for v in g.values()],
               "-", color=f"C{n}", label=f"k_eff, {name}")
        b.plot(list(g), [statistics.mean(r[key]["k_core"] for r in v) for v in g.values()],
               "--", color=f"C{n}", alpha=0.6, label=f"k_core, {name}")
    b.set_xscale("log")
    b.set_yscale("log")
    b.set_xlabel("DEM stiffness k_n (N/m) of the deposit ([KE]: 1e5)")
    b.set_ylabel("k (W/mK)")
    b.set_title(f"3b. beds deposited at k_n ({seeds_text(seeds)}, line: mean)")
    b.legend(fontsize=7)


def section(e_nom, k_bed, same, beds, seeds):
    ref = next(s for e, s in same if e == round(e_nom))
    L = [
        "## 3. Young's modulus and the DEM stiffness",
        "",
        f"(a) The seed-1 bed (deposited with the linear law at k_n = {k_bed:g} N/m; E_nom = "
        f"{e_nom:g} GPa in its record) read as a material of modulus E (`--contact.young`): the "
        "Hertz correction k_n δ_s = (4/3) E* √R* δ_h^{3/2} gives the overlap of a Hertz contact "
        "at E under the bed's forces, so a ∝ E^(-1/3) at the same packing. 300 K, contact + gas.",
        "",
        *report.table_head("E (GPa)", "k_eff (W/mK)", "vs E_nom", "k_core (W/mK)", "vs E_nom",
                           "contact share"),
    ]
    for e, s in same:
        L.append(f"| {e:g} | {s['k_eff']:.4f} | {(s['k_eff'] / ref['k_eff'] - 1) * 100:+.1f} % | "
                 f"{s['k_core']:.4f} | {(s['k_core'] / ref['k_core'] - 1) * 100:+.1f} % | "
                 f"{s['share']['contact']:.3f} |")
    L += [
        "",
        "(b) The beds of keff_softening.py: the scene's bed deposited at k_n = "
        + ", ".join(f"{k:g}" for k in STIFFNESS) + f" N/m ({seeds_text(seeds)}), read with the Hertz "
        "correction at their own k_n (the contacts of the real steel) and with the geometric "
        "radius of the soft overlap (what a soft bed gives without the correction).",
        "",
        *report.table_head("k_n (N/m)", "max overlap / r", "core porosity", "Z (bedstat)",
                           "k_eff, Hertz", "k_eff, geometric", "geometric / Hertz", "k_core, Hertz",
                           "k_core, geometric", "contact share, Hertz / geometric",
                           "deposit wall (s)"),
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
