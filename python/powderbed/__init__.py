"""powderbed from Python: beds as numpy arrays, PSD sampling, bedstat's statistics, the stages
pack (packgen), deposit, spread, keff, sinter and build run in-process on a Bed, and every program's --json
summary as a dict (README "Python", docs/python.md).

    import powderbed
    b = powderbed.read_bed("out/deposit.h5")      # b.x, b.y, b.z, b.r, b.id, b.domain, ...
    print(powderbed.stats(b)["coordination"])     # the entry bedstat --json prints for it
    radii = powderbed.sample_psd("gauss:mean=27e-6,sd=4.25e-6,min=10e-6,max=50e-6", 600, seed=1)
    settled, summary = powderbed.deposit(b, t_end=1e-3, young_scale=1e3)   # in-process
    packed, summary = powderbed.pack((2e-4, 2e-4, 1e-4), "mono:d=20e-6", 1, approach=3)
    summary = powderbed.run("deposit", config="data/scenes/gz2016-deposit.ini", out="gz.h5", seed=1)

Lengths in metres, velocities in m/s, temperatures in K (SI, as the bed files).
"""
try:
    import numpy  # noqa: F401  (the arrays the C++ half returns)
except ImportError as error:
    import sys
    raise ImportError(f"powderbed needs numpy, which {sys.executable} cannot import (Debian: "
                      "python3-numpy, installed by scripts/setup.sh)") from error

import json as _json

from . import _checks, _core
from ._version import __version__
from ._programs import PROGRAMS, ProgramError, run
from ._bed import Bed, bed_of as _bed_of
from ._runs import pack, deposit, spread, keff, sinter, build, build_scene
from ._core import (PackOptions, Scene, Material, WallMaterial, Fines, RunSettings, RestCriteria, LidSettings,
                    InsertionSettings, Recoater, SpreadSettings, SpreadState, KeffScene, ContactRadius,
                    GasLens, SinterScene, PhaseChange, RayTrace, ScanSegment, Hatch, FusionPolicy,
                    BuildPlan, PartRecord)

InputError = _core.InputError
NumericalError = _core.NumericalError

# The programs whose stage runs in-process above are reached through run(name, ...); the others
# are functions of their own name that run the program.
_IN_PROCESS = ("deposit", "keff", "sinter", "build")
_PROGRAM_FUNCTIONS = tuple(name for name in PROGRAMS if name not in _IN_PROCESS)

__all__ = ["__version__", "Bed", "InputError", "NumericalError", "ProgramError", "PROGRAMS",
           "read_bed", "write_bed", "sample_psd", "stats", "run", "pack", "deposit", "spread", "keff",
           "sinter", "build", "build_scene", "PackOptions", "Scene", "Material", "WallMaterial", "Fines", "RunSettings", "RestCriteria",
           "LidSettings", "InsertionSettings", "Recoater", "SpreadSettings", "SpreadState",
           "KeffScene", "ContactRadius", "GasLens", "SinterScene", "PhaseChange", "RayTrace",
           "ScanSegment", "Hatch", "FusionPolicy", "BuildPlan", "PartRecord", *_PROGRAM_FUNCTIONS]


def read_bed(path, domain=None):
    """The bed in `path` (.h5, .csv with domain=(xlo, ylo, zlo, xhi, yhi, zhi), .dump / .lammpstrj
    (the last snapshot), LAMMPS .data, YADE .txt (domain optional), GenGeo .geo, .gz of the text
    ones: docs/decks.md), read by the C++ bed library with all its checks; raises InputError (a
    ValueError) on a bad file or a bad argument."""
    path = _checks.path(path, "read_bed: path")
    bounds = None if domain is None else _checks.numbers_of(domain, 6, "read_bed: domain")
    return Bed(_core.read_bed(path, bounds), source=path)


def write_bed(bed, path):
    """Writes `bed` to `path` by its extension (.h5 with its .xmf sidecar, .csv, .data), through
    a temporary file and a rename, as the programs do; raises InputError on a bad bed or
    argument."""
    _core.write_bed(_bed_of(bed, "write_bed: bed").as_dict(), _checks.path(path, "write_bed: path"))


def sample_psd(spec, n, seed=0):
    """n radii (m) drawn from the PSD string `spec` (README "Particle size distributions") with
    the programs' random engine seeded by `seed`; raises InputError on a bad string or
    argument."""
    return _core.sample_psd(_checks.text(spec, "sample_psd: spec"), _checks.whole(n, "sample_psd: n"),
                            _checks.whole(seed, "sample_psd: seed"))


def stats(bed, tol=1e-6, layer=None, psd=None, profile=0, rdf=0, histogram=0, voronoi=False,
          order=False, order_margin=0.0, label=""):
    """The dict `bedstat --json` prints for this one bed (its entry under "beds"): box_density,
    layer_density (with layer=(z0, z1)), coordination at `tol` and coordination_by_tol, contacts,
    rattlers, wall_contacts, max_overlap, radius, and the optional statistics bedstat's options
    of the same names ask for. Raises InputError on a bad bed or argument."""
    bed = _bed_of(bed, "stats: bed")
    text = _core.stats_json(bed.as_dict(), _checks.number(tol, "stats: tol"),
                            None if layer is None else tuple(_checks.numbers_of(layer, 2, "stats: layer")),
                            None if psd is None else _checks.text(psd, "stats: psd"),
                            _checks.whole(profile, "stats: profile"), _checks.whole(rdf, "stats: rdf"),
                            _checks.whole(histogram, "stats: histogram"), bool(voronoi),
                            _checks.number(order_margin, "stats: order_margin") if order else None,
                            _checks.text(label or bed.source, "stats: label"))
    return _json.loads(text)


def _program(name):
    def call(*args, **options):
        return run(name, *args, **options)
    call.__name__ = name
    call.__doc__ = f"run('{name}', *args, **options): {name}'s --json summary as a dict."
    return call


for _name in _PROGRAM_FUNCTIONS:
    globals()[_name] = _program(_name)
