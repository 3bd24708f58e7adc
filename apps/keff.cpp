// keff: the effective thermal conductivity of a bed between two isothermal walls (docs/keff.md):
// the steady state of the particles' heat-path network (contact and gas conduction, grey-body
// radiation with Monte-Carlo view factors).
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "common/app_main.hpp"
#include "common/material_options.hpp"
#include "powderbed/bed/material_file.hpp"
#include "common/options.hpp"
#include "common/progress.hpp"
#include "common/threads.hpp"
#include "powderbed/bed/json_units.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/temp_files.hpp"
#include "powderbed/keff/core_conductivity.hpp"
#include "powderbed/keff/hot_wall.hpp"
#include "powderbed/keff/profile.hpp"
#include "powderbed/keff/solve.hpp"

namespace {

using namespace powderbed;
namespace po = app::po;
namespace kf = keff;

const char* const kUsage =
    "keff --config SCENE.ini --bed BED.h5 [--axis x|y|z] [--t-hot K --t-cold K | --temperature K] "
    "[--rays N] [--json] [--out RUN.h5]";

// --temperature T puts the walls at T ± kSpan / 2: k_eff at T, linearised. The nonlinear paths
// (T⁴, k_g(T)) change over 1 K by ~4/T relative, so the difference from the tangent is
// O((1 K / T)²), below 1e-5 from 300 K up.
constexpr double kSpan = 1;

// The options; those of a plain type are bound to `s`'s fields (defaults: its values).
void add_options(po::options_description& desc, kf::KeffScene& s) {
  app::add_common_options(desc);
  app::add_threads_option(desc);
  app::add_progress_option(desc);
  app::add_material_options(desc, "keff");
  // t-hot and t-cold are not bound: set_walls chooses between them and --temperature.
  const kf::KeffScene d;
  desc.add_options()
      ("bed", po::value<std::string>(), "the bed (HDF5, CSV, LAMMPS dump)")
      ("out", po::value<std::string>(), "the bed with the particle temperatures (HDF5)")
      ("axis", po::value<std::string>()->default_value("z"),
       "axis of the heat flow: hot wall at its upper face, cold wall at its lower face (x, y: "
       "the side walls a deposited bed was poured against; z: floor and the bed's top)")
      ("t-hot", po::value<double>()->default_value(d.hot_temperature), "T_hot (K)")
      ("t-cold", po::value<double>()->default_value(d.cold_temperature), "T_cold (K)")
      ("temperature", po::value<double>(),
       "bed temperature T (K): the walls at T +- 0.5 K, k_eff at T (instead of --t-hot/--t-cold)")
      ("newton-tolerance",
       po::value<double>(&s.newton_tolerance)->default_value(s.newton_tolerance),
       "Newton stops at |net flows| / |flows| below this (radiation, gas.model = air)")
      ("profile-bins", po::value<std::size_t>()->default_value(0),
       "bins of the temperature profile written beside --out (0: one per mean diameter)")
      ("solid.conductivity",
       po::value<double>(&s.solid_conductivity)->default_value(s.solid_conductivity), "k_s (W/mK)")
      ("gas.model", po::value<std::string>()->default_value("constant"),
       "constant (gas.conductivity) or air (the [KE] polynomial at each gas link's temperature)")
      ("gas.conductivity",
       po::value<double>(&s.gas_conductivity)->default_value(s.gas_conductivity), "k_g (W/mK)")
      ("gas.lens", po::value<double>(&s.lens.lens)->default_value(s.lens.lens),
       "gas lens thickness over the particle radius (Rong-Horio)")
      ("gas.min-gap", po::value<double>(&s.lens.min_gap)->default_value(s.lens.min_gap),
       "l_min (m)")
      ("trust-units", po::bool_switch(),
       "skip the guard against unit slips (gas.min-gap over 1e-4 m: um typed as m?)")
      ("gas.lens-region", po::value<std::string>()->default_value("both-lenses"),
       "outer edge of the gas path: both-lenses (where the two lenses intersect) or larger-lens "
       "(where the larger particle's lens meets the smaller particle, as MFiX computes it)")
      ("contact.calibration", po::value<double>(&s.calibration)->default_value(s.calibration),
       "A_c: scales the contact radius")
      ("contact.hertz-correction",
       po::value<bool>(&s.contact.hertz_correction)->default_value(s.contact.hertz_correction),
       "contact radius from the equivalent Hertz overlap of a softened bed (else the bed's own); "
       "the DEM's law, E, nu and softening S or stiffness k_n are read from the bed")
      ("contact.radius", po::value<std::string>(),
       "hertz (a = sqrt(R* delta)) or geometric (the spheres' intersection circle, as MFiX); "
       "default: hertz with contact.hertz-correction, else geometric")
      ("contact.young", po::value<double>(),
       "E of the particles in the Hertz correction (Pa; default: the bed's): reads the same "
       "packing as a material of this modulus, the walls' modulus scaled alike")
      ("contact.law", po::value<std::string>(),
       "hertz or linear: checked against the bed's record (it is read from the bed)")
      ("contact.young-scale", po::value<double>(),
       "S of the bed's Hertz DEM run: checked against the bed's record (it is read from the bed)")
      ("contact.stiffness", po::value<double>(),
       "k_n of the bed's linear DEM run (N/m): checked against the bed's record")
      ("effects.contact", po::value<bool>(&s.contact_path)->default_value(s.contact_path),
       "contact conduction on/off")
      ("rays", po::value<std::size_t>(&s.rays)->default_value(s.rays),
       "Monte-Carlo view-factor rays per particle (radiation)")
      ("radiation.seed", po::value<std::uint64_t>(&s.seed)->default_value(s.seed),
       "seed of the view-factor rays (each particle its own stream: any thread count agrees)")
      ("radiation.model", po::value<std::string>()->default_value("pair"),
       "pair (the per-pair grey formula of docs/physics.md §6) or radiosity (the grey enclosure: one radiosity node "
       "per surface, docs/keff.md)")
      ("radiation.emissivity", po::value<double>(&s.emissivity)->default_value(s.emissivity),
       "grey emissivity of the particles")
      ("radiation.wall-emissivity",
       po::value<double>(&s.wall_emissivity)->default_value(s.wall_emissivity),
       "grey emissivity of the hot and cold walls")
      ("effects.gas", po::value<bool>(&s.gas_path)->default_value(s.gas_path),
       "gas-lens conduction on/off")
      ("effects.radiation", po::value<bool>(&s.radiation_path)->default_value(s.radiation_path),
       "grey-body radiation on/off (needs absolute wall temperatures)");
}

int axis_index(const std::string& name) {
  if (name == "x") return 0;
  if (name == "y") return 1;
  if (name == "z") return 2;
  throw InputError(fmt::format("--axis: '{}' (accepted: x, y, z)", name));
}

// The wall temperatures: --temperature or --t-hot/--t-cold, whichever the command line gives
// (it wins over the scene, as every option does); both on the command line, or both in the scene, is refused.
void set_walls(const po::variables_map& vm, const po::variables_map& command_line,
               kf::KeffScene& s) {
  const auto walls_given = [](const po::variables_map& m) {
    return (m.count("t-hot") && !m["t-hot"].defaulted()) ||
           (m.count("t-cold") && !m["t-cold"].defaulted());
  };
  const bool cli_temperature = command_line.count("temperature") > 0;
  const bool cli_walls = walls_given(command_line);
  if (cli_temperature && cli_walls)
    throw InputError("--temperature: given with --t-hot/--t-cold (accepted: one or the other)");
  bool use_temperature = cli_temperature;
  if (!cli_temperature && !cli_walls && vm.count("temperature")) {
    if (walls_given(vm))
      throw InputError("temperature: the scene sets it and t-hot/t-cold (accepted: one or the "
                       "other)");
    use_temperature = true;
  }
  if (use_temperature) {
    const double t = vm["temperature"].as<double>();
    if (!(std::isfinite(t) && t > kSpan))
      throw InputError(fmt::format("--temperature: {:f} K (accepted: T > 1 K)", t));
    s.hot_temperature = t + kSpan / 2;
    s.cold_temperature = t - kSpan / 2;
    return;
  }
  s.hot_temperature = vm["t-hot"].as<double>();
  s.cold_temperature = vm["t-cold"].as<double>();
}

// contact.radius, whose default keeps what contact.hertz-correction alone chose before the
// option existed: the Hertz circle of the corrected overlap, else the geometric circle.
kf::ContactCircle contact_circle(const po::variables_map& vm, bool hertz_correction) {
  if (!vm.count("contact.radius"))
    return hertz_correction ? kf::ContactCircle::hertz : kf::ContactCircle::geometric;
  return bed::parse_word(vm["contact.radius"].as<std::string>(), "contact.radius",
                         kf::kContactCircleWords);
}

// The scene: `bound` (what add_options bound) with the axis, the walls and the models named by
// words, validated.
kf::KeffScene make_scene(const po::variables_map& vm, const po::variables_map& command_line,
                         const kf::KeffScene& bound) {
  kf::KeffScene s = bound;
  s.axis = axis_index(vm["axis"].as<std::string>());
  set_walls(vm, command_line, s);
  const auto word = [&vm](const char* option) { return vm[option].as<std::string>(); };
  s.gas_model = bed::parse_word(word("gas.model"), "gas.model", kf::kGasModelWords);
  s.lens.region = bed::parse_word(word("gas.lens-region"), "gas.lens-region", kf::kLensRegionWords);
  s.radiation_model =
      bed::parse_word(word("radiation.model"), "radiation.model", kf::kRadiationModelWords);
  s.contact.circle = contact_circle(vm, s.contact.hertz_correction);
  s.validate();
  return s;
}

// RUN.h5 → RUN-profile.csv beside it.
std::string profile_path_of(const std::string& out) {
  const std::string suffix = ".h5";
  const bool h5 = out.size() > suffix.size() &&
                  out.compare(out.size() - suffix.size(), suffix.size(), suffix) == 0;
  return (h5 ? out.substr(0, out.size() - suffix.size()) : out) + "-profile.csv";
}

std::string profile_csv(const kf::TemperatureProfile& p, const kf::KeffScene& scene) {
  const char* const axis = scene.axis == 0 ? "x" : scene.axis == 1 ? "y" : "z";
  std::string text = "# keff temperature profile along " + std::string(axis) +
                     ": particles binned by centre, cold wall " +
                     std::to_string(scene.cold_temperature) + " K at the lower face, hot wall " +
                     std::to_string(scene.hot_temperature) +
                     " K at the upper face; rattlers left out\n";
  text += std::string(axis) + "_m,mean_K,min_K,max_K,particles\n";
  char line[160];
  for (std::size_t b = 0; b < p.position.size(); ++b) {
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g,%llu\n", p.position[b], p.mean[b],
                  p.min[b], p.max[b], static_cast<unsigned long long>(p.particles[b]));
    text += line;
  }
  return text;
}

