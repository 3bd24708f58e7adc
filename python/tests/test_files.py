"""What the files the programs write say about themselves: every dataset names its SI unit in
a `units` attribute, the step groups of a time series sort in time order, and each XDMF sidecar
gives the particles a Polyvertex connectivity (docs/bed-format.md)."""
import subprocess

import h5py
import numpy as np

import powderbed
from conftest import SMALL_GRID, scene
from powderbed._programs import executable

UNITS = {"position": "m", "radius": "m", "velocity": "m/s", "temperature": "K",
         "particle_temperature": "K", "section_y": "K", "section_x": "K", "top": "K",
         "particle": "K", "substrate": "K", "id": "1", "phase": "1", "particle_phase": "1",
         "material": "1", "polyvertex": "1",
         # /tracks: the melt pool and what each scan segment leaves for the next
         "width": "m", "depth": "m", "height": "m", "length": "m", "particles_molten": "1",
         "peak_temperature": "K", "start_temperature": "K", "stored_energy": "J",
         "t_start": "s", "t_end": "s"}


def datasets(path):
    found = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: found.__setitem__(name, obj.attrs.get("units"))
                     if isinstance(obj, h5py.Dataset) else None)
    return found


def check_units(path):
    found = datasets(path)
    assert found
    for name, units in found.items():
        assert units == UNITS[name.rsplit("/", 1)[-1]], (path, name, units)


def check_time_order(path):
    with h5py.File(path, "r") as f:
        names = sorted(f["steps"])  # lexical, as h5py and h5ls list them
        times = [f["steps"][n].attrs["time"] for n in names]
    assert len(names) > 10  # so that the step numbers have different digit counts
    assert np.all(np.diff(times) > 0), names


def check_polyvertex(path, n):
    with h5py.File(path, "r") as f:
        assert np.array_equal(f["xdmf/polyvertex"][()], np.arange(n))
    text = open(str(path)[:-3] + ".xmf").read()
    assert text.count('TopologyType="Polyvertex"') == text.count(":/xdmf/polyvertex<") > 0
    return text


def test_bed_file(packed):
    path, summary = packed
    check_units(path)
    check_polyvertex(path, summary["n"])


def test_trajectory(packed, tmp_path):
    path, _ = packed
    traj = tmp_path / "t.h5"
    powderbed.run("deposit", **{"in": path}, young_scale=1e3, t_end=2e-6, seed=1,
                  out=tmp_path / "d.h5", trajectory=traj, every=1)
    check_units(traj)
    check_time_order(traj)
    check_polyvertex(traj, 40)


def test_sinter_run(sinter_bed, tmp_path):
    run = tmp_path / "run.h5"
    powderbed.run("sinter", config=scene("gz2016-sinter.ini"), bed=sinter_bed, out=run, snapshots=12,
                  full_fields=True, **SMALL_GRID)
    check_units(run)
    check_time_order(run)
    text = check_polyvertex(run, 12)
    # Three named temporal collections: particles, substrate top face, substrate section.
    for name in ("particles", "top", "section_y"):
        assert f'<Grid Name="{name}" GridType="Collection" CollectionType="Temporal">' in text
