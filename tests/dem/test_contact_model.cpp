// The spreading engine's composed contact (dem/src/contact_model.hpp): a model whose contacts
// neither turn the particles nor keep a history runs its pair pass as a batch
// (contact_kernel.hpp) instead of a call per contact; the batch must be that contact, bit for
// bit, and a run on it the same on any number of threads.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "beds.hpp"
#include "contact_model.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/dem/spread.hpp"

using namespace powderbed;

namespace {

dem::Scene drop_scene(dem::ContactLaw law, bool damping, bool friction) {
  dem::Scene scene = test::scene_with(dem::kGravity | dem::kHertz | dem::kWalls |
                                      (damping ? dem::kDamping : 0u) | (friction ? dem::kFriction : 0u));
  scene.law = law;
  scene.stiffness = 50.0;
  return scene;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

// 200 random contacts (overlaps up to 2 % of R*, approach and tangential velocities of either
// sign) through the batch and through the model's per-contact force: the same bits, for each
// law with and without damping and friction.
TEST(ContactModel, BatchIsTheContactBitForBit) {
  for (const auto law : {dem::ContactLaw::hertz, dem::ContactLaw::linear})
    for (const bool damping : {false, true})
      for (const bool friction : {false, true}) {
        const auto model = dem::detail::choose_contact_model(drop_scene(law, damping, friction), false);
        ASSERT_NE(model.batch, nullptr);
        const dem::detail::ContactPartners partners{1e8, 4e7, 50.0, 10e-6, 3e-11, 1e-21};
        const auto k = model.constants(model.coefficients, partners);
        bed::Rng rng(7);
        constexpr std::size_t m = 200;
        std::vector<double> dx(m), dy(m), dz(m), reach(m, 20e-6), el(m, k.elastic), da(m, k.damping), vx(m), vy(m),
            vz(m), fx(m), fy(m), fz(m);
        for (std::size_t c = 0; c < m; ++c) {
          const double d = reach[c] * (1.0 - bed::uniform(rng, 0.0, 0.02));
          const double t = bed::uniform(rng, 0.0, 3.1), p = bed::uniform(rng, 0.0, 6.2);
          dx[c] = d * std::sin(t) * std::cos(p);
          dy[c] = d * std::sin(t) * std::sin(p);
          dz[c] = d * std::cos(t);
          vx[c] = bed::uniform(rng, -0.1, 0.1);
          vy[c] = bed::uniform(rng, -0.1, 0.1);
          vz[c] = bed::uniform(rng, -0.1, 0.1);
        }
        model.batch(m, model.coefficients.sliding, dx.data(), dy.data(), dz.data(), reach.data(), el.data(),
                    da.data(), vx.data(), vy.data(), vz.data(), fx.data(), fy.data(), fz.data());
        for (std::size_t c = 0; c < m; ++c) {
          const double dist = std::sqrt(dx[c] * dx[c] + dy[c] * dy[c] + dz[c] * dz[c]), inv = 1.0 / dist;
          const double n[3] = {dx[c] * inv, dy[c] * inv, dz[c] * inv}, dv[3] = {vx[c], vy[c], vz[c]};
          const double still[3] = {0, 0, 0};
          double h[dem::detail::kContactHistory] = {};
          dem::detail::ContactForce out;
          model.force(model.coefficients, k, reach[c] - dist, n, dv, still, still, 0, 0, h, true, out);
          EXPECT_TRUE(same_bits(out.f[0], fx[c]) && same_bits(out.f[1], fy[c]) && same_bits(out.f[2], fz[c]))
              << "law " << static_cast<int>(law) << " damping " << damping << " friction " << friction
              << " contact " << c << ": " << out.f[2] << " against " << fz[c];
        }
      }
}

// Models that turn the particles or keep a history have no batch.
TEST(ContactModel, RotatingModelsDoNotBatch) {
  dem::Scene scene = drop_scene(dem::ContactLaw::hertz, true, true);
  EXPECT_EQ(dem::detail::choose_contact_model(scene, true).batch, nullptr);  // sliding at the contact point
  scene.friction_model = dem::FrictionModel::history;
  EXPECT_EQ(dem::detail::choose_contact_model(scene, true).batch, nullptr);
}

// A spreading-engine run on the batch (particles that do not turn, every drop effect) gives the
// same bed bit for bit on 1 and 2 threads: the parallel batch stores each contact's force for
// the per-particle gather, which sums in the serial loop's order.
TEST(ContactModel, BatchedRunIsTheSameOnTwoThreads) {
  bed::Bed start = test::box_bed(2e-4, 2e-4, 4e-4);
  const double lo[3] = {0, 0, 0}, hi[3] = {2e-4, 2e-4, 2e-4};
  test::add_random(start, 40, 10e-6, 20e-6, lo, hi, 11);
  dem::Scene scene = drop_scene(dem::ContactLaw::hertz, true, true);
  scene.gravity = 1e3;  // brings the particles together within the short run
  dem::SpreadSettings run;
  run.with_tool = false;
  run.rotation = false;
  run.t_end = 3e-4;
  run.dt = 2e-8;
  run.young_scale = 1e3;
  run.threads = 1;
  bed::Bed one = start, two = start;
  dem::run_spread(one, scene, run);
  run.threads = 2;
  run.parallel_min_particles = 0;
  dem::run_spread(two, scene, run);
  EXPECT_EQ(one.x, two.x);
  EXPECT_EQ(one.z, two.z);
  EXPECT_EQ(one.vz, two.vz);
  EXPECT_NE(one.z, start.z);  // it ran
}
