"""Running the project's programs from a study: where the build is, one run with --json, the
options a program resolves from a scene (its --print-config, defaults included), the
bedstat, deposit, keff and sinter wrappers more than one study uses, reading the beds and run
files the programs write, and the beds and stored runs one study takes from another (kept under
out/studies/ and made there when missing, so that no study has to import another)."""
import json
import math
import os
import re
import shutil
import subprocess
import time

from . import references

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
# POWDERBED_BUILD selects the build folder (a Release build for the timings), default build/.
BUILD = os.environ.get("POWDERBED_BUILD", os.path.join(ROOT, "build"))
SCENES = os.path.join(ROOT, "data", "scenes")
WORK = os.path.join(ROOT, "out", "studies")


def app(name):
    """The path of program `name` of the build."""
    return os.path.join(BUILD, "apps", name)


def dosed_build_spread(dosing):
    """build's --spread-args that dose data/scenes/build-316L.ini's spreads as machines dose:
    `dosing` times each layer's nominal powder (deposit's supply.dosing) in place of the scene's
    2500 particles, in a supply region 0.7 mm long instead of 0.5 (the first layer's dose of 2 on
    its 90 um gap fills 0.39 of it, near the limit of random placement without overlap), and
    what the blade pushes past the strip kept against the box's far wall (recoater.chamber)."""
    return (f"--supply.dosing {dosing:g} --supply.count 0 --supply.x1 0.9e-3 "
            "--recoater.chamber true")


def dosed_name(stem, dosing):
    """A study's name (its page's stem, its folder or report in out/studies) for a dosed build
    or not."""
    return f"{stem}-dosed" if dosing else stem


def dosed_build_text(dosing):
    """What a page prints of how its build was dosed: the study's option and build's (both
    empty when the build was not dosed)."""
    if not dosing:
        return "", ""
    return f" --dosing {dosing:g}", f" --spread-args \"{dosed_build_spread(dosing)}\""


def scene(name):
    """The path of a scene file of data/scenes/."""
    return os.path.join(SCENES, name)


def scene_value(path, section, key):
    """A key of an INI scene's text as a number (section None: a key before the first
    [section]): what the scene file says (test_references checks the scenes against their
    sources); resolved_options gives what a program runs with."""
    current = None
    for line in open(path):
        line = line.split("#")[0].strip()
        m = re.match(r"\[(.+)\]", line)
        if m:
            current = m.group(1)
        elif "=" in line and current == section:
            k, v = (x.strip() for x in line.split("=", 1))
            if k == key:
                return float(v)
    raise KeyError(f"{key} in {path}")


# --print-config's lines: "key = value", and "# key = value  (default)" for a default or a
# --material file's value (commented out so that --config reads them back as not given); a
# value "quoted" with escapes where its plain form would lose it.
CONFIG_LINE = re.compile(r"([\w.-]+) = (.*)")
COMMENTED = re.compile(r"# (.*)  \((?:default|from --material)\)")
ESCAPES = {"\\": "\\", '"': '"', "n": "\n", "r": "\r", "t": "\t"}


def parse_print_config(text):
    """{dotted name: value text} of a program's --print-config output, the commented-out
    defaults and material values included: what the program runs with."""
    out = {}
    for line in text.splitlines():
        commented = COMMENTED.fullmatch(line)
        m = CONFIG_LINE.fullmatch(commented.group(1) if commented else line)
        if not m:
            continue  # the header
        key, value = m.groups()
        if value.startswith('"'):
            value = re.sub(r"\\(.)", lambda e: ESCAPES[e.group(1)], value[1:-1])
        if key in out:  # a multi-valued option (bedstat's --bed) prints a line per value
            raise ValueError(f"--print-config gives {key} more than once")
        out[key] = value
    return out


def option_args(options):
    """{dotted name: text} as command-line words --name text (the command line wins over the
    scene file)."""
    return [word for key, value in options.items() for word in (f"--{key}", value)]


