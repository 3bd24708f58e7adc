#pragma once
// The OpenMP team of the programs that run in parallel (deposit, sinter, keff). By default the
// team is the cores nobody else is using, so that a busy machine is not punished: OpenMP's own
// default (every core) waits at each of a DEM step's ~10 barriers for a thread the kernel has
// descheduled, and ran deposit 10-20x slower than one thread on a loaded 2-core machine
// (measured in docs/hardening.md "Threads").
#include <boost/program_options.hpp>
#include <string>

namespace powderbed::app {

struct ThreadTeam {
  int size = 1;
  std::string reason;  // "--threads", "OMP_NUM_THREADS" or "idle cores (load ...)"
};

// The team for `requested` (--threads; 0 = choose): requested when > 0; else OMP_NUM_THREADS
// when the user set it; else the processors minus the 1-minute load average, rounded, at least 1.
ThreadTeam choose_thread_team(int requested, int processors, double load_average,
                              const char* omp_num_threads);

// --threads for a program's options.
void add_threads_option(boost::program_options::options_description& desc);

// Chooses the team from --threads and the machine, makes it OpenMP's default and returns it.
ThreadTeam apply_thread_team(const boost::program_options::variables_map& vm);

}  // namespace powderbed::app
