"""4. Emissivity: k_eff and the radiation share at 1000 and 1500 K on the seed-1 steel 1 mm bed
against the particles' emissivity, with the walls at the same ε and at the scene's, in the pair
formula and in the radiosity model."""
from lib import apps, report

from .shared import RAYS, base_bed, groups, keff

EMISSIVITIES = [0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.0]


def run():
    """k_eff and the radiation share at 1000 and 1500 K (air k_g, seed-1 bed) against the
    particles' emissivity, with the walls at the same emissivity and at the scene's 0.5 (the pair
    formula of docs/physics.md §6), and with both at ε in the radiosity model (the grey enclosure)."""
    bed = base_bed()
    options = apps.resolved_options("keff", ["--config", apps.ke2016_keff_scene("steel-1mm")])
    wall_scene = float(options["radiation.wall-emissivity"])
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


def panel(a, emis):
    """k_eff against ε for each temperature and wall setting; dotted: radiation off."""
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


def section(wall_scene, rows):
    L = [
        "## 4. Emissivity",
        "",
        f"Seed-1 bed at 1000 and 1500 K (walls T ± 0.5 K), air k_g(T), {RAYS} rays (the same "
        "view factors for every ε: `radiation.seed` 1). 'Particles and walls': both at ε; "
        f"'particles': walls at the scene's {wall_scene:g}. The pair formula of docs/physics.md §6, and the "
        "radiosity model (`--radiation.model radiosity`: the grey enclosure, one radiosity node "
        "per surface, docs/keff.md) with particles and walls at ε.",
        "",
        *report.table_head("T (K)", "ε", "k_eff, particles and walls", "radiation share",
                           "k_eff, particles", "radiation share", "k_eff, radiosity model",
                           "radiation share", "k_eff, radiation off"),
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
