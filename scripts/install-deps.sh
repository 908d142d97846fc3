#!/usr/bin/env bash
# Installs the Debian (bookworm) packages drvslam needs to build, test and run its demo.
# Installs only what is missing; runs `apt-get update` itself when it has to install.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git ninja-build mold
  clang-16 libclang-rt-16-dev libfuzzer-16-dev
  libeigen3-dev libopencv-dev libceres-dev libopen3d-dev liboctomap-dev
  libcli11-dev libspdlog-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  opencv-doc
  libwebsocketpp-dev libasio-dev
  chromium
  pybind11-dev python3-dev python3-numpy python3-pytest
  cyclonedds-dev cyclonedds-tools
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

# The viewer page's npm packages (three.js; esbuild and playwright-core for the build and the
# browser tests), exactly as web/package-lock.json pins them. Node.js itself is expected.
install_web_packages() {
  local web_dir
  web_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/web"
  if [ -d "$web_dir/node_modules" ]; then
    return 0
  fi
  if ! command -v npm >/dev/null 2>&1; then
    echo "error: npm (Node.js 18 or newer) is needed to install the viewer page's packages" >&2
    exit 2
  fi
  echo "install-deps: npm ci in $web_dir"
  (cd "$web_dir" && npm ci --no-audit --no-fund)
}

if [ ${#missing[@]} -eq 0 ]; then
  install_web_packages
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo_cmd=(sudo)
  else
    echo "error: need root (or sudo) to install: ${missing[*]}" >&2
    exit 2
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
install_web_packages
