#!/usr/bin/env bash
# One-step set-up of dtsl on Debian 12 (bookworm): installs every dependency with apt-get, fetches the
# model data (Debian's libcgal-demo) into the user cache, configures and builds into build/.
# Run from anywhere; as root, or as a user with sudo.
set -euo pipefail
cd "$(dirname "$0")/.."

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

PACKAGES=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  libeigen3-dev libceres-dev libsuitesparse-dev libpcl-dev libcgal-dev
  nlohmann-json3-dev libyaml-cpp-dev catch2 libpng-dev
  clang libclang-rt-14-dev libomp-dev   # .ci/run: the sanitizer build and the libFuzzer targets (fuzz/)
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib  # python/: the dtsl module, its tests, docs/python_example.py
)
echo "== installing: ${PACKAGES[*]}"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${PACKAGES[@]}"

echo "== fetching model data"
scripts/fetch_data.sh

echo "== building (build/)"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
echo "== done: run the tests with  ctest --test-dir build --output-on-failure"
