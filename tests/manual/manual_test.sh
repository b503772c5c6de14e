#!/usr/bin/env bash
# The man pages and bash completion the build made (tools/manual), checked against the programs' own --help:
#   1. every page renders with groff at 80 columns without a warning (-ww), and each program has a page
#      for itself and for each command its --help lists;
#   2. every option and positional that `PROGRAM [COMMAND] --help` lists is in the rendered page;
#   3. every example in a page parses: run with --help added it exits 0 (its options exist, its values
#      are ones the program takes);
#   4. sourced in bash, the completion gives each command from its first two letters, each option of each
#      command from its name less its last letter, exactly the choices --help lists for an option that
#      has them, file names after one that takes text or a path, nothing after one that takes a number or
#      a named kind of value (LENGTH).
# Prints every failure and exits 1 if there is any.
#   tests/manual/manual_test.sh MANUAL_DIR PROGRAM_EXE... (heightpack, heightpack-view)
set -uo pipefail
manual_dir=$(realpath "$1")
shift
exes=()
for exe in "$@"; do exes+=("$(realpath "$exe")"); done
failures=0
fail() { echo "manual_test: $*"; failures=$((failures + 1)); }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# help_options EXE [COMMAND]: "NAME TYPE" a line for every option and positional --help lists (TYPE as
# CLI11 prints it, "TEXT:{a,b}", or empty for a flag).
# Each --help is asked once (a run costs a program start): remember_help keeps it, in this shell.
declare -A helps
remember_help() { [ -n "${helps["$*"]+set}" ] || helps["$*"]=$("$@" --help); }
help_options() {
  local text=${helps["$*"]-}
  [ -n "$text" ] || text=$("$@" --help)
  awk '
    /^[A-Za-z].*:$/ { section = $0; next }
    section == "Positionals:" && /^  [a-z]/ { print $1, $2; next }
    /^  -/ { n = split($1, names, ","); for (i = 1; i <= n; i++) print names[i], ($2 ~ /^[A-Z][A-Z0-9_]*($|:)/ ? $2 : "") }' <<<"$text"
}

# render PAGE: the page as text, 80 columns, no overstrikes; warnings into $scratch/warnings.
render() { groff -man -Tascii -ww -rLL=80n -P-cbou "$1" 2>"$scratch/warnings"; }  # outside files/, where completion looks

check_page() {  # check_page PAGE EXE [COMMAND]
  local page=$1
  shift
  local text name type line
  text=$(render "$page")
  [ -s "$scratch/warnings" ] && fail "$page: groff warns: $(head -3 "$scratch/warnings")"
  remember_help "$@"
  while read -r name type; do
    grep -qE -- "(^|[^-[:alnum:]])${name}([^-[:alnum:]]|\$)" <<<"$text" || fail "$page: no $name, which '$* --help' lists"
  done < <(help_options "$@")
  local examples
  # The examples: the lines of the EXAMPLES section that start with the program's name, each joined with
  # the lines it continues into (a backslash at the end).
  examples=$(awk '/^EXAMPLES/ { on = 1; next } /^[A-Z]/ { on = 0 }
                  on { if (sub(/ \\$/, " ")) { held = held $0; next } print held $0; held = "" }' <<<"$text" |
             grep -E "^ +$(basename "$1")( |\$)")
  [ -z "$examples" ] && [ "$(basename "$page")" != heightpack-info.1 ] && echo "manual_test: note: $page has no examples"
  while read -r line; do
    [ -z "$line" ] && continue
    local all words=() word
    read -ra all <<<"$line"
    # The command itself, without what the shell does with its output (> file, | other, && next).
    for word in "${all[@]}"; do
      case $word in '>'* | '|'* | '&&' | ';' | '2>'*) break ;; esac
      words+=("$word")
    done
    words[0]=$1
    if ! out=$(timeout 30 "${words[@]}" --help 2>&1 >/dev/null); then
      fail "$page: the example '$line' does not parse: $out"
    fi
  done <<<"$examples"
}

