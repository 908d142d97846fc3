#!/usr/bin/env bash
# Installs dependencies, builds the CLI, and runs the embedded default demo (no download needed):
# results and a report land in demo_out/ unless another folder is given.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh --target drvslam_cli
./build/bin/drvslam demo --out "${1:-demo_out}"
