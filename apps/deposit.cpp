// deposit: DEM drop deposition (Ganeriwala & Zohdi 2016). Particles come from a PSD (placed without overlap
// in the insertion region by packgen's 0-contact packing) or from a bed file, fall under the
// scene's effects and settle; the settled bed is written with velocities.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "common/app_main.hpp"
#include "common/deck_export.hpp"
#include "common/material_options.hpp"
#include "common/options.hpp"
#include "common/progress.hpp"
#include "common/thermo_table.hpp"
#include "common/threads.hpp"
#include "deposit_options.hpp"
#include "deposit_spread.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/dem/summary_json.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/bed/temp_files.hpp"
#include "powderbed/dem/contact_provenance.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/scene.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/time_step.hpp"
#include "powderbed/packgen/pack.hpp"

namespace {

using namespace powderbed;
namespace po = app::po;

const char* const kUsage =
    "deposit [--config SCENE.ini] [--in BED.h5 | --psd SPEC --count N] --domain LX,LY,LZ "
    "[--insert-z Z0,Z1 | --insert.enabled true --insert.rate R --insert.speed V] [--t-end T | --until-rest] [--dt DT] [--unsafe-dt] "
    "[--integrator verlet|rk4] [--young-scale S | --contact.law linear --contact.stiffness K] --seed S --out BED.h5 "
    "[--trajectory RUN.h5 --every K] [--lid [--lid.pressure P] [--lid.travel L | --lid.depth L] [--lid.speed V] "
    "[--lid.hold T] [--lid.relax T] [--lid.release false]] [--crop-top true] [--core-margin M] [--json]\n"
    "deposit --config SPREAD.ini (recoater.tool = blade|roller, docs/deposit-spread.md) --seed S --out BED.h5 "
    "[--in SPREAD-BED.h5] [--layers N] [--tool-forces F.csv [--tool-forces-every K]] [--json]";

// The pool of the insertion (dem::InsertionSettings): --count radii drawn from --psd, parked at
// the box's centre until the solver inserts them in order.
bed::Bed insertion_pool(const po::variables_map& vm, const bed::Domain& domain,
                        std::uint64_t seed) {
  const bed::Psd psd = bed::Psd::parse(app::required<std::string>(vm, "psd"), "--psd");
  const std::size_t count = app::required<std::size_t>(vm, "count");
  if (count == 0) throw InputError("--count: 0 (accepted: N >= 1)");
  bed::Bed pool;
  pool.domain = domain;
  pool.reserve(count);
  bed::Rng rng(seed);
  double centre[3];
  for (int a = 0; a < 3; ++a) centre[a] = 0.5 * (domain.lower[a] + domain.upper[a]);
  for (std::size_t i = 0; i < count; ++i)
    pool.add(centre[0], centre[1], centre[2], psd.sample_radius(rng));
  return pool;
}

bed::Bed insert_from_psd(const po::variables_map& vm, const bed::Domain& domain,
                         std::uint64_t seed) {
  const bed::Psd psd = bed::Psd::parse(app::required<std::string>(vm, "psd"), "--psd");
  const std::size_t count = app::required<std::size_t>(vm, "count");
  if (count == 0) throw InputError("--count: 0 (accepted: N >= 1)");
  bed::Domain region = domain;
  if (vm.count("insert-z")) {
    const auto z = app::parse_number_list(vm["insert-z"].as<std::string>(), 2, 2, "--insert-z");
    if (!(z[0] >= domain.lower[2] && z[1] <= domain.upper[2] && z[0] < z[1])) {
      throw InputError(fmt::format("--insert-z: {:g},{:g} (accepted: {:g} <= Z0 < Z1 <= {:g})",
                                   z[0], z[1], domain.lower[2], domain.upper[2]));
    }
    region.lower[2] = z[0];
    region.upper[2] = z[1];
  }
  region.periodic = {false, false, false};  // insertion keeps every particle inside the region
  packgen::PackOptions options;
  options.phases = {packgen::Phase{0, 1.0}};
  options.count = count;
  options.max_failures = 100;
  packgen::validate(region, psd, options);
  packgen::PackResult placed = packgen::pack(region, psd, options, seed);
  if (placed.bed.n() < count) {
    throw InputError(fmt::format("--count: {} particles do not fit the insertion region without "
                                 "overlap ({} placed by 0-contact packing; accepted: N <= {}, or "
                                 "a taller --insert-z)",
                                 count, placed.bed.n(), placed.bed.n()));
  }
  placed.bed.domain = domain;
  return placed.bed;
}

// Inputs and outputs checked before the run, so a bad --out costs no simulation and never
// replaces the input.
void check_files(const po::variables_map& vm, const std::string& out) {
  std::vector<app::PathArg> inputs, outputs{{"--out", out}};
  if (vm.count("in")) inputs.push_back({"--in", vm["in"].as<std::string>()});
  app::check_extension({"--out", out}, {".h5"});
  if (vm.count("trajectory")) {
    app::check_extension({"--trajectory", vm["trajectory"].as<std::string>()}, {".h5"});
    outputs.push_back({"--trajectory", vm["trajectory"].as<std::string>()});
  }
  if (vm.count("export-deck")) {
    for (auto& p : app::deck_outputs(vm["export-deck"].as<std::string>(), out)) outputs.push_back(p);
  }
  if (const auto log = app::log_path(vm)) outputs.push_back(*log);
  app::check_paths(inputs, outputs);
}

struct Particles {
  bed::Bed bed;
  bool inserting = false;  // the bed is the pool of the insertion (dem::InsertionSettings)
};

// One source of particles. A scene's psd (with its count and insertion) gives way to --in on
// the command line, which wins over the scene (so a bed scene can re-run its own bed, e.g. to
// consolidate it); both in the same place is refused.
Particles particles(const po::variables_map& vm, const po::options_description& desc, int argc,
                    char** argv, std::uint64_t seed) {
  if (!vm.count("in") && !vm.count("psd")) {
    throw InputError("--in / --psd: neither given (accepted: --in BED.h5 or --psd SPEC --count N)");
  }
  po::variables_map command_line;
  po::store(po::command_line_parser(argc, argv).options(desc).run(), command_line);
  bool from_bed = vm.count("in") > 0;
  if (vm.count("in") && vm.count("psd")) {
    if ((command_line.count("in") > 0) == (command_line.count("psd") > 0))
      throw InputError("--in and --psd: both given (accepted: one source of particles)");
    from_bed = command_line.count("in") > 0;
  }
  Particles p;
  p.inserting = !from_bed && vm["insert.enabled"].as<bool>();
  const bool insert_typed =
      command_line.count("insert.enabled") > 0 && !command_line["insert.enabled"].defaulted();
  if (from_bed && vm["insert.enabled"].as<bool>() && (insert_typed || !command_line.count("in"))) {
    throw InputError("insert.enabled: with --in (accepted: --psd SPEC --count N, the particles "
                     "to insert)");
  }
  if (from_bed) {
    std::optional<bed::Domain> domain;
    if (vm.count("domain")) domain = app::parse_domain_lengths(vm["domain"].as<std::string>(), "--domain");
    p.bed = bed::read_bed_any(vm["in"].as<std::string>(), domain ? &*domain : nullptr);
    if (domain) p.bed.domain = *domain;
  } else {
    const bed::Domain domain =
        app::parse_domain_lengths(app::required<std::string>(vm, "domain"), "--domain");
    if (domain.dimension != 3) throw InputError("--domain: 2D box (accepted: LX,LY,LZ)");
    p.bed = p.inserting ? insertion_pool(vm, domain, seed) : insert_from_psd(vm, domain, seed);
  }
  return p;
}

void set_periodic(const po::variables_map& vm, bed::Domain& domain) {
  const std::string periodic = vm["periodic"].as<std::string>();
  if (periodic == "x" || periodic == "x,y" || periodic == "xy") domain.periodic[0] = true;
  if (periodic == "y" || periodic == "x,y" || periodic == "xy") domain.periodic[1] = true;
  if (periodic != "none" && periodic != "x" && periodic != "y" && periodic != "x,y" &&
      periodic != "xy") {
    throw InputError(fmt::format("--periodic: '{}' (accepted: none, x, y, x,y)", periodic));
  }
}

// The run's settings: `bound` (the settings add_deposit_options bound: --t-end, --until-rest,
// rest.*, lid.*, insert.*) with the integrator, the time step, the threads, the trajectory and
// the switches; their ranges are dem::check_run_settings's to check.
dem::RunSettings run_settings(const po::variables_map& vm, const dem::RunSettings& bound,
                              bool inserting, std::uint64_t seed) {
  dem::RunSettings s = bound;
  s.integrator = dem::parse_integrator(vm["integrator"].as<std::string>());
  s.young_scale = vm["young-scale"].as<double>();
  if (!s.until_rest && !vm.count("t-end")) {
    throw InputError("--t-end: missing (accepted: --t-end T or --until-rest)");
  }
  if (vm.count("dt")) s.dt = vm["dt"].as<double>();
  s.unsafe_dt = vm["unsafe-dt"].as<bool>();
  s.threads = app::apply_thread_team(vm).size;
  if (vm.count("trajectory")) {
    s.trajectory = vm["trajectory"].as<std::string>();
    s.trajectory_every = vm["every"].as<std::uint64_t>();
  }
  s.lid.enabled = vm["lid"].as<bool>() || vm["lid.enabled"].as<bool>();
  s.insertion.enabled = inserting;
  s.insertion.seed = seed;
  return s;
}

// --unsafe-dt accepts a step above the stable bound; it still says so.
void warn_unsafe_dt(const bed::Bed& bed, const dem::Scene& scene, const dem::RunSettings& s) {
  if (!s.unsafe_dt || !(s.dt > 0)) return;
  scene.validate();
  const auto bound = dem::time_step_bound(bed, scene, s.young_scale);
  if (s.dt > bound.stable) {
    std::cerr << fmt::format("deposit: warning: --dt {:g} s is above the stable bound {:g} s "
                             "(--unsafe-dt)\n",
                             s.dt, bound.stable);
  }
}

// --core-margin, by default two mean diameters of the bed.
double core_margin(const po::variables_map& vm, const bed::Bed& bed) {
  double mean_diameter = 0;
  for (const double r : bed.radius) mean_diameter += 2 * r;
  mean_diameter /= static_cast<double>(std::max<std::size_t>(1, bed.n()));
  const double margin = vm.count("core-margin") ? vm["core-margin"].as<double>() : 2 * mean_diameter;
  if (!(margin >= 0) || !std::isfinite(margin)) {
    throw InputError(fmt::format("--core-margin: {:f} (accepted: M >= 0 m)", margin));
  }
  return margin;
}

// Removes the particles that left the box; returns how many. Particles leave the box only when
// a run goes wrong (a step beyond the stable bound, a bed that does not fit its box): such a bed
// is not a result, so more than --allow-lost is a NumericalError.
std::size_t remove_lost(const po::variables_map& vm, bed::Bed& bed) {
  const std::size_t removed = dem::remove_lost_particles(bed);
  if (removed > vm["allow-lost"].as<std::size_t>()) {
    throw NumericalError(fmt::format(
        "{} of {} particles left the box during the run (accepted: at most --allow-lost {}); the "
        "time step may be beyond the stable bound (--unsafe-dt?) or the bed may not fit its box",
        removed, bed.n() + removed, vm["allow-lost"].as<std::size_t>()));
  }
  return removed;
}

// The box's top at the highest particle top (--crop-top).
void crop_top(bed::Bed& bed) {
  if (bed.n() == 0) return;
  double top = bed.domain.lower[2];
  for (std::size_t i = 0; i < bed.n(); ++i) top = std::max(top, bed.z[i] + bed.radius[i]);
  bed.domain.upper[2] = top;
}

// What made the bed: the program, its command line and seed, the scene, and the contact law
// keff's Hertz correction reads.
void record_provenance(bed::Bed& bed, const po::variables_map& vm, int argc, char** argv,
                       std::uint64_t seed, const dem::Scene& scene, double young_scale) {
  bed.provenance.created_by = app::version_string("deposit");
  bed.provenance.command_line = app::command_line(argc, argv);
  bed.provenance.rng_seed = seed;
  bed.provenance.stage = "deposit";
  bed.provenance.scene = app::scene_text(vm);
  bed.provenance.contact = dem::contact_provenance(scene, young_scale);
}

// The core density, or why there is none: a bed less than two margins thick (a monolayer) has
// no core away from the floor and the surface, and its density is a layer's (bedstat --layer).
std::string core_text(const dem::CoreDensity& core, double margin) {
  if (std::isnan(core.density)) {
    return fmt::format("no core (the bed is thinner than 2 x --core-margin {:g} m from floor and "
                       "surface; see bedstat --layer for a layer's density)",
                       margin);
  }
  return fmt::format("core density {:g}", core.density);
}

// What a run reports, on stdout as JSON (--json) or one line.
struct Report {
  const bed::Bed& bed;
  const dem::Scene& scene;
  const dem::RunSettings& settings;
  const dem::RunSummary& run;
  std::size_t removed;
  dem::CoreDensity core;
  double margin;
  std::string integrator;
  std::string out;
};

std::string json_text(const Report& p) {
  bed::JsonWriter j;
  j.begin_object().value("n", static_cast<std::uint64_t>(p.bed.n()));
  dem::write_run_json(j, p.run);
  app::write_contact_laws(j, p.settings.young_scale, p.scene);
  j.value("integrator", p.integrator)
      .value("fines_scaling", dem::fines_scaling_name(p.scene.fines.scaling))
      .value("fines_radius", p.scene.fines.radius)
      .value("stiffness", p.scene.stiffness)
      .value("lost", static_cast<std::uint64_t>(p.removed))
      .value("core_density", p.core.density)
      .value("core_margin", p.margin)
      .value("domain_top", p.bed.domain.upper[2])
      .value("out", p.out);
  bed::write_units(j, app::deposit_units());
  j.end_object();
  return j.str() + '\n';
}

std::string summary_text(const Report& p) {
  const dem::RunSummary& r = p.run;
  std::ostringstream out;
  out << "deposit: " << p.bed.n() << " particles (" << p.removed << " lost), " << r.steps
            << " steps of " << r.dt << " s to t = " << r.sim_time << " s, " << r.wall_time
            << " s wall, " << r.particle_steps_per_s << " particle-steps/s, max overlap "
            << r.max_overlap << " r" << (r.at_rest ? ", at rest" : "") << ", "
            << core_text(p.core, p.margin);
  if (r.lid_used) {
    out << ", lid " << r.lid.start_z << " -> " << r.lid.stop_z << " m (" << r.lid.stopped_by
              << ", max force " << r.lid.max_force << " N)";
  }
  out << " -> " << p.out << '\n';
  return out.str();
}

int run(int argc, char** argv) {
  po::options_description desc("deposit options (SI units)");
  app::DepositOptions bound;  // what the options of a plain type fill (app::add_deposit_options)
  app::add_deposit_options(desc, bound);
  po::variables_map vm;
  if (!app::parse_options("deposit", kUsage, desc, {}, argc, argv, vm)) return 0;
  if (app::spread_requested(vm))
    return app::spread_command(vm, bound, argc, argv);  // deposit_spread.cpp

  const std::string out = app::required<std::string>(vm, "out");
  const auto seed = app::required<std::uint64_t>(vm, "seed");
  check_files(vm, out);
  auto [bed, inserting] = particles(vm, desc, argc, argv, seed);
  set_periodic(vm, bed.domain);
  const dem::Scene scene = app::deposit_scene(vm, bound.scene);
  if (vm.count("export-deck")) app::check_run_deck(scene, vm["export-deck"].as<std::string>());
  dem::RunSettings s = run_settings(vm, bound.run, inserting, seed);
  warn_unsafe_dt(bed, scene, s);
  const double margin = core_margin(vm, bed);
  const auto table = app::attach_thermo(vm, false, s.thermo, s.thermo_every);
  app::ProgressBar bar("deposit", app::progress_interval(vm));
  s.progress = [&bar](const dem::Progress& p) {
    char detail[64];
    std::snprintf(detail, sizeof detail, "t = %.3e s  KE = %.2e J", p.time, p.kinetic_energy);
    bar.draw(p.t_end > 0 ? p.time / p.t_end : 1.0, detail);
  };

  // The trajectory, out.h5 and the deck replace the old ones together or not at all.
  bed::CommitTogether together;
  const dem::RunSummary r = dem::run_deposition(bed, scene, s);
  bar.finish();
  const std::size_t removed = remove_lost(vm, bed);
  if (vm["crop-top"].as<bool>()) crop_top(bed);
  const dem::CoreDensity core = dem::core_density(bed, margin);
  record_provenance(bed, vm, argc, argv, seed, scene, s.young_scale);
  bed::write_bed_h5(bed, out);
  if (vm.count("export-deck"))
    app::export_run_deck(bed, scene, s.young_scale, r.dt, vm["export-deck"].as<std::string>(), out);
  together.commit();
  const std::string integrator = vm["integrator"].as<std::string>();
  const Report report{bed, scene, s, r, removed, core, margin, integrator, out};
  const std::string summary = vm.count("json") ? json_text(report) : summary_text(report);
  std::cout << summary;
  if (table) table->summary(summary);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return app::run_app("deposit", argc, argv, [&] { return run(argc, argv); });
}
