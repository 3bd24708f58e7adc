"""2. Gas-to-solid conductivity ratio: k_s = k_g / ratio on the seed-1 steel 1 mm bed at 300 K,
contact + gas, against Zehner–Bauer–Schlünder at the bed's core porosity."""
from lib import apps, references, report

from .shared import base_bed, keff

RATIOS = [1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1]  # k_g / k_s


def run():
    """k_s = k_g / ratio on the seed-1 bed, contact + gas at 300 K (k_g 0.026 W/mK constant),
    against ZBS at the bed's core porosity."""
    bed = base_bed()
    options = apps.resolved_options("keff", ["--config", apps.ke2016_keff_scene("steel-1mm")])
    k_g = float(options["gas.conductivity"])
    eps_core = 1 - bed["dep"]["core_density"]
    rows = []
    for ratio in RATIOS:
        k_s = k_g / ratio
        s = keff(bed, "--solid.conductivity", f"{k_s:.6g}")
        rows.append({"ratio": ratio, "k_s": k_s, "k_g": k_g, "run": s,
                     "zbs": references.zbs(eps_core, 1 / ratio)})
    return eps_core, rows


def panel(a, ratio):
    """k_eff/k_g, k_core/k_g and ZBS against k_g/k_s, the contact share on the right axis."""
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


def section(eps_core, rows):
    L = [
        "## 2. Gas-to-solid conductivity ratio",
        "",
        f"Seed-1 bed, 300 K, contact + gas, k_g = {rows[0]['k_g']:g} W/mK, k_s = k_g / ratio. "
        "ZBS: Zehner–Bauer–Schlünder (point contacts, no radiation; bench/studies/lib/references.py "
        f"`zbs`) at the bed's core porosity {eps_core:.3f}.",
        "",
        *report.table_head("k_g / k_s", "k_s (W/mK)", "k_eff (W/mK)", "k_eff / k_g", "k_core / k_g",
                           "ZBS k/k_g", "k_core / ZBS", "contact share", "gas share"),
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
