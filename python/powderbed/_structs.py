"""Keyword arguments onto the library's settings structs (Scene, RunSettings, SinterScene, ...):
each name must be a field, each value of the field's type; a nested struct's field takes a dict
of its own fields. A wrong name or type raises InputError (a ValueError) naming it, not a
TypeError from pybind11."""
import copy
import os

from . import _checks, _core

# The programs whose --material the run functions' material="NAME" is (spread is deposit's).
_MATERIAL_PROGRAMS = {"deposit": "deposit", "spread": "deposit", "sinter": "sinter", "keff": "keff"}


def _is_struct(value):
    return hasattr(type(value), "_fields")


def _set(obj, key, value):
    current = getattr(obj, key)
    if isinstance(current, str) and isinstance(value, os.PathLike):  # a path field (BuildPlan.out)
        value = _checks.path(value, f"{type(obj).__name__}.{key}")
    if isinstance(value, dict) and _is_struct(current):
        configure(current, **value)  # the nested struct, in place (pybind11 hands a reference)
        return
    try:
        setattr(obj, key, value)
    except TypeError:
        if current is None:  # an optional struct (BuildPlan.hatch): its type is in help()
            accepted = f"what help(powderbed.{type(obj).__name__}) says {key} takes"
        else:
            accepted = f"a {type(current).__name__}" + (f" or a dict of {', '.join(type(current)._fields)}"
                                                         if _is_struct(current) else "")
        _checks.refuse(f"{type(obj).__name__}.{key}", value, accepted)


def configure(obj, **fields):
    """Sets `fields` on the struct `obj` (in place) and returns it."""
    for key, value in fields.items():
        if key not in type(obj)._fields:
            _checks.refuse(f"{type(obj).__name__}: keyword", key, ", ".join(type(obj)._fields))
        _set(obj, key, value)
    return obj


def _given(fields, prefix=""):
    """The keywords' dotted names, a nested dict's fields as well ("phase_change.latent_melt")."""
    for key, value in fields.items():
        yield prefix + key
        if isinstance(value, dict):
            yield from _given(value, f"{prefix}{key}.")


def _fill_material(what, name, fields, out):
    """material="NAME" (a name of data/materials or a path): the file's values in the fields the
    program's --material fills (bed/material_fills.hpp), but those given as keywords beside it."""
    name = _checks.path(name, f"{what}: material")
    temperature = (out[0].hot_temperature + out[0].cold_temperature) / 2 if what == "keff" else 0.0
    for field, value in _core.material_fills(name, _MATERIAL_PROGRAMS[what], set(_given(fields)), temperature):
        *path, last = field.split(".")
        owner = next(s for s in out if (path[0] if path else last) in type(s)._fields)
        for step in path:
            owner = getattr(owner, step)  # the nested struct, by reference
        setattr(owner, last, value)


def structs(what, fields, *given_and_kinds):
    """Copies of the given structs (a default one of its kind for None) with `fields` spread over
    them by name: each keyword goes to the first struct that has it as a field. `what` names the
    function in the error a keyword no struct has raises. A material given as a name or a path
    (deposit, spread, sinter, keff) fills what the program's --material fills, then the other
    keywords win."""
    material = fields.get("material")
    named = what in _MATERIAL_PROGRAMS and isinstance(material, (str, os.PathLike))
    if named:
        fields = {key: value for key, value in fields.items() if key != "material"}
    out = []
    for given, kind in given_and_kinds:
        if given is not None and not isinstance(given, kind):
            _checks.refuse(f"{what}: {kind.__name__.lower()}", given, f"a powderbed.{kind.__name__}")
        out.append(kind() if given is None else copy.copy(given))
    for key, value in fields.items():
        owner = next((s for s in out if key in type(s)._fields), None)
        if owner is None:
            accepted = ", ".join(f for s in out for f in type(s)._fields)
            _checks.refuse(f"{what}: keyword", key, accepted)
        _set(owner, key, value)
    if named:
        _fill_material(what, material, fields, out)
    return out
