// Placement hot paths of packgen (docs/physics.md §3, issue 3 "speed and scaling"):
//  - the whole 3D monodisperse 3-contact packing, lowest site first (the rule of
//    docs/results/packgen-speed.md), for N = 1e3, 1e4, 1e5 spheres of r = 0.5 in a cube sized as
//    bench/studies/packgen_speed.py sizes it; `s_per_sphere` is the time per placed sphere;
//  - the collision back-ends (grid, kdtree, raster) answering fits() on one bed: 1e4 spheres
//    packed by the same rule, queried at random centres in the band of the bed surface, where
//    growth tests its sites (both answers common: `free_fraction`).
// Run: build/bench/bench_packgen_place --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "powderbed/bed/psd.hpp"
#include "powderbed/bed/random.hpp"
#include "powderbed/bed/sphere_volume.hpp"
#include "powderbed/packgen/cell_grid.hpp"
#include "powderbed/packgen/kdtree_index.hpp"
#include "powderbed/packgen/pack.hpp"
#include "powderbed/packgen/raster_grid.hpp"

namespace pb = powderbed::bed;
namespace pg = powderbed::packgen;

namespace {

constexpr double kRadius = 0.5;

// The cube that holds N spheres at φ = 0.6 with 25 % head room (packgen_speed.py).
pb::Domain cube_for(std::size_t n) {
  const double volume = double(n) * pb::sphere_volume(kRadius);
  const double side = std::ceil(std::cbrt(volume / 0.6 * 1.25));
  pb::Domain d;
  d.dimension = 3;
  d.upper = {side, side, side};
  return d;
}

pg::PackOptions lowest_site(std::size_t n) {
  pg::PackOptions o;
  o.phases = {pg::Phase{3, 1.0}};
  o.site_order = pg::SiteOrder::lowest;
  o.count = n;
  return o;
}

void BM_PackMono3Contact(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const pb::Domain domain = cube_for(n);
  const pb::Psd psd = pb::Psd::mono_radius(kRadius);
  const pg::PackOptions options = lowest_site(n);
  std::size_t placed = 0;
  for (auto _ : state) {
    const pg::PackResult r = pg::pack(domain, psd, options, 1);
    placed = r.bed.n();
    benchmark::DoNotOptimize(placed);
  }
  state.counters["s_per_sphere"] = benchmark::Counter(
      double(placed), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PackMono3Contact)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// One bed for the back-ends, and query centres: uniform in x, y, and in z within 2 r of the top
// centre (deeper, a sphere of radius r almost never fits; higher, always).
struct QueryBed {
  pb::Domain domain = cube_for(10000);
  pg::Particles particles;
  std::vector<std::array<double, 3>> queries;
  QueryBed() {
    const pg::PackResult r = pg::pack(domain, pb::Psd::mono_radius(kRadius), lowest_site(10000), 1);
    particles.x = r.bed.x;
    particles.y = r.bed.y;
    particles.z = r.bed.z;
    particles.r = r.bed.radius;
    double top = 0;
    for (double z : r.bed.z) top = std::max(top, z);
    pb::Rng rng(2);
    for (int q = 0; q < 4096; ++q) {
      queries.push_back({pb::uniform(rng, kRadius, domain.upper[0] - kRadius),
                         pb::uniform(rng, kRadius, domain.upper[1] - kRadius),
                         pb::uniform(rng, top - 2 * kRadius, top + 2 * kRadius)});
    }
  }
};

const QueryBed& query_bed() {
  static const QueryBed b;
  return b;
}

template <class Index>
void run_queries(benchmark::State& state, const Index& index) {
  const QueryBed& b = query_bed();
  std::size_t k = 0, free = 0;
  for (auto _ : state) {
    const auto& q = b.queries[k++ % b.queries.size()];
    const bool fits = index.fits(q[0], q[1], q[2], kRadius);
    free += fits;
    benchmark::DoNotOptimize(fits);
  }
  state.counters["free_fraction"] = double(free) / double(state.iterations());
}

void BM_FitsGrid(benchmark::State& state) {
  const QueryBed& b = query_bed();
  pg::CellGrid grid(b.domain, kRadius, kRadius, b.particles);
  for (std::uint32_t i = 0; i < b.particles.size(); ++i) grid.insert(i);
  run_queries(state, grid);
}
BENCHMARK(BM_FitsGrid);

void BM_FitsKdTree(benchmark::State& state) {
  const QueryBed& b = query_bed();
  pg::KdTreeIndex tree(3, kRadius, b.particles);
  for (std::uint32_t i = 0; i < b.particles.size(); ++i) tree.insert(i);
  run_queries(state, tree);
}
BENCHMARK(BM_FitsKdTree);

// Raster spacing h = r / 5: ~1.2e7 status bytes for this cube; a query visits the ~(2r / h)^3
// = 1e3 grid points of its sphere's box, so the cost grows as h^-3.
void BM_FitsRaster(benchmark::State& state) {
  const QueryBed& b = query_bed();
  pg::RasterGrid raster(b.domain, kRadius / 5, b.particles);
  for (std::uint32_t i = 0; i < b.particles.size(); ++i) raster.insert(i);
  run_queries(state, raster);
}
BENCHMARK(BM_FitsRaster);

}  // namespace

BENCHMARK_MAIN();
