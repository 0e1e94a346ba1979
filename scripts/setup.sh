#!/usr/bin/env bash
# Installs the Debian 12 packages owsim needs, by part:
#   scripts/setup.sh                 everything: every optional module, the tests, the benchmarks,
#                                    the fuzzers, packaging (what scripts/test.sh and CI use)
#   scripts/setup.sh core            building and running the `owsim` command (the quick start)
#   scripts/setup.sh core png gdal   the core and the named optional modules
# Parts: core, png (quick-look images), gdal (DEM terrain, GIS lines), mesh (model files),
# mpi (mpirun), python (the Python module), tests, fuzz, package, all.
# Quick when everything is already installed: apt is only called for what is missing.
set -euo pipefail

declare -A part
part[core]="build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libgeographiclib-dev libeigen3-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  libboost-dev zlib1g-dev libzstd-dev libcpp-httplib-dev libnova-dev"
# Boost.Math (header-only): Clopper–Pearson intervals of owsim pd/score; zlib: the report page's
# data and flight.mcap's CRCs; zstd: flight.mcap's chunks; cpp-httplib: owsim studio's local
# server; libnova: the sun's position for a scenario's `sun: {time_utc}`.
part[png]="libopenimageio-dev"                                # quicklook/ (libowsim_png.so)
part[gdal]="libgdal-dev"                                      # DEM terrain, GIS lines (libowsim_gdal.so)
part[mesh]="libassimp-dev libtinyobjloader-dev"               # model files (libowsim_mesh.so)
part[mpi]="libopenmpi-dev openmpi-bin"                        # mpirun … owsim run/sweep (libowsim_mpi.so)
part[python]="pybind11-dev python3-dev python3-numpy"         # the Python module (python/)
part[tests]="libgtest-dev libgmock-dev libbenchmark-dev
  python3-numpy python3-scipy python3-pyproj python3-gdal python3-astral
  chromium strace"    # oracles (astral: the sun's position), the report page's and the studio's
                      # browser tests, the strace test
part[fuzz]="clang libclang-rt-14-dev llvm"                    # scripts/fuzz.sh, symbolized reports
part[package]="help2man dpkg-dev file"                        # scripts/package.sh: man pages, .deb
part[all]="${part[core]} ${part[png]} ${part[gdal]} ${part[mesh]} ${part[mpi]} ${part[python]}
  ${part[tests]} ${part[fuzz]} ${part[package]}"

wanted=("$@")
if [ ${#wanted[@]} -eq 0 ]; then wanted=(all); fi
packages=()
for name in "${wanted[@]}"; do
  if [ -z "${part[$name]+set}" ]; then
    echo "setup: unknown part '$name' (core, png, gdal, mesh, mpi, python, tests, fuzz, package, all)" >&2
    exit 2
  fi
  # shellcheck disable=SC2206
  packages+=(${part[$name]})
done
# Node.js and npm bundle the report page's and the studio's scripts at build time (web/); Debian's
# packages unless the machine already has a node and npm of its own.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then packages+=(nodejs npm); fi

missing=()
for p in $(printf '%s\n' "${packages[@]}" | sort -u); do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: the packages of ${wanted[*]} are installed"
else
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The npm packages of web/, at the versions web/package-lock.json pins (again only when the lock
# file changed since the last install).
web="$(cd "$(dirname "$0")/.." && pwd)/web"
if [ ! -f "$web/node_modules/.package-lock.json" ] ||
   [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
  echo "setup: npm ci in web/"
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
fi
