#include "common/threads.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <string>

namespace powderbed::app {

ThreadTeam choose_thread_team(int requested, int processors, double load_average,
                              const char* omp_num_threads) {
  if (requested > 0) return {requested, "--threads"};
  if (omp_num_threads && *omp_num_threads) {
    char* end = nullptr;
    const long n = std::strtol(omp_num_threads, &end, 10);
    if (end != omp_num_threads && n > 0) return {static_cast<int>(std::min(n, 4096L)), "OMP_NUM_THREADS"};
  }
  const int procs = std::max(processors, 1);
  const double load = std::isfinite(load_average) && load_average > 0 ? load_average : 0.0;
  const int busy = static_cast<int>(std::lround(load));
  char reason[96];
  std::snprintf(reason, sizeof reason, "idle cores (%d processors, load %.2f)", procs, load);
  return {std::clamp(procs - busy, 1, procs), reason};
}

void add_threads_option(boost::program_options::options_description& desc) {
  desc.add_options()("threads", boost::program_options::value<int>()->default_value(0),
                     "OpenMP threads (0: the idle cores, i.e. processors minus the 1-minute load "
                     "average, at least 1; OMP_NUM_THREADS when set)");
}

ThreadTeam apply_thread_team(const boost::program_options::variables_map& vm) {
  double load[1] = {0.0};
  if (getloadavg(load, 1) != 1) load[0] = 0.0;
  const ThreadTeam team = choose_thread_team(vm["threads"].as<int>(), omp_get_num_procs(), load[0],
                                             std::getenv("OMP_NUM_THREADS"));
  omp_set_num_threads(team.size);
  return team;
}

}  // namespace powderbed::app
