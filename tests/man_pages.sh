#!/bin/sh
# The man pages (cli/man/man_pages.sh) hold the command's help: one page per command that
# `owsim --help` lists, each with every option `owsim COMMAND --help` prints.
#   man_pages.sh OWSIM MAN_DIR
set -eu
owsim=$1 man_dir=$2
fail() { echo "man_pages: $*" >&2; exit 1; }
roff() { echo "$1" | sed 's/-/\\\\-/g'; }   # help2man writes a '-' as '\-'
[ -f "$man_dir/owsim.1.gz" ] || fail "no owsim.1.gz"
pages=0
for command in $("$owsim" --help | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 && NF { print $1 }'); do
  page="$man_dir/owsim-$command.1.gz"
  [ -f "$page" ] || fail "no page for owsim $command"
  zcat "$page" | grep -q "^\.TH OWSIM-$(echo "$command" | tr a-z A-Z) " || fail "$page: title"
  zcat "$page" | grep -q "^owsim-$command \\\\- " || fail "$page: no NAME line"
  for option in $("$owsim" "$command" --help | grep -oE '^ +(-[A-Za-z],)?--[A-Za-z0-9-]+' |
                  sed -E 's/^ +(-[A-Za-z],)?//'); do
    zcat "$page" | grep -q -- "$(roff "$option")" || fail "owsim-$command(1) lacks $option"
  done
  pages=$((pages + 1))
done
echo "man pages: owsim(1) and $pages command pages, every option in its page"
