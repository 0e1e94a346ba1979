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
  libtinyobjloader-dev             # OBJ meshes, fast (libowsim_mesh.so)
  python3-numpy python3-scipy python3-pyproj
  pybind11-dev python3-dev         # the Python module (python/)
  libopenmpi-dev openmpi-bin       # mpirun … owsim run / sweep (distributed/, libowsim_mpi.so)
  clang libclang-rt-14-dev llvm    # scripts/fuzz.sh (libFuzzer), symbolized sanitizer reports
  libboost-dev                     # Clopper–Pearson intervals (Boost.Math beta quantiles, header-only; owsim pd/score)
  zlib1g-dev                       # the report page's data (owsim view, io/report/)
  chromium                         # the report page's browser test (tests/web/)
  strace                           # scenarios open only their own files (tests/scenario_files_strace.py)
  libcpp-httplib-dev               # owsim studio's local HTTP server (studio/)
)
# Node.js and npm bundle the report page's script at build time (web/); Debian's packages unless
# the machine already has a node and npm of its own.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then packages+=(nodejs npm); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
else
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The report page's npm packages, at the versions web/package-lock.json pins (again only when
# the lock file changed since the last install).
web="$(cd "$(dirname "$0")/.." && pwd)/web"
if [ ! -f "$web/node_modules/.package-lock.json" ] ||
   [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
  echo "setup: npm ci in web/"
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
fi
