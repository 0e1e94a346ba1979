#!/usr/bin/env bash
# Installs every Debian 12 package owsim's build, tests and benchmarks need.
# Quick when everything is already installed: apt is only called for what is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libgeographiclib-dev libeigen3-dev libopenimageio-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  libgdal-dev python3-gdal         # DEM terrain (libowsim_gdal.so) and its test oracle
  libassimp-dev                    # triangle meshes (libowsim_mesh.so)
  python3-numpy python3-scipy python3-pyproj
  pybind11-dev python3-dev         # the Python module (python/)
  libopenmpi-dev openmpi-bin       # mpirun … owsim run / sweep (distributed/, libowsim_mpi.so)
  clang libclang-rt-14-dev llvm    # scripts/fuzz.sh (libFuzzer), symbolized sanitizer reports
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
