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
