#pragma once
// Trajectory snapshots: an HDF5 time series plus an XDMF temporal collection (ParaView opens
// the .xmf as an animation). Layout:
//   /              attrs format = "powderbed.trajectory", version = 1, n
//   /radius        float64 N   (shared by every step)
//   /id            uint64  N
//   /xdmf/polyvertex uint64 N  0..N-1, the Polyvertex cells ParaView's filters need
//   /steps/<k>     group per snapshot (k: the step in 12 digits, lexical order = time order),
//                  attr time (s), attr step; datasets position N×3, velocity N×3 (when the
//                  snapshot's bed has velocities; the .xmf names it in those snapshots only)
// Every dataset has its SI unit as the attribute `units` (m, m/s; "1" without unit).
// The file is written under a temporary name and renamed on close(), so an interrupted run
// leaves no half trajectory under the requested name (bed::H5Output); the constructor and
// close() throw InputError naming the file when it cannot be written.
#include <cstdint>
#include <memory>
#include <string>

#include "powderbed/bed/bed.hpp"

namespace powderbed::dem {

class TrajectoryWriter {
 public:
  // Throws InputError naming the path when the file cannot be created.
  TrajectoryWriter(const std::string& path, const bed::Bed& bed);
  ~TrajectoryWriter();
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;

  void write(std::uint64_t step, double time, const bed::Bed& bed);
  // Closes the HDF5 file, renames it into place and writes `<path without .h5>.xmf`.
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace powderbed::dem
