"""A batch run (stderr not a terminal, as here: a pipe) prints a progress line to stderr every
--progress seconds instead of being silent until it ends (README "The programs")."""
import re
import subprocess

import numpy as np

import powderbed
from conftest import make_bed
from powderbed._programs import executable


def deposit(tmp_path, interval):
    bed = make_bed(np.array([1e-4, 2e-4]), np.array([1.5e-4, 1.5e-4]), np.array([21e-6, 21e-6]),
                   np.array([20e-6, 20e-6]), (0.3e-3, 0.3e-3, 0.3e-3))
    powderbed.write_bed(bed, tmp_path / "in.h5")
    # Two particles falling for 2 ms at the softened stiffness: ~1e5 steps, a progress report
    # every 2000 of them (dem/solver.hpp), well over a millisecond of wall time in all.
    proc = subprocess.run([executable("deposit"), "--in", tmp_path / "in.h5", "--young-scale",
                           "1e3", "--t-end", "2e-3", "--seed", "1", "--out", tmp_path / "out.h5",
                           "--progress", str(interval)], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    return proc.stderr.splitlines()


def test_batch_run_prints_progress_lines(tmp_path):
    lines = deposit(tmp_path, 1e-4)
    progress = [line for line in lines if re.match(r"deposit: +\d+ %  t = .* ETA \d+ s$", line)]
    assert len(progress) >= 2, lines
    percents = [int(re.match(r"deposit: +(\d+) %", line).group(1)) for line in progress]
    assert percents == sorted(percents) and percents[-1] <= 100
    assert not any("\r" in line for line in lines)  # no terminal bar in a log


def test_progress_zero_is_silent(tmp_path):
    assert not any(line.startswith("deposit: ") and "%" in line for line in deposit(tmp_path, 0))
