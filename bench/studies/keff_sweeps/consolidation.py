"""7. Consolidation: [KE]'s lid depths, the beds of keff-validation.md, k_eff and k_core and
what touches the walls."""
import statistics

import numpy as np

from lib import references, report

from .shared import D, bed_panel, groups, keff, pm, seeds_text, validation_bed

DEPTHS = [0.0] + references.KE2016_LID_DEPTHS  # lid depth below the surface (r); 0: none


def run(seeds):
    """[KE]'s consolidation: keff_validation.py's beds, the lid lowered to 0.25-1 r below the
    surface of the unconsolidated bed, held, raised and relaxed."""
    rows = []
    for depth in DEPTHS:
        for seed in seeds:
            b = validation_bed("steel-1mm", seed, depth)
            rows.append({"p": depth, "seed": seed, "bed": b, "run": keff(b)})
    return rows


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


def panel(a, cons, seeds):
    bed_panel(a, cons, "p", "lid depth below the surface (r; 0: unconsolidated)",
              f"7. consolidation ({seeds_text(seeds)}, line: mean)", log_x=False)


def section(rows, seeds):
    g = groups(rows, "p")
    L = [
        "## 7. Consolidation",
        "",
        "[KE]'s consolidation: the unconsolidated bed with the top wall lowered to 0.25, 0.5, "
        "0.75 and 1 particle radius below its surface (the 90th percentile of the particle "
        "tops), held, raised back at its speed and relaxed (`--lid.enabled true --lid.depth L`, "
        f"docs/deposit-lid.md), the beds of keff-validation.md ({seeds_text(seeds)}); keff's hot wall at the "
        "highest particle top of the relaxed bed. Lid force: the largest during the press. "
        "Within reach of the hot wall / touching it: particles with the wall inside their gas "
        "lens (0.2 r) / overlapping it (wall_links); the same for the floor.",
        "",
        *report.table_head("lid depth (r)", "lid travel (D)", "largest lid force (N)",
                           "hot wall: in lens / touching", "floor: in lens / touching",
                           "core porosity", "box porosity", "Z (bedstat)", "k_eff (W/mK)",
                           "k_core (W/mK)", "k_eff / k_core", "contact share"),
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
    mean, lo, hi, sd = report.summary(allk)
    cmean, clo, chi, csd = report.summary(allc)
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
