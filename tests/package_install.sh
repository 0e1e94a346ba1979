#!/usr/bin/env bash
# The Debian packages of scripts/package.sh, used as a user would (CI, as root, on a fresh
# machine): installed with apt-get, `owsim` run from /usr/bin on examples copied out of the tree,
# its man pages and bash completion, the C and C++ embedding examples built against /usr, the
# Python module imported by /usr/bin/python3 — then removed, leaving nothing behind.
#   tests/package_install.sh [PACKAGES_DIR]      (default build/packages)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
packages=$(cd "${1:-$root/build/packages}" && pwd)
version=$(sed -n 's/^project(owsim VERSION \([0-9.]*\) .*/\1/p' "$root/CMakeLists.txt")
fail() { echo "package_install: $*" >&2; exit 1; }
debs=("$packages"/owsim_"$version"_*.deb "$packages"/libowsim-dev_"$version"_*.deb
      "$packages"/python3-owsim_"$version"_*.deb)
for deb in "${debs[@]}"; do [ -f "$deb" ] || fail "no $deb (scripts/package.sh makes it)"; done
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive

"${sudo_cmd[@]}" apt-get install -y -q "${debs[@]}" >/dev/null
installed=$(dpkg -L owsim libowsim-dev python3-owsim | sort -u)

# Everything below runs outside the source and build trees, with a clean environment, on copies.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r "$root/examples" "$work/examples"
cd "$work"
run() { env -i HOME="$work" PATH=/usr/bin:/bin LANG=C.UTF-8 "$@"; }

[ "$(run sh -c "command -v owsim")" = /usr/bin/owsim ] || fail "owsim is not /usr/bin/owsim"
[ "$(run owsim --version)" = "owsim $version" ] || fail "owsim --version: $(run owsim --version)"
run owsim run examples/single_span.yaml --out flight --quiet
for f in flight.d64 points.csv points.las truth.csv summary.json quicklook/map.png; do
  [ -s "flight/$f" ] || fail "owsim run wrote no $f"
done
run owsim info flight/flight.d64 >/dev/null
# the optional modules from /usr: DEM terrain and GIS lines (gdal), a model file (mesh)
run owsim run examples/real_corridor.yaml --frames 2 --outputs summary --out corridor --quiet
echo "owsim $version from /usr/bin: single_span and real_corridor (DEM, GIS lines, mesh) flown"

# man pages: one per command, from its help text
man_dir=/usr/share/man/man1
[ -f "$man_dir/owsim.1.gz" ] || fail "no man page owsim(1)"
for command in $(run owsim --help | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 && NF { print $1 }'); do
  page="$man_dir/owsim-$command.1.gz"
  [ -f "$page" ] || fail "no man page owsim-$command(1)"
  zcat "$page" | grep -q '\\-\\-help' || fail "owsim-$command(1) lists no options"
done
echo "man pages: owsim(1) and $(ls $man_dir/owsim-*.1.gz | wc -l) command pages"

# bash completion
completion=/usr/share/bash-completion/completions/owsim
[ -f "$completion" ] || fail "no bash completion"
words=$(bash -c "source $completion; COMP_WORDS=(owsim run --fr); COMP_CWORD=2; _owsim; echo \${COMPREPLY[*]}")
[ "$words" = "--frames" ] || fail "completing 'owsim run --fr' gave '$words'"

# C++ (find_package(owsim) from /usr) and C (pkg-config owsim) embedding examples
cmake -S examples/embed/cpp -B cpp -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build cpp >/dev/null
run cpp/cosim examples/single_span.yaml | grep -q "first wire detection: frame" ||
  fail "the C++ embedding example found no wire"
# shellcheck disable=SC2046
cc -std=c99 -Wall -Wextra -pedantic-errors -Werror examples/embed/c/frames.c \
  $(pkg-config --cflags --libs owsim) -o frames
run ./frames examples/single_span.yaml words.d64 >/dev/null
run owsim run examples/single_span.yaml --outputs d64 --quiet --out words
cmp words.d64 words/flight.d64 || fail "libowsim_c.so's words differ from owsim run's"
echo "C and C++ embedding examples built against /usr; the C example's words = flight.d64"

# Python: Debian's interpreter finds the module without PYTHONPATH
[ "$(run /usr/bin/python3 -c 'import owsim; print(owsim.__version__)')" = "$version" ] ||
  fail "python3-owsim's __version__ is not $version"
run /usr/bin/python3 -B examples/embed/python/first_wire.py examples/pylon_line.yaml >/dev/null
echo "python3-owsim $version imported by /usr/bin/python3"

# Nothing of the build tree: no run path, no file naming it
for file in $installed; do
  [ -f "$file" ] || continue
  if readelf -d "$file" 2>/dev/null | grep -qE 'R(UN)?PATH'; then fail "$file has a run path"; fi
done
if grep -lF "$root/build" $(for f in $installed; do [ -f "$f" ] && echo "$f"; done) 2>/dev/null |
   grep -v '\.a$'; then
  fail "installed files name the build tree"
fi

cd /
"${sudo_cmd[@]}" apt-get remove --purge -y -q owsim libowsim-dev python3-owsim >/dev/null
left=""
for path in $installed; do  # every path of owsim's own (the shared folders above them stay)
  case $path in *owsim*) [ -e "$path" ] && left="$left $path" ;; esac
done
[ -z "$left" ] || fail "left after removal:$left"
if dpkg -l owsim libowsim-dev python3-owsim 2>/dev/null | grep -q '^ii'; then
  fail "still installed after removal"
fi
echo "removed: owsim, libowsim-dev, python3-owsim; nothing left of their $(echo "$installed" | wc -l) paths"
