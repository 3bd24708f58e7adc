// deposit's spreading mode: options, the supply (packgen's 0-contact placement in the region in
// front of the tool), the per-layer beds with their /restart group, the tool's force log and
// the JSON summary. The physics is dem's run_spread (spread.hpp).
#include "deposit_spread.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/app_main.hpp"
#include "common/deck_export.hpp"
#include "common/progress.hpp"
#include "common/thermo_table.hpp"
#include "common/threads.hpp"
#include "deposit_options.hpp"
#include "spread_deck.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/h5_output.hpp"
#include "powderbed/bed/io.hpp"
#include "powderbed/bed/json.hpp"
#include "powderbed/dem/summary_json.hpp"
#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/softening.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/bed/temp_files.hpp"
#include "powderbed/dem/contact_provenance.hpp"
#include "powderbed/dem/diagnostics.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/packgen/pack.hpp"

namespace powderbed::app {

namespace {

// Options of the drop that a spread does not have: refused rather than ignored.
constexpr const char* kDropOnly[] = {"t-end", "count", "insert-z", "trajectory"};

}  // namespace

SupplyAmount supply_amount(const po::variables_map& vm, std::uint64_t layer, double width) {
  const std::size_t count = vm["supply.count"].as<std::size_t>();
  const double volume = vm["supply.volume"].as<double>();
  const bool dosed = vm.count("supply.dosing") > 0;
  const double dosing = dosed ? vm["supply.dosing"].as<double>() : 0.0;
  const double bulk = vm["supply.bulk-density"].as<double>();
  if (dosed && !(dosing > 0 && std::isfinite(dosing)))
    throw InputError(fmt::format("supply.dosing: {:g} (accepted: a factor > 0, the supply over "
                                 "the powder of the layer's nominal volume)", dosing));
  if (!(bulk > 0 && bulk < 1))
    throw InputError(fmt::format("supply.bulk-density: {:g} (accepted: a solid fraction in (0, 1); "
                                 "a gas-atomised powder's is about 0.5)", bulk));
  const int given = (count > 0) + (volume > 0) + (dosed ? 1 : 0);
  if (given != 1) {
    throw InputError(fmt::format("supply.count / supply.volume / supply.dosing: {} given "
                                 "(accepted: one of them, a count >= 1, a volume > 0 m^3 or a "
                                 "dosing factor > 0)",
                                 given == 0 ? "none" : "more than one"));
  }
  if (!dosed) return {count, volume};
  const double strip = vm["recoater.end"].as<double>() - vm["recoater.start"].as<double>();
  const double t = layer <= 1 ? vm["recoater.gap"].as<double>() : vm["recoater.layer-thickness"].as<double>();
  return {0, dosing * bulk * strip * width * t};
}

namespace {

// The supply of a layer (supply_amount) placed without overlap at random in the region
// (packgen's 0-contact packing; a seed of its own per layer, so that a continued run draws the
// same supply). The options are checked now, before any layer, and copied: the maker outlives
// the caller's map.
dem::SupplyMaker supply_maker(const po::variables_map& vm, std::uint64_t seed) {
  const bed::Psd psd = bed::Psd::parse(required<std::string>(vm, "psd"), "--psd");
  supply_amount(vm, 1, 1.0);
  return [psd, vm, seed](const bed::Domain& region, std::uint64_t layer) {
    const auto [count, volume] = supply_amount(vm, layer, region.upper[1] - region.lower[1]);
    packgen::PackOptions options;
    options.phases = {packgen::Phase{0, 1.0}};
    options.max_failures = 100;
    double space = 1;
    for (int a = 0; a < 3; ++a) space *= region.upper[a] - region.lower[a];
    if (count > 0) {
      options.count = count;
    } else {
      options.target_density = volume / space;
    }
    packgen::validate(region, psd, options);
    packgen::PackResult placed = packgen::pack(region, psd, options, seed + 0x9E3779B97F4A7C15ull * layer);
    if (!placed.target_reached) {
      double solid = 0;
      for (const double r : placed.bed.radius) solid += bed::sphere_volume(r);
      const char* option = count > 0 ? "supply.count" : vm.count("supply.dosing") ? "supply.dosing" : "supply.volume";
      const std::string supply = count > 0 ? fmt::format("{}: {} particles", option, count)
                                           : fmt::format("{}: {:g} m^3", option, volume);
      throw InputError(fmt::format(
          "{} do not fit the supply region {:g} x {:g} x {:g} m of layer {} without overlap ({} "
          "particles, {:g} m^3 placed; accepted: at most that, or a longer or taller region)",
          supply, region.upper[0] - region.lower[0], region.upper[1] - region.lower[1],
          region.upper[2] - region.lower[2], layer, placed.bed.n(), solid));
    }
    return std::move(placed.bed);
  };
}

// "<stem>-NNN.h5" for layer NNN of --out "<stem>.h5".
std::string layer_path(const std::string& out, std::uint64_t layer) {
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "-%03llu.h5", static_cast<unsigned long long>(layer));
  return out.substr(0, out.size() - 3) + suffix;
}

}  // namespace

