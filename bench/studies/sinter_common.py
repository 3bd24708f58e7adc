"""What the sinter studies share: the [GZ] bed (deposited once from the paper's scene and kept in
out/studies/), one run of `sinter` with --json, and the paper's numbers."""
import os
import subprocess

from common import ROOT, app, run_json

SCENE = os.path.join(ROOT, "data", "scenes", "gz2016-sinter.ini")
DEPOSIT_SCENE = os.path.join(ROOT, "data", "scenes", "gz2016-deposit.ini")
WORK = os.path.join(ROOT, "out", "studies")
# [GZ] 2016, SPEC.md §5: melt pool (height, width, depth) in um on the plane x = Lx/2.
PAPER_MODEL = (30.0, 85.0, 20.0)
PAPER_EXPERIMENT = (26.0, 75.0, 30.0)


def gz2016_bed():
    """The deposit scene's bed with seed 1 (about a minute the first time)."""
    os.makedirs(WORK, exist_ok=True)
    path = os.path.join(WORK, "gz2016-deposit.h5")
    if not os.path.exists(path):
        subprocess.run([app("deposit"), "--config", DEPOSIT_SCENE, "--seed", "1", "--out", path],
                       check=True, capture_output=True)
    return path


def run_sinter(bed, out_name, *extra, threads=1):
    """Runs sinter on `bed` with the paper's scene and `extra` options; returns (json, wall s).
    One thread by default: the studies compare settings, not machines (bench/studies/sinter_speed.py
    measures threads)."""
    out = os.path.join(WORK, out_name)
    args = [app("sinter"), "--config", SCENE, "--bed", bed, "--out", out, *extra]
    if threads:
        args += ["--threads", str(threads)]
    summary, wall = run_json(args)
    summary["out_path"] = out
    return summary, wall


def pool_um(summary):
    m = summary["melt_pool"]
    return m["height"] * 1e6, m["width"] * 1e6, m["depth"] * 1e6
