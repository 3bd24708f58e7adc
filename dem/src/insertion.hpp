#pragma once
// The insertion of Kumar Yadav & Eshraghi [KE] 2016 (solver.hpp InsertionSettings): the pool's
// particles, in order, enter one by one at `rate` per second (the first at t = 0), each at a
// free uniform random spot of the box's top layer, moving down at `speed`; the box is full once
// insertion has failed for `patience` s in a row. One code for every engine that runs a drop:
// `Run` gives the engine's side,
//   const RunSettings& settings() const; const Scene& scene() const; RunSummary& summary();
//   double time() const; const Box& box() const;
//   const bed::Bed& pool() const (every particle, in the order they enter);
//   std::size_t inserted() const; const bed::Bed& bed() const (the particles in: its first
//     inserted() particles, at their places);
//   void place(std::size_t k, const double p[3], double vz) (pool particle k enters at p with
//     velocity (0, 0, vz));
//   void entered() (after a step's particles entered: the neighbour list anew);
//   void set_inserting(bool) (rest is not tested while particles enter);
//   void end_insertion() (the pool's rest dropped: the bed is the particles in);
//   void set_rest_energy(double J) (the rest test's default energy, of the particles in).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "box.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/dem/solver.hpp"

namespace powderbed::dem::detail {

template <class Run>
class Insertion {
 public:
  Insertion(Run& run, double r_max)
      : run_(run), ins_(run.settings().insertion), r_max_(r_max), rng_(ins_.seed) {
    // Time a new particle needs to fall one largest diameter (from `speed`, under gravity), twice.
    const double g = run.scene().has(kGravity) ? run.scene().gravity : 0.0;
    const double v = ins_.speed;
    const double fall = g > 0 ? (std::sqrt(v * v + 2 * g * 2 * r_max) - v) / g : 2 * r_max / v;
    patience_ = ins_.patience > 0 ? ins_.patience : 2 * fall;
    active_ = ins_.enabled;
    run.set_inserting(active_);
    if (active_) try_insert();
  }

  bool active() const { return active_; }

  // Before each step: the particles due by now (one at t = 0, then `rate` per second) enter
  // while there is room; insertion ends with the pool in or the box full.
  void insert_due() {
    if (!active_) return;
    const double time = run_.time();
    const std::size_t pool = run_.pool().n();
    const auto due = std::min<std::size_t>(pool, 1 + static_cast<std::size_t>(std::floor(ins_.rate * time)));
    const std::size_t before = run_.inserted();
    while (run_.inserted() < due) {
      if (try_insert()) {
        failing_since_ = kNotFailing;
        continue;
      }
      if (failing_since_ == kNotFailing) failing_since_ = time;
      break;
    }
    if (run_.inserted() != before) run_.entered();
    if (run_.inserted() == pool) {
      end("pool", time);
    } else if (failing_since_ != kNotFailing && time - failing_since_ >= patience_) {
      end("full", time);
    }
  }

  // Ends insertion: the pool's rest is dropped, the bed is the inserted particles, and the rest
  // test's default energy is theirs.
  void end(const char* why, double time) {
    active_ = false;
    run_.set_inserting(false);
    RunSummary& summary = run_.summary();
    summary.inserted = run_.inserted();
    summary.insertion_end = time;
    summary.insertion_stopped_by = why;
    run_.end_insertion();
    if (run_.settings().rest.kinetic_energy > 0) return;
    double mass = 0;  // physical: what gravity acts on and the kinetic energy counts
    const bed::Bed& bed = run_.bed();
    const double density = run_.scene().material.density;
    for (std::size_t i = 0; i < run_.inserted(); ++i) mass += bed::sphere_volume(bed.radius[i]) * density;
    const double v = run_.settings().rest.max_speed;
    run_.set_rest_energy(1e-2 * 0.5 * mass * v * v);
  }

 private:
  static constexpr double kNotFailing = -1;

  // The next particle of the pool at a free spot of the top layer (one largest diameter under
  // the top face, inside the side faces), moving down at `speed`; false after `tries` draws.
  bool try_insert() {
    const std::size_t k = run_.inserted(), n = k;
    const bed::Bed& bed = run_.bed();
    const double r = run_.pool().radius[k];
    const Box& box = run_.box();
    double lo[3], hi[3];
    for (int a = 0; a < 2; ++a) {
      lo[a] = box.lower[a] + (box.periodic[a] ? 0.0 : r);
      hi[a] = box.upper[a] - (box.periodic[a] ? 0.0 : r);
    }
    lo[2] = box.upper[2] - 2 * r_max_ + r;
    hi[2] = box.upper[2] - r;
    for (std::size_t t = 0; t < ins_.tries; ++t) {
      const double p[3] = {bed::uniform(rng_, lo[0], hi[0]), bed::uniform(rng_, lo[1], hi[1]),
                           bed::uniform(rng_, lo[2], hi[2])};
      bool free = true;
      for (std::size_t j = 0; j < n && free; ++j) {
        const double dx = box.image(0, bed.x[j] - p[0]), dy = box.image(1, bed.y[j] - p[1]),
                     dz = bed.z[j] - p[2], reach = r + bed.radius[j];
        free = dx * dx + dy * dy + dz * dz >= reach * reach;
      }
      if (!free) continue;
      run_.place(k, p, -ins_.speed);
      return true;
    }
    return false;
  }

  Run& run_;
  const InsertionSettings& ins_;
  double r_max_;
  bed::Rng rng_;
  double patience_ = 0;
  bool active_ = false;
  double failing_since_ = kNotFailing;  // start of the current run of failed insertions
};

}  // namespace powderbed::dem::detail
