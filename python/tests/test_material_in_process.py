"""material="NAME" of the run functions: what the programs' --material NAME fills (the one table,
bed/material_fills.hpp), a keyword beside it winning, and the program's line for a bad name."""
import numpy as np
import pytest

import powderbed

RUN = {"young_scale": 1e3, "t_end": 1e-4}


@pytest.mark.parametrize("name", ["316L", "copper"])
def test_deposit_with_a_material_is_the_programs(packed, tmp_path, name):
    path, _ = packed
    settled, summary = powderbed.deposit(powderbed.read_bed(path), material=name, **RUN)
    program = powderbed.run("deposit", **{"in": path}, material=name, seed=1, out=tmp_path / "d.h5",
                            progress=0, **RUN)
    theirs = powderbed.read_bed(tmp_path / "d.h5")
    for key in ("x", "y", "z", "vx", "vy", "vz"):
        assert np.array_equal(getattr(settled, key), getattr(theirs, key)), key
    assert summary["dt"] == program["dt"] and summary["kinetic_energy"] == program["kinetic_energy"]
    assert settled.provenance["contact_young"] == theirs.provenance["contact_young"]


def test_copper_fills_the_scene_and_a_keyword_beside_it_wins(packed):
    bed = powderbed.read_bed(packed[0])
    _, copper = powderbed.deposit(bed, material="copper", **RUN)
    _, steel = powderbed.deposit(bed, **RUN)
    assert copper["dt"] != steel["dt"]  # another density and modulus
    _, dense = powderbed.deposit(bed, material="copper", scene=powderbed.Scene(material={"density": 1e4}), **RUN)
    _, kept = powderbed.deposit(bed, material={"density": 1e4}, **RUN)
    assert dense["dt"] != kept["dt"]  # the struct passed in gives way, as a scene file does


def test_keff_with_a_material_is_the_programs(column):
    mine = powderbed.keff(powderbed.read_bed(column), material="IN718")
    theirs = powderbed.run("keff", bed=column, material="IN718")
    assert mine["k_eff"] == theirs["k_eff"]
    assert mine["k_eff"] != powderbed.keff(powderbed.read_bed(column))["k_eff"]
    given = powderbed.keff(powderbed.read_bed(column), material="IN718", solid_conductivity=16.2)
    assert given["k_eff"] == powderbed.keff(powderbed.read_bed(column), solid_conductivity=16.2)["k_eff"]


def test_keff_holds_the_hot_wall_under_the_materials_solidus_as_the_program_does(column):
    # IN718's solidus is 1533 K (data/materials/IN718.csv): a hot wall there asks for k_eff of a
    # bed that has melted; the program refuses it with --material and so must the function.
    with pytest.raises(powderbed.ProgramError) as program:
        powderbed.run("keff", bed=column, material="IN718", t_hot=1540, t_cold=1500)
    line = str(program.value).splitlines()[-1]
    with pytest.raises(powderbed.InputError) as mine:
        powderbed.keff(powderbed.read_bed(column), material="IN718", hot_temperature=1540,
                       cold_temperature=1500)
    assert str(mine.value).startswith("--t-hot: the hot wall at 1540 K is not below IN718's solidus 1533 K")
    assert str(mine.value) in line


def test_keff_without_a_material_holds_the_hot_wall_under_tungstens_melting_point(column):
    # No metal is solid at 4000 K (tungsten melts at 3695 K): the program refuses the wall
    # unless --trust-units, and so must the function unless trust_units=True.
    with pytest.raises(powderbed.ProgramError) as program:
        powderbed.run("keff", bed=column, t_hot=4000, t_cold=3900)
    line = str(program.value).splitlines()[-1]
    bed = powderbed.read_bed(column)
    with pytest.raises(powderbed.InputError) as mine:
        powderbed.keff(bed, hot_temperature=4000, cold_temperature=3900)
    assert str(mine.value) in line
    trusted = powderbed.keff(bed, hot_temperature=4000, cold_temperature=3900, trust_units=True)
    theirs = powderbed.run("keff", bed=column, t_hot=4000, t_cold=3900, trust_units=True)
    assert trusted["k_eff"] == theirs["k_eff"]
    with pytest.raises(powderbed.InputError, match="trust_units"):
        powderbed.keff(bed, trust_units="yes")


def test_an_unknown_material_is_the_programs_line(packed, tmp_path):
    bed = powderbed.read_bed(packed[0])
    with pytest.raises(powderbed.ProgramError) as program:
        powderbed.run("deposit", **{"in": packed[0]}, material="unobtainium", out=tmp_path / "d.h5")
    line = str(program.value).splitlines()[-1]
    with pytest.raises(powderbed.InputError) as mine:
        powderbed.deposit(bed, material="unobtainium", **RUN)
    assert str(mine.value).startswith("--material: 'unobtainium' is not a material (accepted: 316L")
    assert str(mine.value) in line
    with pytest.raises(powderbed.InputError, match=r"^--material: 'unobtainium' is not a material"):
        powderbed.sinter(bed, material="unobtainium")


def test_sinter_with_a_material_is_the_programs(sinter_bed, tmp_path):
    grid = {"nodes": [21, 11, 11], "substrate_depth": 0.1e-3}
    _, mine = powderbed.sinter(powderbed.read_bed(sinter_bed), material="Ti-6Al-4V", **grid)
    theirs = powderbed.run("sinter", bed=sinter_bed, out=tmp_path / "run.h5", material="Ti-6Al-4V",
                           **{"substrate.nodes": "21,11,11", "substrate.depth": 0.1e-3})
    for key in ("max_temperature", "particles_molten", "steps", "dt", "absorptance"):
        assert mine[key] == theirs[key], key
