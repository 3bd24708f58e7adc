"""pvpython under a virtual X server, shared by the ParaView tests (tests/paraview/check_*.py)."""
import shutil
import subprocess

# ParaView 5.11's OpenGL needs a 24-bit screen; xvfb-run's default is 8 bits.
XVFB = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24"]


def missing_tools():
    """The tools a ParaView test needs that are not on PATH (the test skips with them named)."""
    return [tool for tool in ("pvpython", "xvfb-run") if shutil.which(tool) is None]


def skipped():
    """True, having said which tools are missing, when a ParaView test cannot run here (ctest
    reads the test's exit status 77 as skipped)."""
    missing = missing_tools()
    if missing:
        print(f"skipped: {' and '.join(missing)} not found (Debian: python3-paraview, xvfb, "
              "xauth; scripts/setup.sh installs them)")
    return bool(missing)


def pvpython(*args, check=True):
    """pvpython ARGS under a fresh virtual X server; the finished process. Retried (5 tries) when
    ParaView aborts with "bad X server connection": on a loaded machine (here: 2 cores, load 13)
    5.11's render window failed to open its display in about half of the starts, with the
    server up and accepting other clients. `check`: a failure raises with its stderr's tail."""
    for attempt in range(5):
        out = subprocess.run([*XVFB, "pvpython", *args], capture_output=True, text=True,
                             timeout=240)
        if out.returncode == 0 or "bad X server connection" not in out.stderr:
            break
        print(f"pvpython could not open the virtual display (try {attempt + 1} of 5)")
    assert not check or out.returncode == 0, out.stderr[-2000:]
    return out
