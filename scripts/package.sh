#!/usr/bin/env bash
# Debian packages of owsim, made by CPack into build/packages/:
#   owsim_<version>_amd64.deb          /usr/bin/owsim, libowsim_c.so, the optional modules, man
#                                      pages, bash completion, documents
#   libowsim-dev_<version>_amd64.deb   headers, static libraries, CMake package, owsim.pc
#   python3-owsim_<version>_amd64.deb  the Python module
# Built in their own tree (build/package-build, prefix /usr, every optional module, no tests);
# install with `sudo apt-get install ./build/packages/*.deb`.
# OWSIM_PACKAGE_BUILD_DIR=build packages from the test build instead (what CI does: the same
# Release build; reconfigured for prefix /usr without tests, only the unit that compiles the
# prefix in rebuilds and what links it relinks).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="${OWSIM_PACKAGE_BUILD_DIR:-$root/build/package-build}"
out="$root/build/packages"
"$root/scripts/setup.sh" core png gdal mesh mpi python package
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DOWSIM_REQUIRE_ALL=ON -DOWSIM_BUILD_TESTS=OFF -DOWSIM_BUILD_BENCH=OFF -DOWSIM_BUILD_PYTHON=ON \
  >/dev/null
cmake --build "$build" -j "$(nproc)"

# Shared-library dependencies, by dpkg-shlibdeps: what the command and libowsim_c.so link are
# Depends; what an optional module links is Recommends (images, DEM, meshes) or Suggests (MPI), so
# the command installs without GDAL, assimp, OpenImageIO or MPI and says which package a module
# needs when a run asks for it.
shlibs=$(mktemp -d)
trap 'rm -rf "$shlibs"' EXIT
mkdir -p "$shlibs/debian" && touch "$shlibs/debian/control"
field() {  # field NAME: the value of shlibs:NAME in dpkg-shlibdeps' output
  sed -n "s/^shlibs:$1=//p" "$shlibs/substvars"
}
modules="$build/lib/owsim"
(cd "$shlibs" && dpkg-shlibdeps -O -e"$build/owsim" -e"$(readlink -f "$build/capi/libowsim_c.so")" \
  -dRecommends -e"$modules/libowsim_png.so" -e"$modules/libowsim_gdal.so" \
  -e"$modules/libowsim_mesh.so" -dSuggests -e"$modules/libowsim_mpi.so" >substvars 2>/dev/null)
depends=$(field Depends) recommends=$(field Recommends) suggests=$(field Suggests)
python_module=$(find "$build/python" -maxdepth 1 -name 'owsim*.so' | head -1)
(cd "$shlibs" && dpkg-shlibdeps -O -e"$python_module" >substvars 2>/dev/null)
python_depends=$(field Depends)
version=$(sed -n 's/^set(CPACK_PACKAGE_VERSION "\(.*\)")$/\1/p' "$build/CPackConfig.cmake")
read -r python_version python_next < <(/usr/bin/python3 -c \
  'import sys; v = sys.version_info; print(f"{v[0]}.{v[1]} {v[0]}.{v[1] + 1}")')

rm -rf "$out"
cpack --config "$build/CPackConfig.cmake" -B "$out" \
  -D CPACK_DEBIAN_OWSIM_PACKAGE_DEPENDS="$depends" \
  -D CPACK_DEBIAN_OWSIM_PACKAGE_RECOMMENDS="$recommends" \
  -D CPACK_DEBIAN_OWSIM_PACKAGE_SUGGESTS="$suggests, openmpi-bin, bash-completion" \
  -D CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS="$python_depends, python3 (>= $python_version), python3 (<< $python_next), python3-numpy, owsim (= $version)" \
  >/dev/null
rm -rf "$out/_CPack_Packages"
for deb in "$out"/*.deb; do
  echo "$(basename "$deb")  $(du -h "$deb" | cut -f1)"
  dpkg-deb -f "$deb" Depends Recommends Suggests | sed 's/^/    /'
done
