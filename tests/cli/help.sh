#!/usr/bin/env bash
# End-to-end: help and version.
#   - `bouncer --help` exits 0 and lists the orbit subcommand;
#   - `bouncer orbit --help` exits 0 and documents every option of orbit (model, a, eps, c,
#     wall, downward-sticking, theta, v, steps, precision, format, every, out, scene), with
#     the allowed ranges of the numeric ones;
#   - `bouncer --version` exits 0 and names version and commit;
#   - every command the documentation describes (docs/guide/) is listed by `bouncer --help`, and its own --help
#     exits 0 (the table of commands, lib/.../workflow/commands.hpp, and the binding of each
#     row to its options, tools/commands.cpp, are complete);
#   - `bouncer` without a subcommand is bad input (status 2, one line on stderr);
#   - -V is --version ("bouncer X.Y.Z (commit ...)"); usage lines say "bouncer CMD"; no option
#     is typed as bare TEXT; REQUIRED is shown; a repeated option, a missing audit file and
#     an unknown command get bouncer's own one-line errors pointing at the right help.
# Usage: bash help.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"

rc=0
"$BOUNCER" --help >"$TMP/top" 2>&1 || rc=$?
[[ $rc -eq 0 ]] || fail "bouncer --help" "exit status $rc"
grep -qE '^[[:space:]]+orbit[[:space:]]' "$TMP/top" || fail "bouncer --help" "does not list the orbit subcommand: $(cat "$TMP/top")"

rc=0
"$BOUNCER" orbit --help >"$TMP/orbit" 2>&1 || rc=$?
[[ $rc -eq 0 ]] || fail "bouncer orbit --help" "exit status $rc"
for opt in model a eps c wall downward-sticking theta v steps precision format every out scene; do
  grep -qE -- "(^|[[:space:],])--$opt([[:space:]]|$)" "$TMP/orbit" ||
    fail "bouncer orbit --help" "does not document --$opt"
done
# each numeric option's help states what is allowed (the same ranges the errors name)
check_range() {  # OPTION FIXED-STRING
  # (no `| grep -q`: with pipefail an early exit of grep -q can fail the pipeline)
  local line
  line=$(grep -E -- "(^|[[:space:],])--$1[[:space:]]" "$TMP/orbit" || true)
  [[ $line == *"$2"* ]] ||
    fail "bouncer orbit --help" "the line of --$1 does not say '$2'"
}
check_range a "> 0"
check_range eps "[0, 1]"
check_range c "> 0"
check_range theta "[0, 1)"
check_range v "wall velocity"
check_range steps ">= 0"
check_range every ">= 1"
check_range precision "16 <= BITS <= 1048576"
check_range model "elastic"
check_range format "json"

for cmd in orbit certify-sticking certify-periodic certify-chaos check-certificate sweep audit periodic lyapunov classify bifurcation \
  portrait basin scan merge continue trajectory tongues reproduce; do
  grep -qE "^[[:space:]]+$cmd[[:space:]]" "$TMP/top" || fail "bouncer --help" "does not list $cmd"
  rc=0
  "$BOUNCER" "$cmd" --help >"$TMP/cmd" 2>&1 || rc=$?
  [[ $rc -eq 0 ]] || fail "bouncer $cmd --help" "exit status $rc: $(head -c 300 "$TMP/cmd")"
  grep -q "Usage:" "$TMP/cmd" || fail "bouncer $cmd --help" "prints no usage"
done

rc=0
"$BOUNCER" --version >"$TMP/version" 2>&1 || rc=$?
[[ $rc -eq 0 ]] || fail "bouncer --version" "exit status $rc"
grep -qE '[0-9]+\.[0-9]+\.[0-9]+.*commit' "$TMP/version" || fail "bouncer --version" "no version and commit: $(cat "$TMP/version")"

refused "bouncer (no subcommand)" ""

# -V is --version, and names the program
rc=0
"$BOUNCER" -V >"$TMP/V" 2>&1 || rc=$?
[[ $rc -eq 0 ]] || fail "bouncer -V" "exit status $rc: $(cat "$TMP/V")"
grep -qE '^bouncer [0-9]+\.[0-9]+\.[0-9]+ \(commit ' "$TMP/V" || fail "bouncer -V" "not 'bouncer X.Y.Z (commit ...)': $(cat "$TMP/V")"
cmp -s "$TMP/V" "$TMP/version" || fail "bouncer -V" "differs from --version"
# `help` is listed among the ways in
grep -q "bouncer help COMMAND" "$TMP/top" || fail "bouncer --help" "does not mention bouncer help COMMAND"

# Every command's help: usage names the program (not the path it was started from), and no
# option's value is described as bare TEXT (each says NUMBER, INT, PATH, LO:HI, ...: the
# table tools/option_types.cpp); options the command needs say REQUIRED.
for cmd in $("$BOUNCER" --help | awk '/^Subcommands:/ {f = 1; next} f && !NF {exit} f {print $1}'); do
  "$BOUNCER" "$cmd" --help >"$TMP/cmd" 2>&1
  grep -q "^Usage: bouncer $cmd " "$TMP/cmd" || fail "bouncer $cmd --help" "usage does not start 'bouncer $cmd': $(grep Usage "$TMP/cmd")"
  if grep -qE -- '--[a-z0-9-]+ TEXT' "$TMP/cmd"; then
    fail "bouncer $cmd --help" "options typed as bare TEXT: $(grep -oE -- '--[a-z0-9-]+ TEXT' "$TMP/cmd" | tr '\n' ' ')"
  fi
done
"$BOUNCER" continue --help >"$TMP/cont"
grep -qE -- '--period INT REQUIRED' "$TMP/cont" || fail "bouncer continue --help" "--period is not 'INT REQUIRED'"
grep -qE -- '--range LO:HI REQUIRED' "$TMP/cont" || fail "bouncer continue --help" "--range is not 'LO:HI REQUIRED'"
grep -qE -- '--a NUMBER ' "$TMP/cont" || fail "bouncer continue --help" "--a is not NUMBER"
grep -qE -- '--precision PREC ' "$TMP/cont" || fail "bouncer continue --help" "--precision is not PREC"

# An option of one value given twice is bouncer's own one-line error, naming it
refused "orbit --eps twice" "eps: --eps is given twice" orbit --model constant --eps 0.5 --eps 0.6 --a 10 --theta 0.1 --v 5
# A command's missing argument points at that command's help
refused "audit without a file" "see bouncer audit --help" audit
# An unknown command suggests help among the commands
refused "bouncer hlep" "did you mean 'help'" hlep

finish "help.sh: help lists orbit and every orbit option; --version works"
