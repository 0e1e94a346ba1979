# bash completion for owsim: its commands, each command's options, the values an option lists
# ({a,b} in its help), files otherwise. Read from `owsim --help` and `owsim COMMAND --help` when
# completing, so it knows exactly what the installed owsim accepts.
_owsim() {
  local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]}
  local owsim=${COMP_WORDS[0]} command="" i
  for ((i = 1; i < COMP_CWORD; i++)); do
    case ${COMP_WORDS[i]} in -*) ;; *) command=${COMP_WORDS[i]}; break ;; esac
  done
  if [[ -z $command ]]; then
    local commands
    commands=$("$owsim" --help 2>/dev/null | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 && NF { print $1 }')
    COMPREPLY=($(compgen -W "$commands --help --version" -- "$cur"))
    return
  fi
  local help
  help=$("$owsim" "$command" --help 2>/dev/null)
  if [[ $prev == -* ]]; then
    # The option's line: `  --sensor TEXT:{milows,hellas} ...` lists its values; a flag takes none.
    local line
    line=$(grep -E "^ +(-[A-Za-z],)?$prev( |,|$)" <<<"$help" | head -1)
    if [[ $line =~ \{([^}]*)\} ]]; then
      COMPREPLY=($(compgen -W "${BASH_REMATCH[1]//,/ }" -- "$cur"))
      return
    fi
    if [[ $line =~ ^\ +(-[A-Za-z],)?$prev\ +[A-Z] ]]; then
      COMPREPLY=($(compgen -f -- "$cur"))
      compopt -o filenames 2>/dev/null
      return
    fi
  fi
  if [[ $cur == -* ]]; then
    local options
    options=$(grep -oE '^ +(-[A-Za-z],)?--[A-Za-z0-9-]+' <<<"$help" | sed -E 's/^ +(-[A-Za-z],)?//')
    COMPREPLY=($(compgen -W "$options" -- "$cur"))
    return
  fi
  COMPREPLY=($(compgen -f -- "$cur"))
  compopt -o filenames 2>/dev/null
}
complete -F _owsim owsim
