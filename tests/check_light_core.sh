#!/bin/sh
# check_light_core.sh MODULE OBJECT...: the dynamic section (readelf -d, NEEDED entries, direct
# and through every library they load: ldd) of each OBJECT names none of the heavy libraries
# that only optional modules may load, while MODULE (libowsim_png.so) does need OpenImageIO,
# so the pattern is known to match what it is meant to catch.
set -eu
heavy='libOpenImageIO|libopencv|libgdal|libassimp|libavcodec|libavformat|libhdf5|libpoppler|libmpi|libopen-pal|libpmix'
module=$1
shift
if ! ldd "$module" | grep -Eq "$heavy"; then
  echo "FAIL: $module does not load OpenImageIO: the check's pattern is stale"
  exit 1
fi
status=0
for object in "$@"; do
  needed=$(readelf -d "$object" | grep -c NEEDED)
  loaded=$(ldd "$object" | wc -l)
  if ldd "$object" | grep -E "$heavy"; then
    echo "FAIL: $(basename "$object") loads the libraries above"
    status=1
  else
    echo "ok: $(basename "$object"): $needed direct, $loaded loaded in all, none heavy"
  fi
done
exit $status
