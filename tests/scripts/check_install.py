"""`cmake --install` into a temporary prefix puts the powderbed package where the build's
interpreter (Debian's /usr/bin/python3) finds it, and that package imports from there, knows its
version, runs the installed programs and a stage in-process; build/scripts/NAME runs a script
with the build's interpreter even when another python3 (one without h5py) comes first on PATH.

Usage: check_install.py CMAKE BUILD_DIR PACKAGE_DIR VERSION PYTHON
(PACKAGE_DIR relative to the prefix, e.g. lib/python3.11/dist-packages)."""
import os
import subprocess
import sys
import tempfile

cmake, build, package_dir, version, python = sys.argv[1:6]


def check(condition, what):
    if not condition:
        sys.exit(f"FAIL: {what}")


with tempfile.TemporaryDirectory() as prefix:
    subprocess.run([cmake, "--install", build, "--prefix", prefix], check=True,
                   stdout=subprocess.DEVNULL)
    site = os.path.join(prefix, package_dir)
    check(os.path.isfile(os.path.join(site, "powderbed", "__init__.py")), f"no package in {site}")
    # From the prefix only: run in a folder outside the build, the build's package not on the path.
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = site
    # The last line: a deposit in-process, from the installed _core and its libraries.
    code = ("import powderbed; print(powderbed.__version__); print(powderbed.__file__); "
            "print(powderbed._programs.executable('packgen')); "
            "print(powderbed.run('packgen', version=True)['version']); "
            "bed = powderbed.Bed({'x': [5e-5], 'y': [5e-5], 'z': [5e-5], 'r': [1e-5], 'id': [0], "
            "'domain': {'dimension': 3, 'lower': [0, 0, 0], 'upper': [1e-4] * 3, "
            "'periodic': [False] * 3}}); print(powderbed.deposit(bed, t_end=1e-5)[1]['n'])")
    out = subprocess.run([python, "-c", code], env=env, cwd=prefix, capture_output=True,
                         text=True)
    check(out.returncode == 0, f"import from {site}: {out.stderr}")
    got_version, module, packgen, program_version, deposited = out.stdout.split("\n")[:5]
    check(got_version == version, f"powderbed.__version__ {got_version!r}, expected {version!r}")
    check(module.startswith(site), f"powderbed imported from {module}, not {site}")
    check(packgen == os.path.join(prefix, "bin", "packgen"), f"programs at {packgen}")
    check(program_version == version, f"installed packgen says {program_version}")
    check(deposited == "1", f"an in-process deposit from the prefix gave n = {deposited!r}")
    # build's picture plotters where the installed build looks for them (apps/build_pictures.cpp).
    for name in ("plot_build_layer", "plot_build_map"):
        plotter = os.path.join(prefix, "libexec", "powderbed", name)
        out = subprocess.run([plotter, "--help"], capture_output=True, text=True)
        check(out.returncode == 0 and "usage" in out.stdout, f"{plotter} --help: {out.stderr}")

# A python3 first on PATH that is not the build's (pyenv's without h5py): the wrapper still runs.
with tempfile.TemporaryDirectory() as fake:
    with open(os.path.join(fake, "python3"), "w") as f:
        f.write("#!/bin/sh\necho 'not the build interpreter' >&2\nexit 1\n")
    os.chmod(os.path.join(fake, "python3"), 0o755)
    env = dict(os.environ, PATH=fake + os.pathsep + os.environ.get("PATH", ""))
    for name in ("plot_bed", "plot_build_layer", "plot_build_map", "plot_sinter",
                 "plot_keff_profile", "plot_height_map"):
        wrapper = os.path.join(build, "scripts", name)
        out = subprocess.run([wrapper, "--help"], env=env, capture_output=True, text=True)
        check(out.returncode == 0 and "usage" in out.stdout, f"{wrapper} --help: {out.stderr}")
print(f"installed powderbed {version} imports from the prefix; the script wrappers run")
