"""What the sweeps of keff_parameters.py share: the steel 1 mm beds ([KE]'s, made by lib/apps.py
and kept with bedstat's summary), the keff run on them, and the table cells and groupings of
their sections."""
import json
import os
import statistics

from lib import apps, report

WORK = os.path.join(apps.WORK, "keff-parameters")
ENV = apps.omp_env(1)  # one thread: the sweeps compare settings, not machines
D = 1.0e-3  # the steel case's diameter (m)
RAYS = 1000


def seeds_text(seeds):
    return "seed 1" if len(seeds) == 1 else f"seeds 1–{len(seeds)}"


def pm(values, digits=4):
    """mean ± sd of the seeds, or the value alone for one seed."""
    mean, _, _, sd = report.summary(values)
    return f"{mean:.{digits}f}" if len(values) == 1 else f"{mean:.{digits}f} ± {sd:.{digits}f}"


def groups(rows, key):
    out = {}
    for r in rows:
        out.setdefault(r[key], []).append(r)
    return out


def record(path, dep, wall):
    """A bed made elsewhere (lib/apps.py's [KE] beds) with bedstat's summary (kept in WORK):
    dict with path, dep, stat, wall."""
    os.makedirs(WORK, exist_ok=True)
    meta = os.path.join(WORK, os.path.basename(path) + ".bedstat.json")
    if os.path.exists(meta):
        with open(meta) as f:
            stat = json.load(f)
    else:
        stat = apps.bedstat([path], env=ENV)
        with open(meta, "w") as f:
            json.dump(stat, f)
    return {"path": path, "dep": dep, "stat": stat, "wall": wall}


def validation_bed(case, seed, depth=0.0):
    """keff-validation.md's bed of the case and seed: unconsolidated (depth 0) or with the lid
    lowered to `depth` particle radii below the surface, raised and relaxed."""
    return record(*apps.ke2016_bed(case, seed, depth))


def base_bed(seed=1):
    return validation_bed("steel-1mm", seed)


def deposit(name, seed, *extra, case="steel-1mm"):
    """A bed of the case's deposit scene with `extra` options (cached with its --json summary and
    bedstat's): dict with path, dep, stat, wall."""
    os.makedirs(WORK, exist_ok=True)
    path = os.path.join(WORK, f"{name}-seed{seed}.h5")
    meta = path + ".json"
    if os.path.exists(path) and os.path.exists(meta):
        with open(meta) as f:
            return json.load(f)
    dep, wall = apps.run_json(apps.ke2016_deposit(case, seed) + ["--out", path, *extra], env=ENV)
    stat = apps.bedstat([path], env=ENV)
    bed = {"path": path, "dep": dep, "stat": stat, "wall": wall}
    with open(meta, "w") as f:
        json.dump(bed, f)
    print(f"deposit {name} seed {seed}: {wall:.1f} s, core density {dep['core_density']}",
          flush=True)
    return bed


def keff(bed, *extra, case="steel-1mm", core=True):
    """keff's --json summary on the bed (the case's keff scene), plus k_core (the core-gradient
    conductivity, lib/apps.py core_gradient) when the bed is tall enough to have a core more than
    2 D from both walls."""
    s, _ = apps.keff(apps.ke2016_keff_scene(case), bed["path"], *extra,
                     out=os.path.join(WORK, "keff-temperatures.h5"), env=ENV, core=core)
    return s


def seed_spread():
    """The relative sd of k_eff over keff_validation.py's bed-generation seeds (bed-seeds.json),
    as text, or 'not measured' when that study has not run."""
    path = apps.KE2016_BED_SEEDS
    if not os.path.exists(path):
        return "not measured"
    with open(path) as f:
        k = [r["k_eff"] for r in json.load(f).values()]
    return (f"{statistics.stdev(k) / statistics.mean(k) * 100:.0f} % ({len(k)} seeds)"
            if len(k) > 1 else "not measured")


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
