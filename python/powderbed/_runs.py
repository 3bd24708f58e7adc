"""The stages in-process: pack, deposit, spread, keff, sinter and build run the C++ libraries on a Bed
and the libraries' own structs (PackOptions, Scene, RunSettings, SpreadSettings, KeffScene, SinterScene,
BuildPlan), with no file and no program in between (a build writes its layers' files, as the
program build does). Keyword arguments set the structs' fields by name; what is not
given keeps the struct's default, which is the library's (the programs' defaults are the same
structs'). The GIL is released while a stage runs; `progress` is called with a dict as it goes,
and an exception it raises stops the run and comes out of the call. Bad input raises InputError
(a ValueError) with the library's one-line message, a run that goes non-finite NumericalError
(an ArithmeticError); what the programs print as a warning is a RuntimeWarning. build_scene
builds from a build scene file, read by the program build's own option code."""
import os

from . import _checks, _core, _programs, _structs
from ._bed import Bed, bed_of

Scene, RunSettings, SpreadSettings = _core.Scene, _core.RunSettings, _core.SpreadSettings
KeffScene, SinterScene, BuildPlan = _core.KeffScene, _core.SinterScene, _core.BuildPlan
PackOptions = _core.PackOptions


def _callable_or_none(value, what):
    if value is not None and not callable(value):
        _checks.refuse(what, value, "a callable or None")
    return value


def _supply_maker(supply, what):
    """The user's supply(region, layer) -> Bed as the C++ half calls it: returning a bed dict."""
    if _callable_or_none(supply, f"{what}: supply") is None:
        return None

    def maker(region, layer):
        return bed_of(supply(region, layer), f"{what}: what supply returned").as_dict()
    return maker


def _pack_domain(value):
    """pack's domain as the C++ half takes it: a domain dict, or the 2 or 3 lengths of the box."""
    if isinstance(value, dict):
        return value
    try:
        count = len(value)
    except TypeError:
        count = 0
    if count not in (2, 3) or isinstance(value, (str, bytes)):
        _checks.refuse("pack: domain", value, "LX, LY[, LZ] in m, or a domain dict as Bed.domain")
    return _checks.numbers_of(value, count, "pack: domain")


def pack(domain, psd, seed, options=None, *, progress=None, **fields):
    """Packs the box `domain` with particles of the PSD string `psd` one at a time by contact
    rules (packgen::pack, as the program packgen) and returns (Bed, summary dict): for the same
    options and seed the bed packgen writes, bit for bit.

    domain: (LX, LY) for disks or (LX, LY, LZ) for spheres, in m, the box [0, L] as packgen's
    --domain; or a domain dict as Bed.domain. seed: the random seed (packgen's --seed).
    options: a powderbed.PackOptions (approach or phases, collision, count or target_density,
    tries, directions, site_order, size_sampling, ...); keyword arguments set its fields by name,
    e.g. pack((2e-4, 2e-4, 1e-4), "mono:d=20e-6", 1, approach=3, count=40).
    progress(p) is called about every 0.25 s with p = {"n", "density", "fraction"}.
    The summary has packgen --json's keys: n, density, coordination, coordination_by_tol,
    rattlers, wall_contacts, max_relative_overlap, attempts, tries, failed_placements,
    target_reached, stop_reason, ... A count or target density not reached is a RuntimeWarning
    (the bed is returned all the same, as the program writes it)."""
    (options,) = _structs.structs("pack", fields, (options, PackOptions))
    out, summary = _core.pack(_pack_domain(domain), _checks.text(psd, "pack: psd"),
                              _checks.whole(seed, "pack: seed"), options,
                              _callable_or_none(progress, "pack: progress"))
    return Bed(out), summary


def deposit(bed, scene=None, settings=None, *, progress=None, **fields):
    """Drops and settles `bed` (dem::run_deposition, as the program deposit) and returns
    (settled Bed, summary dict). The input Bed is not changed.

    scene: a powderbed.Scene (the powder, walls, contact law, effects); settings: a
    powderbed.RunSettings (t_end or until_rest, dt, young_scale, lid, insertion, ...). Keyword
    arguments set fields of either by name, e.g. deposit(bed, t_end=2e-3, young_scale=1e3,
    material={"density": 4430}, effects=["gravity", "hertz", "walls"]).
    material="NAME" (a name of data/materials such as "316L", or a path to a material CSV) fills
    what the program's --material NAME fills; keywords beside it win.
    progress(p) is called every settings.progress_every steps and at the end with p = {"step",
    "time", "t_end", "fraction", "kinetic_energy", "max_speed"}.
    The summary has deposit --json's run keys (n, steps, sim_time, dt, dt_stable, kinetic_energy,
    max_speed, max_overlap, lost, at_rest, ...; insertion and lid when used). Particles that left
    the box stay in the bed (summary["lost"] counts them; the program refuses such a run). The
    bed's provenance records the contact law, as the program's, for keff's Hertz correction.
    A scene with history friction or rolling resistance drops on the spreading engine without a
    tool, as the program's (no until_rest, lid, insertion, rk4 or trajectory there)."""
    scene, settings = _structs.structs("deposit", fields, (scene, Scene), (settings, RunSettings))
    out, summary = _core.deposit(bed_of(bed, "deposit: bed").as_dict(), scene, settings,
                                 _callable_or_none(progress, "deposit: progress"))
    return Bed(out), summary


