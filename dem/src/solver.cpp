// The deposition run of docs/physics.md §4 (solver.hpp): what run_deposition refuses, then the
// drop on the one engine (drop_on_engine.cpp).
#include "powderbed/dem/solver.hpp"

#include <cmath>
#include <fmt/format.h>
#include <string>

#include "box.hpp"
#include "drop_on_engine.hpp"
#include "powderbed/bed/errors.hpp"

namespace powderbed::dem {

Integrator parse_integrator(const std::string& text, const std::string& option) {
  return bed::parse_word(text, option, kIntegratorWords, "an integrator");
}

std::size_t remove_lost_particles(bed::Bed& bed) {
  const detail::Box box = detail::Box::from(bed.domain);
  std::size_t kept = 0;
  const bool vel = bed.has_velocity();
  const bool mat = !bed.material.empty(), temp = !bed.temperature.empty(),
             phase = !bed.phase.empty();
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double p[3] = {bed.x[i], bed.y[i], bed.z[i]};
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      inside = inside && (box.periodic[a] || (p[a] >= box.lower[a] && p[a] <= box.upper[a]));
    }
    if (!inside) continue;
    bed.x[kept] = bed.x[i];
    bed.y[kept] = bed.y[i];
    bed.z[kept] = bed.z[i];
    bed.radius[kept] = bed.radius[i];
    bed.id[kept] = bed.id[i];
    if (vel) {
      bed.vx[kept] = bed.vx[i];
      bed.vy[kept] = bed.vy[i];
      bed.vz[kept] = bed.vz[i];
    }
    if (mat) bed.material[kept] = bed.material[i];
    if (temp) bed.temperature[kept] = bed.temperature[i];
    if (phase) bed.phase[kept] = bed.phase[i];
    ++kept;
  }
  const std::size_t removed = bed.n() - kept;
  for (auto* v : {&bed.x, &bed.y, &bed.z, &bed.radius}) v->resize(kept);
  bed.id.resize(kept);
  if (vel) {
    bed.vx.resize(kept);
    bed.vy.resize(kept);
    bed.vz.resize(kept);
  }
  if (mat) bed.material.resize(kept);
  if (temp) bed.temperature.resize(kept);
  if (phase) bed.phase.resize(kept);
  return removed;
}