# complete_words WORD...: what the completion offers for the last word, into $got (words in the order
# offered, spaces between). No subshell: a few hundred of these run in a second.
complete_words() {
  COMP_WORDS=("$@")
  COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
  COMPREPLY=()
  "$completer"
  got="${COMPREPLY[*]}"
}

expect_completion() {  # expect_completion EXPECTED WORD...: EXPECTED is the whole answer, in --help's order
  local expected=$1
  shift
  complete_words "$@"
  [ "$got" == "$expected" ] || fail "completing '$*': got '$got', expected '$expected'"
}

check_completion() {  # check_completion PROGRAM EXE [COMMAND]: every option of one command
  local program=$1 exe=$2
  shift 2
  local name type
  while read -r name type; do
    [[ $name == -* ]] || continue
    type=${type%%=*}  # TEXT:LENGTH=100km: the default follows an '=' 
    complete_words "$program" "$@" "${name%?}"
    [[ " $got " == *" $name "* ]] || fail "completing '$program $* ${name%?}' does not offer $name"
    if [[ $type == *"{"*"}"* ]]; then
      local choices=${type#*\{}
      choices=${choices%%\}*}
      expect_completion "${choices//,/ }" "$program" "$@" "$name" ""
    elif [ -n "$type" ]; then
      # Files after text or a path; nothing after a number or a value of its own kind (TEXT:LENGTH).
      local kind=${type%%:*} named=${type#*:}
      [[ $kind == TEXT && $type == *:* && $named =~ ^[A-Z][A-Z0-9_]*$ ]] && kind=$named
      case $kind in
        TEXT | FILE | PATH | DIR) expect_completion "swell.png" "$program" "$@" "$name" "sw" ;;
        *) expect_completion "" "$program" "$@" "$name" "" ;;
      esac
    fi
  done < <(help_options "$exe" "$@")
}

mkdir "$scratch/files" && cd "$scratch/files" && touch swell.png
for exe in "${exes[@]}"; do
  program=$(basename "$exe")
  pages="$manual_dir/$program/man1"
  script="$manual_dir/$program/completions/$program"
  commands=$("$exe" --help | awk '/^[A-Za-z].*:$/ { section = $0; next } section == "Subcommands:" && /^  [a-z]/ { print $1 }')
  [ -f "$pages/$program.1" ] || fail "no page $pages/$program.1"
  check_page "$pages/$program.1" "$exe"
  for command in $commands; do
    if [ -f "$pages/$program-$command.1" ]; then check_page "$pages/$program-$command.1" "$exe" "$command"
    else fail "no page for '$program $command' in $pages"; fi
  done
  for page in "$pages"/*.1; do
    name=$(basename "$page" .1)
    [ "$name" == "$program" ] || grep -qx "${name#"$program"-}" <<<"$commands" || fail "$page: a page for no command"
  done

  # shellcheck source=/dev/null
  source "$script" || fail "$script does not load in bash"
  completer=$(complete -p "$program" 2>/dev/null | sed -E 's/.*-F ([^ ]+) .*/\1/')
  [ -z "$completer" ] && { fail "$script registers no completion for $program"; continue; }
  for command in $commands; do
    complete_words "$program" "${command:0:2}"
    [[ " $got " == *" $command "* ]] || fail "completing '$program ${command:0:2}' does not offer $command"
    check_completion "$program" "$exe" "$command"
  done
  [ -z "$commands" ] && check_completion "$program" "$exe"
done

if [ -f "$manual_dir/heightpack/completions/heightpack" ]; then
  source "$manual_dir/heightpack/completions/heightpack"
  completer=_heightpack
  # The two the issue names, and the --name=value form.
  expect_completion "pack" heightpack pa
  expect_completion "--filter" heightpack pack --fi
  expect_completion "periodic clamp" heightpack pack --wrap =
  expect_completion "periodic" heightpack pack --wrap = per
fi

if [ "$failures" -gt 0 ]; then
  echo "manual_test: $failures failure(s)"
  exit 1
fi
echo "manual_test: every page renders, lists what --help lists, and its examples parse; the completion offers the same"
