// packgen: geometric packing (Luberto & de Payrebrune, extended to 3D) -> one bed file, with a short summary or --json.
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/app_main.hpp"
#include "powderbed/bed/contact_report.hpp"
#include "powderbed/bed/json_units.hpp"
#include "common/options.hpp"
#include "common/progress.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/stats.hpp"
#include "powderbed/packgen/pack.hpp"
#include "powderbed/packgen/summary_json.hpp"

namespace {

using namespace powderbed;
namespace po = app::po;

const char* const kUsage =
    "packgen --dim 2|3 --domain LX,LY[,LZ] --psd SPEC --approach 0|1|2|3 --seed S --out BED.h5 "
    "[options]";

// packgen's options with their help: one entry per option, so the list is as long as it is.
// Those of a plain type are bound to `o`'s fields (defaults: its values).
void add_options(po::options_description& desc, packgen::PackOptions& o) {
  app::add_common_options(desc);
  app::add_progress_option(desc);
  const std::string directions_help = fmt::format(
      "K: directions per 1-contact try, circle angles per 3D 2-contact try (default {} in 2D: the "
      "[LP] 1-contact density, docs/results/packgen-2d-study.md; {} in 3D)",
      packgen::kDirections2D, packgen::kDirections3D);
  desc.add_options()
      ("dim", po::value<std::string>()->required(), "2 (disks) or 3 (spheres); must match --domain")
      ("domain", po::value<std::string>()->required(), "LX,LY[,LZ] (m): the box [0, L]")
      ("psd", po::value<std::string>()->required(), "size distribution (PSD string syntax)")
      ("size-sampling", po::value<std::string>()->default_value("iid"),
       "iid (independent draws, [LP]) or stratified (the k-th size from the golden-ratio "
       "sequence u_k = frac(u_0 + 0.618.. k) through the PSD's inverse CDF: every prefix matches "
       "the PSD to O(log N / N), so a bed of a few hundred particles honours its histogram; "
       "variance reduction, same marginal law)")
      ("approach", po::value<int>()->default_value(1),
       "contacts per new particle: 0 random, 1, 2, 3 (3D only); walls count as partners")
      ("site-order", po::value<std::string>()->default_value("lowest"),
       "3D approach 3: lowest (fill the lowest free 3-contact site first, growing from the "
       "floor: densest, O(N)) or random (a random particle and two random partners, [LP] tries)")
      ("floor-seed", po::value<double>(&o.floor_seed)->default_value(o.floor_seed),
       "site order lowest: fraction of the floor first covered by particles dropped at random "
       "onto it (0 <= F < 1)")
      ("phases", po::value<std::string>(),
       "approach[:density],... e.g. 0:0.3,1 = 0-contact to density 0.3, then 1-contact; "
       "replaces --approach")
      ("collision", po::value<std::string>()->default_value("grid"),
       "raster (status grid of [LP], approximate), grid (exact cell list) or kdtree (exact)")
      ("raster-spacing", po::value<double>(&o.raster_spacing),
       "raster grid spacing h (m), needed by raster")
      ("tries", po::value<int>(&o.tries)->default_value(o.tries),
       "n_T: tries per size before a new size is drawn")
      ("directions", po::value<int>(), directions_help.c_str())
      ("count", po::value<std::size_t>(&o.count), "stop at N particles")
      ("target-density", po::value<double>(&o.target_density),
       "stop at this density (0 < F < 1); if it cannot be reached the run stops by "
       "--max-failures or the default stop rule, still writes the bed, warns on stderr and "
       "exits 0")
      ("max-failures", po::value<std::size_t>(),
       "stop after M consecutive failed placements (default: 100, and in 3D approach 3 with "
       "--site-order lowest also when more than half of the last 20 sizes found no place)")
      ("retire-after", po::value<int>(&o.retire_after)->default_value(o.retire_after),
       "drop a particle from the partner list after this many consecutive failed tries "
       "around it (0 = never; O(N) front advancing)")
      ("edge-fraction", po::value<double>(&o.edge_fraction)->default_value(o.edge_fraction),
       "fraction of 0-contact tries drawn within one largest diameter of a wall")
      ("allow-huge",
       "accept a domain holding more than 1e9 particles of the PSD's mean size, or a --count "
       "above 1e9 (otherwise refused as a likely unit slip: lengths are in m)")
      ("seed", po::value<std::uint64_t>()->required(), "random seed")
      ("out", po::value<std::string>()->required(),
       "output bed (.h5; other extensions are refused: bedconv converts to .csv or .data)");
}

// --dim and --domain, which must agree.
bed::Domain domain_of(const po::variables_map& vm) {
  const std::string dim_text = vm["dim"].as<std::string>();
  if (dim_text != "2" && dim_text != "3")
    throw InputError(fmt::format("--dim: '{}' (accepted: 2 or 3)", dim_text));
  const int dim = dim_text == "2" ? 2 : 3;
  const bed::Domain domain = app::parse_domain_lengths(vm["domain"].as<std::string>(), "--domain");
  if (dim != domain.dimension) {
    throw InputError(fmt::format("--dim: {} but --domain '{}' has {} lengths (accepted: equal)",
                                 dim, vm["domain"].as<std::string>(), domain.dimension));
  }
  return domain;
}

// The packing options: `bound` (what add_options bound) with the phases, the collision test,
// the directions, the site order and the size sampling. pack() checks them (packgen::validate)
// except what only the command line can get wrong: --count 0 and --target-density 0 (to the
// library, "no such stop rule") and a --count that cannot fit, which packgen refuses at any size
// (packgen::check_count_fits).
packgen::PackOptions pack_options(const po::variables_map& vm, const packgen::PackOptions& bound,
                                  const bed::Domain& domain, const bed::Psd& psd) {
  packgen::PackOptions o = bound;
  o.phases = vm.count("phases") ? packgen::parse_phases(vm["phases"].as<std::string>())
                                : std::vector<packgen::Phase>{{vm["approach"].as<int>(), 1.0}};
  o.collision = packgen::parse_collision(vm["collision"].as<std::string>());
  if (vm.count("directions")) o.directions = vm["directions"].as<int>();
  if (vm.count("max-failures")) o.max_failures = vm["max-failures"].as<std::size_t>();
  if (vm.count("count")) {
    if (o.count == 0) throw InputError("--count: 0 (accepted: a number of particles >= 1)");
    packgen::check_count_fits(domain, psd, o.count);
  }
  o.allow_huge = vm.count("allow-huge") > 0;
  if (vm.count("target-density") && o.target_density == 0)
    throw InputError("--target-density: 0 (accepted: 0 < F < 1)");
  o.site_order = packgen::parse_site_order(vm["site-order"].as<std::string>());
  o.size_sampling = packgen::parse_size_sampling(vm["size-sampling"].as<std::string>());
  return o;
}

// The units of packgen's --json numbers (common/json_units).
constexpr bed::UnitEntry kUnits[] = {
    {"n", "1"}, {"density", "1"}, {"coordination", "1"},
    // coordination_by_tol, keyed by the relative tolerance (contact_report.hpp)
    {"1e-06", "1"}, {"0.001", "1"}, {"0.01", "1"},
    {"rattlers", "1"}, {"wall_contacts", "1"}, {"max_relative_overlap", "1"}, {"wall_time", "s"},
    {"attempts", "1"}, {"tries", "1"}, {"failed_placements", "1"}, {"retired", "1"},
    {"refused_valid", "1"}, {"accepted_overlapping", "1"}, {"approach", "1"}, {"sites", "1"},
    {"seed", "1"},
};

// What --json prints: the library's summary (summary_json.hpp) with its units.
void print_json(const packgen::PackResult& result, const packgen::PackOptions& o, std::uint64_t seed) {
  bed::JsonWriter j;
  j.begin_object();
  packgen::write_pack_json(j, result, o, seed);
  bed::write_units(j, kUnits);
  j.end_object();
  std::cout << j.str() << '\n';
}

// The result: the bed (with its provenance) to --out, a warning for a stop rule not reached,
// and the summary (--json: JSON).
void report(packgen::PackResult& result, const packgen::PackOptions& o, std::uint64_t seed,
            const po::variables_map& vm, int argc, char** argv) {
  bed::Bed& b = result.bed;
  b.provenance.created_by = app::version_string("packgen");
  b.provenance.command_line = app::command_line(argc, argv);
  b.provenance.rng_seed = seed;
  b.provenance.stage = "packgen";
  b.provenance.scene = app::scene_text(vm);
  bed::write_bed_h5(b, vm["out"].as<std::string>());

  if (!result.target_reached)
    std::cerr << "packgen: warning: " << packgen::unreached_warning(result, o) << '\n';
  if (vm.count("json")) {
    print_json(result, o, seed);
    return;
  }
  const double density = bed::packing_density(b);
  const bed::ContactStats contacts = bed::contact_stats(b, bed::kReportedTolerances[0]);
  std::cout << "packgen: " << b.n() << " particles, density " << density << ", coordination "
            << contacts.coordination << " (tol 1e-6), " << result.wall_time << " s, "
            << result.attempts << " attempts, stopped by " << result.stop_reason << " ("
            << packgen::collision_name(o.collision) << ", approach " << o.phases.back().approach
            << ") -> " << vm["out"].as<std::string>() << '\n';
}

int run(int argc, char** argv) {
  po::options_description desc("packgen options (SI units: m)");
  packgen::PackOptions bound;  // what the options of a plain type fill (add_options)
  add_options(desc, bound);
  po::variables_map vm;
  if (!app::parse_options("packgen", kUsage, desc, {}, argc, argv, vm)) return 0;
  // The output is checked before any work (docs/hardening.md): extension, folder, not a folder.
  const app::PathArg out{"--out", vm["out"].as<std::string>()};
  app::check_extension(out, {".h5"}, "bedconv converts an .h5 bed to .csv or .data");
  app::check_paths({}, {out});
  const bed::Domain domain = domain_of(vm);
  const bed::Psd psd = bed::Psd::parse(vm["psd"].as<std::string>(), "--psd");
  packgen::PackOptions o = pack_options(vm, bound, domain, psd);
  app::ProgressBar bar("packgen", app::progress_interval(vm));
  o.progress = [&bar](const packgen::PackProgress& p) {
    char detail[64];
    std::snprintf(detail, sizeof detail, "%zu particles, density %.4f", p.n, p.density);
    bar.draw(p.fraction_done, detail);
  };
  const std::uint64_t seed = vm["seed"].as<std::uint64_t>();
  packgen::PackResult result = packgen::pack(domain, psd, o, seed);
  bar.finish();
  report(result, o, seed, vm, argc, argv);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return powderbed::app::run_app("packgen", argc, argv, [&] { return run(argc, argv); });
}