// l_min removes the gas lens's singularity at contact (1 um by default, Rong & Horio): a gap
// of a tenth of a millimetre is a slip of units, not a model.
void check_units(const po::variables_map& vm, const kf::KeffScene& scene) {
  if (vm["trust-units"].as<bool>() || scene.lens.min_gap <= 1e-4) return;
  throw InputError(fmt::format("gas.min-gap: {:g} m: a unit slip? (accepted: l_min in metres up "
                               "to 1e-4, e.g. 1e-6; --trust-units if it is meant)",
                               scene.lens.min_gap));
}

// The hot wall below the powder's solidus (keff/hot_wall.hpp), the material's when --material
// names one.
void check_wall_temperatures(const po::variables_map& vm, const kf::KeffScene& scene) {
  if (!vm.count("material")) {
    kf::check_hot_wall(scene.hot_temperature, nullptr, vm["trust-units"].as<bool>());
    return;
  }
  const bed::MaterialFile file =
      bed::read_material_file(app::material_file(vm["material"].as<std::string>(), vm, "--material"));
  kf::check_hot_wall(scene.hot_temperature, &file, vm["trust-units"].as<bool>());
}

// Inputs and outputs checked before the work: a folder where the profile goes, or --out = the
// bed, must not cost a solve or an existing file.
void check_files(const po::variables_map& vm) {
  std::vector<app::PathArg> outputs;
  if (vm.count("out")) {
    const std::string out = vm["out"].as<std::string>();
    app::check_extension({"--out", out}, {".h5"});
    outputs = {{"--out", out}, {"--out (its profile)", profile_path_of(out)}};
  }
  app::check_paths({{"--bed", vm["bed"].as<std::string>()}}, outputs);
}