def resolved_options(program, args):
    """The options program `program` of the build resolves from `args` (--config SCENE, options):
    parse_print_config of its --print-config, so a study reads the program's defaults rather
    than a copy of them."""
    proc = subprocess.run([app(program), *args, "--print-config"], capture_output=True, text=True)
    if proc.returncode != 0:
        raise RuntimeError(f"{program} {' '.join(args)} --print-config exited {proc.returncode}: "
                           f"{proc.stderr.strip()}")
    return parse_print_config(proc.stdout)


def omp_env(threads):
    """The environment with OMP_NUM_THREADS = `threads`, for programs whose thread count is
    OpenMP's (keff)."""
    return dict(os.environ, OMP_NUM_THREADS=str(threads))


def run_json(args, env=None):
    """Runs a program with --json and returns (summary dict, wall seconds of the whole process)."""
    start = time.perf_counter()
    proc = subprocess.run(args + ["--json"], capture_output=True, text=True, env=env)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} exited {proc.returncode}: {proc.stderr.strip()}")
    return json.loads(proc.stdout), wall


def perf_profile(args, data, env=None, limit=1.0):
    """perf's flat profile of one run of `args` (199 samples/s, written to `data`): the functions
    over `limit` % of the samples (inlined callees count in their caller), as (percent, short
    name); None when perf is not installed."""
    if not shutil.which("perf"):
        return None
    subprocess.run(["perf", "record", "-q", "-F", "199", "-o", data] + list(args), check=True,
                   capture_output=True, env=env)
    text = subprocess.run(["perf", "report", "-i", data, "--stdio", "--sort", "symbol",
                           "--percent-limit", str(limit)], check=True, capture_output=True,
                          text=True).stdout
    out = []
    for line in text.splitlines():
        m = re.match(r"\s*([\d.]+)%\s+\[(.)\]\s+(.+?)\s*(-\s+-)?\s*$", line)
        if m:
            name = re.sub(r"<.*", "", m.group(3)).replace("(anonymous namespace)::", "")
            out.append((float(m.group(1)), name + (" (kernel)" if m.group(2) == "k" else "")))
    return out


def timed(args, env=None):
    """One run of `args` under /usr/bin/time -v: {"stdout", "wall" (s, the whole process),
    "cpu" (user + system s), "rss" (the process's peak resident set, MiB)}. Raises naming the
    command when it fails."""
    import tempfile
    with tempfile.NamedTemporaryFile("r", suffix=".time") as times:
        start = time.perf_counter()
        proc = subprocess.run(["/usr/bin/time", "-v", "-o", times.name] + list(args),
                              capture_output=True, text=True, env=env)
        wall = time.perf_counter() - start
        fields = dict(line.strip().rsplit(": ", 1) for line in times if ": " in line)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(args)} exited {proc.returncode}: {proc.stderr.strip()}")
    return {"stdout": proc.stdout, "wall": wall,
            "cpu": float(fields["User time (seconds)"]) + float(fields["System time (seconds)"]),
            "rss": int(fields["Maximum resident set size (kbytes)"]) / 1024}


def cached_json(path, args, env=None):
    """Runs `args` + `--out path` unless `path` is there with its record `path`.json (the --json
    summary and the wall seconds of the run that made it): (summary, wall s). A study rerun, or
    another study on the same beds, reads the record instead of remaking the file."""
    meta = path + ".json"
    if os.path.exists(path) and os.path.exists(meta):
        with open(meta) as f:
            cached = json.load(f)
        return cached["summary"], cached["wall"]
    os.makedirs(os.path.dirname(path), exist_ok=True)
    s, wall = run_json(args + ["--out", path], env=env)
    with open(meta, "w") as f:
        json.dump({"summary": s, "wall": wall}, f)
    return s, wall


def memo_json(path, fresh, make):
    """make()'s record (a dict), kept in `path`: read from there unless `fresh` or missing, else
    made and written. A study's rows are measured once and a rerun rewrites its page from them."""
    if os.path.exists(path) and not fresh:
        with open(path) as f:
            return json.load(f)
    out = make()
    with open(path, "w") as f:
        json.dump(out, f)
    return out