bed::Domain spread_box(const po::variables_map& vm, std::optional<bed::Domain> given) {
  // Periodic across (y) unless the scene says otherwise: a strip of a wider bed.
  const std::string periodic = vm["periodic"].defaulted() ? "y" : vm["periodic"].as<std::string>();
  if (periodic != "none" && periodic != "x" && periodic != "y" && periodic != "x,y" && periodic != "xy") {
    throw InputError(fmt::format("--periodic: '{}' (accepted: none, x, y, x,y)", periodic));
  }
  bed::Domain d;
  if (given) {
    d = *given;
  } else {
    d = parse_domain_lengths(required<std::string>(vm, "domain"), "--domain");
    if (d.dimension != 3) throw InputError("--domain: 2D box (accepted: LX,LY,LZ)");
    d.periodic[0] = periodic == "x" || periodic == "x,y" || periodic == "xy";
    d.periodic[1] = periodic == "y" || periodic == "x,y" || periodic == "xy";
  }
  if (d.periodic[0]) {
    throw InputError("--periodic: x with recoater.tool (accepted: none or y; the tool travels "
                     "along x between the box's end walls)");
  }
  return d;
}

dem::SpreadSettings spread_settings(const po::variables_map& vm, const dem::SpreadSettings& bound,
                                    std::uint64_t seed, std::shared_ptr<ThermoTable>* table) {
  dem::SpreadSettings s = bound;
  s.tool.shape = dem::parse_tool_shape(vm["recoater.tool"].as<std::string>());
  s.supply = supply_maker(vm, seed);
  if (vm.count("supply.platform-edge")) s.platform_edge = vm["supply.platform-edge"].as<double>();
  s.young_scale = vm["young-scale"].as<double>();
  if (vm.count("dt")) s.dt = vm["dt"].as<double>();
  s.unsafe_dt = vm["unsafe-dt"].as<bool>();
  s.rest.max_speed = vm["rest.speed"].as<double>();
  s.rest.window = vm["rest.window"].as<double>();
  auto thermo = attach_thermo(vm, true, s.thermo, s.thermo_every);
  if (table) *table = std::move(thermo);
  return s;
}

void set_spread_provenance(bed::Bed& b, const po::variables_map& vm, const dem::Scene& scene,
                           const char* program, int argc, char** argv) {
  b.provenance.created_by = version_string(program);
  b.provenance.command_line = command_line(argc, argv);
  b.provenance.rng_seed = vm["seed"].as<std::uint64_t>();
  b.provenance.stage = "deposit";
  b.provenance.scene = scene_text(vm);
  b.provenance.contact = dem::contact_provenance(scene, vm["young-scale"].as<double>());
}

