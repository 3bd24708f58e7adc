// keff: the effective thermal conductivity of a bed between two isothermal walls (SPEC.md §6):
// the steady state of the particles' heat-path network (contact and gas conduction, grey-body
// radiation with Monte-Carlo view factors).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <string>

#include "common/app_main.hpp"
#include "common/options.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/thermal/keff_solve.hpp"

namespace {

using namespace powderbed;
namespace po = app::po;
namespace th = thermal;

const char* const kUsage =
    "keff --config SCENE.ini --bed BED.h5 [--axis x|y|z] [--t-hot K --t-cold K] [--rays N] "
    "[--json] [--out RUN.h5]";

void add_options(po::options_description& desc) {
  app::add_common_options(desc);
  const th::KeffScene d;
  desc.add_options()
      ("bed", po::value<std::string>(), "the bed (HDF5, CSV, LAMMPS dump)")
      ("out", po::value<std::string>(), "the bed with the particle temperatures (HDF5)")
      ("axis", po::value<std::string>()->default_value("z"),
       "axis of the heat flow: hot wall at its upper face, cold wall at its lower face")
      ("t-hot", po::value<double>()->default_value(d.hot_temperature), "T_hot (K)")
      ("t-cold", po::value<double>()->default_value(d.cold_temperature), "T_cold (K)")
      ("solid.conductivity", po::value<double>()->default_value(d.solid_conductivity), "k_s (W/mK)")
      ("gas.model", po::value<std::string>()->default_value("constant"),
       "constant (gas.conductivity) or air (the [KE] polynomial at the mean wall temperature)")
      ("gas.conductivity", po::value<double>()->default_value(d.gas_conductivity), "k_g (W/mK)")
      ("gas.lens", po::value<double>()->default_value(d.lens.lens),
       "gas lens thickness over the particle radius (Rong-Horio)")
      ("gas.min-gap", po::value<double>()->default_value(d.lens.min_gap), "l_min (m)")
      ("gas.lens-region", po::value<std::string>()->default_value("both-lenses"),
       "outer edge of the gas path: both-lenses (where the two lenses intersect) or larger-lens "
       "(where the larger particle's lens meets the smaller particle, as MFiX computes it)")
      ("contact.calibration", po::value<double>()->default_value(d.calibration),
       "A_c: scales the contact radius")
      ("contact.hertz-correction", po::value<bool>()->default_value(d.contact.hertz_correction),
       "contact radius from the equivalent Hertz overlap of a softened bed (else geometric)")
      ("contact.young-scale", po::value<double>()->default_value(d.contact.young_scale),
       "S of the DEM run that made the bed (E used = E / S)")
      ("effects.contact", po::value<bool>()->default_value(true), "contact conduction on/off")
      ("rays", po::value<std::size_t>()->default_value(d.rays),
       "Monte-Carlo view-factor rays per particle (radiation)")
      ("radiation.seed", po::value<std::uint64_t>()->default_value(d.seed),
       "seed of the view-factor rays (each particle its own stream: any thread count agrees)")
      ("radiation.emissivity", po::value<double>()->default_value(d.emissivity),
       "grey emissivity of the particles")
      ("radiation.wall-emissivity", po::value<double>()->default_value(d.wall_emissivity),
       "grey emissivity of the hot and cold walls")
      ("effects.gas", po::value<bool>()->default_value(true), "gas-lens conduction on/off")
      ("effects.radiation", po::value<bool>()->default_value(d.radiation_path),
       "grey-body radiation on/off (needs absolute wall temperatures)");
}

int axis_index(const std::string& name) {
  if (name == "x") return 0;
  if (name == "y") return 1;
  if (name == "z") return 2;
  throw InputError("--axis: '" + name + "' (accepted: x, y, z)");
}

th::KeffScene make_scene(const po::variables_map& vm) {
  th::KeffScene s;
  s.axis = axis_index(vm["axis"].as<std::string>());
  s.hot_temperature = vm["t-hot"].as<double>();
  s.cold_temperature = vm["t-cold"].as<double>();
  s.solid_conductivity = vm["solid.conductivity"].as<double>();
  const std::string model = vm["gas.model"].as<std::string>();
  if (model != "constant" && model != "air")
    throw InputError("gas.model: '" + model + "' (accepted: constant, air)");
  s.gas_model = model == "air" ? th::GasModel::air : th::GasModel::constant;
  s.gas_conductivity = vm["gas.conductivity"].as<double>();
  s.lens.lens = vm["gas.lens"].as<double>();
  s.lens.min_gap = vm["gas.min-gap"].as<double>();
  const std::string region = vm["gas.lens-region"].as<std::string>();
  if (region != "both-lenses" && region != "larger-lens")
    throw InputError("gas.lens-region: '" + region + "' (accepted: both-lenses, larger-lens)");
  s.lens.region =
      region == "larger-lens" ? th::LensRegion::larger_lens : th::LensRegion::both_lenses;
  s.calibration = vm["contact.calibration"].as<double>();
  s.contact.hertz_correction = vm["contact.hertz-correction"].as<bool>();
  s.contact.young_scale = vm["contact.young-scale"].as<double>();
  s.contact_path = vm["effects.contact"].as<bool>();
  s.gas_path = vm["effects.gas"].as<bool>();
  s.radiation_path = vm["effects.radiation"].as<bool>();
  s.rays = vm["rays"].as<std::size_t>();
  s.seed = vm["radiation.seed"].as<std::uint64_t>();
  s.emissivity = vm["radiation.emissivity"].as<double>();
  s.wall_emissivity = vm["radiation.wall-emissivity"].as<double>();
  s.validate();
  return s;
}

int run(int argc, char** argv) {
  po::options_description desc("keff options (SI units)");
  add_options(desc);
  po::variables_map vm;
  if (!app::parse_options("keff", kUsage, desc, {}, argc, argv, vm)) return 0;
  if (!vm.count("bed")) throw InputError("--bed: missing (required)");
  const th::KeffScene scene = make_scene(vm);
  bed::Bed bed = bed::read_bed_any(vm["bed"].as<std::string>());

  const auto start = std::chrono::steady_clock::now();
  const th::KeffResult r = th::solve_keff(bed, scene);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (vm.count("out")) {
    bed.temperature = r.temperature;
    bed.provenance.created_by = app::version_string("keff");
    bed.provenance.command_line = app::command_line(argc, argv);
    bed.provenance.stage = "keff";
    bed.provenance.scene = app::scene_text(vm);
    bed::write_bed_h5(bed, vm["out"].as<std::string>());
  }
  if (vm.count("json")) {
    bed::JsonWriter j;
    j.begin_object()
        .value("k_eff", r.k_eff)
        .value("heat_flow_hot", r.heat_flow_hot)
        .value("heat_flow_cold", r.heat_flow_cold)
        .begin_object("share")
        .value("contact", r.share_contact)
        .value("gas", r.share_gas)
        .value("radiation", r.share_radiation)
        .end_object()
        .value("rattlers", static_cast<std::uint64_t>(r.rattlers.size()))
        .value("newton_iterations", static_cast<std::uint64_t>(r.newton_iterations))
        .value("newton_residual", r.residual)
        .value("solver_iterations", static_cast<std::uint64_t>(r.solver_iterations))
        .value("particles", static_cast<std::uint64_t>(bed.n()))
        .value("contact_links", static_cast<std::uint64_t>(r.contact_links))
        .value("gas_links", static_cast<std::uint64_t>(r.gas_links))
        .value("radiation_links", static_cast<std::uint64_t>(r.radiation_links))
        .value("rays", static_cast<std::uint64_t>(scene.radiation_path ? scene.rays : 0))
        .value("lost_rays", static_cast<std::uint64_t>(r.lost_rays))
        .value("gas_conductivity", scene.gas_path ? scene.gas_conductivity_used() : 0.0)
        .value("wall_time", wall)
        .end_object();
    std::cout << j.str() << '\n';
  } else {
    std::printf("keff: k_eff = %.6g W/mK; wall flows %.6g / %.6g W (hot / cold); contact %.1f %%, "
                "gas %.1f %%, radiation %.1f %%; %zu rattlers of %zu particles; %zu Newton "
                "steps; %.3g s\n",
                r.k_eff, r.heat_flow_hot, r.heat_flow_cold, 100 * r.share_contact,
                100 * r.share_gas, 100 * r.share_radiation, r.rattlers.size(), bed.n(),
                r.newton_iterations, wall);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return app::run_app("keff", argc, argv, [&] { return run(argc, argv); });
}
