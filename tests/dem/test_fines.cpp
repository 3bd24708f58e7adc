// Scaling of the fines (fines_scaling.hpp, docs/physics.md §4 "Fines"): the factor, the time-step
// bound it gives (the Rayleigh step and the drag relaxation of a particle of R_ref), gravity and
// drag on the physical mass under mass scaling, the pair and wall E* of stiffness-scaled fines
// against Hertz's closed forms, runs that scale nothing equal to runs without scaling bit for
// bit (on the drop and on the spreading engine), and the bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "beds.hpp"
#include "powderbed/bed/errors.hpp"
#include "powderbed/dem/fines_scaling.hpp"
#include "powderbed/dem/hertz_normal.hpp"
#include "powderbed/dem/solver.hpp"
#include "powderbed/dem/spread.hpp"
#include "powderbed/dem/time_step.hpp"

using namespace powderbed;

namespace {

constexpr double kFine = 2e-6, kMiddle = 3e-6, kCoarse = 10e-6;  // radii, m
constexpr double kReference = 6e-6;                                // R_ref, m

dem::Scene fines_scene(unsigned effects, dem::FinesScaling scaling, double reference) {
  dem::Scene s = test::scene_with(effects);
  s.fines = {scaling, reference};
  return s;
}

// The two engines a scene runs on: the drop solver, and the spreading solver as a granular run
// without a tool (what deposit's drops with history friction or rolling use).
enum class Engine { drop, spread };
constexpr Engine kEngines[] = {Engine::drop, Engine::spread};
const char* engine_name(Engine e) { return e == Engine::drop ? "drop" : "spread"; }

void run_on(Engine engine, bed::Bed& b, const dem::Scene& scene, double t_end, double young_scale = 1) {
  if (engine == Engine::drop) {
    dem::RunSettings run;
    run.t_end = t_end;
    run.young_scale = young_scale;
    dem::run_deposition(b, scene, run);
  } else {
    dem::SpreadSettings spread;
    spread.with_tool = false;
    spread.t_end = t_end;
    spread.young_scale = young_scale;
    dem::run_spread(b, scene, spread);
  }
}

bed::Bed three_sizes() {
  bed::Bed b = test::box_bed(1e-4, 1e-4, 1e-4);
  b.add(2e-5, 5e-5, 5e-5, kFine);
  b.add(5e-5, 5e-5, 5e-5, kMiddle);
  b.add(8e-5, 5e-5, 5e-5, kCoarse);
  return b;
}

TEST(Fines, FactorIsTheSquaredRadiusRatioBelowTheReference) {
  EXPECT_DOUBLE_EQ(dem::fines_factor(kFine, kReference), 9.0);
  EXPECT_EQ(dem::fines_factor(kReference, kReference), 1.0);
  EXPECT_EQ(dem::fines_factor(kCoarse, kReference), 1.0);
  const dem::Fines mass{dem::FinesScaling::mass, kReference};
  const dem::Fines stiffness{dem::FinesScaling::stiffness, kReference};
  EXPECT_DOUBLE_EQ(dem::fines_mass_factor(mass, kFine), 9.0);
  EXPECT_EQ(dem::fines_stiffness_factor(mass, kFine), 1.0);
  EXPECT_DOUBLE_EQ(dem::fines_stiffness_factor(stiffness, kFine), 1.0 / 9.0);
  EXPECT_EQ(dem::fines_mass_factor(stiffness, kFine), 1.0);
}

// Either scaling gives the fines the Rayleigh step of R_ref: t_R grows as r sqrt(rho / E).
TEST(Fines, BoundIsTheRayleighStepOfTheReferenceRadius) {
  const bed::Bed b = three_sizes();
  const double young_scale = 1e3;
  const dem::Material m;
  const double reference = dem::rayleigh_time_step(kReference, m.density, m.young / young_scale,
                                                   m.poisson);
  for (const auto scaling : {dem::FinesScaling::mass, dem::FinesScaling::stiffness}) {
    const dem::Scene scene = fines_scene(dem::kHertz | dem::kWalls, scaling, kReference);
    const dem::TimeStepBound bound = dem::time_step_bound(b, scene, young_scale);
    EXPECT_NEAR(bound.stable, reference, 1e-12 * reference) << dem::fines_scaling_name(scaling);
    EXPECT_STREQ(bound.limited_by, "rayleigh");
    EXPECT_LT(bound.limiting_radius, kReference);
  }
  const dem::Scene none = fines_scene(dem::kHertz | dem::kWalls, dem::FinesScaling::none, 0);
  const dem::TimeStepBound plain = dem::time_step_bound(b, none, young_scale);
  EXPECT_EQ(plain.stable, dem::rayleigh_time_step(kFine, m.density, m.young / young_scale, m.poisson));
  EXPECT_EQ(plain.limiting_radius, kFine);
  // A reference below every radius scales nothing: the bound of no scaling, to the bit.
  const dem::Scene below = fines_scene(dem::kHertz | dem::kWalls, dem::FinesScaling::mass, 1e-6);
  EXPECT_EQ(dem::time_step_bound(b, below, young_scale).stable, plain.stable);
}

// Drag acts on the particle's own radius, so the relaxation m s / (6 pi mu r) of a mass-scaled
// fine is 2 rho R_ref^2 / (9 mu), that of R_ref; stiffness scaling leaves it at the fine's.
TEST(Fines, DragRelaxationUsesTheScaledMass) {
  const bed::Bed b = three_sizes();
  const dem::Scene s;
  const auto relaxation = [&](double r) { return 2 * s.material.density * r * r / (9 * s.fluid_viscosity); };
  const dem::Scene mass = fines_scene(dem::kDrag | dem::kGravity, dem::FinesScaling::mass, kReference);
  const dem::TimeStepBound scaled = dem::time_step_bound(b, mass, 1);
  EXPECT_NEAR(scaled.stable, relaxation(kReference), 1e-12 * relaxation(kReference));
  EXPECT_STREQ(scaled.limited_by, "drag");
  const dem::Scene stiffness =
      fines_scene(dem::kDrag | dem::kGravity, dem::FinesScaling::stiffness, kReference);
  EXPECT_NEAR(dem::time_step_bound(b, stiffness, 1).stable, relaxation(kFine),
              1e-12 * relaxation(kFine));
}

// One particle of radius kFine alone in a tall box under the scene's body forces.
bed::Bed lone_fine() {
  bed::Bed b = test::box_bed(1e-4, 1e-4, 1e-2);
  b.add(5e-5, 5e-5, 9e-3, kFine);
  return b;
}

// Gravity acts on the physical mass (docs/physics.md §4 "Fines"): a mass-scaled fine in vacuum
// falls at g / s, and with drag it reaches its physical Stokes speed 2 r^2 rho g / (9 mu).
TEST(Fines, MassScaledFineFallsUnderItsPhysicalWeight) {
  const double s = dem::fines_factor(kFine, kReference);
  const dem::Scene vacuum = fines_scene(dem::kGravity, dem::FinesScaling::mass, kReference);
  bed::Bed b = lone_fine();
  dem::RunSettings run;
  run.dt = 1e-6;
  run.t_end = 1e-3;
  dem::run_deposition(b, vacuum, run);
  const double g = vacuum.gravity;
  EXPECT_NEAR(b.vz[0], -g * run.t_end / s, 1e-9 * g * run.t_end);
  const dem::Scene air = fines_scene(dem::kGravity | dem::kDrag, dem::FinesScaling::mass, kReference);
  bed::Bed c = lone_fine();
  run.dt = 0;  // the automatic step: 0.2 of the scaled relaxation time
  run.t_end = 20 * dem::time_step_bound(c, air, 1).stable;  // 20 relaxation times
  dem::run_deposition(c, air, run);
  const double stokes = 2 * kFine * kFine * air.material.density * g / (9 * air.fluid_viscosity);
  EXPECT_NEAR(c.vz[0], -stokes, 1e-6 * stokes);
}

// The largest overlap of a fine (E / s) and a coarse particle (E) meeting head on at relative
// speed v without damping, against Hertz's delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^{2/5}
// with E* = 1 / ((1 - nu^2)/E_i + (1 - nu^2)/E_j).
TEST(Fines, StiffnessScaledPairTakesEStarOfBothModuli) {
  const double v = 1.0;
  bed::Bed b = test::box_bed(1e-4, 1e-4, 1e-4);
  test::add_moving(b, 5e-5 - kFine - 1e-8, 5e-5, 5e-5, kFine, v / 2, 0, 0);
  test::add_moving(b, 5e-5 + kCoarse, 5e-5, 5e-5, kCoarse, -v / 2, 0, 0);
  const dem::Scene scene = fines_scene(dem::kHertz, dem::FinesScaling::stiffness, kReference);
  dem::RunSettings run;
  run.dt = 1e-3 * dem::time_step_bound(b, scene, 1).stable;
  run.t_end = 6e-8;
  double deepest = 0;
  run.observer = [&](std::uint64_t, double, const bed::Bed& bb) {
    deepest = std::max(deepest, kFine + kCoarse - (bb.x[1] - bb.x[0]));
    return false;
  };
  dem::run_deposition(b, scene, run);
  const dem::Material& m = scene.material;
  const double fine_young = m.young / dem::fines_factor(kFine, kReference);
  const double e_star = dem::effective_modulus(fine_young, m.poisson, m.young, m.poisson);
  const double mi = test::sphere_mass(kFine, m.density), mj = test::sphere_mass(kCoarse, m.density);
  const double m_star = mi * mj / (mi + mj), r_star = kFine * kCoarse / (kFine + kCoarse);
  const double expected = std::pow(15 * m_star * v * v / (16 * e_star * std::sqrt(r_star)), 0.4);
  EXPECT_NEAR(deepest, expected, 1e-3 * expected);
}

// A fine at rest on the floor: the Hertz overlap (3 m g / (4 E* sqrt(r)))^{2/3} with the wall's
// E* of the fine's scaled E and the wall's E (stiffness), or of the scene's E* and the physical
// weight (mass: the scaled inertia does not load the contact). On both engines.
TEST(Fines, FineAtRestOnTheFloorCarriesItsPhysicalWeight) {
  const unsigned effects = dem::kGravity | dem::kWalls | dem::kDamping;
  for (const Engine engine : kEngines)
    for (const auto scaling : {dem::FinesScaling::mass, dem::FinesScaling::stiffness}) {
      dem::Scene scene = fines_scene(effects, scaling, kReference);
      scene.material.damping = 0.5;
      bed::Bed b = test::box_bed(1e-4, 1e-4, 1e-4);
      b.add(5e-5, 5e-5, kFine, kFine);
      run_on(engine, b, scene, 2e-5);
      const dem::Material& m = scene.material;
      const double young = m.young * dem::fines_stiffness_factor(scene.fines, kFine);
      const double e_star = dem::effective_modulus(young, m.poisson, scene.wall.young, scene.wall.poisson);
      const double weight = test::sphere_mass(kFine, m.density) * scene.gravity;
      const double expected = std::pow(3 * weight / (4 * e_star * std::sqrt(kFine)), 2.0 / 3.0);
      EXPECT_NEAR(kFine - b.z[0], expected, 1e-4 * expected)
          << engine_name(engine) << " " << dem::fines_scaling_name(scaling);
    }
}

// A drop of 60 particles of 2-10 um with every effect on, under a gravity of 1e4 m/s^2 that
// brings them onto the floor and each other within the run's 2e-4 s. On the spreading engine
// with history friction and rolling resistance, which it alone has.
bed::Bed small_drop(dem::Scene scene, Engine engine) {
  scene.gravity = 1e4;
  if (engine == Engine::spread) {
    scene.friction_model = dem::FrictionModel::history;
    scene.material.rolling = 0.1;
  }
  bed::Bed b = test::box_bed(1e-4, 1e-4, 1e-4);
  const double lo[3] = {0, 0, 0}, hi[3] = {1e-4, 1e-4, 1e-4};
  test::add_random(b, 60, kFine, kCoarse, lo, hi, 7);
  run_on(engine, b, scene, 2e-4, 1e3);
  return b;
}

// With a reference below every radius nothing is scaled, and the scaled code paths (the
// per-particle moduli of the contacts, the separate weights) must give the run without
// scaling to the bit.
TEST(Fines, ScalingNothingIsBitForBitNoScaling) {
  for (const Engine engine : kEngines) {
    const bed::Bed plain = small_drop(fines_scene(dem::kAllEffects, dem::FinesScaling::none, 0), engine);
    for (const auto scaling : {dem::FinesScaling::mass, dem::FinesScaling::stiffness}) {
      const bed::Bed scaled = small_drop(fines_scene(dem::kAllEffects, scaling, 1e-6), engine);
      EXPECT_EQ(scaled.x, plain.x) << engine_name(engine) << " " << dem::fines_scaling_name(scaling);
      EXPECT_EQ(scaled.z, plain.z) << engine_name(engine) << " " << dem::fines_scaling_name(scaling);
      EXPECT_EQ(scaled.vz, plain.vz) << engine_name(engine) << " " << dem::fines_scaling_name(scaling);
    }
    // ... and scaling that does act changes the run (the comparison above can fail).
    for (const auto scaling : {dem::FinesScaling::mass, dem::FinesScaling::stiffness}) {
      const bed::Bed scaled = small_drop(fines_scene(dem::kAllEffects, scaling, kReference), engine);
      EXPECT_NE(scaled.z, plain.z) << engine_name(engine) << " " << dem::fines_scaling_name(scaling);
    }
  }
}

TEST(Fines, BadInputsNameTheOption) {
  EXPECT_THROW(dem::parse_fines_scaling("volume"), InputError);
  for (const double radius : {0.0, -1e-6, std::nan(""), HUGE_VAL}) {
    const dem::Scene s = fines_scene(dem::kAllEffects, dem::FinesScaling::mass, radius);
    try {
      s.validate();
      ADD_FAILURE() << "fines.radius " << radius << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("fines.radius"), std::string::npos) << e.what();
    }
  }
  dem::Scene linear = fines_scene(dem::kAllEffects, dem::FinesScaling::stiffness, kReference);
  linear.law = dem::ContactLaw::linear;
  linear.stiffness = 1e3;
  EXPECT_THROW(linear.validate(), InputError);
  linear.fines.scaling = dem::FinesScaling::mass;
  EXPECT_NO_THROW(linear.validate());
}

}  // namespace
