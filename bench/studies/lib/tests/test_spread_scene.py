"""lib/spread_scene.py's Scene holds what deposit resolves (its --print-config), defaults and
overrides included. Needs the build's deposit (POWDERBED_BUILD, default build/). Run from
bench/studies: python3 -m pytest lib/tests"""
import re
import subprocess

import pytest

from lib import apps
from lib.spread_scene import Scene, read_scene

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
