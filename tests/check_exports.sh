#!/bin/sh
# Checks that the shared library $1 exports only symbols starting with $2 (and some of them):
# prints any other exported symbol and fails.
set -eu
symbols=$(nm -D --defined-only "$1" | awk '{print $3}')
[ -n "$symbols" ] || { echo "$1 exports nothing"; exit 1; }
others=$(printf '%s\n' "$symbols" | grep -v "^$2" || true)
if [ -n "$others" ]; then
  echo "$1 exports symbols outside the API:"
  printf '%s\n' "$others" | head -20
  exit 1
fi
echo "$1: $(printf '%s\n' "$symbols" | wc -l) symbols, all $2*"
