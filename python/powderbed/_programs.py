"""The programs of the build, run with --json; their summary comes back as a dict."""
import json
import os
import re
import subprocess

from ._paths import APPS

PROGRAMS = ("packgen", "deposit", "bedstat", "bedconv", "sinter", "keff")


class ProgramError(RuntimeError):
    """A program exited non-zero: status 2 bad input, 3 a non-physical result."""

    def __init__(self, program, status, message):
        super().__init__(f"{program} exited {status}: {message}")
        self.program, self.status, self.message = program, status, message


def executable(program):
    """The built program beside this module (build/apps/<program>)."""
    if program not in PROGRAMS:
        raise ValueError(f"program '{program}' (accepted: {', '.join(PROGRAMS)})")
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


def _text(value):
    """A value as the programs parse it: floats to full precision, lists comma-joined."""
    if isinstance(value, (list, tuple)):
        return ",".join(_text(v) for v in value)
    return repr(value) if isinstance(value, float) else str(value)


def _arguments(program, args, options):
    argv = [str(a) for a in args]
    for key, value in options.items():
        name = key.replace("_", "-")
        if value is None:
            continue
        if isinstance(value, bool) and name in _switches(program):
            argv += ["--" + name] if value else []
        elif isinstance(value, bool):
            argv += ["--" + name, "true" if value else "false"]
        else:
            argv += ["--" + name, _text(value)]
    return argv


def run(program, *args, **options):
    """Runs `program` with positional `args` and `options` (key=value -> --key value; '_' in a
    key becomes '-'; dotted options as run(..., **{"material.density": 4430}); True for a switch
    such as explain=True; lists join with commas) and --json; returns its summary as a dict.
    Raises ProgramError with the program's one-line message when it exits non-zero."""
    argv = [executable(program), *_arguments(program, args, options), "--json"]
    proc = subprocess.run(argv, capture_output=True, text=True)
    if proc.returncode != 0:
        lines = proc.stderr.strip().splitlines()
        raise ProgramError(program, proc.returncode, lines[-1] if lines else "")
    return json.loads(proc.stdout)
