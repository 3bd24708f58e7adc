// bedconv: converts a bed between the formats of docs/bed-format.md, chosen by extension
// (readable: .h5, .csv, .dump, .lammpstrj, .data, YADE .txt, GenGeo .geo, .gz of the text ones;
// writable: .h5, .csv, .data), writes LAMMPS / LIGGGHTS decks (--deck, docs/decks.md) and
// turns a multi-snapshot dump into a trajectory (--all-snapshots).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "common/app_main.hpp"
#include "common/deck_export.hpp"
#include "deposit_options.hpp"
#include "common/options.hpp"
#include "powderbed/bed/json_units.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/dem/time_step.hpp"
#include "powderbed/dem/trajectory.hpp"

namespace {

using powderbed::InputError;
namespace app = powderbed::app;
namespace bed = powderbed::bed;
namespace dem = powderbed::dem;
namespace po = boost::program_options;

const char* const kUsage =
    "bedconv IN OUT [--domain ...] [--density RHO[,RHO...]] [--deck lammps|liggghts "
    "[--deck-scene SCENE.ini] [--deck-steps N] [--dt DT]] [--all-snapshots [--dt DT]] [--tol T]";

void add_options(po::options_description& desc) {
  desc.add_options()(
      "in", po::value<std::string>()->required(),
      "input bed: .h5, .csv (x,y,z,r in m; needs --domain), .dump / .lammpstrj (LAMMPS/LIGGGHTS "
      "text dump; the last snapshot), .data (LAMMPS data file, ours or write_data's), .txt (YADE "
      "text export x y z r; --domain or the spheres' bounding box), .geo (GenGeo); text files "
      "may be gzipped (.gz)")(
      "out", po::value<std::string>()->required(),
      "output: .h5 (with an .xmf sidecar for ParaView), .csv or .data (LAMMPS, atom_style "
      "sphere, one atom type per material, velocities); with --all-snapshots a trajectory .h5")(
      "domain", po::value<std::string>(),
      "domain of a CSV or YADE input, m: xlo,ylo,zlo,xhi,yhi,zhi (zlo = zhi = 0 makes it 2D)")(
      "density", po::value<std::string>(),
      "particle density of .data output, kg/m^3: one for every material, or one per material "
      "index (default: the bed's deposit scene's material.density, else 7952, 316L steel)")(
      "deck", po::value<std::string>(),
      "also write an input deck for lammps or liggghts beside the .data OUT (in.<name>.<engine>): "
      "the laws of the deposit scene that made the bed (its /provenance), --deck-scene, or "
      "deposit's defaults (docs/decks.md)")(
      "deck-scene", po::value<std::string>(),
      "deposit scene (INI, deposit's keys: material.*, wall.*, contact.*, effects.*, gravity, "
      "fluid.viscosity, young-scale, dt) whose keys override the bed's own scene in the deck")(
      "deck-steps", po::value<std::uint64_t>()->default_value(1000),
      "steps the deck runs by default (its variable NSTEPS)")(
      "dt", po::value<double>(),
      "time step (s): the deck's (default: the scene's dt, else deposit's default step for this "
      "bed), or a dump's step for --all-snapshots when it has no ITEM: TIME (default: the "
      "timestep of the deck bedconv wrote beside it)")(
      "all-snapshots", po::bool_switch(),
      "IN a .dump / .lammpstrj: every snapshot into OUT, a trajectory .h5 (+ .xmf), time from "
      "ITEM: TIME or step x --dt (or x the timestep of the deck beside it)")(
      "tol", po::value<double>()->default_value(1e-6),
      "contact tolerance the precision warning of a text IN is judged against (bedstat --tol)");
  app::add_common_options(desc);
}

// Densities per atom type for .data output, with where they came from.
std::vector<double> densities(const po::variables_map& vm, const app::DeckScene& scene,
                              bool scene_has_density, std::string& origin) {
  if (vm.count("density")) {
    const auto list = app::parse_number_list(vm["density"].as<std::string>(), 1, 65536, "--density");
    for (double rho : list) {
      if (!(rho > 0))
        throw InputError(fmt::format("--density: {:f} (accepted: > 0 kg/m^3)", rho));
    }
    origin = "--density";
    return list;
  }
  if (scene_has_density) {
    origin = "material.density of the scene (every material)";
    return {scene.scene.material.density};
  }
  origin = "default 7952 (316L; the bed records no density: give --density)";
  return {bed::kDefaultLammpsDensity};
}

// The time step of the deck that wrote the dump `dump`: a deck bedconv exported (in.*) in the
// dump's folder whose `variable DUMP index NAME` names it, and its `timestep` line. LAMMPS
// decks also write ITEM: TIME into their dumps; LIGGGHTS 3.8 has no such option, so its dumps
// take the step from here. nullopt when no deck there names the dump.
std::optional<double> deck_timestep(const std::string& dump) {
  namespace fs = std::filesystem;
  const fs::path path(dump);
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    if (!entry.is_regular_file(error) || entry.path().filename().string().rfind("in.", 0) != 0)
      continue;
    std::ifstream deck(entry.path());
    bool names_dump = false;
    std::optional<double> dt;
    for (std::string line; std::getline(deck, line);) {
      std::istringstream words(line);
      std::string first, second, third, fourth;
      words >> first >> second >> third >> fourth;
      if (first == "variable" && second == "DUMP" && third == "index")
        names_dump = fs::path(fourth).filename() == path.filename();
      if (first == "timestep") {
        try {
          dt = std::stod(second);
        } catch (const std::exception&) {
          dt.reset();
        }
      }
    }
    if (names_dump && dt && *dt > 0) return dt;
  }
  return std::nullopt;
}