def spread(bed, scene=None, settings=None, *, state=None, supply=None, progress=None, **fields):
    """Spreads settings.layers layers on `bed` with the recoater (dem::run_spread, as deposit
    with a recoater scene) and returns (Bed, summary dict, SpreadState). The input Bed is not
    changed; it may be empty (no particles) when a supply brings the powder.

    scene: a powderbed.Scene; settings: a powderbed.SpreadSettings (tool: a Recoater, the
    supply region supply_x0, supply_x1, supply_height, layers, layer_thickness, ...); keyword
    arguments set fields of either by name, e.g. spread(bed, tool={"gap": 60e-6, "end": 2e-3}).
    material="NAME" (a name of data/materials such as "316L", or a path to a material CSV) fills
    what the program's --material NAME fills; keywords beside it win.
    state: the SpreadState a previous spread returned, to continue it on the Bed it returned.
    supply(region, layer) -> Bed fills a layer's supply region (region: a domain dict as
    Bed.domain; layer from 1); None: no supply (the bed holds the powder).
    progress(p) is called every settings.progress_every steps with p = {"fraction" (of the
    current layer, or of t_end), "kinetic_energy"}.
    The summary: one dict per layer under "layers" (n, supplied, tool_bottom, max_tool_force,
    density_under_gap, overflow, ...), and the run's steps, dt, dt_stable, wall_time."""
    scene, settings = _structs.structs("spread", fields, (scene, Scene), (settings, SpreadSettings))
    if state is not None and not isinstance(state, _core.SpreadState):
        _checks.refuse("spread: state", state, "a powderbed.SpreadState from spread, or None")
    out, summary, end = _core.spread(bed_of(bed, "spread: bed").as_dict(), scene, settings, state,
                                     _supply_maker(supply, "spread"),
                                     _callable_or_none(progress, "spread: progress"))
    return Bed(out), summary, end


def keff(bed, scene=None, *, progress=None, **fields):
    """The effective conductivity of `bed` between two isothermal walls (keff's network and
    solve, as the program keff) as a dict: k_eff, k_core, heat_flow_hot, heat_flow_cold, the
    shares of the contact, gas and radiation paths, drop_hot, drop_cold, temperature (K, per
    particle), rattlers (indices), link counts, newton_iterations, residual.

    scene: a powderbed.KeffScene (axis, hot_temperature, cold_temperature, solid_conductivity,
    gas_model, radiation_path, contact, lens, ...); keyword arguments set its fields by name,
    e.g. keff(bed, hot_temperature=1005, cold_temperature=995, radiation_path=True).
    material="NAME" (a name of data/materials such as "316L", or a path to a material CSV) fills
    what the program's --material NAME fills (k_s at the mean of the walls); keywords beside
    it win. The hot wall is held where the program holds it: under that material's solidus, or
    without one under tungsten's melting point (3695 K) unless trust_units=True.
    With contact={"hertz_correction": True} the DEM law is read from the bed's provenance (a
    bed from deposit or spread has it); contact.circle stays as given (the program keff
    switches it to hertz with the correction unless told). progress(fraction) hears the
    view factors' tracing (radiation only). Raises NumericalError when no heat path joins the
    walls."""
    material = fields.get("material")
    trust_units = fields.pop("trust_units", False)
    if not isinstance(trust_units, bool):
        _checks.refuse("keff: trust_units", trust_units, "True or False")
    (scene,) = _structs.structs("keff", fields, (scene, KeffScene))
    # The program's hot-wall check: under the solidus of --material, else under tungsten's
    # melting point unless --trust-units.
    named = _checks.path(material, "keff: material") if isinstance(material, (str, os.PathLike)) else None
    _core.check_keff_hot_wall(named, scene.hot_temperature, trust_units)
    return _core.keff(bed_of(bed, "keff: bed").as_dict(), scene,
                      _callable_or_none(progress, "keff: progress"))


