"""What a run melted, read from its run file (sinter --out): the studies' shared yardstick for
evaporated / melted mass (the issue's bar: measured evaporative losses in LPBF are well under
1 % of the melt)."""
import numpy as np


def plate_plane(f):
    """The plate's top plane k of a run file (planes above it are room for a raised part)."""
    sub = f["substrate"].attrs
    return int(sub["plate_plane"]) if "plate_plane" in sub else int(sub["nodes"][2]) - 1


def melted_mass(run_path, length=None):
    """Mass that melted along a track along x, kg: the particles whose peak reached T_m (their
    starting mass), and the substrate's molten cross-section on x = Lx/2 (nodes whose peak
    reached T_m, each its cell's area; the top row half a cell) times the track's `length` (m;
    None: the plate's), at the solid density at T0. The track is quasi-steady, so one section
    stands for all; the ends where the beam enters and leaves make it an upper bound."""
    import h5py
    with h5py.File(run_path, "r") as f:
        rad = np.array(f["particles/radius"])
        peak = np.array(f["melt/particle"])
        section = np.array(f["melt/section_x"])  # nz x ny
        section = section[:plate_plane(f) + 1]  # up to the plate's top face
        t_m = float(f["melt"].attrs["melting_point"])
        nx = f["melt/top"].shape[1]
        dx, dy, dz = f["substrate"].attrs["spacing"]
    rho = 7952.0  # kg/m^3: data/materials/316L.csv ([GZ] Table 2, at 293 K)
    cells = np.full(section.shape, dy * dz)
    cells[-1, :] *= 0.5
    area = float(cells[section >= t_m].sum())
    particles = rho * 4.0 / 3.0 * np.pi * float((rad[peak >= t_m] ** 3).sum())
    return particles + rho * area * (dx * (nx - 1) if length is None else length)
