// Bed statistics at scale (docs/physics.md §2): packing density and contact statistics on ~1e6
// particles, Laguerre tessellation on ~1e5, and the two neighbour-search back-ends side by side.
// Beds: FCC lattices (touching spheres, r = 1) jittered by up to 0.005 r per coordinate (seed 1),
// in a non-periodic box, so spheres cross every face, edge and corner of it (the exact-cap and
// quadrature paths of packing_density both run). Results: docs/results/bed-stats.md, from
//   build/bench/bench_bed_stats --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>

#include "powderbed/bed/neighbours.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/bed/stats.hpp"

namespace pb = powderbed::bed;

namespace {

// n^3 conventional cells (4 n^3 spheres of radius 1), built directly (Bed::add is O(N) per call).
pb::Bed jittered_fcc(int n) {
  const double r = 1.0, a = 2.0 * std::sqrt(2.0) * r, jitter = 0.005 * r;
  static const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  pb::Bed bed;
  bed.domain.upper = {n * a, n * a, n * a};
  bed.reserve(4 * static_cast<std::size_t>(n) * n * n);
  pb::Rng rng(1);
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        for (const auto& b : basis) {
          bed.id.push_back(bed.n());
          bed.x.push_back((i + b[0] + 0.25) * a + pb::uniform(rng, -jitter, jitter));
          bed.y.push_back((j + b[1] + 0.25) * a + pb::uniform(rng, -jitter, jitter));
          bed.z.push_back((k + b[2] + 0.25) * a + pb::uniform(rng, -jitter, jitter));
          bed.radius.push_back(r);
        }
      }
    }
  }
  return bed;
}

const pb::Bed& million() {
  static const pb::Bed bed = jittered_fcc(63);  // 1,000,188 spheres
  return bed;
}

const pb::Bed& hundred_thousand() {
  static const pb::Bed bed = jittered_fcc(29);  // 97,556 spheres
  return bed;
}

void BM_PackingDensity_1e6(benchmark::State& state) {
  const pb::Bed& bed = million();
  for (auto _ : state) benchmark::DoNotOptimize(pb::packing_density(bed));
  state.counters["particles"] = static_cast<double>(bed.n());
  state.counters["phi"] = pb::packing_density(bed);
}

void BM_ContactStats_1e6(benchmark::State& state) {
  const pb::Bed& bed = million();
  pb::ContactStats s;
  for (auto _ : state) {
    s = pb::contact_stats(bed, 1e-2);
    benchmark::DoNotOptimize(s.coordination);
  }
  state.counters["particles"] = static_cast<double>(bed.n());
  state.counters["Z_tol1e-2"] = s.coordination;
}

// The headline figure: both statistics a bed report needs, together.
void BM_DensityAndContacts_1e6(benchmark::State& state) {
  const pb::Bed& bed = million();
  for (auto _ : state) {
    benchmark::DoNotOptimize(pb::packing_density(bed));
    benchmark::DoNotOptimize(pb::contact_stats(bed, 1e-2).coordination);
  }
  state.counters["particles"] = static_cast<double>(bed.n());
}

void BM_Voronoi_1e5(benchmark::State& state) {
  const pb::Bed& bed = hundred_thousand();
  pb::VoronoiStats v;
  for (auto _ : state) {
    v = pb::voronoi_stats(bed);
    benchmark::DoNotOptimize(v.mean);
  }
  state.counters["particles"] = static_cast<double>(bed.n());
  state.counters["interior"] = static_cast<double>(v.interior);
  state.counters["mean_phi"] = v.mean;
}

void BM_NeighbourPairs_CellList_1e5(benchmark::State& state) {
  const pb::Bed& bed = hundred_thousand();
  std::size_t pairs = 0;
  for (auto _ : state) pairs = pb::neighbour_pairs_cell_list(bed, 0.02).size();
  state.counters["pairs"] = static_cast<double>(pairs);
}

void BM_NeighbourPairs_KdTree_1e5(benchmark::State& state) {
  const pb::Bed& bed = hundred_thousand();
  std::size_t pairs = 0;
  for (auto _ : state) pairs = pb::neighbour_pairs_kdtree(bed, 0.02).size();
  state.counters["pairs"] = static_cast<double>(pairs);
}

}  // namespace

// One iteration per repetition: each call is a whole-bed pass of 0.1-3 s.
BENCHMARK(BM_PackingDensity_1e6)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ContactStats_1e6)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_DensityAndContacts_1e6)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_Voronoi_1e5)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_NeighbourPairs_CellList_1e5)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_NeighbourPairs_KdTree_1e5)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