void add_spread_options(po::options_description& desc, dem::SpreadSettings& spread,
                        dem::Scene& scene) {
  dem::Recoater& t = spread.tool;
  desc.add_options()
      ("friction.model", po::value<std::string>()->default_value("sliding"),
       "friction law of every contact: sliding (regularised Coulomb, no static friction) or "
       "history (tangential spring capped at mu F_n: static friction; spreading runs only)")
      ("material.rolling",
       po::value<double>(&scene.material.rolling)->default_value(scene.material.rolling),
       "rolling resistance mu_r (EPSD model, docs/deposit-spread.md; 0: off; spreading runs only)")
      ("recoater.tool", po::value<std::string>()->default_value(""),
       "spread with a recoater instead of a drop: blade or roller (docs/deposit-spread.md)")
      ("recoater.thickness", po::value<double>(&t.thickness)->default_value(t.thickness),
       "blade: thickness along x (m)")
      ("recoater.edge-radius", po::value<double>(&t.edge_radius)->default_value(t.edge_radius),
       "blade: radius of its bottom edges (m; 0: sharp)")
      ("recoater.radius", po::value<double>(&t.radius)->default_value(t.radius),
       "roller: radius (m)")
      ("recoater.omega", po::value<double>(&t.omega)->default_value(t.omega),
       "roller: spin about +y (rad/s; < 0 counter-rotating: the bottom moves along the travel)")
      ("recoater.gap", po::value<double>(&t.gap)->default_value(t.gap),
       "height of the tool's lowest point above the plate (m) in the first layer")
      ("recoater.speed", po::value<double>(&t.speed)->default_value(t.speed),
       "tool speed along +x (m/s)")
      ("recoater.start", po::value<double>(&t.start)->default_value(t.start),
       "x of the tool's centre (blade mid-plane, roller axis) at the start (m)")
      ("recoater.end", po::value<double>(&t.end)->default_value(t.end),
       "x where the tool stops (m)")
      ("recoater.delay", po::value<double>(&t.delay)->default_value(t.delay),
       "time before the tool moves, the supply settling (s)")
      ("recoater.settle", po::value<double>(&t.settle)->default_value(t.settle),
       "time after the tool stopped, the layer settling (s)")
      ("recoater.until-rest", po::value<bool>(&spread.until_rest)->default_value(spread.until_rest),
       "after recoater.settle, settle on until the powder behind the tool rests (its fastest "
       "particle below rest.speed for rest.window; layers[k].settle_time, at_rest)")
      ("recoater.rest-cap", po::value<double>(&spread.rest_cap)->default_value(spread.rest_cap),
       "recoater.until-rest: the most a layer settles (s)")
      ("recoater.overflow",
       po::value<bool>(&spread.remove_overflow)->default_value(spread.remove_overflow),
       "after each layer remove the powder pushed past the tool's end (the machine's overflow "
       "slot; false keeps every particle)")
      ("recoater.chamber", po::value<bool>(&spread.chamber)->default_value(spread.chamber),
       "with recoater.overflow: remove only the powder past the tool's end above the tool's "
       "bottom, so the bed reaches the box's far wall as a machine's stands against its "
       "chamber wall (false: the bed ends in a free face at the tool's end)")
      ("recoater.layer-thickness",
       po::value<double>(&spread.layer_thickness)->default_value(spread.layer_thickness),
       "how far the plate goes down before each layer after the first (m)")
      ("recoater.freeze-depth",
       po::value<double>(&spread.freeze_depth)->default_value(spread.freeze_depth),
       "at each layer's start freeze the particles more than this below the tool's bottom (m; "
       "0: off, the default: powder 4 D90 under a blade still moves under the supply's heap, "
       "docs/deposit-spread.md \"Many layers\"; more than the largest diameter keeps the "
       "frozen out of the tool's reach, layers[k].frozen_tool_contacts counts any it meets)")
      ("sleep.on", po::value<bool>(&spread.sleep.on)->default_value(spread.sleep.on),
       "powder at rest under the tool sleeps (is not integrated) until what moves pushes it "
       "(docs/deposit-spread.md \"Sleeping powder\"; layers[k].asleep reports how many slept)")
      ("sleep.speed", po::value<double>(&spread.sleep.speed)->default_value(spread.sleep.speed),
       "sleep.on: at rest below this speed, of the centre and of the surface about it (m/s)")
      ("sleep.wake-speed", po::value<double>(&spread.sleep.wake_speed)->default_value(spread.sleep.wake_speed),
       "sleep.on: a sleeper wakes, with the sleepers it touches, when an awake particle touching "
       "it moves faster than this (m/s)")
      ("sleep.steps", po::value<std::uint64_t>(&spread.sleep.steps)->default_value(spread.sleep.steps),
       "sleep.on: steps in a row at rest before a particle sleeps")
      ("supply.x0", po::value<double>(&spread.supply_x0)->default_value(spread.supply_x0),
       "supply region: start along x (m)")
      ("supply.x1", po::value<double>(&spread.supply_x1)->default_value(spread.supply_x1),
       "supply region: end along x (m)")
      ("supply.height",
       po::value<double>(&spread.supply_height)->default_value(spread.supply_height),
       "supply region: height above the plate or the powder under it (m)")
      ("supply.platform-edge", po::value<double>(),
       "the dosing platform's edge along x (m; supply.x1 <= edge < recoater.end): the floor at "
       "x <= edge stands at the tool's bottom each layer, the table a machine doses on, so the "
       "supply lies on it and not on the earlier layers' powder (docs/deposit-spread.md \"The "
       "dosing platform\"; unset: none)")
      ("supply.count", po::value<std::size_t>()->default_value(0),
       "supply per layer: particles of --psd (or supply.volume)")
      ("supply.volume", po::value<double>()->default_value(0),
       "supply per layer: solid volume of --psd particles (m^3; or supply.count)")
      ("supply.dosing", po::value<double>(),
       "supply per layer: dosing factor d, the powder of d layers' nominal volume at "
       "supply.bulk-density: d phi_b (recoater.end - recoater.start) L_y t of solid, t the first "
       "layer's gap, then recoater.layer-thickness (or supply.count, supply.volume)")
      ("supply.bulk-density", po::value<double>()->default_value(0.5),
       "the dosed powder's solid fraction phi_b (supply.dosing; a gas-atomised powder's apparent "
       "density is about half its metal's)")
      ("layers", po::value<std::uint64_t>(&spread.layers)->default_value(spread.layers),
       "layers to spread (with --in a spread bed: after its own); each is also written to "
       "OUT-NNN.h5 when N > 1")
      ("tool-forces", po::value<std::string>(),
       "CSV of the tool's force on the powder over time: layer,time,x,fx,fy,fz (s, m, N)")
      ("tool-forces-every", po::value<std::uint64_t>()->default_value(100),
       "steps between two rows of --tool-forces");
}

