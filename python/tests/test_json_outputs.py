"""Every --json output of every program parses as one JSON object (README "The programs"):
each program's main modes, --version --json and sinter --explain --json, read with Python's
JSON parser; bad input with --json prints nothing on stdout and one line on stderr."""
import json
import subprocess

import numpy as np
import pytest

import powderbed
from conftest import SMALL_GRID, make_bed, scene
from powderbed._programs import executable


def run_json(program, *args):
    """stdout of `program args --json` parsed; the program must exit 0."""
    proc = subprocess.run([executable(program), *map(str, args), "--json"], capture_output=True,
                          text=True)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


@pytest.mark.parametrize("program", powderbed.PROGRAMS)
def test_version_json(program):
    out = run_json(program, "--version")
    assert out["program"] == program and out["version"]


def test_packgen_2d_and_3d(tmp_path):
    for dim, domain in (("2", "2e-4,2e-4"), ("3", "2e-4,2e-4,1e-4")):
        out = run_json("packgen", "--dim", dim, "--domain", domain, "--psd", "mono:d=20e-6",
                       "--count", 20, "--seed", 1, "--out", tmp_path / f"p{dim}.h5")
        assert out["n"] == 20


def test_bedstat_is_one_shape_for_one_and_many_beds(packed, tmp_path):
    path, _ = packed
    one = run_json("bedstat", path)
    two = run_json("bedstat", path, path, "--layer", "0,20e-6")
    # "units" (each numeric key's SI unit) follows the beds.
    assert list(one) == ["beds", "units"] and len(one["beds"]) == 1
    assert list(two) == ["beds", "units"] and len(two["beds"]) == 2
    assert one["units"]["box_density"] == "1" and two["units"]["z0"] == "m"
    assert "layer_density" in two["beds"][0] and "layer_density" not in one["beds"][0]
    # Every optional statistic on a simple cubic lattice of 8^3 spheres (g(r) needs centres
    # 5 mean radii from the walls, which a one-layer bed has not).
    r = 10e-6
    g = (np.arange(8) * 2 + 1) * r
    x, y, z = (a.ravel() for a in np.meshgrid(g, g, g, indexing="ij"))
    powderbed.write_bed(make_bed(x, y, z, np.full(512, r), (16 * r,) * 3), tmp_path / "sc.h5")
    full = run_json("bedstat", tmp_path / "sc.h5", "--profile", 4, "--rdf", 8, "--histogram", 3,
                    "--psd", "mono:d=20e-6", "--voronoi", "--order")
    for key in ("density_profile", "rdf", "radius_histogram", "ks_distance", "voronoi",
                "q6_global"):
        assert key in full["beds"][0], key


def test_bedconv(packed, tmp_path):
    path, _ = packed
    out = run_json("bedconv", path, tmp_path / "b.csv")
    assert out["particles"] == 40


def test_deposit_from_a_bed_and_by_insertion(packed, tmp_path):
    path, _ = packed
    out = run_json("deposit", "--in", path, "--young-scale", 1e3, "--t-end", 2e-6, "--seed", 1,
                   "--out", tmp_path / "d.h5", "--trajectory", tmp_path / "t.h5", "--every", 5)
    assert out["n"] == 40
    out = run_json("deposit", "--config", scene("gz2016-deposit.ini"), "--t-end", 1e-6,
                   "--seed", 1, "--out", tmp_path / "gz.h5")
    assert out["n"] > 0


def test_sinter_run_and_explain(sinter_bed, tmp_path):
    grid = [a for k, v in SMALL_GRID.items() for a in ("--" + k, v)]
    base = ["--config", scene("gz2016-sinter.ini"), "--bed", sinter_bed, *grid]
    explain = run_json("sinter", *base, "--explain")
    assert explain["laser_flux"] > 0 and "text" in explain
    out = run_json("sinter", *base, "--out", tmp_path / "run.h5")
    assert out["particles"] == 12


def test_keff(column, tmp_path):
    # The column stands on z; the scene's walls are the x faces, with radiation on.
    out = run_json("keff", "--config", scene("ke2016-steel-1mm.ini"), "--bed", column,
                   "--axis", "z", "--effects.radiation", "false", "--effects.gas", "false",
                   "--out", tmp_path / "k.h5")
    assert out["k_eff"] > 0


@pytest.mark.parametrize("program", powderbed.PROGRAMS)
def test_bad_input_with_json_prints_nothing_on_stdout(program, tmp_path):
    proc = subprocess.run([executable(program), "--bogus", "1", "--json"], capture_output=True,
                          text=True)
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert len(proc.stderr.splitlines()) == 1 and "bogus" in proc.stderr
