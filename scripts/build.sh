#!/usr/bin/env bash
# Configures and builds drvslam (Release) into build/. Extra arguments go to cmake --build
# (for example `--target drvslam_cli`).
#
# A unity build (cmake/DrvslamUnity.cmake): one compiler run per target. A build from
# scratch, as CI makes on every run, took 749 CPU-s against 1,315 file by file (Ninja, no
# ccache). The program is the same as a file-by-file build's (the --sequential outputs are
# byte-identical). Editing one file recompiles its batch, so while working on the code
# DRVSLAM_UNITY=OFF may rebuild faster.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# Ninja (installed by install-deps.sh) when the folder is new: it schedules every target's
# compiles at once. An existing folder keeps the generator it was made with.
generator=()
if command -v ninja >/dev/null && [ ! -e build/CMakeCache.txt ]; then
  generator=(-G Ninja)
fi
cmake -S . -B build ${generator[@]+"${generator[@]}"} -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_UNITY_BUILD="${DRVSLAM_UNITY:-ON}" >/dev/null
cmake --build build -j "$(nproc)" "$@"
