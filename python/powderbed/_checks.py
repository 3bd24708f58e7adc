"""The checks on the arguments of the module's functions: a value of the wrong type or range
raises InputError (a ValueError) naming the argument, as the C++ readers do for a bad file,
instead of a TypeError from deep inside numpy, pybind11 or subprocess."""
import math
import numbers
import os

from ._core import InputError


def refuse(what, value, accepted):
    raise InputError(f"{what}: {value!r} (accepted: {accepted})")


def path(value, what):
    """A file name: str or os.PathLike (pathlib.Path), without NUL bytes."""
    try:
        text = os.fspath(value)
    except TypeError:
        refuse(what, value, "a path: str or pathlib.Path")
    if isinstance(text, bytes):
        text = os.fsdecode(text)
    if "\0" in text:
        refuse(what, value, "a path without NUL characters")
    return text


def number(value, what):
    """A finite real number (bool is not one)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value):
        refuse(what, value, "a finite number")
    return float(value)


def whole(value, what):
    """A whole number >= 0: an int, or a float such as 1e6 that is one."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        if isinstance(value, numbers.Integral) and value >= 0:
            return int(value)
        if math.isfinite(value) and value >= 0 and float(value).is_integer():
            return int(value)
    refuse(what, value, "a whole number >= 0")


def numbers_of(value, count, what):
    """`count` finite numbers, from any sequence (tuple, list, numpy array)."""
    if isinstance(value, (str, bytes)):
        refuse(what, value, f"{count} numbers")
    try:
        items = list(value)
    except TypeError:
        refuse(what, value, f"{count} numbers")
    if len(items) != count:
        refuse(what, value, f"{count} numbers")
    return [number(v, what) for v in items]


def text(value, what):
    """A str without NUL characters."""
    if not isinstance(value, str) or "\0" in value:
        refuse(what, value, "a str")
    return value
