#!/bin/sh
# Writes owsim's man pages from the help text the command itself prints, so the two cannot drift:
#   man_pages.sh OWSIM OUT_DIR
# OUT_DIR/owsim.1.gz from `owsim --help`, and OUT_DIR/owsim-COMMAND.1.gz from `owsim COMMAND
# --help` for every command `owsim --help` lists (help2man; gzip -9n as Debian installs them).
set -eu
owsim=$1 out=$2
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
version=$("$owsim" --version | sed 's/^owsim //')
commands=$("$owsim" --help | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 && NF { print $1 }')
[ -n "$commands" ] || { echo "man_pages.sh: $owsim --help lists no commands" >&2; exit 1; }

# SEE ALSO of every page: the others.
{
  echo "[SEE ALSO]"
  printf '.BR owsim (1)'
  for command in $commands; do printf ',\n.BR owsim-%s (1)' "$command"; done
  echo
} >"$work/see_also.h2m"
cat "$here/owsim.h2m" >>"$work/see_also.h2m"

page() {  # page NAME DESCRIPTION HELP_OPTION
  ln -sf "$(cd "$(dirname "$owsim")" && pwd)/$(basename "$owsim")" "$work/$1"
  help2man --no-info --locale=C.UTF-8 --section=1 --manual="owsim manual" --source="owsim $version" \
    --name="$2" --help-option="$3" --version-string="$version" \
    --include="$work/see_also.h2m" --output="$work/$1.1" "$work/$1"
  gzip -9n -c "$work/$1.1" >"$out/$1.1.gz"
}
page owsim "MilOWS/HELLAS obstacle-warning LiDAR simulator" "--help"
for command in $commands; do
  summary=$("$owsim" --help | sed -n '/^Subcommands:/,$p' |
    awk -v c="$command" '$1 == c { $1 = ""; sub(/^ +/, ""); print }')
  page "owsim-$command" "$summary" "$command --help"
done