def sinter(bed, scene=None, *, progress=None, **fields):
    """Runs the laser over `bed` (thermal::Sinter, as the program sinter without its run file)
    and returns (Bed with each particle's final temperature and phase, summary dict).

    scene: a powderbed.SinterScene (power, speed, spot_radius, nodes, substrate_depth, t_end,
    scan_path, material_table, effects, ...); keyword arguments set its fields by name, e.g.
    sinter(bed, power=150, nodes=[21, 11, 11], substrate_depth=1e-4).
    material="NAME" (a name of data/materials such as "316L", or a path to a material CSV) fills
    what the program's --material NAME fills; keywords beside it win.
    progress(p) is called about once a second of wall time with p = {"step", "time", "t_end",
    "fraction", "max_temperature_particles", "max_temperature_substrate"}.
    The summary has sinter --json's keys: melt_pool {height, width, depth}, melt_pool_along,
    max_temperature, particles_molten, energy_balance_error, energy (the ledger, J), absorptance,
    tracks, steps, dt, t_end, ..."""
    (scene,) = _structs.structs("sinter", fields, (scene, SinterScene))
    out, summary = _core.sinter(bed_of(bed, "sinter: bed").as_dict(), scene,
                                _callable_or_none(progress, "sinter: progress"))
    return Bed(out), summary


def build(bed, plan=None, *, layers=1, state=None, part=None, supply=None, progress=None, **fields):
    """Builds `layers` layers on `bed` (process::build_layer, as the program build): each layer
    the recoater spreads the supply on the solid of the layers before, the laser scans it, what
    melted fuses into the solid's top; each layer's files (layer-NNN-spread.h5, -scan.h5, .h5)
    go to plan.out. Returns (the powder left as a Bed, a report dict per layer, SpreadState,
    PartRecord); pass the last three's Bed, state and part back to build more layers.

    plan: a powderbed.BuildPlan (scene: the powder's Scene; spread: SpreadSettings with the tool
    and the supply region; scan: SinterScene; hatch: a Hatch turned by its rotation per layer,
    or None; fusion: FusionPolicy; out: the folder; finest_diameter; snapshots); keyword
    arguments set its fields by name, nested structs by dict, e.g. build(box, out="part",
    spread={"tool": {"gap": 60e-6}}, scan={"power": 150}). `bed` is the empty box (its domain)
    for a new build. supply(region, layer) -> Bed fills each layer's supply region, as in
    spread(). progress(p) hears each stage with p = {"layer", "stage" ("spread" or "scan"),
    "fraction"}. Each report has build.json's layer keys (layer_density, fused_fraction,
    lack_of_fusion, part_porosity, ...) and the stages' own summaries under "spread" and "scan".
    The build's warning (the solid's top above the recoater's bottom) is a RuntimeWarning."""
    (plan,) = _structs.structs("build", fields, (plan, BuildPlan))
    if state is not None and not isinstance(state, _core.SpreadState):
        _checks.refuse("build: state", state, "a powderbed.SpreadState from build, or None")
    if part is not None and not isinstance(part, _core.PartRecord):
        _checks.refuse("build: part", part, "a powderbed.PartRecord from build, or None")
    out, reports, end, record = _core.build(
        bed_of(bed, "build: bed").as_dict(), plan, _checks.whole(layers, "build: layers"), state,
        part, _supply_maker(supply, "build"), _callable_or_none(progress, "build: progress"))
    return Bed(out), reports, end, record


def build_scene(scene, out, *, layers=None, progress=None, **options):
    """Builds the part of the build scene file `scene` (what the program build reads with
    --config, e.g. data/scenes/build-316L.ini) in-process, as `build --config scene --out out`
    builds it: the same options, defaults and refusals (the program's option code reads them),
    the same layers' files in the new or empty folder `out` and the same build.json.
    Returns (the powder left as a Bed, the report dict, SpreadState, PartRecord, BuildPlan): the
    report is build.json, which `build --json` prints (layers_done, first_layer, particles,
    wall_time, layers: one dict per layer with layer_density, fused_fraction, lack_of_fusion,
    part_porosity, ..., out, units); the last four continue it in-process through
    build(bed, plan, state=state, part=part).

    layers: how many (None: the scene's, or 1). Options are the program's (key=value ->
    --key value; '_' in a key becomes '-'; dotted options as **{"fuse.melt-fraction": 0.6}),
    e.g. spread_args="--supply.count 80", sinter_args="--power 150", seed=2, **{"in":
    "run/layer-002.h5"}. progress(p) hears each stage with p = {"layer", "stage" ("spread" or
    "scan"), "fraction"}. Bad input raises InputError with the line the program prints before
    exit 2 (less its "build: "); the build's warning is a RuntimeWarning. What the program does
    besides building is refused: json, help, version, print_config, map.* (powderbed.run("build",
    ...) runs the program), and pictures (none are drawn here, as with --pictures false). As the
    program, the spreads print deposit's thermo table on stderr (spread_args="--thermo 0": none)."""
    args = ["--config", _checks.path(scene, "build_scene: scene"), "--out", _checks.path(out, "build_scene: out")]
    if layers is not None:
        args += ["--layers", str(_checks.whole(layers, "build_scene: layers"))]
    for key, value in options.items():
        name = key.replace("_", "-")
        if value is not None:  # as run(): None leaves the option to the scene
            args += ["--" + name, _programs.option_text(value, f"build_scene: {name}")]
    bed, report, state, part, plan = _core.build_scene(
        args, _callable_or_none(progress, "build_scene: progress"))
    return Bed(bed), report, state, part, plan
