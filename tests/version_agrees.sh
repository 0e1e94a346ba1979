#!/bin/sh
# The version is in one place (CMakeLists.txt's project(owsim VERSION …)); everything that states
# it must agree: owsim --version, CHANGELOG.md's newest release, the CMake package's version file,
# owsim.pc, the C ABI's macros (owsim_version() itself: test_c_api), the Debian packages' version
# (CPackConfig.cmake), the man pages, and Python's owsim.__version__ when the module is built.
#   version_agrees.sh SOURCE_DIR BUILD_DIR OWSIM VERSION
set -eu
source_dir=$1 build=$2 owsim=$3 version=$4
fail() { echo "version_agrees: $*" >&2; exit 1; }
major=${version%%.*} rest=${version#*.}
minor=${rest%%.*} patch=${rest#*.}

said=$("$owsim" --version)
[ "$said" = "owsim $version" ] || fail "owsim --version says '$said', CMakeLists.txt $version"
released=$(sed -n 's/^## \[\([0-9][0-9.]*\)\] - .*/\1/p' "$source_dir/CHANGELOG.md" | head -1)
[ "$released" = "$version" ] || fail "CHANGELOG.md's newest release is '$released', not $version"
grep -q "^set(PACKAGE_VERSION \"$version\")" "$build/owsimConfigVersion.cmake" ||
  fail "owsimConfigVersion.cmake is not $version"
grep -qx "Version: $version" "$build/owsim.pc" || fail "owsim.pc is not $version"
header="$build/generated/owsim/owsim_version.h"
grep -q "#define OWSIM_VERSION_STRING \"$version\"" "$header" || fail "$header string"
grep -q "#define OWSIM_VERSION_MAJOR $major$" "$header" || fail "$header major"
grep -q "#define OWSIM_VERSION_MINOR $minor$" "$header" || fail "$header minor"
grep -q "#define OWSIM_VERSION_PATCH $patch$" "$header" || fail "$header patch"
grep -q "^set(CPACK_PACKAGE_VERSION \"$version\")" "$build/CPackConfig.cmake" ||
  fail "the Debian packages' version (CPackConfig.cmake) is not $version"
if [ -f "$build/man/owsim.1.gz" ]; then
  zcat "$build/man/owsim.1.gz" | grep -q "^\.TH OWSIM .*\"owsim $version\"" ||
    fail "owsim(1) is not of owsim $version"
fi
if ls "$build"/python/owsim*.so >/dev/null 2>&1; then
  # OWSIM_PYTHON_PRELOAD: the sanitizer runtimes an instrumented module needs loaded first
  python_version=$(PYTHONPATH="$build/python" LD_PRELOAD="${OWSIM_PYTHON_PRELOAD:-}" \
    ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 /usr/bin/python3 -c \
    'import owsim; print(owsim.__version__)')
  [ "$python_version" = "$version" ] || fail "Python's owsim.__version__ is $python_version"
fi
echo "owsim $version everywhere"
