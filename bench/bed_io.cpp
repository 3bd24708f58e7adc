// HDF5 bed write and read speed (docs/bed-format.md: contiguous datasets, one H5Dread
// each). Results: docs/results/bed-io.md, regenerated with
//   build/bench/bench_bed_io --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "powderbed/bed/io.hpp"
#include "powderbed/bed/random.hpp"

namespace {

namespace bed = powderbed::bed;

// N particles at uniform random centres in a unit box (seed 1), radii 5-25 um.
bed::Bed random_bed(std::size_t n) {
  bed::Rng rng(1);
  bed::Bed b;
  b.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    b.x.push_back(bed::uniform01(rng));
    b.y.push_back(bed::uniform01(rng));
    b.z.push_back(bed::uniform01(rng));
    b.radius.push_back(bed::uniform(rng, 5e-6, 25e-6));
    b.id.push_back(i);
  }
  return b;
}

std::string bench_path() {
  return (std::filesystem::temp_directory_path() /
          ("powderbed_bench_bed_io_" + std::to_string(::getpid()) + ".h5"))
      .string();
}

void remove_bed(const std::string& path) {
  std::remove(path.c_str());
  std::remove((path.substr(0, path.size() - 3) + ".xmf").c_str());
}

void BM_WriteBedH5(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const bed::Bed b = random_bed(n);
  const std::string path = bench_path();
  for (auto _ : state) bed::write_bed_h5(b, path);
  remove_bed(path);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

void BM_ReadBedH5(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const std::string path = bench_path();
  bed::write_bed_h5(random_bed(n), path);
  for (auto _ : state) benchmark::DoNotOptimize(bed::read_bed_h5(path));
  remove_bed(path);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

BENCHMARK(BM_WriteBedH5)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReadBedH5)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
