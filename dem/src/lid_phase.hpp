#pragma once
// The lid of the consolidation step (solver.hpp LidSettings; [KE], docs/physics.md §6): the
// box's top face, moved between steps, lowered onto the bed, held, then released (the bed
// relaxes) or kept as the bed's top face. One code for every engine that runs a drop: `Run`
// gives the engine's side,
//   RunSummary& summary(); bool stopped() const; double time() const; double dt() const;
//   const bed::Bed& bed() const; std::size_t count() const (the particles in the box);
//   Box& box(); void set_top_velocity(double v); void keep_top(double z) (the bed's top face);
//   const RunSettings& settings() const;
//   void top_reset()  (the lid has jumped: every particle that can touch it found anew);
//   void top_moved()  (the lid has moved a step: the same, when it may have come into reach);
//   double top_force() (the bed's force on the lid now, N);
//   bool advance(steps, until_rest, before, after): `steps` more steps, before() ahead of each,
//     after() after it (true ends them); with until_rest, until the bed rests (then true).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "box.hpp"
#include "powderbed/dem/solver.hpp"

namespace powderbed::dem::detail {

template <class Run>
class LidPhase {
 public:
  explicit LidPhase(Run& run)
      : run_(run), lid_(run.settings().lid), out_(run.summary().lid), box_(run.box()), top_(box_.upper[2]) {}

  void run() {
    run_.summary().lid_used = true;
    out_.released = lid_.release;
    lower();
    if (!run_.stopped()) hold();
    if (!lid_.release) {  // the lid stays: it is the bed's top face from now on
      run_.keep_top(box_.upper[2]);
      run_.summary().at_rest = false;
      return;
    }
    release();
    if (run_.stopped()) return;
    run_.top_reset();
    const auto relax_steps = static_cast<std::uint64_t>(std::ceil(lid_.relax / run_.dt() - 1e-9));
    run_.summary().at_rest = run_.advance(relax_steps, true, [] {}, [] { return false; });
  }

 private:
  // The held lid's servo (LidSettings::hold): full speed once the force is 10 % off the target.
  static constexpr double kServoGain = 10;

  // Where the lowering starts (the highest particle top) and how far it may go: to the target
  // force, the travel or depth asked for, or one smallest diameter above the floor.
  void plan_travel() {
    const bed::Bed& bed = run_.bed();
    const std::size_t n = run_.count();
    double highest = box_.lower[2], r_min = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      highest = std::max(highest, bed.z[i] + bed.radius[i]);
      r_min = std::min(r_min, bed.radius[i]);
    }
    out_.start_z = std::min(top_, highest);
    out_.target_force = lid_.pressure * box_.length[0] * box_.length[1];
    // No bed is thinner than one particle: the lid stops one smallest diameter above the floor.
    floor_travel_ = std::max(0.0, out_.start_z - (box_.lower[2] + 2 * r_min));
    requested_ = lid_.travel;
    if (lid_.depth > 0) {  // to `depth` below the surface, the 90th percentile of the tops
      std::vector<double> tops(n);
      for (std::size_t i = 0; i < n; ++i) tops[i] = bed.z[i] + bed.radius[i];
      const auto k = tops.begin() + static_cast<std::ptrdiff_t>(0.9 * static_cast<double>(n - 1));
      std::nth_element(tops.begin(), k, tops.end());
      out_.surface_z = *k;
      requested_ = std::max(0.0, out_.start_z - (out_.surface_z - lid_.depth));
    }
    travel_ = requested_ > 0 ? std::min(requested_, floor_travel_) : floor_travel_;
    per_step_ = lid_.speed * run_.dt();
  }

  void lower() {
    plan_travel();
    box_.upper[2] = out_.start_z;
    run_.top_reset();
    std::uint64_t lowered = 0;
    const auto move = [&] {
      ++lowered;
      box_.upper[2] = out_.start_z - std::min(travel_, static_cast<double>(lowered) * per_step_);
      run_.top_moved();
    };
    const auto lowered_enough = [&] {
      out_.stop_force = record();
      if (out_.target_force > 0 && out_.stop_force >= out_.target_force) {
        out_.stopped_by = "force";
      } else if (static_cast<double>(lowered) * per_step_ >= travel_) {
        out_.stopped_by = requested_ > 0 && requested_ <= floor_travel_
                              ? (lid_.depth > 0 ? "depth" : "travel")
                              : "floor";
      }
      return !out_.stopped_by.empty();
    };
    run_.set_top_velocity(-lid_.speed);
    const auto lowering_steps = static_cast<std::uint64_t>(std::ceil(travel_ / per_step_)) + 1;
    run_.advance(lowering_steps, false, move, lowered_enough);
    if (out_.stopped_by.empty()) out_.stopped_by = "floor";  // travel 0: the lid could not move
    out_.stop_z = box_.upper[2];
    run_.set_top_velocity(0);
  }

  // Held for lid.hold: with a pressure by the servo of LidSettings::hold, never below the floor
  // limit, never above where the lid started; in place otherwise.
  void hold() {
    const auto hold_steps = static_cast<std::uint64_t>(std::ceil(lid_.hold / run_.dt() - 1e-9));
    double late_sum = 0;
    std::uint64_t taken = 0, late = 0;
    const auto track = [&] {
      out_.hold_end_force = record();
      if (2 * ++taken >= hold_steps) {  // the second half of the hold
        late_sum += out_.hold_end_force;
        ++late;
      }
      return false;
    };
    const double lowest = out_.start_z - floor_travel_;
    const auto servo = [&] {
      const double error = (out_.target_force - out_.hold_end_force) / out_.target_force;
      const double v = lid_.speed * std::clamp(kServoGain * error, -1.0, 1.0);
      box_.upper[2] = std::clamp(box_.upper[2] - v * run_.dt(), lowest, top_);
      run_.set_top_velocity(-v);
      run_.top_moved();
    };
    out_.hold_end_force = out_.stop_force;
    if (out_.target_force > 0)
      run_.advance(hold_steps, false, servo, track);
    else
      run_.advance(hold_steps, false, [] {}, track);
    run_.set_top_velocity(0);
    out_.hold_end_z = box_.upper[2];
    out_.hold_late_force = late ? late_sum / static_cast<double>(late) : out_.hold_end_force;
  }

  // Raised back to the top of the box at lid.speed ([KE]: "raised again"), so that the bed
  // unloads as slowly as it was loaded; at once, a bed pressed on stiff linear springs throws
  // its top layers up.
  void release() {
    out_.release_time = run_.time();
    run_.set_top_velocity(lid_.speed);
    const auto raise = [&] {
      box_.upper[2] = std::min(top_, box_.upper[2] + per_step_);
      run_.top_moved();
    };
    const auto raised = [&] {
      record();
      return box_.upper[2] >= top_;
    };
    const auto raising_steps =
        static_cast<std::uint64_t>(std::ceil((top_ - box_.upper[2]) / per_step_)) + 1;
    if (!run_.stopped()) run_.advance(raising_steps, false, raise, raised);
    run_.set_top_velocity(0);
    box_.upper[2] = top_;
  }

  // The bed's force on the lid now (its largest so far kept).
  double record() {
    const double force = run_.top_force();
    out_.max_force = std::max(out_.max_force, force);
    return force;
  }

  Run& run_;
  const LidSettings& lid_;
  LidSummary& out_;
  Box& box_;
  double top_;                 // m, the box's top face
  double floor_travel_ = 0, requested_ = 0, travel_ = 0, per_step_ = 0;  // m
};

}  // namespace powderbed::dem::detail
