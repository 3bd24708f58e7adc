"""The programs of the build, run with --json; their summary comes back as a dict."""
import json
import numbers
import os
import re
import subprocess

from . import _checks
from ._core import InputError
from ._paths import APPS

PROGRAMS = ("packgen", "deposit", "bedstat", "bedconv", "sinter", "keff", "build")


class ProgramError(RuntimeError):
    """A program exited non-zero (status 2 bad input, 3 a non-physical result, negative: killed
    by that signal), or exited 0 without printing a JSON summary (status 0: e.g. help=True or
    print_config=True, which print text). `message` is the program's last line on stderr, or
    what it printed instead of a summary."""

    def __init__(self, program, status, message):
        super().__init__(f"{program} exited {status}: {message}")
        self.program, self.status, self.message = program, status, message


def executable(program):
    """The built program beside this module (build/apps/<program>)."""
    if not isinstance(program, str) or program not in PROGRAMS:
        raise InputError(f"program {program!r} (accepted: {', '.join(PROGRAMS)})")
    return os.path.join(APPS, program)


_SWITCHES = {}


def _switches(program):
    """The options of `program` that take no value: in its --help, Boost prints "arg" after
    every option that takes one ("  --tol arg (=1e-06)", "  --voronoi", "  -h [ --help ]")."""
    if program not in _SWITCHES:
        text = subprocess.run([executable(program), "--help"], capture_output=True, text=True).stdout
        found = (re.match(r"\s+(?:-\w \[ )?--([\w.-]+)(?: \])?( arg)?", line) for line in text.splitlines())
        _SWITCHES[program] = {m.group(1) for m in found if m and not m.group(2)}
    return _SWITCHES[program]


def option_text(value, what):
    """A value as the programs parse it: floats to full precision, lists comma-joined; anything
    else (a dict, None inside a list, bytes) raises InputError naming the option."""
    if isinstance(value, (list, tuple)):
        return ",".join(option_text(v, what) for v in value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Real) and not isinstance(value, numbers.Integral):
        return repr(float(value))  # nan, inf: the program refuses them with its own message
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, (str, os.PathLike)):
        return _checks.path(value, what)
    _checks.refuse(what, value, "str, a number, True/False, a path, or a list of them")


def _arguments(program, args, options):
    argv = [option_text(a, f"{program}: argument {k + 1}") for k, a in enumerate(args)]
    for key, value in options.items():
        name = key.replace("_", "-")
        if value is None:
            continue
        if isinstance(value, bool) and name in _switches(program):
            argv += ["--" + name] if value else []
        else:
            argv += ["--" + name, option_text(value, f"{program}: {name}")]
    return argv


def _decoded(data):
    """A program's output as text: bytes that are not UTF-8 (a path or a file's bytes quoted in
    a message) are kept as \\xNN escapes instead of failing the call with UnicodeDecodeError."""
    return data.decode("utf-8", errors="backslashreplace")


def run(program, *args, **options):
    """Runs `program` with positional `args` and `options` (key=value -> --key value; '_' in a
    key becomes '-'; dotted options as run(..., **{"material.density": 4430}); True for a switch
    such as explain=True; lists join with commas) and --json; returns its summary as a dict.
    Raises ProgramError with the program's one-line message when it exits non-zero."""
    argv = [executable(program), *_arguments(program, args, options), "--json"]
    proc = subprocess.run(argv, capture_output=True)
    if proc.returncode != 0:
        lines = _decoded(proc.stderr).strip().splitlines()
        raise ProgramError(program, proc.returncode, lines[-1] if lines else "")
    out = _decoded(proc.stdout)
    try:
        return json.loads(out)
    except json.JSONDecodeError:
        first = out.strip().splitlines()[0] if out.strip() else ""
        raise ProgramError(program, 0, f"printed no JSON summary (first line: {first!r})") from None
