"""Helpers shared by the study scripts: run a program of the build, read its --json summary."""
import json
import os
import statistics
import subprocess
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
BUILD = os.environ.get("POWDERBED_BUILD", os.path.join(ROOT, "build"))
RESULTS = os.path.join(ROOT, "docs", "results")


def app(name):
    return os.path.join(BUILD, "apps", name)


def run_json(args, env=None):
    """Runs a program with --json and returns (summary dict, wall seconds of the whole process)."""
    start = time.perf_counter()
    proc = subprocess.run(args + ["--json"], capture_output=True, text=True, env=env)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} exited {proc.returncode}: {proc.stderr.strip()}")
    return json.loads(proc.stdout), wall


def bedstat(args, env=None):
    """bedstat's --json entry of the one bed in `args` (its path and options): the element of
    the "beds" array bedstat always prints."""
    out, _ = run_json([app("bedstat"), *args], env=env)
    return out["beds"][0]


def summary(values):
    """mean, min, max, sd of a list of numbers."""
    sd = statistics.stdev(values) if len(values) > 1 else 0.0
    return statistics.mean(values), min(values), max(values), sd


def write_text(name, text):
    os.makedirs(RESULTS, exist_ok=True)
    path = os.path.join(RESULTS, name)
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)
    return path


def read_bed(path):
    """Centres (N x 3) and radii of a bed file (docs/bed-format.md); needs h5py and numpy."""
    import h5py
    import numpy as np
    with h5py.File(path, "r") as f:
        return np.array(f["particles/position"]), np.array(f["particles/radius"])


def coordination_at_gaps(centres, radii, gaps):
    """Z = 2 contacts / N (docs/physics.md §2) with a contact when the surface gap d - ri - rj <= g, for each
    absolute gap g (m) in `gaps`: the raster-bed reading of a contact (docs/physics.md §3: gaps of order h).
    Overlapping pairs (negative gap) count as contacts."""
    import numpy as np
    from scipy.spatial import cKDTree
    n = len(radii)
    if n < 2:
        return [0.0 for _ in gaps]
    pairs = cKDTree(centres).query_pairs(2 * radii.max() + max(gaps), output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    gap = np.linalg.norm(centres[i] - centres[j], axis=1) - radii[i] - radii[j]
    return [2.0 * np.count_nonzero(gap <= g) / n for g in gaps]
