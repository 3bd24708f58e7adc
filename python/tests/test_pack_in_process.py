"""packgen in-process (powderbed.pack): the bed the program writes for the same options and seed,
bit for bit, its --json summary, the warning, progress and the library's refusals."""
import warnings

import numpy as np
import pytest

import powderbed

ARRAYS = ("x", "y", "z", "r", "id", "material", "vx", "vy", "vz", "temperature", "phase")


def same_bed(mine, theirs):
    for key in ARRAYS:
        a, b = getattr(mine, key), getattr(theirs, key)
        assert (a is None) == (b is None), key
        if a is not None:
            assert a.dtype == b.dtype and np.array_equal(a, b), key
    for key in ("dimension", "lower", "upper", "periodic"):
        assert np.array_equal(mine.domain[key], theirs.domain[key]), key


@pytest.mark.parametrize("domain, psd, options", [
    ((2e-4, 2e-4, 1e-4), "mono:d=20e-6", {"approach": 3, "count": 40}),
    ((4e-6, 4e-6), "mono:r=0.2e-6", {"phases": "0:0.3,1", "collision": "kdtree", "tries": 200}),
    ((1.5e-4, 1.5e-4, 1e-4), "gauss:mean=10e-6,sd=2e-6,min=5e-6,max=15e-6",
     {"approach": 2, "size_sampling": "stratified", "target_density": 0.2}),
])
def test_pack_is_the_bed_packgen_writes(tmp_path, domain, psd, options):
    mine, summary = powderbed.pack(domain, psd, 3, **options)
    out = tmp_path / "bed.h5"
    theirs = powderbed.packgen(dim=len(domain), domain=domain, psd=psd, seed=3, out=out, **options)
    same_bed(mine, powderbed.read_bed(out))
    assert mine.provenance["stage"] == "packgen" and mine.provenance["rng_seed"] == 3
    del theirs["units"], theirs["wall_time"], summary["wall_time"]
    assert summary == theirs


def test_pack_takes_options_and_a_domain_dict():
    options = powderbed.PackOptions(approach=3, count=20)
    assert options.phases == "3" and powderbed.PackOptions(phases="0:0.25,1").approach == 1
    first, _ = powderbed.pack((2e-4, 2e-4, 1e-4), "mono:d=20e-6", 1, options)
    again, _ = powderbed.pack(first.domain, "mono:d=20e-6", 1, options)
    same_bed(first, again)
    assert options.count == 20  # the caller's struct is not changed by keywords
    fewer, _ = powderbed.pack((2e-4, 2e-4, 1e-4), "mono:d=20e-6", 1, options, count=10)
    assert len(fewer) == 10 and options.count == 20


def test_an_unreached_target_is_a_warning_with_the_bed():
    with pytest.warns(RuntimeWarning, match=r"^packgen: --target-density 0\.95 not reached"):
        bed, summary = powderbed.pack((4e-6, 4e-6), "mono:r=0.2e-6", 3, approach=0,
                                      target_density=0.95, max_failures=10, tries=50)
    assert not summary["target_reached"] and len(bed) == summary["n"] > 0


def test_progress_hears_a_longer_pack():
    heard = []
    bed, _ = powderbed.pack((2e-3, 1e-3), "mono:d=10e-6", 2, approach=1, progress=heard.append)
    assert heard and set(heard[0]) == {"n", "density", "fraction"}
    assert all(p["n"] <= len(bed) for p in heard)


@pytest.mark.parametrize("call, message", [
    (lambda: powderbed.pack((2e-4, 2e-4), "mono:d=20e-6", 1, approach=3),
     r"^--approach: 3 needs a 3D domain \(accepted in 2D: 0, 1 or 2 contacts\)$"),
    (lambda: powderbed.pack((2e-4, 2e-4, 1e-4), "mono:d=20e-6", 1, collision="octree"),
     r"^collision: 'octree'"),
    (lambda: powderbed.pack((2e-4, 2e-4, 1e-4), "mono:d=20e-6", 1, phases="1:2"),
     r"^phases: "),
    (lambda: powderbed.pack((1e-5, 1e-5, 1e-5), "mono:d=20e-6", 1),
     r"^--domain: 1e-05 x 1e-05 x 1e-05 is smaller than the smallest particle diameter 2e-05$"),
    (lambda: powderbed.pack((2e-4, 2e-4, 1e-4), "mono:d=20e-6", 1, count=10**7),
     r"^--count: 10000000 particles cannot fit"),
    (lambda: powderbed.pack((2e-4,), "mono:d=20e-6", 1), r"^pack: domain: "),
    (lambda: powderbed.pack({"dimension": 3, "lower": [0, 0, 0], "upper": "wide", "periodic": [False] * 3},
                            "mono:d=20e-6", 1),
     r"^domain of the wrong type \(accepted: a dict as Bed.domain, or 2 or 3 lengths in m\)"),
    (lambda: powderbed.pack({"dimension": 3, "lower": [0, 0, 0]}, "mono:d=20e-6", 1),
     r"^domain is missing or wrong \(accepted: a dict as Bed.domain, or 2 or 3 lengths in m\)"),
    (lambda: powderbed.pack((2e-4, 2e-4, 1e-4), "mono:d=-1", 1), r"^psd: "),
    (lambda: powderbed.pack((2e-4, 2e-4, 1e-4), "mono:d=20e-6", 1, approch=3), r"^pack: keyword: 'approch'"),
])
def test_bad_input_is_the_librarys_one_line(call, message):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(powderbed.InputError, match=message):
            call()
