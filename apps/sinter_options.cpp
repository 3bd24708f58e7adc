// sinter's options and the scene they make (docs/sinter.md): shared by sinter and build, which
// reads a sinter scene file for each layer's scan.
#include "sinter_options.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "common/material_options.hpp"
#include "common/progress.hpp"
#include "common/threads.hpp"
#include "powderbed/bed/errors.hpp"

namespace powderbed::app {

namespace {

namespace th = thermal;

// The scan path options (docs/sinter.md "Scan paths"): a CSV of segments or a hatch; neither
// keeps the single track of laser.*.
void add_scan_options(po::options_description& desc, th::SinterScene& s) {
  const th::Hatch h;
  desc.add_options()
      ("scan-path", po::value<std::string>(),
       "CSV of segments, header x0,y0,x1,y1,power,speed (SI); replaces the single track")
      ("scan.hatch", po::value<double>(), "hatch spacing h between tracks (m); replaces the single track")
      ("scan.tracks", po::value<std::size_t>()->default_value(0),
       "number of hatch tracks (0: as many as the region holds)")
      ("scan.direction", po::value<std::string>()->default_value("alternating"),
       "one-way (every track the same way) or alternating (serpentine)")
      ("scan.rotation", po::value<double>()->default_value(h.rotation),
       "hatch rotation per layer about the region's centre (degrees)")
      ("scan.layer", po::value<std::size_t>()->default_value(0),
       "layer k: the tracks run at k x rotation from +x")
      ("scan.region", po::value<std::string>(),
       "X0,X1,Y0,Y1: the rectangle the hatch covers (m); default the bed's x-y extent")
      ("scan.jump-speed", po::value<double>(&s.jump_speed)->default_value(s.jump_speed),
       "speed of the jumps between segments, laser off (m/s)");
}

// The hatch of the options (none: --scan-path or the single track); its tracks run at --power
// and --speed, at layer `layer` (none: scan.layer).
std::optional<th::Hatch> hatch_of(const po::variables_map& vm, const th::SinterScene& s,
                                  const bed::Bed& bed, std::optional<std::size_t> layer) {
  const bool csv = vm.count("scan-path") > 0, hatch = vm.count("scan.hatch") > 0;
  if (csv && hatch)
    throw InputError("--scan-path, --scan.hatch: both given (accepted: one of them)");
  if (!hatch) {  // a hatch option without the hatch is a mistake, not a default
    for (const char* name : {"scan.tracks", "scan.direction", "scan.rotation", "scan.layer", "scan.region"})
      if (vm.count(name) && !vm[name].defaulted())
        throw InputError(fmt::format(
            "--{}: given without --scan.hatch (accepted: --scan.hatch H with it)", name));
    return std::nullopt;
  }
  th::Hatch h;
  h.spacing = vm["scan.hatch"].as<double>();
  h.tracks = vm["scan.tracks"].as<std::size_t>();
  h.direction = bed::parse_word(vm["scan.direction"].as<std::string>(), "--scan.direction",
                                th::kHatchDirectionWords);
  h.rotation = vm["scan.rotation"].as<double>();
  if (!std::isfinite(h.rotation))
    throw InputError("--scan.rotation: not a finite number (accepted: degrees, e.g. 67)");
  h.layer = layer ? *layer : vm["scan.layer"].as<std::size_t>();
  h.region = {bed.domain.lower[0], bed.domain.upper[0], bed.domain.lower[1], bed.domain.upper[1]};
  if (vm.count("scan.region")) {
    const auto r = parse_number_list(vm["scan.region"].as<std::string>(), 4, 4, "--scan.region");
    const auto& lo = bed.domain.lower;
    const auto& hi = bed.domain.upper;
    if (!(r[0] >= lo[0] && r[1] <= hi[0] && r[2] >= lo[1] && r[3] <= hi[1]))
      throw InputError(fmt::format("--scan.region: {:g},{:g},{:g},{:g} leaves the plate (accepted: "
                                   "x0,x1,y0,y1 within x {:g} to {:g} m, y {:g} to {:g} m)",
                                   r[0], r[1], r[2], r[3], lo[0], hi[0], lo[1], hi[1]));
    h.region = {r[0], r[1], r[2], r[3]};
  }
  h.power = s.power;
  h.speed = s.speed;
  return h;
}

// The scene's scan path from --scan-path or scan.hatch (empty: the single track).
std::vector<th::ScanSegment> scan_path_of(const po::variables_map& vm, const th::SinterScene& s,
                                          const bed::Bed& bed, std::optional<std::size_t> layer) {
  if (const auto h = hatch_of(vm, s, bed, layer)) return th::hatch_segments(*h);
  if (vm.count("scan-path")) return th::read_scan_csv(vm["scan-path"].as<std::string>());
  return {};
}

// The run: its files, --explain and --fuse, the laser's headline numbers, the grid spacing and
// the steps.
void add_run_options(po::options_description& desc, th::SinterScene& s) {
  desc.add_options()
      ("bed", po::value<std::string>(), "the bed (HDF5, CSV, LAMMPS dump) resting on z = floor")
      ("out", po::value<std::string>(), "run file: HDF5 time series + XDMF sidecar")
      ("explain", po::bool_switch(), "print the scene's scale analysis and exit")
      ("fuse", po::bool_switch(),
       "after the scan, fuse the particles that melted into the solid: /fusion in the run file")
      ("fuse.melt-fraction", po::value<double>()->default_value(0.5),
       "--fuse: the melt fraction a particle must have reached (0.5: T_m; 1: wholly liquid)")
      ("fuse.level", po::value<double>()->default_value(0.0),
       "--fuse: level the fused deposit by a Gaussian of this standard deviation (m), as the melt "
       "levels before it freezes (build levels by half the beam radius); 0 leaves it where it fell")
      ("fused-bed", po::value<std::string>(), "--fuse: write the powder left as this bed (.h5)")
      ("power", po::value<double>(&s.power)->default_value(s.power), "laser power P (W)")
      ("speed", po::value<double>(&s.speed)->default_value(s.speed), "scan speed v (m/s)")
      ("spot", po::value<double>(&s.spot_radius)->default_value(s.spot_radius),
       "beam radius w at 1/e^2 (m)")
      ("grid-spacing", po::value<double>(),
       "substrate node spacing (m); overrides substrate.nodes (nodes = L / DX + 1, rounded)")
      ("dt", po::value<double>(&s.dt), "grid time step (s); default: safety x the stable bound")
      ("unsafe-dt", po::bool_switch(&s.unsafe_dt),
       "accept a --dt above the stable bound (with a warning)")
      ("integrator", po::value<std::string>()->default_value("explicit"),
       "explicit (forward Euler, multirate) or implicit (backward Euler, Eigen CG)")
      ("t-end", po::value<double>(&s.t_end),
       "simulated time (s); default: until the laser reaches its end")
      ("snapshots", po::value<std::size_t>()->default_value(20),
       "number of snapshots in the time series (besides t = 0)")
      ("full-fields", po::bool_switch(), "also store the whole substrate field in each snapshot")
      ("trust-units", po::bool_switch(),
       "skip the guards against unit slips (a spot larger than the bed, over 10 kW, a substrate "
       "deeper than 1 cm)");
}

// The laser's absorption (Beer–Lambert or ray tracing) and track line; wetting's contact angle.
void add_laser_options(po::options_description& desc, th::SinterScene& s) {
  desc.add_options()
      ("laser.absorptivity", po::value<double>(&s.absorptivity)->default_value(s.absorptivity),
       "alpha")
      ("laser.y", po::value<double>(&s.laser_y), "track line y (m); default Ly/2")
      ("laser.start-x", po::value<double>(&s.start_x),
       "track start x (m); default one spot radius before")
      ("laser.end-x", po::value<double>(&s.end_x), "track end x (m); default one spot radius past")
      ("laser.absorption",
       po::value<std::string>()->default_value(
           s.absorption == th::LaserAbsorption::ray_trace ? "ray-trace" : "beer-lambert"),
       "beer-lambert (exp(-beta z) on projected areas, Gusarov's beta) or ray-trace (rays on "
       "the bed's own spheres and the substrate, absorbed alpha per hit, reflected)")
      ("laser.substrate-shading", po::value<std::string>()->default_value("layer"),
       "beer-lambert: beam reaching the substrate: layer (exp(-beta H_layer) everywhere) or "
       "column (exp(-beta H) with H the bed height above each node; bare spots get the full beam)")
      ("laser.absorptivity-liquid", po::value<double>(&s.absorptivity_liquid),
       "ray-trace: alpha of molten surfaces (default: laser.absorptivity in every phase)")
      ("laser.rays", po::value<std::size_t>(&s.rays.rays)->default_value(s.rays.rays),
       "ray-trace: rays per traced beam position")
      ("laser.retrace-interval",
       po::value<double>(&s.retrace_interval)->default_value(s.retrace_interval),
       "ray-trace: the beam is traced anew each time it moves this fraction of w")
      ("laser.reflection", po::value<std::string>()->default_value("rough"),
       "ray-trace: specular, diffuse (Lambert) or rough (the solid top face reflects by its "
       "roughness, particles and melt as mirrors)")
      ("laser.roughness", po::value<double>(&s.rays.roughness)->default_value(s.rays.roughness),
       "rough: rms height of the solid top face, m")
      ("laser.wavelength", po::value<double>(&s.rays.wavelength)->default_value(s.rays.wavelength),
       "rough: the laser's vacuum wavelength, m")
      ("laser.ray-cutoff", po::value<double>(&s.rays.cutoff)->default_value(s.rays.cutoff),
       "ray-trace: a ray carrying less than this fraction of its power is dropped")
      ("laser.ray-seed", po::value<std::uint64_t>(&s.rays.seed)->default_value(s.rays.seed),
       "ray-trace: seed of the rays' jitter")
      ("laser.optics", po::value<std::string>()->default_value("fresnel"),
       "ray-trace: fresnel (absorptance from the phase's refractive index n + ik at the angle of "
       "incidence) or constant (laser.absorptivity, laser.absorptivity-liquid)")
      ("laser.index-n-solid", po::value<double>(&s.index_n_solid)->default_value(s.index_n_solid),
       "fresnel: n of the solid at the laser's wavelength")
      ("laser.index-k-solid", po::value<double>(&s.index_k_solid)->default_value(s.index_k_solid),
       "fresnel: k of the solid")
      ("laser.index-n-liquid",
       po::value<double>(&s.index_n_liquid)->default_value(s.index_n_liquid),
       "fresnel: n of the liquid")
      ("laser.index-k-liquid",
       po::value<double>(&s.index_k_liquid)->default_value(s.index_k_liquid),
       "fresnel: k of the liquid")
      ("evaporation.back-condensation",
       po::value<double>(&s.back_condensation)->default_value(s.back_condensation),
       "effects.evaporation: back-condensed fraction beta_r of the Hertz-Knudsen flux")
      ("wetting.contact-angle",
       po::value<double>(&s.contact_angle)->default_value(s.contact_angle),
       "effects.wetting: contact angle of the melt on remelted solid (degrees)")
      ("wetting.arrested-conductance",
       po::value<double>(&s.arrested_conductance)->default_value(s.arrested_conductance),
       "effects.wetting: interfacial conductance of a molten particle on solid that has not "
       "remelted (W/m^2K)");
}

// The material's phase change and properties, the environment, the substrate and the steps'
// safety margins.
void add_material_and_grid_options(po::options_description& desc, th::SinterScene& s) {
  th::PhaseChange& p = s.phase_change;
  desc.add_options()
      ("material.table", po::value<std::string>()->default_value(s.material_table),
       "material file with the property table (solid rows + one liquid row): a name of "
       "--list-materials or a path (relative paths: to the scene file's folder too)")
      ("material.melting-point",
       po::value<double>(&p.melting_point)->default_value(p.melting_point),
       "T_m (K)")
      ("material.boiling-point",
       po::value<double>(&p.boiling_point)->default_value(p.boiling_point),
       "T_v (K)")
      ("material.latent-melt", po::value<double>(&p.latent_melt)->default_value(p.latent_melt),
       "L_m (J/kg)")
      ("material.latent-vapour",
       po::value<double>(&p.latent_vapour)->default_value(p.latent_vapour),
       "L_v (J/kg)")
      ("material.molar-mass", po::value<double>(&s.molar_mass)->default_value(s.molar_mass),
       "M of the vapour (kg/mol): evaporation, depression")
      ("material.surface-tension",
       po::value<double>(&s.surface_tension)->default_value(s.surface_tension),
       "gamma of the liquid (N/m): depression")
      ("material.window", po::value<double>(&p.window)->default_value(p.window),
       "phase-change window dT of the apparent heat capacity (K)")
      ("material.hold-from", po::value<double>(&s.hold_from)->default_value(s.hold_from),
       "solid properties extrapolated to this T, then held (K)")
      ("material.liquid-conductivity", po::value<std::string>()->default_value("solid"),
       "solid ([GZ]: the solid value held in the liquid) or table (the liquid row)")
      ("environment.convection", po::value<double>(&s.convection)->default_value(s.convection),
       "h (W/m^2K)")
      ("environment.emissivity", po::value<double>(&s.emissivity)->default_value(s.emissivity),
       "eps")
      ("environment.temperature",
       po::value<double>(&s.environment_temperature)->default_value(s.environment_temperature),
       "T_env (K)")
      ("environment.pressure",
       po::value<double>(&s.ambient_pressure)->default_value(s.ambient_pressure),
       "p0, the ambient pressure at which the boiling point holds (Pa)")
      ("environment.initial-temperature",
       po::value<double>(&s.initial_temperature)->default_value(s.initial_temperature),
       "T0 of bed and substrate, and the substrate's Dirichlet value (K)")
      ("substrate.depth", po::value<double>(&s.substrate_depth)->default_value(s.substrate_depth),
       "depth (m)")
      ("substrate.nodes", po::value<std::string>()->default_value("201,101,61"), "NX,NY,NZ")
      ("substrate.periodic", po::value<std::string>()->default_value("none"),
       "none (Dirichlet y sides at T0) or y (the y sides one seam; the bed periodic along y)")
      ("time.safety", po::value<double>(&s.safety)->default_value(s.safety),
       "fraction of the stable step")
      ("time.max-particle-rise",
       po::value<double>(&s.max_particle_rise)->default_value(s.max_particle_rise),
       "particle steps subcycle so the laser raises no particle more than this per step (K)");
}

// effects.NAME: one switch per row of the scene's list of effects.
void add_effect_options(po::options_description& desc, const th::SinterScene& s) {
  for (const th::SinterEffectRow& row : th::kSinterEffects) {
    const std::string name = std::string("effects.") + row.name;
    desc.add_options()(name.c_str(), po::value<bool>()->default_value(s.has(row.effect)),
                       "effect on/off");
  }
}

}  // namespace

void add_sinter_options(po::options_description& desc, th::SinterScene& scene) {
  add_common_options(desc);
  add_threads_option(desc);
  add_progress_option(desc);
  add_material_options(desc, "sinter");
  add_scan_options(desc, scene);
  add_run_options(desc, scene);
  add_laser_options(desc, scene);
  add_material_and_grid_options(desc, scene);
  add_effect_options(desc, scene);
}

namespace {

// material.table, material.liquid-conductivity (the other material.* and environment.* options
// are bound to the scene).
void set_material(const po::variables_map& vm, th::SinterScene& s) {
  // A name of the shipped materials, or a path (relative: to the scene file's folder too).
  s.material_table =
      material_file(vm["material.table"].as<std::string>(), vm, "material.table");
  s.liquid_conductivity = bed::parse_word(vm["material.liquid-conductivity"].as<std::string>(),
                                          "material.liquid-conductivity", th::kLiquidConductivityWords);
}

// The laser's models: the substrate's shading, the absorption, the rays' reflection (its numbers
// are bound to the scene).
void set_laser(const po::variables_map& vm, th::SinterScene& s) {
  const auto word = [&vm](const char* option) { return vm[option].as<std::string>(); };
  s.substrate_shading =
      bed::parse_word(word("laser.substrate-shading"), "laser.substrate-shading", th::kShadingWords);
  s.absorption = bed::parse_word(word("laser.absorption"), "laser.absorption", th::kAbsorptionWords);
  s.rays.reflection =
      bed::parse_word(word("laser.reflection"), "laser.reflection", th::kReflectionWords);
  s.optics = bed::parse_word(word("laser.optics"), "laser.optics", th::kOpticsWords);
  s.periodic_y = bed::parse_word(word("substrate.periodic"), "substrate.periodic", th::kSubstratePeriodicWords);
}

// The substrate's nodes (--grid-spacing: from the bed's x-y extent lx, ly and its depth).
void set_grid(const po::variables_map& vm, double lx, double ly, th::SinterScene& s) {
  const auto nodes = parse_number_list(vm["substrate.nodes"].as<std::string>(), 3, 3,
                                            "substrate.nodes");
  for (std::size_t a = 0; a < 3; ++a) {
    if (!(nodes[a] >= 0 && nodes[a] == std::floor(nodes[a])))
      throw InputError(fmt::format("substrate.nodes: '{}' (accepted: three whole numbers >= 3)",
                                   vm["substrate.nodes"].as<std::string>()));
    s.nodes[a] = static_cast<std::size_t>(nodes[a]);
  }
  if (vm.count("grid-spacing")) {
    const double h = vm["grid-spacing"].as<double>();
    if (!(h > 0 && std::isfinite(h)))
      throw InputError(fmt::format("--grid-spacing: {:f} (accepted: DX > 0 m)", h));
    const double lengths[3] = {lx, ly, s.substrate_depth};
    for (std::size_t a = 0; a < 3; ++a)
      s.nodes[a] = static_cast<std::size_t>(std::llround(lengths[a] / h)) + 1;
  }
}

// The integrator, and --dt checked when given (the steps and the end of the run are bound).
void set_time(const po::variables_map& vm, th::SinterScene& s) {
  s.integrator = bed::parse_word(vm["integrator"].as<std::string>(), "--integrator",
                                 th::kIntegratorWords);
  if (vm.count("dt") && !(s.dt > 0))
    throw InputError(fmt::format("--dt: {:f} (accepted: dt > 0 s)", s.dt));
}

// A material file named by --material must give what the scene's models read of it: the
// defaults are 316L's, wrong for any other metal.
void require_material_keys(const po::variables_map& vm, const th::SinterScene& s) {
  if (!vm.count("material")) return;
  struct Need {
    const char* option;
    const char* why;
    const char* instead;
  };
  std::vector<Need> needed;
  if (s.absorption == th::LaserAbsorption::ray_trace && s.optics == th::Optics::fresnel)
    for (const char* o : {"laser.index-n-solid", "laser.index-k-solid", "laser.index-n-liquid",
                          "laser.index-k-liquid"})
      needed.push_back({o, "laser.optics = fresnel", "laser.optics = constant"});
  if (s.has(th::kEvaporation))
    for (const char* o : {"material.boiling-point", "material.molar-mass"})
      needed.push_back({o, "effects.evaporation", "effects.evaporation = false"});
  if (s.has(th::kDepression))
    for (const char* o : {"material.boiling-point", "material.molar-mass", "material.surface-tension"})
      needed.push_back({o, "effects.depression", "effects.depression = false"});
  for (const Need& n : needed) {
    if (!vm[n.option].defaulted()) continue;  // from the file, the scene or the command line
    throw InputError(fmt::format(
        "--material: '{}' gives no {} for {} (accepted: a material file with it, --{} given, "
        "or {})",
        vm["material"].as<std::string>(), n.option, n.why, n.option, n.instead));
  }
}

th::SinterScene make_scene(const po::variables_map& vm, const th::SinterScene& bound, double lx,
                           double ly) {
  th::SinterScene s = bound;
  set_material(vm, s);
  set_laser(vm, s);
  set_grid(vm, lx, ly, s);
  set_time(vm, s);
  s.effects = 0;
  for (const th::SinterEffectRow& row : th::kSinterEffects)
    if (vm[std::string("effects.") + row.name].as<bool>()) s.effects |= row.effect;
  require_material_keys(vm, s);
  return s;
}

// Guards against the unit slips users make (metres for micrometres, W for mW): each names the
// likely mistake; --trust-units skips them where a huge value is meant.
void check_units(const th::SinterScene& s, const bed::Bed& bed) {
  const double size = std::max(bed.domain.length(0), bed.domain.length(1));
  const auto refuse = [](const std::string& what) {
    throw InputError(fmt::format("{} (--trust-units if it is meant)", what));
  };
  if (s.spot_radius > size) {
    refuse(fmt::format("--spot: w = {:g} m is wider than the bed ({:g} m): a unit slip? "
                       "(accepted: a beam radius in metres, e.g. 54e-6)",
                       s.spot_radius, size));
  }
  if (s.power > 1e4) {
    refuse(fmt::format("--power: {:g} W is beyond the lasers of powder-bed machines (accepted: "
                       "up to 1e4 W)",
                       s.power));
  }
  for (std::size_t m = 0; m < s.scan_path.size(); ++m) {
    if (s.scan_path[m].power > 1e4)
      refuse(fmt::format("--scan-path: segment {}: power {:g} W is beyond the lasers of powder-bed "
                         "machines (accepted: up to 1e4 W)",
                         m + 1, s.scan_path[m].power));
  }
  if (s.substrate_depth > 1e-2) {
    refuse(fmt::format("substrate.depth: {:g} m: a unit slip? (accepted: a depth in metres up "
                       "to 1e-2, e.g. 0.3e-3)",
                       s.substrate_depth));
  }
}

// A grid that cannot fit in memory is refused before anything is allocated: a step keeps about
// eight doubles per node.
void check_grid_memory(const th::SinterScene& s) {
  const double nodes = static_cast<double>(s.nodes[0]) * static_cast<double>(s.nodes[1]) *
                       static_cast<double>(s.nodes[2]);
  const double bytes = 8.0 * sizeof(double) * nodes;
  const double memory = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
                        static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  if (bytes > memory) {
    throw InputError(fmt::format("substrate.nodes: {},{},{} ({:g} nodes) needs about {:g} GiB; "
                                 "this machine has {:g} GiB (accepted: fewer nodes, or a "
                                 "coarser --grid-spacing)",
                                 s.nodes[0], s.nodes[1], s.nodes[2], nodes, bytes / (1u << 30),
                                 memory / (1u << 30)));
  }
}

}  // namespace

thermal::SinterScene sinter_scene(const po::variables_map& vm, const thermal::SinterScene& bound,
                                  const bed::Bed& bed, std::optional<std::size_t> layer) {
  th::SinterScene scene = make_scene(vm, bound, bed.domain.length(0), bed.domain.length(1));
  scene.scan_path = scan_path_of(vm, scene, bed, layer);
  if (!vm["trust-units"].as<bool>()) check_units(scene, bed);
  check_grid_memory(scene);
  return scene;
}

std::optional<thermal::Hatch> scan_hatch(const po::variables_map& vm, const thermal::SinterScene& scene,
                                         const bed::Bed& bed, std::optional<std::size_t> layer) {
  return hatch_of(vm, scene, bed, layer);
}

}  // namespace powderbed::app
