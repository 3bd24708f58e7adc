"""lib/references.py against what the models are defined by and what the scenes were made from.
Run from bench/studies (ctest sets PYTHONPATH to it): python3 -m pytest lib/tests"""
import math

import numpy as np
import pytest

from lib import apps, references


def zbs_unit_cell(porosity, kappa, c=1.25):
    """Zehner–Schlünder's unit cell integrated numerically: at radius r (cell radius 1, height 1)
    the solid fills z(r) = B s / (1 + (B - 1) s), s = sqrt(1 - r^2), in series with the gas
    above it, k_core/k_g = int_0^1 2 r dr / (1 - z + z / kappa); the core carries the area
    fraction sqrt(1 - eps), gas alone the rest. With r = sin(t) the integrand is smooth; Gauss
    rules on intervals halving towards t = 0 resolve its peak of height kappa there."""
    b = c * ((1 - porosity) / porosity) ** (10 / 9)
    x, w = np.polynomial.legendre.leggauss(32)
    edges = [0.0] + [math.pi / 2 * 2.0 ** -k for k in range(40, -1, -1)]
    core = 0.0
    for lo, hi in zip(edges, edges[1:]):
        t = lo + (x + 1) * (hi - lo) / 2
        r, s = np.sin(t), np.cos(t)
        z = b * s / (1 + (b - 1) * s)
        core += float(np.sum(w * (hi - lo) / 2 * 2 * r * s / (1 - z + z / kappa)))
    root = math.sqrt(1 - porosity)
    return 1 - root + root * core


@pytest.mark.parametrize("porosity", [0.36, 0.4, 0.45])
@pytest.mark.parametrize("kappa", [10.0, 1e3, 1e4])
def test_zbs_is_the_unit_cell(porosity, kappa):
    assert references.zbs(porosity, kappa) == pytest.approx(zbs_unit_cell(porosity, kappa),
                                                            rel=1e-10)


@pytest.mark.parametrize("porosity", [0.36, 0.4, 0.45])
def test_zbs_of_a_homogeneous_medium_is_one(porosity):
    assert references.zbs(porosity, 1.0) == pytest.approx(1.0, rel=1e-12)


def test_zbs_at_the_steel_bed():
    # keff-parameters.md's ratio study: core porosity 0.397, k_g/k_s = 1e-4 and 1e-1
    assert references.zbs(0.397, 1e4) == pytest.approx(22.6, abs=0.5)
    assert references.zbs(0.397, 10.0) == pytest.approx(3.67, abs=0.05)


@pytest.mark.parametrize("t, k", [(300, 0.0263), (600, 0.0469), (1000, 0.0667)])
def test_k_air_follows_air_tables(t, k):
    # air at 1 atm, Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, Table A.4
    assert references.k_air(t) == pytest.approx(k, rel=0.02)


@pytest.mark.parametrize("case", references.KE2016_CASES, ids=lambda c: c.case)
def test_ke2016_scenes_hold_the_middles_of_table_2(case):
    """The keff and bed scenes take the middles of [KE]'s ranges (their headers say so)."""
    keff_scene, bed_scene = apps.ke2016_keff_scene(case.case), apps.ke2016_bed_scene(case.case)
    assert apps.scene_value(keff_scene, "solid", "conductivity") == pytest.approx(
        sum(case.k_s) / 2, rel=1e-3)
    assert apps.scene_value(keff_scene, "gas", "conductivity") == pytest.approx(
        sum(case.k_g) / 2, rel=1e-3)
    assert apps.scene_value(bed_scene, "material", "young") == pytest.approx(
        sum(case.young) / 2 * 1e9, rel=1e-2)
    psd = next(line.split("=", 1)[1].strip() for line in open(bed_scene)
               if line.startswith("psd"))
    assert psd == f"mono:d={case.diameter:g}"


def test_ke2016_case_lookup():
    assert references.ke2016_case("copper-0.15mm").diameter == 0.15e-3
    with pytest.raises(StopIteration):
        references.ke2016_case("gold")


def test_fresnel_normal_of_316L():
    # a flat 316L surface near 1.06 um absorbs about 0.35 at normal incidence
    # 4n / ((n + 1)^2 + k^2) for data/materials/316L.csv's index
    assert references.fresnel_normal(complex(3.235, 4.322)) == pytest.approx(0.3534, abs=1e-4)
    assert references.fresnel_normal(complex(1.0, 0.0)) == pytest.approx(1.0)


@pytest.mark.parametrize("xi, y, z", [(-300e-6, 0.0, 0.0), (-100e-6, 50e-6, -20e-6),
                                      (50e-6, 0.0, -80e-6)])
def test_eagar_tsai_tends_to_rosenthal(xi, y, z):
    """A spot far smaller than the distance: Rosenthal's point source,
    T - T0 = q / (2 pi k R) exp(-v (xi + R) / (2 kappa)) on the semi-infinite body."""
    pytest.importorskip("scipy")  # EagarTsai integrates with scipy (not in scripts/setup.sh)
    q, k, rho_c, v = 100.0, 20.0, 4.5e6, 1.0
    et = references.EagarTsai(q, k, rho_c, 0.2e-6, v)
    r = math.sqrt(xi * xi + y * y + z * z)
    rosenthal = q / (2 * math.pi * k * r) * math.exp(-v * (xi + r) / (2 * k / rho_c))
    assert et.temperature(xi, y, z) == pytest.approx(rosenthal, rel=2e-3)


def test_eagar_tsai_point_source_pool_is_a_half_circle():
    """Rosenthal's isotherms are spheres about the source in the cross-section's metric: the
    widest half-width on the surface equals the deepest depth (W = 2 D)."""
    pytest.importorskip("scipy")
    et = references.EagarTsai(100.0, 20.0, 4.5e6, 0.5e-6, 1.0)
    width, depth, length = et.melt_pool(1400.0)
    assert width == pytest.approx(2 * depth, rel=1e-3)
    assert length > width


def validation_rows():
    """The rows of data/validation/*.csv (header comments skipped), with their file."""
    import csv
    import glob
    import os
    rows = []
    for path in sorted(glob.glob(os.path.join(apps.ROOT, "data", "validation", "*.csv"))):
        with open(path) as f:
            for r in csv.DictReader(line for line in f if not line.startswith("#")):
                rows.append((os.path.basename(path), r))
    return rows


def test_validation_rows_are_complete():
    """Every measured track names its source and has SI numbers of the right size: a power, a
    speed, a width or a depth in metres (tens to hundreds of um), a spot radius or none."""
    rows = validation_rows()
    assert len(rows) >= 30
    for name, r in rows:
        assert r["source"].strip(), name
        assert 10 < float(r["power_W"]) < 2000 and 0.05 < float(r["speed_m_per_s"]) < 5, name
        sizes = [float(r[k]) for k in ("width_m", "depth_m") if r[k].strip()]
        assert sizes and all(5e-6 < x < 1e-3 for x in sizes), name
        if r["spot_radius_m"].strip():
            assert 10e-6 < float(r["spot_radius_m"]) < 200e-6, name
        assert r["plate"] in ("bare", "powder", "unknown"), name


def test_validation_ornl_depth_is_the_mean_and_w_is_half_d4sigma():
    for name, r in validation_rows():
        if name.startswith("ornl"):
            assert float(r["depth_m"]) == pytest.approx(
                0.5 * (float(r["depth_1_m"]) + float(r["depth_2_m"])), rel=1e-9)
            assert float(r["spot_radius_m"]) == pytest.approx(109.69e-6 / 2, rel=1e-9)
