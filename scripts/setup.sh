#!/usr/bin/env bash
# Installs the Debian 12 packages powderbed needs that are not yet installed (idempotent).
# Runs apt-get as root, or through sudo when started as another user.
set -euo pipefail

packages=(
  build-essential cmake
  libcgal-dev libnanoflann-dev libeigen3-dev libhdf5-dev libboost-program-options-dev
  libgtest-dev libbenchmark-dev
  libfmt-dev  # error messages (fmt::format)
  python3 python3-h5py python3-matplotlib python3-numpy
  python3-dev pybind11-dev python3-pytest  # the Python module powderbed (python/) and its tests
  # scripts/render_paraview.py and its test (tests/paraview): pvpython under a virtual X server;
  # paraview + python3-paraview are ~540 MB installed (VTK, Qt, GDAL): the largest download here
  python3-paraview xvfb xauth
  zlib1g-dev gzip  # gzipped dumps (bed/src/io_text.cpp) and their test
  # the exported decks run in ctest decks.* (docs/decks.md): LAMMPS, LIGGGHTS, mpirun for 2 ranks;
  # LIGGGHTS is also the peer of bench/studies/deposit_speed.py and spread_peer.py
  lammps liggghts mpi-default-bin
  python3-gengeo  # GenGeo, the packing peer: its .geo files read back in ctest decks.gengeo
  clang libclang-rt-14-dev  # the bed-reader fuzz target (tests/fuzz, ~40 s build + 30 s run)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

as_root=()
if [[ $(id -u) -ne 0 ]]; then as_root=(sudo); fi
echo "setup: installing ${missing[*]}"
"${as_root[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