// Every snapshot of the dump `in` into the trajectory `out`; returns the number of snapshots.
// A snapshot's time: its ITEM: TIME, else step x (--dt, else the timestep of the deck that
// wrote the dump, deck_timestep).
std::size_t write_trajectory(const std::string& in, const std::string& out,
                             const po::variables_map& vm) {
  const auto snapshots = bed::read_lammps_dump_all(in);
  const bed::Bed& first = snapshots.front().bed;
  for (std::size_t k = 0; k < snapshots.size(); ++k) {
    const bed::Bed& b = snapshots[k].bed;
    if (b.id != first.id || b.radius != first.radius)
      throw InputError(fmt::format("{}: snapshot {} (step {}) holds other atoms than the first "
                                   "(accepted: the same atoms, sorted alike, in every snapshot: "
                                   "dump_modify sort id)",
                                   in, k, snapshots[k].step));
  }
  std::optional<double> dt;
  if (vm.count("dt")) dt = vm["dt"].as<double>();
  for (const auto& s : snapshots) {
    if (s.time >= 0 || dt) continue;
    dt = deck_timestep(in);
    if (!dt)
      throw InputError(fmt::format("{}: no ITEM: TIME in step {} and no deck beside it naming it "
                                   "(accepted: a dump with times, --dt DT for time = step x DT, "
                                   "or the dump's folder holding the in.* deck bedconv wrote)",
                                   in, s.step));
  }
  dem::TrajectoryWriter writer(out, first);
  for (const auto& s : snapshots) {
    const double time = s.time >= 0 ? s.time : static_cast<double>(s.step) * *dt;
    writer.write(s.step, time, s.bed);
  }
  writer.close();
  return snapshots.size();
}

// What the bed records of the DEM that made it: the contact_* attributes of /provenance (kept
// by later stages), then the scene text of a bed that deposit made (another stage's scene has
// other laws: sinter's dt is its thermal step).
app::DeckScene scene_of(const bed::Bed& b, const std::string& in) {
  app::DeckScene scene;
  const bed::ContactProvenance& c = b.provenance.contact;
  if (!c.law.empty()) {
    std::ostringstream ini;
    ini.precision(17);
    ini << "contact.law = " << c.law << "\nmaterial.young = " << c.young << "\nmaterial.poisson = "
        << c.poisson << "\nwall.young = " << c.wall_young << "\nwall.poisson = " << c.wall_poisson
        << "\nyoung-scale = " << c.young_scale << "\n";
    if (c.law == "linear") ini << "contact.stiffness = " << c.stiffness << "\n";
    app::apply_scene_text(ini.str(), fmt::format("{} /provenance contact_* attributes", in), scene);
  }
  if (b.provenance.stage == "deposit")
    app::apply_scene_text(b.provenance.scene, fmt::format("{} /provenance scene", in), scene);
  return scene;
}