namespace {

void check_bed(const bed::Bed& bed) {
  if (bed.domain.dimension != 3) {
    throw InputError("deposit: the bed is 2D (accepted: 3D beds only)");
  }
  if (bed.domain.periodic[2]) {
    throw InputError("--periodic: z cannot be periodic (accepted: x, y; gravity acts along z)");
  }
  const double lo[3] = {bed.domain.lower[0], bed.domain.lower[1], bed.domain.lower[2]};
  const double hi[3] = {bed.domain.upper[0], bed.domain.upper[1], bed.domain.upper[2]};
  for (std::size_t i = 0; i < bed.n(); ++i) {
    const double p[3] = {bed.x[i], bed.y[i], bed.z[i]};
    for (int a = 0; a < 3; ++a) {
      if (p[a] < lo[a] || p[a] > hi[a]) {
        throw InputError(fmt::format(
            "--in: particle id {} has {} = {:g} outside the domain [{:g}, {:g}] (accepted: every "
            "centre inside the domain)",
            bed.id[i], "xyz"[a], p[a], lo[a], hi[a]));
      }
    }
  }
}

void check_insertion(const InsertionSettings& ins, const RunSettings& s, const Scene& scene) {
  if (!ins.enabled) return;
  const auto require = require_in_range;  // bed/errors.hpp
  const auto finite = [](double v) { return std::isfinite(v); };
  require(finite(ins.rate) && ins.rate > 0, "insert.rate", ins.rate, "rate > 0 particles/s");
  require(finite(ins.speed) && ins.speed >= 0, "insert.speed", ins.speed, "speed >= 0 m/s");
  require(ins.tries >= 1, "insert.tries", static_cast<double>(ins.tries), "tries >= 1");
  require(finite(ins.patience) && ins.patience >= 0, "insert.patience", ins.patience,
          "patience >= 0 s");
  if (ins.patience == 0 && ins.speed == 0 && !(scene.has(kGravity) && scene.gravity > 0)) {
    throw InputError("insert.patience: 0 with neither an insertion speed nor gravity (accepted: "
                     "a patience > 0 s, an insert.speed > 0 or gravity)");
  }
  if (!s.trajectory.empty()) {
    throw InputError("--trajectory: with insertion (accepted: one or the other; the snapshots "
                     "have a fixed particle count)");
  }
}

void check_lid(const LidSettings& lid, const Scene& scene) {
  if (!lid.enabled) return;
  const auto require = require_in_range;  // bed/errors.hpp
  const auto finite = [](double v) { return std::isfinite(v); };
  require(finite(lid.speed) && lid.speed > 0, "lid.speed", lid.speed, "speed > 0 m/s");
  require(finite(lid.pressure) && lid.pressure >= 0, "lid.pressure", lid.pressure, "P >= 0 Pa");
  require(finite(lid.travel) && lid.travel >= 0, "lid.travel", lid.travel, "travel >= 0 m");
  require(finite(lid.hold) && lid.hold >= 0, "lid.hold", lid.hold, "hold >= 0 s");
  require(finite(lid.relax) && lid.relax >= 0, "lid.relax", lid.relax, "relax >= 0 s");
  require(finite(lid.depth) && lid.depth >= 0, "lid.depth", lid.depth, "depth >= 0 m");
  if (lid.depth > 0 && lid.travel > 0) {
    throw InputError("lid.depth / lid.travel: both set (accepted: one of them)");
  }
  if (!(lid.pressure > 0 || lid.travel > 0 || lid.depth > 0)) {
    throw InputError("lid.pressure / lid.travel / lid.depth: none set (accepted: a pressure > 0 "
                     "Pa, a travel or depth > 0 m, or a pressure with one of them)");
  }
  if (!scene.has(kWalls)) {
    throw InputError("lid: on with effects.walls off (accepted: the lid is the box's top wall; "
                     "turn effects.walls on)");
  }
}

// Everything run_deposition refuses, before any work.
void check_run(const bed::Bed& bed, const Scene& scene, const RunSettings& settings) {
  scene.validate();
  detail::refuse_rotation_with_rk4(scene, settings);
  bed.validate("deposit input bed");
  check_bed(bed);
  check_run_settings(settings);
  check_lid(settings.lid, scene);
  check_insertion(settings.insertion, settings, scene);
  if (scene.law == ContactLaw::linear && settings.young_scale != 1) {
    throw InputError(fmt::format(
        "--young-scale: {:g} with contact.law = linear (accepted: 1; the linear law's stiffness "
        "is contact.stiffness)",
        settings.young_scale));
  }
}

}  // namespace

void check_run_settings(const RunSettings& s) {
  const auto bad = [](const char* what, double v, const char* accepted) {
    throw InputError(fmt::format("{}: {:g} is out of range (accepted: {})", what, v, accepted));
  };
  if (!(s.t_end >= 0) || !std::isfinite(s.t_end)) bad("--t-end", s.t_end, "T >= 0 s");
  if (!s.until_rest && !(s.t_end > 0)) bad("--t-end", s.t_end, "T > 0 s, or --until-rest");
  if (!(s.dt >= 0) || !std::isfinite(s.dt)) bad("--dt", s.dt, "dt > 0 s");
  if (!(s.skin >= 0) || !std::isfinite(s.skin)) bad("skin", s.skin, ">= 0 m");
  if (!s.trajectory.empty() && s.trajectory_every == 0) {
    throw InputError("--every: 0 with --trajectory (accepted: K >= 1 steps)");
  }
  // Keys as deposit's options name them (rest.kinetic_energy has no option: library callers).
  if (!(s.rest.max_speed > 0) || !std::isfinite(s.rest.max_speed))
    bad("--rest.speed", s.rest.max_speed, "v > 0 m/s");
  if (!(s.rest.window >= 0) || !std::isfinite(s.rest.window))
    bad("--rest.window", s.rest.window, "window >= 0 s");
  if (!(s.rest.kinetic_energy >= 0)) bad("rest kinetic energy", s.rest.kinetic_energy, ">= 0 J");
}

RunSummary run_deposition(bed::Bed& bed, const Scene& scene, const RunSettings& settings) {
  check_run(bed, scene, settings);
  return detail::run_drop_on_engine(bed, scene, settings);
}

}  // namespace powderbed::dem
