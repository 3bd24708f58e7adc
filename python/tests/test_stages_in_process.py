"""spread, keff and sinter in-process: the same numbers as the programs on the same bed, a
spread continued from its state, the structs' checks."""
import numpy as np
import pytest

import powderbed
from conftest import make_bed


def test_keff_in_process_is_the_programs(column):
    mine = powderbed.keff(powderbed.read_bed(column))
    theirs = powderbed.run("keff", bed=column)
    assert mine["k_eff"] == theirs["k_eff"]  # the same solve on the same scene
    assert mine["k_eff"] > 0 and len(mine["temperature"]) == 4
    hot = powderbed.keff(powderbed.read_bed(column), hot_temperature=315)
    assert hot["temperature"].max() > mine["temperature"].max()


def test_keff_hertz_correction_reads_the_beds_contact_law(column):
    bed = powderbed.read_bed(column)
    corrected = powderbed.keff(bed, contact={"hertz_correction": True})
    assert corrected["k_eff"] > 0
    del bed.provenance["contact_law"]
    with pytest.raises(ValueError, match="contact law"):
        powderbed.keff(bed, contact={"hertz_correction": True})
    with pytest.raises(ValueError, match=r"^gas_model: 'argon' \(accepted: constant, air\)$"):
        powderbed.keff(bed, gas_model="argon")


SMALL_GRID = {"nodes": [21, 11, 11], "substrate_depth": 0.1e-3}


def test_sinter_in_process_is_the_programs(sinter_bed, tmp_path):
    bed = powderbed.read_bed(sinter_bed)
    heated, mine = powderbed.sinter(bed, **SMALL_GRID)
    theirs = powderbed.run("sinter", bed=sinter_bed, out=tmp_path / "run.h5",
                           **{"substrate.nodes": "21,11,11", "substrate.depth": 0.1e-3})
    for key in ("max_temperature", "particles_molten", "steps", "dt", "absorptance"):
        assert mine[key] == theirs[key], key
    assert mine["melt_pool"]["width"] == theirs["melt_pool"]["width"]
    assert heated.temperature.max() > 363 and heated.phase is not None
    assert bed.temperature is None  # the input Bed is untouched
    dt = 2 * mine["dt_stable_grid"]  # three steps beyond the bound: told, not refused
    with pytest.warns(RuntimeWarning, match=r"^sinter: dt .* s is above the stable bound .* s \(unsafe_dt\)$"):
        powderbed.sinter(bed, dt=dt, unsafe_dt=True, t_end=3 * dt, **SMALL_GRID)


def test_sinter_scene_is_a_class_with_the_librarys_defaults():
    scene = powderbed.SinterScene(power=150, rays={"rays": 100})
    assert scene.power == 150 and scene.rays.rays == 100 and scene.speed == 2.0
    assert scene.absorption == "ray-trace" and "wetting" in scene.effects
    with pytest.raises(ValueError, match=r"^absorption: 'lambert' \(accepted: beer-lambert, ray-trace\)$"):
        scene.absorption = "lambert"
    assert scene.substrate_periodic == "none"
    with pytest.raises(ValueError, match=r"^substrate_periodic: 'x' \(accepted: none, y\)$"):
        scene.substrate_periodic = "x"


def test_a_periodic_plate_needs_a_bed_periodic_along_y(sinter_bed):
    bed = powderbed.read_bed(sinter_bed)
    with pytest.raises(powderbed.InputError, match=r"^substrate.periodic: y on a bed bounded along y"):
        powderbed.sinter(bed, substrate_periodic="y", **SMALL_GRID)


# A strip 1.5 mm along the blade's travel, periodic across, as tests/dem/test_spread.cpp's
# small_spread: a 100 um blade at a 60 um gap from x = 0.1 to 1.2 mm, the supply a lattice of
# 15 um spheres in front of it.
SPREAD = {"young_scale": 1e3, "layer_thickness": 30e-6, "supply_x0": 0.16e-3, "supply_x1": 0.4e-3,
          "supply_height": 0.15e-3, "remove_overflow": False,
          "tool": {"thickness": 100e-6, "gap": 60e-6, "speed": 0.2, "start": 0.1e-3, "end": 1.2e-3}}
SCENE = {"material": {"friction": 0.5, "rolling": 0.05}, "friction_model": "history",
         "effects": ["gravity", "hertz", "damping", "friction", "walls"]}


def strip():
    bed = make_bed(np.zeros(0), np.zeros(0), np.zeros(0), np.zeros(0), (1.5e-3, 0.3e-3, 0.6e-3))
    bed.domain["periodic"] = [False, True, False]
    return bed


def lattice_supply(region, layer):
    r, pitch = 15e-6, 32e-6
    lo, hi = region["lower"], region["upper"]
    axes = [np.arange(lo[a] + r + 1e-6, hi[a] - r + 1e-12, pitch) for a in range(3)]
    z, y, x = (g.ravel() for g in np.meshgrid(axes[2], axes[1], axes[0], indexing="ij"))
    return make_bed(x, y, z, np.full(len(x), r), hi)


def test_spread_continued_from_its_state_equals_the_straight_run():
    straight, two, _ = powderbed.spread(strip(), supply=lattice_supply, layers=2, **SPREAD, **SCENE)
    first, one, state = powderbed.spread(strip(), supply=lattice_supply, **SPREAD, **SCENE)
    assert state.layers_done == 1 and one["layers"][0]["supplied"] > 100
    again, rest, _ = powderbed.spread(first, state=state, supply=lattice_supply, **SPREAD, **SCENE)
    assert rest["layers"][0]["layer"] == 2 and len(two["layers"]) == 2
    for key in ("x", "y", "z", "vx", "vz", "id"):
        assert np.array_equal(getattr(again, key), getattr(straight, key)), key
    assert again.provenance["contact_law"] == "hertz"


def test_spread_on_the_dosing_platform_counts_what_it_removes():
    # platform_edge 0.45 mm, past the supply's end: its floor stands at the blade's bottom, the
    # report counts under_platform, and every particle is in the bed or counted.
    bed, report, _ = powderbed.spread(strip(), supply=lattice_supply, platform_edge=0.45e-3,
                                          **SPREAD, **SCENE)
    layer = report["layers"][0]
    assert layer["under_platform"] == 0 and layer["overflow"] == 0  # SPREAD keeps the overflow
    assert layer["supplied"] > 100 and len(bed.x) == layer["supplied"]
    gap = SPREAD["tool"]["gap"]
    on_it = bed.x < 0.45e-3 - bed.r
    assert np.all(bed.z[on_it] > gap + 0.99 * bed.r[on_it])
    with pytest.raises(powderbed.InputError, match=r"^supply.platform-edge: 0.0003 m"):
        powderbed.spread(strip(), supply=lattice_supply, platform_edge=0.3e-3, **SPREAD, **SCENE)


def test_spread_progress_and_supply_errors_propagate():
    fractions = []
    powderbed.spread(strip(), supply=lattice_supply, progress_every=500,
                     progress=lambda p: fractions.append(p["fraction"]), **SPREAD, **SCENE)
    assert len(fractions) > 2 and fractions == sorted(fractions) and fractions[-1] <= 1
    with pytest.raises(ValueError, match="spread: what supply returned: 7"):
        powderbed.spread(strip(), supply=lambda region, layer: 7, **SPREAD, **SCENE)
    with pytest.raises(ValueError, match=r"spread: keyword: 'blade'"):
        powderbed.spread(strip(), blade={"gap": 1e-5})
