#!/bin/bash
# The bash completion (cli/man/owsim.bash) against the command's own help:
#   bash_completion.sh OWSIM COMPLETION_FILE
set -eu
owsim=$1
# shellcheck disable=SC1090
source "$2"
fail() { echo "bash_completion: $*" >&2; exit 1; }
complete_line() {  # the completions of the words given, the last being completed
  COMP_WORDS=("$owsim" "$@")
  COMP_CWORD=$#
  COMPREPLY=()
  _owsim
  echo "${COMPREPLY[*]}"
}
commands=$("$owsim" --help | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 && NF { print $1 }')
[ "$(complete_line "")" = "$(echo $commands --help --version)" ] || fail "commands: $(complete_line "")"
[ "$(complete_line st)" = "studio" ] || fail "st: $(complete_line st)"
[ "$(complete_line run --fr)" = "--frames" ] || fail "run --fr: $(complete_line run --fr)"
[ "$(complete_line pattern --sensor "")" = "milows hellas" ] ||
  fail "pattern --sensor: $(complete_line pattern --sensor "")"
[ "$(complete_line pattern --sensor h)" = "hellas" ] || fail "pattern --sensor h"
# every option of every command's help is offered after its command
for command in $commands; do
  offered=" $(complete_line "$command" --) "
  for option in $("$owsim" "$command" --help | grep -oE '^ +(-[A-Za-z],)?--[A-Za-z0-9-]+' |
                  sed -E 's/^ +(-[A-Za-z],)?//'); do
    case $offered in *" $option "*) ;; *) fail "owsim $command: $option not offered" ;; esac
  done
done
# a scenario file after `run`
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
touch "$work/flight.yaml"
[ "$(complete_line run "$work/fli")" = "$work/flight.yaml" ] || fail "run FILE"
echo "completion: $(echo $commands | wc -w) commands and their options"
