"""1. Bed temperature, radiation off and on: k_eff at T on the seed-1 steel 1 mm and 3.2 mm beds,
air's k_g(T) at each gas link, against [KE]'s measure of radiation σT³D/k_g(T)."""
from lib import references, report

from .shared import RAYS, groups, keff, validation_bed

SIGMA = 5.670374419e-8  # Stefan–Boltzmann, W/m^2K^4
TEMPERATURES = [300, 500, 700, 900, 1100, 1300, 1500]


def radiation_number(t, d):
    """sigma T^3 D / k_g(T), [KE]'s measure of radiation against gas conduction."""
    return SIGMA * t ** 3 * d / references.k_air(t)


def crossing(d, target=0.5):
    """The temperature where sigma T^3 D / k_g(T) = target (bisection; it rises with T)."""
    lo, hi = 175.0, 1900.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if radiation_number(mid, d) < target else (lo, mid)
    return 0.5 * (lo + hi)


def run():
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


def panel(a, b, temps):
    """k_eff against T (a) and the radiation share against σT³D/k_g (b)."""
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
    for n, (case, rows) in enumerate(groups(temps, "case").items()):
        for marker, key in (("o", 0.5), ("s", 0.9)):
            b.plot([r["number"] for r in rows], [r["runs"][key]["share"]["radiation"]
                                                 for r in rows], marker + "-", color=f"C{n}",
                   ms=4, label=f"{case}, ε {key}")
    b.axvline(0.5, color="k", lw=0.8)
    b.set_xscale("log")
    b.set_xlabel("σT³D / k_g(T)")
    b.set_ylabel("radiation share of the heat flow")
    b.set_title("1. radiation share against [KE]'s number")
    b.legend(fontsize=7)


def section(temps):
    L = [
        "## 1. Bed temperature, with and without radiation",
        "",
        "`--temperature T` (walls at T ± 0.5 K), `--gas.model air` (docs/physics.md §6 k_g(T) at each gas "
        f"link), radiation off and on (`--effects.radiation true --rays {RAYS}`, particles and "
        "walls at ε 0.5 or 0.9), seed-1 beds of steel 1 mm and steel 3.2 mm (its own scenes). "
        "In bold: the temperature where σT³D/k_g(T) = 0.5.",
        "",
        *report.table_head("bed", "T (K)", "k_g(T) (W/mK)", "σT³D/k_g", "k_eff, no radiation",
                           "contact / gas share", "k_eff, ε 0.5", "radiation adds",
                           "radiation share", "k_eff, ε 0.9", "radiation adds", "radiation share"),
    ]
    for r in temps:
        off, e5, e9 = r["runs"]["off"], r["runs"][0.5], r["runs"][0.9]
        t = f"**{r['t']:g}**" if r["star"] else f"{r['t']:g}"
        L.append(f"| {r['case']} | {t} | {references.k_air(r['t']):.4f} | {r['number']:.3f} | "
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