// The deck's laws: deposit's defaults, then the scene of the deposit that made the bed, then
// --deck-scene.
bed::DeckLaws laws_for(const bed::Bed& b, const std::string& in, const po::variables_map& vm) {
  app::DeckScene scene = scene_of(b, in);
  if (vm.count("deck-scene")) {
    const std::string path = vm["deck-scene"].as<std::string>();
    // Read first as deposit reads its --config, so that a line that is not key = value, a key
    // deposit does not know or a value it refuses exits 2 naming the line, instead of being
    // skipped (apply_scene_text takes the deck's keys and ignores deposit's others).
    app::DepositOptions bound;
    po::options_description deposit("deposit");
    app::add_deposit_options(deposit, bound);
    po::variables_map checked;
    app::store_scene_file(path, deposit, checked, "--deck-scene");
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    if (!file) throw InputError(fmt::format("--deck-scene: cannot read '{}'", path));
    app::apply_scene_text(text.str(), path, scene);
  }
  bool has_density = false;
  for (const auto& [key, source] : scene.origin) has_density |= key == "material.density";
  std::string density_origin;
  const auto rho = densities(vm, scene, has_density, density_origin);
  double dt = scene.dt;
  std::string dt_origin = "dt of the scene";
  if (vm.count("dt")) {
    dt = vm["dt"].as<double>();
    dt_origin = "--dt";
  } else if (!(dt > 0)) {
    scene.scene.validate();
    dt = dem::time_step_bound(b, scene.scene, scene.young_scale).recommended;
    dt_origin = "deposit's default for this bed and scene (0.2 x the stable bound)";
  }
  bed::DeckLaws laws = app::deck_laws(scene, rho, density_origin + " [" + in + "]", dt, dt_origin);
  laws.steps = vm["deck-steps"].as<std::uint64_t>();
  return laws;
}

// What to convert: IN, OUT and the options that change what is written, checked against each
// other before any file is touched.
struct Request {
  std::string in, out, in_ext;
  bool data_out = false, all = false, deck = false;
  double tol = 0;
  bed::DeckEngine engine = bed::DeckEngine::lammps;
};

Request request_of(const po::variables_map& vm) {
  Request r;
  r.in = vm["in"].as<std::string>();
  r.out = vm["out"].as<std::string>();
  r.in_ext = bed::readable_extension_of(r.in);
  r.data_out = bed::extension_of(r.out) == ".data";
  r.all = vm["all-snapshots"].as<bool>();
  r.deck = vm.count("deck") > 0;
  if (vm.count("density") && !r.data_out)
    throw InputError(fmt::format("--density: only used for .data output (OUT is '{}')", r.out));
  if (r.deck && !r.data_out)
    throw InputError(fmt::format("--deck: OUT must be the deck's .data file (OUT is '{}')", r.out));
  if (!r.deck && (vm.count("deck-scene") || !vm["deck-steps"].defaulted()))
    throw InputError("--deck-scene / --deck-steps: only with --deck");
  if (r.all && r.in_ext != ".dump" && r.in_ext != ".lammpstrj")
    throw InputError(
        fmt::format("--all-snapshots: IN must be a .dump or .lammpstrj (IN is '{}')", r.in));
  if (vm.count("dt") && !r.deck && !r.all)
    throw InputError("--dt: only with --deck or --all-snapshots");
  if (vm.count("dt") && !(vm["dt"].as<double>() > 0))
    throw InputError(fmt::format("--dt: {:f} (accepted: dt > 0 s)", vm["dt"].as<double>()));
  r.tol = vm["tol"].as<double>();
  if (!(r.tol >= 0)) throw InputError(fmt::format("--tol: {:f} (accepted: T >= 0)", r.tol));
  if (r.deck) r.engine = bed::parse_deck_engine(vm["deck"].as<std::string>(), "--deck");
  return r;
}

