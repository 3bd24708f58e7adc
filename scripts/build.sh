#!/usr/bin/env bash
# Configures and builds powderbed (Release) in ./build. Under CI (CI=true) warnings are errors.
# Extra CMake arguments are passed through, e.g. scripts/build.sh -DPOWDERBED_SANITIZE=ON
set -euo pipefail
cd "$(dirname "$0")/.."

werror=OFF
if [[ "${CI:-}" == "true" ]]; then werror=ON; fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPOWDERBED_WERROR="$werror" "$@" >/dev/null
cmake --build build -j "$(nproc)"
