"""Fixtures of the Python tests: small beds made by the module itself, and the source tree.
ctest runs these with PYTHONPATH = the build's python/ folder (tests/CMakeLists.txt)."""
import os

import numpy as np
import pytest

import powderbed

SOURCE = os.environ.get("POWDERBED_SOURCE_DIR",
                        os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))


def scene(name):
    return os.path.join(SOURCE, "data", "scenes", name)


def make_bed(x, y, z, r, upper, **extra):
    """A Bed of spheres at (x, y, z) with radii r in the box [0, upper]."""
    n = len(x)
    fields = {"x": x, "y": y, "z": z, "r": r, "id": np.arange(n, dtype=np.uint64),
              "domain": {"dimension": 3, "lower": [0.0, 0.0, 0.0], "upper": list(upper),
                         "periodic": [False, False, False]},
              "provenance": {"stage": "test"}}
    fields.update(extra)
    return powderbed.Bed(fields)


@pytest.fixture
def packed(tmp_path):
    """A packgen bed of 40 spheres of 20 um (3-contact growth from the floor): (path, summary)."""
    path = tmp_path / "packed.h5"
    summary = powderbed.packgen(dim=3, domain=(2e-4, 2e-4, 1e-4), psd="mono:d=20e-6", count=40,
                                approach=3, seed=1, out=path)
    return path, summary


@pytest.fixture
def sinter_bed(tmp_path):
    """Two rows of six 15 um particles resting on the floor along the track of
    data/scenes/gz2016-sinter.ini (as tests/apps/test_sinter_cli.cpp): a run of about a second
    on a 21 x 11 x 11 substrate grid."""
    r = 15e-6
    x = np.array([25e-6 + i * 29.9e-6 for row in range(2) for i in range(6)])
    y = np.array([35e-6 + row * 29.9e-6 for row in range(2) for i in range(6)])
    bed = make_bed(x, y, np.full(12, r * (1 - 1e-4)), np.full(12, r), (0.2e-3, 0.1e-3, 0.1e-3))
    path = tmp_path / "sinter-bed.h5"
    powderbed.write_bed(bed, path)
    return path


SMALL_GRID = {"substrate.nodes": "21,11,11", "substrate.depth": 0.1e-3}


@pytest.fixture
def column(tmp_path):
    """Four 1 mm steel spheres stacked between keff's walls, overlapping by 1e-3 r, recorded as
    a full-stiffness Hertz bed (as tests/apps/test_keff_cli.cpp)."""
    r, overlap = 0.5e-3, 0.5e-6
    pitch = 2 * r - overlap
    z = np.array([r - overlap + k * pitch for k in range(4)])
    bed = make_bed(np.full(4, r), np.full(4, r), z, np.full(4, r),
                   (2 * r, 2 * r, 3 * pitch + 2 * (r - overlap)),
                   provenance={"stage": "test", "contact_law": "hertz", "contact_young": 198e9,
                               "contact_poisson": 0.28, "contact_wall_young": 198e9,
                               "contact_wall_poisson": 0.28, "contact_young_scale": 1.0,
                               "contact_stiffness": 0.0})
    path = tmp_path / "column.h5"
    powderbed.write_bed(bed, path)
    return path
