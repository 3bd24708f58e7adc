"""deposit in-process (powderbed.deposit on a Bed and the dem structs): the program's bed bit
for bit, progress through a callback, its exceptions, the library's messages and warnings."""
import warnings

import numpy as np
import pytest

import powderbed

# The packed fixture's 40 spheres settling for 0.2 ms at the scenes' softening (E / 1000): ~2,000
# steps of the Rayleigh step, long enough for contacts and walls to act on every particle.
RUN = {"young_scale": 1e3, "t_end": 2e-4}


# The drop solver, and (history friction, rolling resistance) the spreading engine without a
# tool that run_deposition picks for a scene that needs particle rotation.
SCENES = [({}, {}),
          ({"friction_model": "history", "material": {"rolling": 0.05}},
           {"friction.model": "history", "material.rolling": 0.05})]


@pytest.mark.parametrize("mine, theirs", SCENES, ids=["drop", "rotating"])
def test_in_process_deposit_gives_the_programs_bed_bit_for_bit(packed, tmp_path, mine, theirs):
    path, _ = packed
    bed = powderbed.read_bed(path)
    settled, summary = powderbed.deposit(bed, **mine, **RUN)
    program = powderbed.run("deposit", **{"in": path}, young_scale=RUN["young_scale"],
                            t_end=RUN["t_end"], seed=1, out=tmp_path / "d.h5", progress=0, **theirs)
    theirs = powderbed.read_bed(tmp_path / "d.h5")
    for key in ("x", "y", "z", "r", "id", "vx", "vy", "vz"):
        assert np.array_equal(getattr(settled, key), getattr(theirs, key)), key
    assert not np.array_equal(settled.z, bed.z)  # it ran, and the input Bed is untouched
    assert np.array_equal(bed.z, powderbed.read_bed(path).z)
    for key in ("n", "steps", "dt", "dt_stable", "kinetic_energy", "max_overlap", "at_rest"):
        assert summary[key] == program[key], key
    assert settled.provenance["contact_law"] == "hertz"
    assert settled.provenance["contact_young_scale"] == 1e3


def test_structs_passed_in_equal_the_same_keywords(packed):
    bed = powderbed.read_bed(packed[0])
    scene = powderbed.Scene(material={"friction": 0.3})
    settings = powderbed.RunSettings(**RUN)
    a, _ = powderbed.deposit(bed, scene, settings)
    b, _ = powderbed.deposit(bed, material={"friction": 0.3}, **RUN)
    assert np.array_equal(a.z, b.z)
    assert scene.material.friction == 0.3 and settings.t_end == 2e-4  # not changed by the call


def test_progress_is_called_with_monotone_steps_and_fractions(packed):
    seen = []
    powderbed.deposit(powderbed.read_bed(packed[0]), progress_every=200, progress=seen.append, **RUN)
    assert len(seen) >= 5
    steps = [p["step"] for p in seen]
    fractions = [p["fraction"] for p in seen]
    assert steps == sorted(steps) and fractions == sorted(fractions)
    assert 0 < fractions[0] and fractions[-1] == 1.0  # the last call is the run's end
    assert all(p["kinetic_energy"] >= 0 for p in seen)


class Stop(Exception):
    pass


def test_an_exception_in_progress_stops_the_run_and_propagates(packed):
    bed = powderbed.read_bed(packed[0])
    calls = []

    def progress(p):
        calls.append(p["step"])
        if len(calls) == 2:
            raise Stop(f"stopped at step {p['step']}")

    with pytest.raises(Stop, match="stopped at step 400"):
        powderbed.deposit(bed, progress_every=200, progress=progress, **RUN)
    assert calls == [200, 400]  # nothing called after it: the run stopped there
    settled, _ = powderbed.deposit(bed, **RUN)  # and the module still runs
    assert len(settled) == 40


def test_bad_values_raise_value_error_with_the_librarys_message(packed):
    bed = powderbed.read_bed(packed[0])
    with pytest.raises(ValueError, match=r"^--t-end: -1 is out of range \(accepted: T >= 0 s\)$"):
        powderbed.deposit(bed, t_end=-1)
    with pytest.raises(ValueError, match=r"^law: 'cubic' is not a contact law \(accepted: hertz, linear\)$"):
        powderbed.deposit(bed, law="cubic", **RUN)
    with pytest.raises(ValueError, match=r"effects: 'magnetism' is not an effect \(accepted: a list of gravity, "):
        powderbed.deposit(bed, effects=["gravity", "magnetism"], **RUN)
    with pytest.raises(powderbed.InputError, match=r"deposit: keyword: 'tend' \(accepted: material, wall, "):
        powderbed.deposit(bed, tend=1e-3)
    with pytest.raises(ValueError, match=r"RunSettings.t_end: 'soon' \(accepted: a float\)"):
        powderbed.deposit(bed, t_end="soon")
    with pytest.raises(ValueError, match=r"Material: keyword: 'hardness'"):
        powderbed.deposit(bed, material={"hardness": 1}, **RUN)
    with pytest.raises(ValueError, match="deposit: progress: 3"):
        powderbed.deposit(bed, progress=3, **RUN)


def test_a_step_above_the_stable_bound_warns(packed):
    bed = powderbed.read_bed(packed[0])
    _, summary = powderbed.deposit(bed, **RUN)
    dt = 1.5 * summary["dt_stable"]
    with pytest.warns(RuntimeWarning, match=r"^deposit: dt .* s is above the stable bound .* s \(unsafe_dt\)$"):
        powderbed.deposit(bed, young_scale=1e3, dt=dt, unsafe_dt=True, t_end=5 * dt)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the safe run says nothing
        powderbed.deposit(bed, young_scale=1e3, dt=0.5 * summary["dt_stable"], t_end=5 * dt)


def test_struct_defaults_are_the_librarys():
    scene, settings = powderbed.Scene(), powderbed.RunSettings()
    assert scene.material.density == 7952 and scene.law == "hertz"
    assert scene.effects == ["gravity", "hertz", "damping", "friction", "drag", "walls"]
    assert settings.integrator == "verlet" and settings.rest.window == 1e-3
    assert "young=" in repr(scene.material)
