"""lib/melted.py's melted mass on a run file made by hand: two particles (one reached T_m), a
substrate section with a known molten area. Run from bench/studies: python3 -m pytest lib/tests"""
import math

import numpy as np
import pytest

h5py = pytest.importorskip("h5py")

from lib.melted import melted_mass  # noqa: E402

RHO = 7952.0  # the density melted_mass books at


def run_file(path, peaks, section):
    with h5py.File(path, "w") as f:
        f["particles/radius"] = np.array([10e-6, 20e-6])
        f["melt/particle"] = np.array(peaks)
        f["melt/section_x"] = section
        f["melt/top"] = np.zeros((3, 11))  # ny x nx: 11 nodes along x, 1 mm at 0.1 mm
        f["melt"].attrs["melting_point"] = 1700.0
        f["substrate"] = h5py.Empty("f")
        f["substrate"].attrs["spacing"] = np.array([1e-4, 1e-5, 1e-5])
        f["substrate"].attrs["nodes"] = np.array([11, 3, section.shape[0]])


def test_particles_that_reached_t_m_and_the_molten_section_times_the_length(tmp_path):
    section = np.full((4, 3), 300.0)  # nz x ny, the top row is the plate's face
    section[3, 1] = section[2, 1] = 2000.0  # one interior cell and half a top cell molten
    path = str(tmp_path / "run.h5")
    run_file(path, [1800.0, 1000.0], section)
    particle = RHO * 4 / 3 * math.pi * (10e-6) ** 3
    area = 1.5 * 1e-5 * 1e-5
    assert melted_mass(path) == pytest.approx(particle + RHO * area * 1e-3, rel=1e-12)
    assert melted_mass(path, 0.6e-3) == pytest.approx(particle + RHO * area * 0.6e-3, rel=1e-12)


def test_nothing_molten_is_no_mass(tmp_path):
    path = str(tmp_path / "run.h5")
    run_file(path, [1000.0, 1000.0], np.full((4, 3), 300.0))
    assert melted_mass(path) == 0
