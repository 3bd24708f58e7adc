"""The material files of data/materials as the studies read them: the scalar properties and the
solid rows (bed/material_file.hpp is the programs' reader; a study needs only these two)."""
import csv
import os

from .apps import ROOT

MATERIALS = os.path.join(ROOT, "data", "materials")


def material(name):
    """A material file of data/materials: its scalar properties and its solid rows (T, c, k,
    rho)."""
    props, table = {}, []
    with open(os.path.join(MATERIALS, f"{name}.csv")) as f:
        lines = [line for line in f if not line.startswith("#")]
    head = None
    for line in lines:
        cells = next(csv.reader([line]))
        if cells[0] == "temperature_K":
            head = cells
            continue
        if head is None:
            if len(cells) >= 2 and cells[0] != "property":
                props[cells[0]] = cells[1]
        elif cells[head.index("phase")] == "solid":
            table.append(tuple(float(cells[i]) for i in range(4)))
    return props, table


def constant_properties(name, t_ref):
    """(k, rho c) of a material at t_ref, linear in its solid rows and held beyond them."""
    _, table = material(name)
    if t_ref <= table[0][0]:
        t, c, k, rho = table[0]
        return k, rho * c
    for a, b in zip(table, table[1:]):
        if a[0] <= t_ref <= b[0]:
            f = (t_ref - a[0]) / (b[0] - a[0])
            c, k, rho = (a[i] + f * (b[i] - a[i]) for i in (1, 2, 3))
            return k, rho * c
    t, c, k, rho = table[-1]
    return k, rho * c
