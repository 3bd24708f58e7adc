"""The Python module: beds through the C++ library, PSD sampling, bedstat's statistics and the
programs' summaries (README "Python")."""
import math

import numpy as np
import pytest

import powderbed
from conftest import make_bed


def test_read_bed_gives_the_arrays_the_program_wrote(packed):
    path, summary = packed
    bed = powderbed.read_bed(path)
    assert len(bed) == summary["n"] == 40
    assert bed.x.dtype == np.float64 and bed.id.dtype == np.uint64
    assert np.all(bed.r == 10e-6)
    assert bed.domain["dimension"] == 3 and list(bed.domain["periodic"]) == [False] * 3
    assert list(bed.domain["upper"]) == [2e-4, 2e-4, 1e-4]
    assert bed.provenance["created_by"].startswith("packgen ")
    assert bed.provenance["rng_seed"] == 1
    assert bed.vx is None and bed.velocity is None  # packgen beds carry no velocities


def test_write_bed_round_trip_is_bit_exact(tmp_path):
    rng = np.random.default_rng(3)
    n = 25
    bed = make_bed(rng.uniform(0, 1e-3, n), rng.uniform(0, 1e-3, n), rng.uniform(0, 1e-3, n),
                   rng.uniform(5e-6, 2e-5, n), (1e-3, 1e-3, 1e-3),
                   vx=rng.normal(size=n), vy=rng.normal(size=n), vz=rng.normal(size=n),
                   material=np.arange(n) % 2)
    bed.domain["periodic"] = [True, False, False]
    powderbed.write_bed(bed, tmp_path / "b.h5")
    back = powderbed.read_bed(tmp_path / "b.h5")
    for key in ("x", "y", "z", "r", "id", "vx", "vy", "vz", "material"):
        assert np.array_equal(getattr(back, key), getattr(bed, key)), key
    assert list(back.domain["periodic"]) == [True, False, False]
    assert back.provenance["stage"] == "test"


def test_bad_bed_raises_input_error_naming_the_field(tmp_path):
    bed = make_bed([1e-4], [1e-4], [1e-4], [-1e-5], (1e-3, 1e-3, 1e-3))
    with pytest.raises(powderbed.InputError, match="radius"):
        powderbed.write_bed(bed, tmp_path / "bad.h5")
    with pytest.raises(ValueError, match="missing.h5"):
        powderbed.read_bed(tmp_path / "missing.h5")


def test_stats_is_bedstats_entry_for_the_bed(packed):
    path, _ = packed
    bed = powderbed.read_bed(path)
    options = {"layer": (0, 20e-6), "profile": 5}
    mine = powderbed.stats(bed, **options)
    theirs = powderbed.bedstat(path, layer="0,20e-6", profile=5)["beds"]
    assert len(theirs) == 1
    assert mine == theirs[0]  # the same code, the same numbers, the same keys
    assert "layer_density" in mine and "density" not in mine
    assert set(mine["coordination_by_tol"]) == {"1e-06", "0.001", "0.01"}


def test_stats_of_a_simple_cubic_lattice(tmp_path):
    # 4 x 4 x 4 touching spheres filling their box: phi = pi/6 exactly (up to the rounding of
    # positions); each interior sphere has 6 contacts, so Z = 2 * 3 * 4^2 * 3 / 64 = 4.5.
    r = 1e-5
    g = (np.arange(4) * 2 + 1) * r
    x, y, z = (a.ravel() for a in np.meshgrid(g, g, g, indexing="ij"))
    s = powderbed.stats(make_bed(x, y, z, np.full(64, r), (8 * r,) * 3))
    assert s["box_density"] == pytest.approx(math.pi / 6, rel=1e-12)
    assert s["coordination"] == pytest.approx(4.5, abs=1e-12)
    assert s["rattlers"] == 0


def test_sample_psd_follows_the_string(tmp_path):
    assert np.all(powderbed.sample_psd("mono:d=30e-6", 10, seed=1) == 15e-6)
    psd = "gauss:mean=27e-6,sd=4.25e-6,min=10e-6,max=50e-6"
    r = powderbed.sample_psd(psd, 20000, seed=7)
    assert r.min() >= 5e-6 and r.max() <= 25e-6
    # The window [10, 50] um lies 4 sd and more from the mean: truncation moves the mean by
    # ~1e-4 sd; the sample mean's sd is 2.125 um / sqrt(20000) = 15 nm, so 0.1 um is ~7 sd.
    assert abs(r.mean() - 13.5e-6) < 0.1e-6
    assert np.array_equal(r, powderbed.sample_psd(psd, 20000, seed=7))
    assert not np.array_equal(r, powderbed.sample_psd(psd, 20000, seed=8))
    with pytest.raises(ValueError, match="psd"):
        powderbed.sample_psd("gauss:mean=3e-5", 1)


def test_a_failing_program_raises_with_its_message_and_status(tmp_path):
    with pytest.raises(powderbed.ProgramError, match="nope.h5") as error:
        powderbed.bedstat(tmp_path / "nope.h5")
    assert error.value.status == 2