bool spread_requested(const po::variables_map& vm) {
  return vm.count("recoater.tool") && !vm["recoater.tool"].as<std::string>().empty();
}

namespace {

// The options a drop has and a spread refuses (one line each, exit 2).
void refuse_drop_options(const po::variables_map& vm) {
  for (const char* name : kDropOnly) {
    if (vm.count(name) && !vm[name].defaulted()) {
      throw InputError(fmt::format("--{}: given with recoater.tool (accepted: a drop option; a "
                                   "spread lasts the tool's travel and takes its particles from "
                                   "the supply)",
                                   name));
    }
  }
  if (vm["until-rest"].as<bool>()) {
    throw InputError("--until-rest: given with recoater.tool (accepted: recoater.until-rest, "
                     "which settles each layer to rest)");
  }
  if (vm["lid"].as<bool>() || vm["lid.enabled"].as<bool>() ||
      vm["insert.enabled"].as<bool>() || vm["integrator"].as<std::string>() != "verlet") {
    throw InputError("recoater.tool: with the lid, insertion or --integrator rk4 "
                     "(accepted: none of them; the spread integrates with velocity Verlet)");
  }
}

std::optional<std::string> tool_forces_path(const po::variables_map& vm) {
  return vm.count("tool-forces") ? std::optional(vm["tool-forces"].as<std::string>()) : std::nullopt;
}

// The files of the run: extensions, inputs that exist, outputs that do not clash with them.
void check_spread_paths(const po::variables_map& vm, const std::string& out) {
  std::vector<PathArg> inputs, outputs{{"--out", out}};
  if (vm.count("in")) inputs.push_back({"--in", vm["in"].as<std::string>()});
  check_extension({"--out", out}, {".h5"});
  if (const auto forces = tool_forces_path(vm)) {
    check_extension({"--tool-forces", *forces}, {".csv"});
    outputs.push_back({"--tool-forces", *forces});
  }
  if (const auto log = log_path(vm)) outputs.push_back(*log);
  check_paths(inputs, outputs);
}

// A bed whose provenance scene names a recoater: a spread's layer, which is written with its
// /restart (dem::write_spread_bed) and continues only with it.
bool made_by_a_spread(const bed::Bed& bed) {
  std::istringstream lines(bed.provenance.scene);
  for (std::string line; std::getline(lines, line);)
    if (line == "recoater.tool = blade" || line == "recoater.tool = roller") return true;
  return false;
}

// The bed to spread on: --in's (with its /restart state when it has one) or an empty box.
bed::Bed spread_input(const po::variables_map& vm, std::optional<dem::SpreadState>& restart) {
  if (!vm.count("in")) {
    bed::Bed bed;
    bed.domain = spread_box(vm);
    return bed;
  }
  const std::string in = vm["in"].as<std::string>();
  if (bed::extension_of(in) != ".h5") {
    throw InputError(fmt::format("--in: '{}' with recoater.tool (accepted: an .h5 bed)", in));
  }
  bed::Bed bed = bed::read_bed_h5(in);
  if (dem::has_spread_state(in)) {
    restart = dem::read_spread_state(in, bed);
  } else if (made_by_a_spread(bed)) {
    throw InputError(fmt::format("--in: '{}' was written by a spreading run but has no /restart "
                                 "group (damaged?; accepted: a layer file with its /restart, or a "
                                 "bed that no spread made)",
                                 in));
  }
  bed.domain = spread_box(vm, bed.domain);
  return bed;
}

// A spread that lost particles or left none is not a result.
std::size_t check_spread_result(const po::variables_map& vm, const dem::SpreadSummary& r,
                                const bed::Bed& bed) {
  std::size_t lost = 0;
  for (const auto& l : r.layers) lost = l.lost;
  if (lost > vm["allow-lost"].as<std::size_t>()) {
    throw NumericalError(fmt::format(
        "{} of {} particles left the box through the plate or a wall (accepted: at most "
        "--allow-lost {}); the time step may be beyond the stable bound or the tool too fast for "
        "the softening",
        lost, bed.n(), vm["allow-lost"].as<std::size_t>()));
  }
  if (bed.n() == 0) {  // a layer of nothing is not a result
    throw InputError(fmt::format(
        "recoater.end: the tool pushed the whole supply past its end ({} particles into the "
        "overflow), so no powder is left on the plate (accepted: a travel that leaves powder "
        "behind the tool, or recoater.overflow = false)",
        r.layers.empty() ? 0 : r.layers.back().overflow));
  }
  return lost;
}

std::string spread_summary(const po::variables_map& vm, const dem::SpreadSummary& r,
                           const dem::Scene& scene, const dem::SpreadSettings& s,
                           const bed::Bed& bed, std::size_t lost, const std::string& out) {
  if (vm.count("json")) {
    bed::JsonWriter j;
    j.begin_object().value("n", static_cast<std::uint64_t>(bed.n()));
    dem::write_spread_json(j, r);
    write_contact_laws(j, s.young_scale, scene);
    j.value("rolling", scene.material.rolling)
        .value("tool", vm["recoater.tool"].as<std::string>())
        .value("lost", static_cast<std::uint64_t>(lost))
        .value("out", out);
    bed::write_units(j, deposit_units());
    j.end_object();
    return j.str() + '\n';
  }
  std::ostringstream text;
  text << "deposit: spread " << r.layers.size() << " layer(s) with a "
            << vm["recoater.tool"].as<std::string>() << ", " << bed.n() << " particles ("
            << lost << " lost), " << r.steps << " steps of " << r.dt << " s to t = "
            << r.sim_time << " s, " << r.wall_time << " s wall";
  if (!r.layers.empty()) {
    text << ", layer " << r.layers.back().layer << " density under the gap "
         << r.layers.back().density_under_gap;
  }
  text << " -> " << out << '\n';
  return text.str();
}

// --export-deck in spreading mode: the deck of the spread instead of the spread (docs/decks.md
// "Spreading decks"): the bed (--in's or none) with the first layer's supply as deposit places
// it, the time step deposit would take, and the deck, tool and floor files beside --out.
int export_spread_deck(const po::variables_map& vm, const DepositOptions& bound, std::uint64_t seed,
                       const std::string& out, int argc, char** argv) {
  const std::string engine = vm["export-deck"].as<std::string>();
  check_paths({}, deck_outputs(engine, out));
  std::optional<dem::SpreadState> restart;
  bed::Bed bed = spread_input(vm, restart);
  const dem::Scene scene = deposit_scene(vm, bound.scene);
  const dem::SpreadSettings s = spread_settings(vm, bound.spread, seed);
  if (s.chamber && s.remove_overflow) {  // the decks' overflow deletes everything past the end
    throw InputError("recoater.chamber: true with --export-deck (accepted: false; the decks "
                     "remove all the powder past the tool's end)");
  }
  if (s.freeze_depth > 0) {  // the decks integrate every particle: the deck would not be this run
    throw InputError(fmt::format("recoater.freeze-depth: {:g} m with --export-deck (accepted: 0; "
                                 "the decks freeze nothing)",
                                 s.freeze_depth));
  }
  if (s.sleep.on) {
    throw InputError("sleep.on: true with --export-deck (accepted: false; the decks integrate every "
                     "particle)");
  }
  if (s.platform_edge) {
    throw InputError("supply.platform-edge: set with --export-deck (accepted: unset; the decks' "
                     "supply falls on the plate)");
  }
  if (s.until_rest) {
    throw InputError("recoater.until-rest: true with --export-deck (accepted: false; the decks "
                     "settle for the fixed recoater.settle)");
  }
  SpreadDeckRequest r;
  r.engine = bed::parse_deck_engine(engine, "--export-deck");
  r.first = (restart ? restart->layers_done : 0) + 1;
  if (restart) r.floor = restart->floor;
  const std::size_t supplied = dem::add_layer_supply(bed, s, r.floor, r.first);
  set_spread_provenance(bed, vm, scene, "deposit", argc, argv);
  const bed::Psd psd = bed::Psd::parse(required<std::string>(vm, "psd"), "--psd");
  r.bed = &bed;
  r.scene = &scene;
  r.settings = &s;
  r.psd = &psd;
  r.seed = seed;
  r.layers = vm["layers"].as<std::uint64_t>();
  r.dt = restart ? restart->dt : spread_time_step(bed, scene, s);
  // Layers 2.. of the deck (layer 1's supply is in the bed).
  const SupplyAmount later = supply_amount(vm, 2, bed.domain.length(1));
  r.supply_count = later.count;
  r.supply_volume = later.volume;
  r.made_by = "the deposit scene of " + out;
  const std::string data = deck_data_file(out);
  write_spread_deck(r, data);
  const bool lammps = r.engine == bed::DeckEngine::lammps;
  std::cout << fmt::format("deposit: wrote the {} deck of {} layer(s) from layer {} ({} particles, "
                           "{} supplied, dt {:g} s): {} and {}{}; run it in its folder (docs/decks.md)\n",
                           lammps ? "LAMMPS" : "LIGGGHTS", r.layers, r.first, bed.n(), supplied, r.dt, data,
                           bed::deck_files(data, r.engine).input,
                           lammps ? "" : " and " + bed::spread_tool_stl(data));
  return 0;
}

}  // namespace

