"""lib/spread_scene.py's Scene holds what deposit resolves (its --print-config), defaults and
overrides included. Needs the build's deposit (POWDERBED_BUILD, default build/). Run from
bench/studies: python3 -m pytest lib/tests"""
import math
import re
import subprocess

import pytest

from lib import apps
from lib import spread_scene
from lib.spread_scene import Scene, read_scene, solid_volume

BLADE = apps.scene("spread-blade.ini")
# Scene's attributes and the deposit options they hold
NUMBERS = {"young": "material.young", "poisson": "material.poisson", "density": "material.density",
           "damping": "material.damping", "friction": "material.friction",
           "rolling": "material.rolling", "wall_young": "wall.young", "wall_poisson": "wall.poisson",
           "young_scale": "young-scale", "gravity": "gravity", "gap": "recoater.gap",
           "speed": "recoater.speed", "start": "recoater.start", "end": "recoater.end",
           "thickness": "recoater.thickness", "delay": "recoater.delay",
           "settle": "recoater.settle"}


def printed(scene, key):
    """deposit's --print-config line of `key` for `scene`, read here on its own (not through
    lib.apps): (value, whether it is the default)."""
    text = subprocess.run([apps.app("deposit"), "--config", str(scene), "--print-config"],
                          capture_output=True, text=True, check=True).stdout
    m = re.search(rf"^(# )?{re.escape(key)} = (.*?)(  \(default\))?$", text, re.M)
    return m.group(2), m.group(3) is not None


def test_scene_holds_what_deposit_prints():
    scene = Scene(BLADE, {})
    for attribute, key in NUMBERS.items():
        assert getattr(scene, attribute) == float(printed(BLADE, key)[0]), key


def test_scene_takes_deposit_defaults(tmp_path):
    # the blade scene less its [material] poisson line: deposit's default fills it
    text = open(BLADE).read()
    assert text.count("\npoisson = ") == 2  # [material] and [wall]
    path = tmp_path / "no-poisson.ini"
    path.write_text(text.replace("\npoisson = ", "\n# poisson = ", 1))
    value, default = printed(path, "material.poisson")
    assert default
    assert Scene(str(path), {}).poisson == float(value)


def test_scene_drag_and_friction_law_follow_deposit(tmp_path):
    # a blade scene that names neither: deposit's defaults, not ones typed again in Python
    path = tmp_path / "bare.ini"
    path.write_text("psd = mono:d=30e-6\ndomain = 1e-3,0.5e-3,1e-3\nperiodic = y\n"
                    "[recoater]\ntool = blade\nend = 0.8e-3\n")
    scene = Scene(str(path), {})
    assert scene.drag == (printed(path, "effects.drag")[0] == "true")
    law = printed(path, "friction.model")[0]
    assert scene.tangential == ("history" if law == "history" else "no_history")


def test_overrides_reach_the_resolved_values():
    scene = Scene(BLADE, {"recoater.gap": "1.5e-4", "effects.drag": "false"})
    assert scene.gap == 1.5e-4
    assert not scene.drag
    assert read_scene(BLADE, {"material.rolling": "0.2"})["material.rolling"] == "0.2"


def test_a_refused_scene_names_deposit(tmp_path):
    path = tmp_path / "bad.ini"
    path.write_text("no-such-option = 1\n")
    with pytest.raises(RuntimeError, match="no-such-option"):
        read_scene(str(path))


def test_nominal_layer_is_deposit_dosing_by_volume(tmp_path):
    # deposit's supply.dosing d supplies d times Scene.nominal_layer() of solid: the blade
    # scene's psd (D10/D50/D90 by volume) on a 0.2 mm travel (crossed in 0.2 ms), the overflow
    # kept. Within one largest particle (53 um: 7.8e-14 m^3): packgen stops at the first that
    # reaches the target. A dosing that counted particles of the D50 would miss by a third.
    overrides = {"recoater.end": "0.3e-3", "recoater.delay": "1e-5", "recoater.speed": "1",
                 "recoater.settle": "0", "recoater.overflow": "false", "supply.count": "0",
                 "supply.dosing": "1.5"}
    bed = str(tmp_path / "supply.h5")
    out, _ = apps.run_json([apps.app("deposit"), "--config", BLADE, "--seed", "1", "--threads", "1",
                            "--out", bed, *apps.option_args(overrides)])
    assert out["lost"] == 0
    _, radii = apps.read_bed(bed)
    largest = 4.0 / 3.0 * math.pi * (53e-6 / 2) ** 3
    assert abs(solid_volume(radii) - 1.5 * Scene(BLADE, overrides).nominal_layer()) <= largest


def test_run_rows_runs_seed_1_of_every_row_first_and_returns_row_order():
    rows = [("a", "A", [], [1, 2]), ("b", "B", [], [1])]
    calls = []

    def run(key, label, options, seed):
        calls.append((key, seed))
        return f"{key}{seed}"

    assert spread_scene.run_rows(rows, run) == ["a1", "a2", "b1"]
    assert calls == [("a", 1), ("b", 1), ("a", 2)]
