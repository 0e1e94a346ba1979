#!/bin/sh
# Builds and runs one of examples/embed/ against an owsim install prefix, as a user would:
#   embed_example.sh cpp|c|python PREFIX WORK_DIR
# cpp: a CMake project with find_package(owsim); c: cc with pkg-config; python: the installed
# module. Prints the example's output; fails if building or running it fails (the C example's
# words must equal the installed `owsim run`'s flight.d64).
set -eu
kind=$1 prefix=$2 work=$3
source_dir=$(cd "$(dirname "$0")/.." && pwd)
examples="$source_dir/examples"
rm -rf "$work" && mkdir -p "$work"
case "$kind" in
  cpp)
    cmake -S "$examples/embed/cpp" -B "$work" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
    cmake --build "$work"
    "$work/cosim" "$examples/single_span.yaml"
    ;;
  c)
    export PKG_CONFIG_PATH="$(dirname "$(find "$prefix" -name owsim.pc | head -1)")"
    libdir=$(pkg-config --variable=libdir owsim)
    # shellcheck disable=SC2046
    cc -std=c99 -Wall -Wextra -pedantic-errors -Werror "$examples/embed/c/frames.c" \
      $(pkg-config --cflags --libs owsim) -Wl,-rpath,"$libdir" -o "$work/frames"
    (cd "$work" && ./frames "$examples/single_span.yaml" words.d64)
    # the same bytes as the installed owsim run writes
    "$prefix/bin/owsim" run "$examples/single_span.yaml" --outputs d64 --quiet --out "$work/run"
    cmp "$work/words.d64" "$work/run/flight.d64"
    echo "words.d64 = owsim run's flight.d64 ($(wc -c <"$work/words.d64") bytes)"
    # the installed owsim finds its optional image module (lib/owsim/libowsim_png.so)
    "$prefix/bin/owsim" run "$examples/single_span.yaml" --outputs quicklook --frames 1 --quiet \
      --out "$work/images"
    test -s "$work/images/quicklook/map.png"
    echo "installed owsim wrote quicklook/map.png through $(ls "$prefix"/lib*/owsim/)"
    ;;
  python)
    module=$(find "$prefix" -name 'owsim*.so' -path '*python*' | head -1)
    PYTHONPATH=$(dirname "$module") /usr/bin/python3 -B "$examples/embed/python/first_wire.py" \
      "$examples/pylon_line.yaml"
    ;;
  *) echo "unknown example kind $kind"; exit 2 ;;
esac