// Before any reading or writing (docs/hardening.md): the extensions, the input a file, the
// outputs' folders writable and no output the input.
void check_files(const Request& r, const bed::DeckFiles& files, const po::variables_map& vm) {
  app::check_extension({"IN", r.in}, {".h5", ".csv", ".dump", ".lammpstrj", ".data", ".txt", ".geo",
                                      ".gz"});
  if (r.all) app::check_extension({"OUT", r.out}, {".h5"});
  else app::check_extension({"OUT", r.out}, {".h5", ".csv", ".data"});
  std::vector<app::PathArg> outputs{{"OUT", r.out}};
  if (r.deck) outputs.push_back({"deck", files.input});
  std::vector<app::PathArg> inputs{{"IN", r.in}};
  if (vm.count("deck-scene")) {
    inputs.push_back({"--deck-scene", vm["deck-scene"].as<std::string>()});
  }
  app::check_paths(inputs, outputs);
}

// IN as a bed: a CSV needs --domain, a YADE text may have one, other formats carry their own.
bed::Bed read_input(const Request& r, const po::variables_map& vm) {
  if (vm.count("domain")) {
    if (r.in_ext != ".csv" && r.in_ext != ".txt")
      throw InputError(
          fmt::format("--domain: only for CSV or YADE input ('{}' carries its own domain)", r.in));
    const bed::Domain domain = app::parse_domain_bounds(vm["domain"].as<std::string>(), "--domain");
    return bed::read_bed_any(r.in, &domain);
  }
  if (r.in_ext == ".csv")
    throw InputError(
        fmt::format("{}: CSV carries no domain; give --domain xlo,ylo,zlo,xhi,yhi,zhi (m)", r.in));
  return bed::read_bed_any(r.in);
}

// The bed to OUT: a deck (its .data and input), a LAMMPS data file, or a bed file.
void write_output(const bed::Bed& b, const Request& r, const po::variables_map& vm) {
  if (r.deck) {
    bed::write_deck(b, laws_for(b, r.in, vm), r.engine, r.out);
  } else if (r.data_out) {
    const app::DeckScene scene = scene_of(b, r.in);
    bool has_density = false;
    for (const auto& [key, source] : scene.origin) has_density |= key == "material.density";
    std::string origin;
    bed::LammpsDataOptions options;
    options.type_density = densities(vm, scene, has_density, origin);
    options.comments = {"density: " + origin};
    bed::write_lammps_data(b, r.out, options);
  } else {
    bed::write_bed_any(b, r.out);
  }
}

int convert(int argc, char** argv) {
  po::options_description desc("bedconv options");
  add_options(desc);
  po::positional_options_description positional;
  positional.add("in", 1).add("out", 1);
  po::variables_map vm;
  if (!app::parse_options("bedconv", kUsage, desc, positional, argc, argv, vm)) return 0;
  const Request r = request_of(vm);
  const bed::DeckFiles files = bed::deck_files(r.out, r.engine);
  check_files(r, files, vm);

  bed::JsonWriter json;
  json.begin_object().value("in", r.in).value("out", r.out);
  if (r.all) {
    const std::size_t count = write_trajectory(r.in, r.out, vm);
    json.value("snapshots", static_cast<std::uint64_t>(count));
  } else {
    bed::Bed b = read_input(r, vm);
    const std::string warning = bed::printed_precision_warning(b, r.tol);
    if (!warning.empty()) std::cerr << "bedconv: warning: " << r.in << ": " << warning << '\n';
    b.provenance.created_by = app::version_string("bedconv");
    b.provenance.command_line = app::command_line(argc, argv);
    write_output(b, r, vm);
    json.value("particles", static_cast<std::uint64_t>(b.n()));
    json.value("dimension", b.domain.dimension);
    if (r.deck) json.value("deck", files.input);
  }
  // The units of bedconv's --json numbers (common/json_units).
  static constexpr bed::UnitEntry kUnits[] = {{"snapshots", "1"}, {"particles", "1"}, {"dimension", "1"}};
  bed::write_units(json, kUnits);
  json.end_object();
  if (vm.count("json")) std::cout << json.str() << '\n';
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return app::run_app("bedconv", argc, argv, [&] { return convert(argc, argv); });
}
