"""5. Bed height: boxes of 10 x 10 x H D filled by [KE]'s insertion until full, k_eff at 300 K and
at 1000 K with radiation, against the 10 D bed."""
import statistics

from lib import report

from .shared import D, RAYS, base_bed, deposit, groups, keff, pm, seed_spread, seeds_text

HEIGHTS = [1, 2, 3, 5, 7, 10]  # box height H/D, insertion until full


def run(seeds):
    """Boxes of 10 x 10 x H D filled by the scene's insertion (until full, top cropped at the
    highest particle top), seed 1: k_eff at 300 K, and at 1000 K with radiation (eps 0.5,
    air)."""
    rows = []
    for h in HEIGHTS:
        for seed in seeds:
            b = base_bed(seed) if h == 10 else deposit(
                f"steel-1mm-H{h}", seed, "--domain", f"{10 * D:g},{10 * D:g},{h * D:g}")
            cold = keff(b, core=False)
            hot = keff(b, "--temperature", "1000", "--gas.model", "air", "--effects.radiation",
                       "true", "--rays", str(RAYS), core=False)
            rows.append({"h": h, "seed": seed, "bed": b, "cold": cold, "hot": hot})
    return rows


def panel(a, heights, seeds):
    """k_eff over k_eff(10 D) against the measured height, at 300 K and at 1000 K."""
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
    a.set_title(f"5. bed height ({seeds_text(seeds)}, line: mean)")
    a.legend(fontsize=7)


def section(rows, seeds):
    g = groups(rows, "h")
    ref_cold = statistics.mean(r["cold"]["k_eff"] for r in g[10])
    ref_hot = statistics.mean(r["hot"]["k_eff"] for r in g[10])
    L = [
        "## 5. Bed height",
        "",
        "A 10 × 10 × H D box filled by the scene's insertion until full (`--domain "
        f"0.01,0.01,H`), unconsolidated, {seeds_text(seeds)}. k_eff at 300 K (scene) and at 1000 K with "
        f"radiation (ε 0.5, air k_g(T), {RAYS} rays). H/D (measured) is keff's wall-to-wall "
        "distance, floor to the highest particle top.",
        "",
        *report.table_head("H/D nominal", "particles", "H/D (floor to the hot wall)",
                           "box porosity", "k_eff 300 K (W/mK)", "/ k_eff(10 D)", "contact share",
                           "k_eff 1000 K, radiation", "/ k_eff(10 D)", "radiation share"),
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
        + f" ({seeds_text(seeds)}). The 300 K k_eff of an unconsolidated bed is set by the few "
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
