// sinter: the DE–FD laser thermal solver (docs/sinter.md) on a bed: one laser track or a scan
// path (a hatch or a CSV of segments), the melt pool on the plane x = Lx/2 and per track, fusion
// of what melted into a raised solid top (--fuse), an HDF5 + XDMF time series, and the energy
// balance of the run.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <cstdio>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "common/app_main.hpp"
#include "common/material_options.hpp"
#include "common/options.hpp"
#include "common/progress.hpp"
#include "common/threads.hpp"
#include "powderbed/bed/json_units.hpp"
#include "sinter_options.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/temp_files.hpp"
#include "powderbed/thermal/explain.hpp"
#include "powderbed/thermal/fusion.hpp"
#include "powderbed/thermal/result_json.hpp"
#include "powderbed/thermal/run_output.hpp"
#include "powderbed/thermal/solver.hpp"

namespace {

using namespace powderbed;
namespace po = app::po;
namespace th = thermal;

const char* const kUsage =
    "sinter --config SCENE.ini --bed BED.h5 --out RUN.h5 [--power P] [--speed V] [--spot W] "
    "[--grid-spacing DX] [--dt DT] [--unsafe-dt] [--integrator explicit|implicit] "
    "[--scan-path PATH.csv | --scan.hatch H [--scan.tracks N] [--scan.direction one-way|alternating] "
    "[--scan.rotation DEG --scan.layer K] [--scan.region X0,X1,Y0,Y1]] [--scan.jump-speed V] "
    "[--fuse [--fused-bed BED.h5]] [--json] [--explain]";

// The units of sinter's --json numbers, the run's summary and --explain's (common/json_units).
constexpr bed::UnitEntry kUnits[] = {
    // --explain
    {"laser_flux", "W/m^2"}, {"conduction_scale", "1"}, {"conduction_ratio", "1"},
    {"substrate_ratio", "1"}, {"convection_ratio", "1"}, {"radiation_ratio", "1"},
    {"biot_surface", "1"}, {"biot_laser", "1"}, {"optical_thickness", "1"}, {"dwell_time", "s"},
    {"heating_time", "s"}, {"absorptance", "1"}, {"wetting_time", "s"},
    {"normalised_enthalpy", "1"}, {"keyhole_threshold", "1"}, {"evaporation_ratio", "1"},
    {"cooling_time", "s"}, {"conduction_cooling", "1"}, {"substrate_cooling", "1"},
    {"convection_cooling", "1"}, {"radiation_cooling", "1"},
    // the melt pool and its tracks
    {"height", "m"}, {"width", "m"}, {"depth", "m"}, {"sections", "1"}, {"width_mean", "m"},
    {"width_sd", "m"}, {"depth_mean", "m"}, {"depth_sd", "m"}, {"length", "m"},
    {"peak_temperature", "K"}, {"start_temperature", "K"}, {"stored_energy", "J"},
    {"t_start", "s"},
    // the run
    {"max_temperature", "K"}, {"max_temperature_particles", "K"},
    {"max_temperature_substrate", "K"}, {"evaporated_mass", "kg"},
    {"evaporated_mass_particles", "kg"}, {"peak_recoil_pressure", "Pa"},
    {"depression_temperature", "K"}, {"depression_depth", "m"}, {"particles", "1"},
    {"particles_molten", "1"}, {"particles_vaporised", "1"}, {"energy_balance_error", "1"},
    {"substrate_wetted", "1"}, {"substrate_arrested", "1"}, {"particles_merged", "1"},
    {"particles_coalesced", "1"}, {"bridges", "1"}, {"steps", "1"},
    {"particle_steps", "1"}, {"dt", "s"}, {"dt_particle", "s"}, {"dt_stable_grid", "s"},
    {"dt_stable_particle", "s"}, {"t_end", "s"}, {"implicit_iterations", "1"}, {"nodes", "1"},
    {"extinction", "1/m"}, {"porosity", "1"}, {"layer_height", "m"}, {"wall_time", "s"},
    // ray_trace: fractions of the beam (particles: also the run's particle count, 1)
    {"traces", "1"}, {"bed_absorptance", "1"}, {"substrate", "1"}, {"escaped", "1"},
    {"outside", "1"}, {"dropped", "1"}, {"hits_per_ray", "1"}, {"depression", "1"},
    // fusion
    {"threshold", "K"}, {"fused", "1"}, {"vaporised", "1"}, {"balled", "1"}, {"powder_left", "1"},
    {"powder_mass_before", "kg"}, {"powder_mass_after", "kg"}, {"solid_mass_before", "kg"},
    {"solid_mass_after", "kg"}, {"vaporised_mass", "kg"}, {"mass_error", "1"},
    {"bead_height", "m"}, {"bead_sections", "1"}, {"bead_height_mean", "m"},
    {"bead_height_sd", "m"}, {"top_min", "m"}, {"top_max", "m"},
    // energy: the ledger
    {"laser_particles", "J"}, {"laser_substrate", "J"}, {"convection", "J"}, {"radiation", "J"},
    {"evaporation", "J"}, {"boundary", "J"}, {"internal_particles", "J"},
    {"internal_substrate", "J"},
};

// --explain --json: the scale analysis's numbers (SI; ratios to the absorbed laser flux) and the
// printed report as "text".
std::string explain_json(const th::ExplainReport& r) {
  bed::JsonWriter j;
  j.begin_object()
      .value("laser_flux", r.laser_flux)
      .value("conduction_scale", r.conduction_scale)
      .value("conduction_ratio", r.conduction_ratio)
      .value("substrate_ratio", r.substrate_ratio)
      .value("convection_ratio", r.convection_ratio)
      .value("radiation_ratio", r.radiation_ratio)
      .value("biot_surface", r.biot_surface)
      .value("biot_laser", r.biot_laser)
      .value("optical_thickness", r.optical_thickness)
      .value("dwell_time", r.dwell_time)
      .value("heating_time", r.heating_time)
      .value("absorptance", r.absorptance)
      .value("wetting_time", r.wetting_time)
      .value("normalised_enthalpy", r.normalised_enthalpy)
      .value("keyhole_threshold", r.keyhole_threshold)
      .value("evaporation_ratio", r.evaporation_ratio)
      .value("cooling_time", r.cooling_time)
      .value("conduction_cooling", r.conduction_cooling)
      .value("substrate_cooling", r.substrate_cooling)
      .value("convection_cooling", r.convection_cooling)
      .value("radiation_cooling", r.radiation_cooling)
      .value("text", r.text);
  bed::write_units(j, kUnits);
  j.end_object();
  return j.str() + '\n';
}

// --json "fusion": what fusion moved, in kg, and the solid's top above the plate, m.
void fusion_json(bed::JsonWriter& j, const th::Fusion& f, const th::SubstrateGeometry& g) {
  const auto [low, high] = std::minmax_element(f.top.begin(), f.top.end());
  j.begin_object("fusion")
      .value("threshold", f.threshold)
      .value("fused", static_cast<std::uint64_t>(f.fused))
      .value("vaporised", static_cast<std::uint64_t>(f.vaporised))
      .value("balled", static_cast<std::uint64_t>(f.balled))
      .value("powder_left", static_cast<std::uint64_t>(f.powder.n()))
      .value("powder_mass_before", f.powder_mass_before)
      .value("powder_mass_after", f.powder_mass_after)
      .value("solid_mass_before", f.solid_mass_before)
      .value("solid_mass_after", f.solid_mass_after)
      .value("vaporised_mass", f.vaporised_mass)
      .value("mass_error", f.mass_error())
      .value("bead_height", f.bead.height)
      .value("bead_sections", static_cast<std::uint64_t>(f.bead.sections))
      .value("bead_height_mean", f.bead.height_mean)
      .value("bead_height_sd", f.bead.height_sd)
      .value("top_min", *low - g.z_top)
      .value("top_max", *high - g.z_top)
      .end_object();
}

// The text report's line per track (a scan path only: the single track's line is the run's).
void print_tracks(const std::vector<th::TrackStats>& tracks) {
  for (std::size_t m = 0; m < tracks.size(); ++m) {
    const auto& t = tracks[m];
    std::printf("sinter: track %zu: width %.1f um, depth %.1f um, height %.1f um, length %.1f um; "
                "T_peak %.0f K; %zu particles molten; starts at %.0f K; %.3g J stored at its end\n",
                m + 1, t.pool.width * 1e6, t.pool.depth * 1e6, t.pool.height * 1e6, t.length * 1e6,
                t.peak_temperature, t.particles_molten, t.start_temperature, t.stored_energy);
  }
}

// What a run made, for the report: the result, the fusion (--fuse), the wall time in seconds.
struct RunReport {
  const bed::Bed& bed;
  const th::Sinter& sinter;
  const th::SinterResult& result;
  const std::optional<th::Fusion>& fused;
  double wall;
  std::string out;
};

// --json: the run's result (thermal's result_json.hpp) and what the program adds: the bed's
// particles, the options, the fusion, the stable steps, the grid and the surface (SI).
std::string result_json(const po::variables_map& vm, const RunReport& run) {
  const th::Sinter& sinter = run.sinter;
  bed::JsonWriter j;
  j.begin_object();
  th::write_melt_pool_json(j, run.result);
  j.value("particles", static_cast<std::uint64_t>(run.bed.n()))
      .value("laser_absorption", vm["laser.absorption"].as<std::string>());
  th::write_run_json(j, run.result);
  if (run.fused) fusion_json(j, *run.fused, sinter.grid());
  j.value("dt_stable_grid", sinter.stable_steps().grid)
      .value("dt_stable_particle", sinter.stable_steps().particle)
      .value("integrator", vm["integrator"].as<std::string>())
      .value("nodes", static_cast<std::uint64_t>(sinter.grid().size()))
      .value("extinction", sinter.extinction())
      .value("porosity", sinter.surface().porosity)
      .value("layer_height", sinter.surface().layer_height)
      .value("wall_time", run.wall)
      .value("out", run.out);
  bed::write_units(j, kUnits);
  j.end_object();
  return j.str() + '\n';
}

// The text report: the run's line, a line per track of a scan path, the fusion's line.
void print_result(const th::SinterScene& scene, const RunReport& run) {
  const th::SinterResult& r = run.result;
  std::printf("sinter: melt pool height %.1f um, width %.1f um, depth %.1f um; peak T %.0f K "
              "(particles), %.0f K (substrate); %zu of %zu particles molten, %zu vaporised; "
              "evaporated %.3g kg; absorptance %.3f; energy balance "
              "%.1e; %llu steps of %.3g s, %.1f s wall -> %s\n",
              r.melt_pool.height * 1e6, r.melt_pool.width * 1e6, r.melt_pool.depth * 1e6,
              r.peaks.particles, r.peaks.substrate, r.particles_molten, run.bed.n(),
              r.particles_vaporised, r.evaporated_mass,
              r.absorptance, r.energy.relative_error(), static_cast<unsigned long long>(r.steps),
              r.dt_grid, run.wall, run.out.c_str());
  if (r.along.sections > 0)
    std::printf("sinter: along the track's steady part (%zu sections): width %.1f +- %.1f um, "
                "depth %.1f +- %.1f um\n",
                r.along.sections, r.along.width_mean * 1e6, r.along.width_sd * 1e6,
                r.along.depth_mean * 1e6, r.along.depth_sd * 1e6);
  if (!scene.scan_path.empty()) print_tracks(r.tracks);
  if (run.fused) {
    const th::Fusion& fused = *run.fused;
    const double z_top = run.sinter.grid().z_top;
    const auto [low, high] = std::minmax_element(fused.top.begin(), fused.top.end());
    std::printf("sinter: fused %zu particles (%zu vaporised, %zu left in the bed, %zu of them "
                "balls that melted on solid that did not); solid top %.1f to %.1f um above the "
                "plate; bead %.1f um high on x = Lx/2, %.1f +- %.1f um over %zu sections; mass "
                "conserved to %.1e\n",
                fused.fused, fused.vaporised, fused.powder.n(), fused.balled, (*low - z_top) * 1e6,
                (*high - z_top) * 1e6, fused.bead.height * 1e6, fused.bead.height_mean * 1e6,
                fused.bead.height_sd * 1e6, fused.bead.sections, fused.mass_error());
  }
}

// The files a run reads and writes, checked before any work: --out and --fused-bed end in .h5
// and can be written, the bed and the scan path can be read; --fuse's options agree.
void check_files(const po::variables_map& vm, const std::string& bed_path,
                 const std::string& out) {
  std::vector<app::PathArg> outputs;
  if (!out.empty()) {
    app::check_extension({"--out", out}, {".h5"});
    outputs.push_back({"--out", out});
  }
  const bool fuse = vm["fuse"].as<bool>();
  const double melt_fraction = vm["fuse.melt-fraction"].as<double>();
  if (!fuse && !vm["fuse.melt-fraction"].defaulted())
    throw InputError("--fuse.melt-fraction: given without --fuse (accepted: --fuse --fuse.melt-fraction F)");
  const double level = vm["fuse.level"].as<double>();
  if (!fuse && !vm["fuse.level"].defaulted())
    throw InputError("--fuse.level: given without --fuse (accepted: --fuse --fuse.level L)");
  if (fuse && !(level >= 0 && std::isfinite(level)))
    throw InputError(fmt::format("--fuse.level: {:g} (accepted: a length >= 0 m)", level));
  if (fuse && !(melt_fraction > 0 && melt_fraction <= 1))
    throw InputError(fmt::format("--fuse.melt-fraction: {:f} (accepted: 0 < f <= 1; 0.5 fuses what "
                                 "reached T_m, 1 what was wholly liquid)",
                                 melt_fraction));
  if (vm.count("fused-bed")) {
    if (!fuse) throw InputError("--fused-bed: given without --fuse (accepted: --fuse --fused-bed BED.h5)");
    const std::string fused_bed = vm["fused-bed"].as<std::string>();
    app::check_extension({"--fused-bed", fused_bed}, {".h5"});
    outputs.push_back({"--fused-bed", fused_bed});
  }
  std::vector<app::PathArg> inputs{{"--bed", bed_path}};
  if (vm.count("scan-path")) inputs.push_back({"--scan-path", vm["scan-path"].as<std::string>()});
  app::check_paths(inputs, outputs);
}

// The scan, snapshots into `writer` (--snapshots of them besides t = 0), progress on stderr;
// `wall` gets its wall time in seconds.
th::SinterResult scan(const po::variables_map& vm, th::Sinter& sinter, th::RunWriter& writer,
                      double& wall) {
  const auto steps_total =
      static_cast<std::uint64_t>(std::ceil(sinter.t_end() / sinter.dt() * (1 - 1e-12)));
  const std::size_t snapshots = vm["snapshots"].as<std::size_t>();
  const std::uint64_t every = snapshots > 0 ? std::max<std::uint64_t>(1, steps_total / snapshots) : 0;
  const auto start = std::chrono::steady_clock::now();
  app::ProgressBar bar("sinter", app::progress_interval(vm));
  const auto progress = [&bar](const th::SinterProgress& p) {
    char detail[96];
    std::snprintf(detail, sizeof detail, "t = %.3e s  peak T: particles %.0f K, substrate %.0f K",
                  p.time, p.peaks.particles, p.peaks.substrate);
    bar.draw(p.time / p.t_end, detail);
  };
  const th::SinterResult r = sinter.run(
      [&](const th::Sinter& s) { writer.snapshot(s); }, every, progress);
  bar.finish();
  wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// The run file's /summary: the headline numbers, SI.
std::vector<std::pair<std::string, double>> summary_of(const th::SinterResult& r, double wall) {
  return {{"melt_pool_height", r.melt_pool.height}, {"melt_pool_width", r.melt_pool.width},
          {"melt_pool_depth", r.melt_pool.depth}, {"max_temperature", r.max_temperature},
          {"max_temperature_particles", r.peaks.particles},
          {"max_temperature_substrate", r.peaks.substrate},
          {"evaporated_mass", r.evaporated_mass},
          {"particles_molten", static_cast<double>(r.particles_molten)},
          {"particles_vaporised", static_cast<double>(r.particles_vaporised)},
          {"energy_balance_error", r.energy.relative_error()},
          {"laser_absorbed", r.energy.absorbed()}, {"steps", static_cast<double>(r.steps)},
          {"dt", r.dt_grid}, {"wall_time", wall}};
}

// --fuse: what melted fused into the solid's top, written to the run file (and the powder left
// to --fused-bed); nothing without --fuse.
std::optional<th::Fusion> fuse_if_asked(const po::variables_map& vm, const bed::Bed& bed,
                                        const th::Sinter& sinter, th::RunWriter& writer) {
  if (!vm["fuse"].as<bool>()) return std::nullopt;
  th::Fusion fused = th::fuse(bed, sinter, vm["fuse.melt-fraction"].as<double>(), 0.0,
                              vm["fuse.level"].as<double>());
  writer.fusion(fused);
  if (vm.count("fused-bed")) {
    fused.powder.provenance.stage = "sinter --fuse";
    bed::write_bed_h5(fused.powder, vm["fused-bed"].as<std::string>());
  }
  return fused;
}

// Particles that touch nothing exchange heat with nothing but the beam, and under it run to
// their boiling point: in a spread bed they are powder still in the air (docs/deposit-spread.md
// "Settling to rest"); in a packgen 0-contact bed, as meant. Said after the run (or --explain's
// report), so that a run that fails keeps its one line.
void warn_isolated(const th::Sinter& sinter, std::size_t n) {
  const std::size_t isolated = sinter.network().isolated.size();
  if (isolated == 0) return;
  std::cerr << fmt::format("sinter: warning: {} of {} particles touch nothing (no particle, not "
                           "the plate): the beam heats them on their own (a spread still "
                           "settling? deposit's recoater.until-rest)\n",
                           isolated, n);
}

int run(int argc, char** argv) {
  po::options_description desc("sinter options (SI units)");
  th::SinterScene bound;  // what the options of a plain type fill (app::add_sinter_options)
  app::add_sinter_options(desc, bound);
  po::variables_map vm;
  if (!app::parse_options("sinter", kUsage, desc, {}, argc, argv, vm)) return 0;
  const std::string bed_path = app::required<std::string>(vm, "bed");
  const bool explain_only = vm["explain"].as<bool>();
  const std::string out = explain_only && !vm.count("out") ? "" : app::required<std::string>(vm, "out");
  app::apply_thread_team(vm);
  check_files(vm, bed_path, out);

  bed::Bed bed = bed::read_bed_any(bed_path);
  const th::SinterScene scene = app::sinter_scene(vm, bound, bed);
  const th::MaterialTable table = th::read_material_table(scene.material_table);
  th::Sinter sinter(bed, scene, table);
  if (scene.unsafe_dt && scene.dt > sinter.stable_steps().grid &&
      scene.integrator == th::Integrator::explicit_euler) {
    std::cerr << fmt::format("sinter: warning: --dt {:g} s is above the stable bound {:g} s "
                             "(--unsafe-dt)\n",
                             scene.dt, sinter.stable_steps().grid);
  }
  if (explain_only) {
    const th::ExplainReport report = th::explain(bed, scene, sinter);
    std::cout << (vm.count("json") ? explain_json(report) : report.text);
    warn_isolated(sinter, bed.n());
    return 0;
  }

  bed.provenance.created_by = app::version_string("sinter");
  bed.provenance.command_line = app::command_line(argc, argv);
  bed.provenance.stage = "sinter";
  bed.provenance.scene = app::scene_text(vm);
  // The run file and --fused-bed replace the old ones together or not at all.
  bed::CommitTogether together;
  th::RunWriter writer(out, bed, sinter, vm["full-fields"].as<bool>());
  double wall = 0;
  const th::SinterResult r = scan(vm, sinter, writer, wall);
  const std::optional<th::Fusion> fused = fuse_if_asked(vm, bed, sinter, writer);
  writer.finish(sinter, r, summary_of(r, wall));
  together.commit();
  warn_isolated(sinter, bed.n());
  const RunReport report{bed, sinter, r, fused, wall, out};
  if (vm.count("json")) std::cout << result_json(vm, report);
  else print_result(scene, report);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return app::run_app("sinter", argc, argv, [&] { return run(argc, argv); });
}
