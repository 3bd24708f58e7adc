"""build_scene: a build scene file built in-process gives what the program build gives on it (the
same report, bit for bit the same beds), refuses what the program refuses with the program's
line, and its plan, state and part record continue it in-process as --in continues the program."""
import os

import numpy as np
import pytest

import powderbed
from conftest import SOURCE

# tests/data/build-small (the program's end-to-end tests), with 80 particles a layer instead of
# 120: two layers take well under a second.
SCENE = os.path.join(SOURCE, "tests", "data", "build-small", "build.ini")
SMALL = {"spread_args": "--supply.count 80 --thermo 0"}
FIELDS = ("x", "y", "z", "r", "id", "vx", "vy", "vz")


def comparable(report):
    """A build's report less what differs between two runs of the same build: the wall times
    and the folder."""
    report = {k: v for k, v in report.items() if k not in ("wall_time", "out")}
    report["layers"] = [{k: v for k, v in layer.items() if not k.endswith("wall_time")}
                        for layer in report["layers"]]
    return report


def same_beds(a, b):
    for key in FIELDS:
        assert np.array_equal(getattr(a, key), getattr(b, key)), key


@pytest.fixture(scope="module")
def program(tmp_path_factory):
    """The program's two layers of the scene: its build --json report and folder."""
    out = tmp_path_factory.mktemp("program") / "run"
    return powderbed.run("build", config=SCENE, out=out, layers=2, pictures=False, **SMALL), out


def test_a_scene_file_builds_as_the_program_builds_it(program, tmp_path):
    stages = []
    bed, report, state, part, plan = powderbed.build_scene(
        SCENE, tmp_path / "run", layers=2, progress=lambda p: stages.append((p["layer"], p["stage"])),
        **SMALL)
    expected, folder = program
    assert comparable(report) == comparable(expected)
    assert report["out"] == str(tmp_path / "run") and report["layers_done"] == 2
    assert {(1, "spread"), (2, "spread")} <= set(stages)
    assert state.layers_done == 2 and part.layers == 2 and plan.out == str(tmp_path / "run")
    # the powder left is the last layer file's, which is the program's
    same_beds(bed, powderbed.read_bed(tmp_path / "run" / "layer-002.h5"))
    same_beds(bed, powderbed.read_bed(folder / "layer-002.h5"))
    assert sorted(os.listdir(tmp_path / "run")) == sorted(os.listdir(folder))


def test_its_plan_state_and_part_continue_it_as_the_program_continues(program, tmp_path):
    bed, _, state, part, plan = powderbed.build_scene(SCENE, tmp_path / "two", layers=2, **SMALL)
    more, reports, _, _ = powderbed.build(bed, plan, state=state, part=part, out=tmp_path / "three")
    _, folder = program
    expected = powderbed.run("build", config=SCENE, out=tmp_path / "program", layers=1,
                             pictures=False, **{"in": folder / "layer-002.h5"}, **SMALL)
    assert reports[0]["layer"] == 3
    layer = {k: v for k, v in reports[0].items() if k not in ("spread", "scan")}
    assert comparable({"layers": [layer]}) == comparable({"layers": [
        {k: v for k, v in expected["layers"][0].items() if k != "pictures"}]})
    same_beds(more, powderbed.read_bed(tmp_path / "program" / "layer-003.h5"))


def program_line(**options):
    """The line the program prints before exit 2 for these options, less its "build: "."""
    with pytest.raises(powderbed.ProgramError) as refused:
        powderbed.run("build", config=SCENE, **options)
    assert refused.value.status == 2
    return refused.value.message.removeprefix("build: ")


@pytest.mark.parametrize("bad", [
    {"fuse.melt-fraction": 2},                # the build's own check
    {"bogus": 1},                             # Boost's: an unknown option
    {"spread_args": "--seed 3"},              # an option the build sets itself
    {"sinter_args": "--power -5"},            # the scan stage's check, naming its scene
    {"layers": 40},                           # the plan's: the tool above the box's top
])
def test_bad_input_is_refused_with_the_programs_line(tmp_path, bad):
    line = program_line(out=tmp_path / "program", **bad)
    with pytest.raises(powderbed.InputError) as refused:
        powderbed.build_scene(SCENE, tmp_path / "run", **bad)
    assert str(refused.value) == line
    assert not os.path.exists(tmp_path / "run")  # refused before the folder is made


@pytest.mark.parametrize("option", [{"json": True}, {"help": True}, {"map.power": "100,200"},
                                    {"pictures": True}])
def test_what_only_the_program_does_is_refused_by_name(tmp_path, option, capsys):
    (name,) = option
    with pytest.raises(powderbed.InputError, match=rf"^{name}: "):
        powderbed.build_scene(SCENE, tmp_path / "run", **option)
    assert capsys.readouterr().out == ""  # nothing printed (help, usage)