int spread_command(const po::variables_map& vm, const DepositOptions& bound, int argc, char** argv) {
  const std::string out = required<std::string>(vm, "out");
  const auto seed = required<std::uint64_t>(vm, "seed");
  refuse_drop_options(vm);
  const std::optional<std::string> forces_path = tool_forces_path(vm);
  const auto layers = vm["layers"].as<std::uint64_t>();
  check_spread_paths(vm, out);
  if (layers == 0) throw InputError("--layers: 0 (accepted: N >= 1)");
  if (vm.count("export-deck")) return export_spread_deck(vm, bound, seed, out, argc, argv);

  std::optional<dem::SpreadState> restart;
  bed::Bed bed = spread_input(vm, restart);
  const dem::Scene scene = deposit_scene(vm, bound.scene);
  std::shared_ptr<ThermoTable> table;
  dem::SpreadSettings s = spread_settings(vm, bound.spread, seed, &table);
  s.threads = apply_thread_team(vm).size;
  std::ostringstream forces;
  forces << std::setprecision(17) << "layer,time,x,fx,fy,fz\n";
  if (forces_path) {
    s.tool_force_every = vm["tool-forces-every"].as<std::uint64_t>();
    if (s.tool_force_every == 0) throw InputError("--tool-forces-every: 0 (accepted: K >= 1 steps)");
    s.tool_force = [&forces](const dem::ToolForceSample& f) {
      forces << f.layer << ',' << f.time << ',' << f.x << ',' << f.force[0] << ',' << f.force[1]
             << ',' << f.force[2] << '\n';
    };
  }
  ProgressBar bar("deposit", progress_interval(vm));
  const std::uint64_t first_layer = (restart ? restart->layers_done : 0) + 1;
  std::uint64_t layer_now = first_layer;
  s.progress = [&](double fraction, double kinetic_energy) {  // of the layer; the bar: the run's
    const double done = static_cast<double>(layer_now - first_layer) + fraction;
    char detail[64];
    std::snprintf(detail, sizeof detail, "layer %llu  KE = %.2e J",
                  static_cast<unsigned long long>(layer_now), kinetic_energy);
    bar.draw(done / static_cast<double>(layers), detail);
  };
  const auto write = [&](const bed::Bed& b, const std::string& path, const dem::SpreadState& st) {
    bed::Bed copy = b;
    set_spread_provenance(copy, vm, scene, "deposit", argc, argv);
    dem::write_spread_bed(path, copy, st);
  };
  if (layers > 1) {
    s.layer_done = [&](const dem::LayerSummary& l, const bed::Bed& b, const dem::SpreadState& st) {
      write(b, layer_path(out, l.layer), st);
      layer_now = l.layer + 1;
    };
  }
  const dem::SpreadSummary r = dem::run_spread(bed, scene, s, restart ? &*restart : nullptr);
  bar.finish();
  const std::size_t lost = check_spread_result(vm, r, bed);
  bed::CommitTogether together;  // out.h5 and the tool forces replace the old ones together
  write(bed, out, r.state);
  if (forces_path) bed::write_text_file(*forces_path, forces.str());
  together.commit();
  const std::string summary = spread_summary(vm, r, scene, s, bed, lost, out);
  std::cout << summary;
  if (table) table->summary(summary);
  return 0;
}

}  // namespace powderbed::app
