"""build in-process (powderbed.build on a BuildPlan of the bound structs): a build continued
from its state and part record equals the straight one, the layers' files are written, the
plan's checks are the library's."""
import os

import numpy as np
import pytest

import powderbed
from test_stages_in_process import lattice_supply, strip

# tests/data/build-small's scenes (the program's end-to-end tests) as structs: a blade spreads
# a 1.2 mm strip at a 60 um gap, a two-track hatch is scanned at 100 W and 1 m/s on a 20 um
# substrate grid (76 x 16 x 6 nodes over the 1.5 x 0.3 mm box, 0.1 mm deep). The supply is the
# lattice of test_stages_in_process.py instead of the program's packgen placement.
PLAN = {
    "scene": {"material": {"friction": 0.5, "rolling": 0.05}, "friction_model": "history",
              "effects": ["gravity", "hertz", "damping", "friction", "walls"]},
    "spread": {"young_scale": 1e4, "layer_thickness": 30e-6, "supply_x0": 0.16e-3,
               "supply_x1": 0.4e-3, "supply_height": 0.2e-3,
               "tool": {"thickness": 100e-6, "gap": 60e-6, "speed": 0.2, "start": 0.1e-3,
                        "end": 1.2e-3, "delay": 3e-3, "settle": 5e-3}},
    "scan": {"power": 100, "speed": 1, "spot_radius": 30e-6, "absorption": "beer-lambert",
             "nodes": [76, 16, 6], "substrate_depth": 0.1e-3},
    "snapshots": 2, "finest_diameter": 30e-6,
}


def hatch():
    return powderbed.Hatch(spacing=60e-6, tracks=2, region=[0.6e-3, 1.1e-3, 0.05e-3, 0.25e-3],
                           power=100, speed=1)


def test_a_build_continued_layer_by_layer_equals_the_straight_build(tmp_path):
    stages = []
    straight, reports, state, part = powderbed.build(
        strip(), out=tmp_path / "two", layers=2, hatch=hatch(), supply=lattice_supply,
        progress=lambda p: stages.append((p["layer"], p["stage"])), **PLAN)
    assert [r["layer"] for r in reports] == [1, 2] and state.layers_done == 2 and part.layers == 2
    assert reports[0]["fused"] > 0 and reports[0]["scan"]["max_temperature"] > 1700
    assert {(1, "spread"), (2, "spread")} <= set(stages)
    for name in ("layer-001-spread.h5", "layer-001-scan.h5", "layer-002.h5"):
        assert os.path.isfile(tmp_path / "two" / name), name

    first, _, state1, part1 = powderbed.build(strip(), out=tmp_path / "one", hatch=hatch(),
                                              supply=lattice_supply, **PLAN)
    again, rest, _, _ = powderbed.build(first, out=tmp_path / "one", state=state1, part=part1,
                                        hatch=hatch(), supply=lattice_supply, **PLAN)
    assert rest[0]["layer"] == 2 and rest[0]["fused"] == reports[1]["fused"]
    for key in ("x", "y", "z", "vx", "vz", "id"):
        assert np.array_equal(getattr(again, key), getattr(straight, key)), key


def test_the_plans_checks_are_the_librarys(tmp_path):
    with pytest.raises(ValueError, match=r"^--layers: 40 from layer 1: the tool rises above the box's top"):
        powderbed.build(strip(), out=tmp_path / "b", layers=40, hatch=hatch(), **PLAN)
    with pytest.raises(ValueError, match=r"^out: '' \(accepted: the folder for the layers' files\)$"):
        powderbed.build(strip(), hatch=hatch(), **PLAN)
    with pytest.raises(ValueError, match=r"BuildPlan.hatch: 6e-05 \(accepted: what help"):
        powderbed.build(strip(), out=tmp_path / "b", hatch=60e-6)
    assert not os.path.exists(tmp_path / "b")  # refused before anything was written