def spread_layer(scene_path, seed, options, bed, window):
    """One layer of a spread scene at `seed` with `options` (deposit, one thread) into `bed`, and
    bedstat --spread over `window` (x0, x1): (deposit's --json summary, its wall seconds, the
    layer's statistics without the segregation table), the bed file and its sidecar removed."""
    dep, wall = run_json([app("deposit"), "--config", scene_path, "--seed", str(seed), "--threads", "1",
                          "--out", bed] + list(options))
    stats = bedstat([bed, "--spread", "--window", f"{window[0]!r},{window[1]!r}"])["spread"]
    stats.pop("segregation", None)
    return dep, wall, stats


def remove_bed(path):
    """Removes a bed file and its XDMF sidecar (a study that keeps only its JSON)."""
    for p in (path, os.path.splitext(path)[0] + ".xmf"):
        if os.path.exists(p):
            os.remove(p)


def bedstat(args, env=None):
    """bedstat's --json entry of the one bed in `args` (its path and options): the element of
    the "beds" array bedstat always prints."""
    out, _ = run_json([app("bedstat"), *args], env=env)
    return out["beds"][0]


def read_bed(path):
    """Centres (N x 3) and radii of a bed file (docs/bed-format.md); needs h5py and numpy."""
    import h5py
    import numpy as np
    with h5py.File(path, "r") as f:
        return np.array(f["particles/position"]), np.array(f["particles/radius"])