// The contact.* options that must agree with the bed's record of its DEM run.
kf::ContactOptions contact_options(const po::variables_map& vm) {
  kf::ContactOptions given;
  if (vm.count("contact.law")) given.law = vm["contact.law"].as<std::string>();
  if (vm.count("contact.young-scale")) given.young_scale = vm["contact.young-scale"].as<double>();
  if (vm.count("contact.stiffness")) given.stiffness = vm["contact.stiffness"].as<double>();
  if (vm.count("contact.young")) given.young = vm["contact.young"].as<double>();
  return given;
}

// The network (view factors with progress on stderr) and its steady state; `wall` gets the
// wall time in seconds. Throws NumericalError when no heat path joins the walls.
kf::KeffResult solve(const po::variables_map& vm, const bed::Bed& bed, const kf::KeffScene& scene,
                     kf::KeffNetwork& network, double& wall) {
  const auto start = std::chrono::steady_clock::now();
  app::ProgressBar bar("keff", app::progress_interval(vm));
  std::function<void(double)> progress;
  if (scene.radiation_path)
    progress = [&bar](double fraction) { bar.draw(fraction, "view factors"); };
  network = kf::build_keff_network(bed, scene, progress);
  bar.finish();
  kf::KeffResult r = kf::solve_keff(bed, scene, network);
  // No conducting path from wall to wall gives k_eff = 0 up to round-off: not a result.
  if (!(r.k_eff > 0) || !std::isfinite(r.k_eff)) {
    throw NumericalError(fmt::format("k_eff = {:g} W/mK: no heat path joins the two walls ({} of "
                                     "{} particles isolated; accepted: a bed whose particles "
                                     "connect the walls, e.g. a settled bed from deposit)",
                                     r.k_eff, r.rattlers.size(), bed.n()));
  }
  wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// --out: the bed with the particle temperatures and, beside it, the binned profile; returns
// the profile's path. The two files are written together or not at all.
std::string write_outputs(const po::variables_map& vm, bed::Bed& bed, const kf::KeffScene& scene,
                          const kf::KeffResult& r, const kf::TemperatureProfile& profile,
                          int argc, char** argv) {
  const std::string out = vm["out"].as<std::string>();
  const std::string profile_path = profile_path_of(out);
  bed.temperature = r.temperature;
  bed.provenance.created_by = app::version_string("keff");
  bed.provenance.command_line = app::command_line(argc, argv);
  bed.provenance.stage = "keff";
  bed.provenance.scene = app::scene_text(vm);
  bed::CommitTogether together;  // a full disk on the profile leaves the old out.h5
  bed::write_bed_h5(bed, out);
  bed::write_text_file(profile_path, profile_csv(profile, scene));
  together.commit();
  return profile_path;
}

// What a run found, for the report.
struct RunReport {
  const bed::Bed& bed;
  const kf::KeffScene& scene;
  const kf::KeffNetwork& network;
  const kf::KeffResult& result;
  const kf::CoreConductivity& core;  // k_core and the walls' shares of the drop
  double r_squared;                  // of the profile's bin means
  double wall;
  std::string profile_path;  // empty without --out
};

// The units of keff's --json numbers (common/json_units).
constexpr bed::UnitEntry kUnits[] = {
    {"k_eff", "W/(m K)"}, {"k_core", "W/(m K)"}, {"core_particles", "1"}, {"core_margin", "m"},
    {"profile_r_squared", "1"}, {"wall_drop_hot", "1"}, {"wall_drop_cold", "1"},
    {"heat_flow_hot", "W"}, {"heat_flow_cold", "W"},
    // share: of the heat flow through each path
    {"contact", "1"}, {"gas", "1"}, {"radiation", "1"},
    {"rattlers", "1"}, {"newton_iterations", "1"}, {"newton_residual", "1"},
    {"solver_iterations", "1"}, {"particles", "1"}, {"contact_links", "1"}, {"gas_links", "1"},
    {"radiation_links", "1"}, {"rays", "1"}, {"lost_rays", "1"}, {"view_factor_error", "1"},
    {"gas_conductivity", "W/(m K)"}, {"t_hot", "K"}, {"t_cold", "K"}, {"wall_time", "s"},
};

// --json: k_eff, the wall flows, each path's share and the solve's counters (SI).
std::string result_json(const RunReport& run) {
  const kf::KeffResult& r = run.result;
  const kf::KeffScene& scene = run.scene;
  bed::JsonWriter j;
  j.begin_object()
      .value("k_eff", r.k_eff)
      .value("k_core", run.core.k_core)
      .value("core_particles", static_cast<std::uint64_t>(run.core.particles))
      .value("core_margin", run.core.margin)
      .value("profile_r_squared", run.r_squared)
      .value("wall_drop_hot", run.core.drop_hot)
      .value("wall_drop_cold", run.core.drop_cold)
      .value("axis", scene.axis == 0 ? "x" : scene.axis == 1 ? "y" : "z")
      .value("contact_radius",
             scene.contact.circle == kf::ContactCircle::hertz ? "hertz" : "geometric")
      .value("heat_flow_hot", r.heat_flow_hot)
      .value("heat_flow_cold", r.heat_flow_cold)
      .begin_object("share")
      .value("contact", r.share_contact)
      .value("gas", r.share_gas)
      .value("radiation", r.share_radiation)
      .end_object()
      .value("hertz_correction", scene.contact.hertz_correction)
      .value("contact_law", run.bed.provenance.contact.law)
      .value("rattlers", static_cast<std::uint64_t>(r.rattlers.size()))
      .value("newton_iterations", static_cast<std::uint64_t>(r.newton_iterations))
      .value("newton_residual", r.residual)
      .value("solver_iterations", static_cast<std::uint64_t>(r.solver_iterations))
      .value("particles", static_cast<std::uint64_t>(run.bed.n()))
      .value("contact_links", static_cast<std::uint64_t>(r.contact_links))
      .value("gas_links", static_cast<std::uint64_t>(r.gas_links))
      .value("radiation_links", static_cast<std::uint64_t>(r.radiation_links))
      .value("rays", static_cast<std::uint64_t>(scene.radiation_path ? scene.rays : 0))
      .value("radiation_model", scene.radiation_model == kf::RadiationModel::radiosity
                                    ? "radiosity"
                                    : "pair")
      .value("lost_rays", static_cast<std::uint64_t>(r.lost_rays))
      .value("view_factor_error", run.network.reciprocity_error)
      .value("gas_conductivity", scene.gas_path ? scene.gas_conductivity_used() : 0.0)
      .value("t_hot", scene.hot_temperature)
      .value("t_cold", scene.cold_temperature)
      .value("wall_time", run.wall);
  if (!run.profile_path.empty()) j.value("profile", run.profile_path);
  bed::write_units(j, kUnits);
  j.end_object();
  return j.str() + '\n';
}

// The text report: the conductivities and the profile's shape, then the flows and paths, and
// where the profile went.
void print_result(const RunReport& run) {
  const kf::KeffResult& r = run.result;
  std::printf("keff: k_eff = %.6g W/mK wall to wall, k_core = %.6g W/mK (flux over the mean "
              "gradient of the %zu particles over %.3g m from both walls); profile R^2 = %.4f; "
              "wall drops: hot %.1f %%, cold %.1f %% of T_hot - T_cold\n",
              r.k_eff, run.core.k_core, run.core.particles, run.core.margin, run.r_squared,
              100 * run.core.drop_hot, 100 * run.core.drop_cold);
  std::printf("keff: wall flows %.6g / %.6g W (hot / cold); contact %.1f %%, "
              "gas %.1f %%, radiation %.1f %%; %zu rattlers of %zu particles; %zu Newton "
              "step%s; %.3g s\n",
              r.heat_flow_hot, r.heat_flow_cold, 100 * r.share_contact,
              100 * r.share_gas, 100 * r.share_radiation, r.rattlers.size(), run.bed.n(),
              r.newton_iterations, r.newton_iterations == 1 ? "" : "s", run.wall);
  if (!run.profile_path.empty())
    std::printf("keff: temperature profile in %s\n", run.profile_path.c_str());
}

int run(int argc, char** argv) {
  po::options_description desc("keff options (SI units)");
  kf::KeffScene bound;  // what the options of a plain type fill (add_options)
  add_options(desc, bound);
  po::variables_map vm;
  if (!app::parse_options("keff", kUsage, desc, {}, argc, argv, vm)) return 0;
  app::apply_thread_team(vm);
  if (!vm.count("bed")) throw InputError("--bed: missing (required)");
  po::variables_map command_line;  // what the command line alone says (walls)
  po::store(po::command_line_parser(argc, argv).options(desc).run(), command_line);
  kf::KeffScene scene = make_scene(vm, command_line, bound);
  check_units(vm, scene);
  check_wall_temperatures(vm, scene);
  const auto bins = app::option_in_range<std::size_t>(vm, "profile-bins", 0, 1000000);
  check_files(vm);
  bed::Bed bed = bed::read_bed_any(vm["bed"].as<std::string>());
  const kf::ContactCircle circle = scene.contact.circle;
  scene.contact = kf::contact_radius_params(bed.provenance.contact,
                                            scene.contact.hertz_correction, contact_options(vm));
  scene.contact.circle = circle;
  kf::KeffNetwork network;
  double wall = 0;
  const kf::KeffResult r = solve(vm, bed, scene, network, wall);
  const kf::TemperatureProfile profile =
      kf::temperature_profile(bed, scene.axis, r.temperature, r.rattlers, bins);
  const double flux = (r.heat_flow_hot + r.heat_flow_cold) / 2 / network.wall_area;
  const kf::CoreConductivity core = kf::core_conductivity(
      bed, scene.axis, r.temperature, r.rattlers, flux, scene.hot_temperature,
      scene.cold_temperature);
  const std::string profile_path =
      vm.count("out") ? write_outputs(vm, bed, scene, r, profile, argc, argv) : "";
  const RunReport report{bed, scene, network, r, core, kf::profile_r_squared(profile),
                         wall, profile_path};
  if (vm.count("json")) std::cout << result_json(report);
  else print_result(report);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return app::run_app("keff", argc, argv, [&] { return run(argc, argv); });
}