def coordination_at_gaps(centres, radii, gaps):
    """Z = 2 contacts / N (docs/physics.md §2) with a contact when the surface gap d - ri - rj <= g, for each
    absolute gap g (m) in `gaps`: the raster-bed reading of a contact (docs/physics.md §3: gaps of order h).
    Overlapping pairs (negative gap) count as contacts."""
    import numpy as np
    from scipy.spatial import cKDTree
    n = len(radii)
    if n < 2:
        return [0.0 for _ in gaps]
    pairs = cKDTree(centres).query_pairs(2 * radii.max() + max(gaps), output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    gap = np.linalg.norm(centres[i] - centres[j], axis=1) - radii[i] - radii[j]
    return [2.0 * np.count_nonzero(gap <= g) / n for g in gaps]


# ------------------------------------------------------------------------------------------------
# keff

def keff(scene_path, bed, *options, out=None, env=None, core=False):
    """keff on `bed` with the scene and `options`: (--json summary, process wall s). `out`: where
    the temperatures go (none written without). The summary carries k_core (the flux over the
    core's mean gradient, keff's own since issue 35); `core` is kept for the callers that asked
    for it when this script computed it."""
    args = [app("keff"), "--config", scene_path, "--bed", bed, *options]
    if out:
        args += ["--out", out]
    s, wall = run_json(args, env=env)
    return s, wall


# [KE]'s beds, made as [KE] made theirs (data/scenes/ke2016-<case>-bed.ini, one thread), for
# keff_validation.py, keff_softening.py and keff_parameters.py; and the results one of them
# stores for the others.
KE2016_WORK = os.path.join(WORK, "keff-validation")
KE2016_SOFT_WORK = os.path.join(WORK, "keff-softening")
KE2016_RESULTS = os.path.join(KE2016_WORK, "results.json")  # keff_validation.py: per case, seed
KE2016_BED_SEEDS = os.path.join(KE2016_WORK, "bed-seeds.json")  # keff_validation.py: per seed


def ke2016_bed_scene(case):
    return scene(f"ke2016-{case}-bed.ini")


def ke2016_keff_scene(case):
    return scene(f"ke2016-{case}.ini")


def ke2016_deposit(case, seed):
    """The deposit command of [KE]'s bed of `case` with `seed` (without --out)."""
    return [app("deposit"), "--config", ke2016_bed_scene(case), "--seed", str(seed), "--threads",
            "1"]


def ke2016_bed(case, seed=1, depth=0.0):
    """[KE]'s bed of `case` and `seed`: unconsolidated (depth 0), or that bed consolidated by the
    top wall lowered `depth` particle radii below its surface, held, raised and relaxed
    (docs/deposit-lid.md): (path, deposit summary, wall s), kept in KE2016_WORK."""
    base = os.path.join(KE2016_WORK, f"{case}-seed{seed}.h5")
    s, wall = cached_json(base, ke2016_deposit(case, seed))
    if depth == 0:
        return base, s, wall
    d = references.ke2016_case(case).diameter
    path = os.path.join(KE2016_WORK, f"{case}-seed{seed}-depth{depth:g}.h5")
    # --in on the command line replaces the scene's particle source (psd, count, insertion).
    args = ke2016_deposit(case, seed) + ["--in", base, "--t-end", "1e-4", "--lid.enabled", "true",
                                         "--lid.depth", f"{depth * d / 2:.6g}"]
    return (path, *cached_json(path, args))


def ke2016_keff(case, bed, *options, tag="nominal"):
    """keff with [KE]'s scene of `case` on `bed` and `options`: the --json summary with k_core;
    the temperatures go to BED-T-<tag>.h5 beside the bed."""
    s, _ = keff(ke2016_keff_scene(case), bed, *options, out=bed.replace(".h5", f"-T-{tag}.h5"),
                core=True)
    return s


def ke2016_soft_bed(case, k_n):
    """[KE]'s unconsolidated bed of `case`, seed 1, deposited at the DEM stiffness k_n (N/m;
    the scene's is [KE]'s 1e5): (path, deposit summary, wall s), kept in KE2016_SOFT_WORK."""
    path = os.path.join(KE2016_SOFT_WORK, f"{case}-kn{k_n:g}.h5")
    args = ke2016_deposit(case, 1) + ["--contact.stiffness", f"{k_n:g}"]
    return (path, *cached_json(path, args))


# The held-lid steel 1 mm bed of keff_speed.py and keff_accuracy.py, and keff_speed.py's stored
# measurements (keff_accuracy.py reads the 100,000-particle runs).
KEFF_SPEED_WORK = os.path.join(WORK, "keff-speed")
KEFF_SPEED_RUNS = os.path.join(KEFF_SPEED_WORK, "speed-runs.json")


# Radius factor that gives packgen's touching spheres a contact (keff's +0.1 % beds).
GROW = 1.001


def packgen_mono_bed(count, width):
    """packgen's bed of `count` touching 1 mm spheres (approach 3, lowest site first, seed 1) in
    a box `width` diameters wide, top wall at the highest sphere top, and its copy with radii
    grown by GROW (top wall moved likewise): (placed, grown, packgen --json summary), kept in
    KEFF_SPEED_WORK. keff reads them with contact.hertz-correction = false (KEFF_GEOMETRIC):
    packgen records no contact law."""
    import h5py
    import numpy as np
    raw = os.path.join(KEFF_SPEED_WORK, f"packgen-{count}-raw.h5")
    placed = os.path.join(KEFF_SPEED_WORK, f"packgen-{count}.h5")
    grown = os.path.join(KEFF_SPEED_WORK, f"packgen-{count}-grown.h5")
    meta = raw + ".json"
    if not os.path.exists(meta):
        os.makedirs(KEFF_SPEED_WORK, exist_ok=True)
        d = 1e-3
        height = 1.3 * count * 0.5236 / 0.58 / width ** 2 * d  # 3-lowest fills ~0.58 of the box
        s, _ = run_json([app("packgen"), "--dim", "3", "--domain",
                         f"{width * d:g},{width * d:g},{height:g}", "--psd", "mono:d=0.001",
                         "--approach", "3", "--site-order", "lowest", "--count", str(count),
                         "--seed", "1", "--out", raw])
        if s["n"] != count:
            raise RuntimeError(f"packgen placed {s['n']} of {count}")
        for path, factor in ((placed, 1.0), (grown, GROW)):
            shutil.copyfile(raw, path + ".tmp")
            with h5py.File(path + ".tmp", "r+") as f:
                r = np.array(f["particles/radius"]) * factor
                f["particles/radius"][...] = r
                upper = np.array(f["domain"].attrs["upper"])
                upper[2] = float(np.max(np.array(f["particles/position"])[:, 2] + r))
                f["domain"].attrs["upper"] = upper
            os.replace(path + ".tmp", path)
        with open(meta, "w") as f:
            json.dump(s, f)
    with open(meta) as f:
        return placed, grown, json.load(f)


# keff's option for a bed without a recorded contact law (packgen's): the geometric contact circle.
KEFF_GEOMETRIC = ("--contact.hertz-correction", "false")


def held_lid_bed(count, width):
    """data/scenes/ke2016-steel-1mm-held-lid-bed.ini, seed 1, with `count` spheres in a box
    `width` diameters wide (the insertion height keeps the scene's 19 % solid fraction; 1,100
    spheres, 10 wide, is the scene itself, the validation bed): (path, deposit summary, wall s),
    kept in KEFF_SPEED_WORK."""
    path = os.path.join(KEFF_SPEED_WORK, f"deposit-{count}.h5")
    d = 1e-3
    height = math.ceil(count * 0.5236 / 0.19 / width ** 2) * d
    args = [app("deposit"), "--config", scene("ke2016-steel-1mm-held-lid-bed.ini"), "--seed", "1",
            "--threads", "1"]
    if count != 1100:
        args += ["--count", str(count), "--domain", f"{width * d:g},{width * d:g},{height:g}",
                 "--insert-z", f"0,{height:g}"]
    return (path, *cached_json(path, args))


# ------------------------------------------------------------------------------------------------
# sinter on the [GZ] scene (sinter_accuracy.py, sinter_gz2016.py, sinter_speed.py, process_map.py)

GZ2016_SINTER_SCENE = scene("gz2016-sinter.ini")


def gz2016_bed():
    """The bed of data/scenes/gz2016-deposit.ini with seed 1, kept in out/studies/ (about a
    minute the first time)."""
    os.makedirs(WORK, exist_ok=True)
    path = os.path.join(WORK, "gz2016-deposit.h5")
    if not os.path.exists(path):
        subprocess.run([app("deposit"), "--config", scene("gz2016-deposit.ini"), "--seed", "1",
                        "--out", path], check=True, capture_output=True)
    return path


# [GZ] Table 3's beds for Fig. 13 (PSD, count): 550 particles of 30 +- 5 um in [20, 40] um, and
# the same with 3,000 fines of 8 +- 2 um in [4, 12] um (diameters); sinter_gz2016.py's Fig. 13
# and deposit_fines.py deposit them.
GZ2016_TABLE3_PSDS = [
    ("550 of 30 +- 5 um", "gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6", 550),
    ("+ 3000 of 8 +- 2 um", "gauss:mean=30e-6,sd=5e-6,min=20e-6,max=40e-6,count=550"
                            "+gauss:mean=8e-6,sd=2e-6,min=4e-6,max=12e-6,count=3000", 3550),
]

# The two laser models the [GZ] sweeps run: sinter's default and the paper's own.
GZ2016_LASER_MODELS = [
    ("default (ray-traced, wetting)", []),
    ("Beer-Lambert, no wetting", ["--laser.absorption", "beer-lambert", "--effects.wetting", "false"]),
]


def vaporised_by_size(run_path, boiling_point, split_diameter):
    """Particles of a sinter run file whose peak reached T_v: (fine, coarse, fines, coarse ones)
    counted below and above `split_diameter` (m)."""
    import h5py
    import numpy as np
    with h5py.File(run_path, "r") as f:
        peak = np.array(f["melt/particle"])
        radius = np.array(f["particles/radius"])
    gone = peak >= boiling_point
    fine = 2 * radius < split_diameter
    return int((gone & fine).sum()), int((gone & ~fine).sum()), int(fine.sum()), int((~fine).sum())


def sinter(scene_path, bed, out, *options, threads=1):
    """sinter on `bed` with the scene and `options`, its run file at `out` (a bare name: in
    out/studies/): (--json summary with "out_path", process wall s). One thread by default: the
    studies compare settings, not machines (sinter_speed.py measures threads)."""
    out = os.path.join(WORK, out)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    args = [app("sinter"), "--config", scene_path, "--bed", bed, "--out", out, *options]
    if threads:
        args += ["--threads", str(threads)]
    summary, wall = run_json(args)
    summary["out_path"] = out
    return summary, wall


def pool_um(summary):
    """sinter's melt pool on x = Lx/2 (height, width, depth) in um."""
    m = summary["melt_pool"]
    return m["height"] * 1e6, m["width"] * 1e6, m["depth"] * 1e6
