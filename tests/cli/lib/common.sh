# Shared by the CLI tests (tests/cli/*.sh; this file is in lib/ so that the tests' glob in
# tests/CMakeLists.txt does not register it as a test). Each script keeps its own `set`
# line (with or without -e) and then sources this file with its arguments:
#
#     set -euo pipefail
#     source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
#
# which gives it
#   BOUNCER, SRC   the two arguments, `bash SCRIPT <bouncer-binary> <source-dir>`, both
#                  required (ctest passes both); BOUNCER must be executable;
#   TMP            a private temporary directory (mktemp -d), removed on exit, with the
#                  commands given to `on_exit` run first;
#   CLI_NAME       the script's name without .sh, for messages;
# and the functions below. Failures are counted (`fail`), and `finish` gives the verdict:
# every check runs and every failure is reported, not just the first. `die` is for checks
# after which nothing else can be checked (exit 1 at once), `skip` for a test that cannot run
# here (exit 77: ctest reports it as skipped, never as passed).
#
# Every function returns 0 unless its description says otherwise, so that a call is safe
# as the last command of a function under `set -e`.

CLI_NAME=$(basename "$0" .sh)
BOUNCER=${1:?usage: bash $CLI_NAME.sh <bouncer-binary> <source-dir>}
# shellcheck disable=SC2034  # SRC is for the scripts that source this file
SRC=${2:?usage: bash $CLI_NAME.sh <bouncer-binary> <source-dir>}
# The inline Python checks import clichecks (check, done) from this directory.
export PYTHONPATH="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)${PYTHONPATH:+:$PYTHONPATH}"
[[ -x $BOUNCER ]] || { echo "FAIL: bouncer binary '$BOUNCER' is not executable" >&2; exit 1; }
TMP=$(mktemp -d)
CLI_ON_EXIT=()
cli_cleanup() {
  local hook
  for hook in "${CLI_ON_EXIT[@]}"; do eval "$hook" || true; done
  rm -rf "$TMP"
}
trap cli_cleanup EXIT
failures=0

# on_exit COMMAND: run COMMAND (eval) on exit, before TMP is removed.
on_exit() { CLI_ON_EXIT+=("$1"); }

# fail NAME MESSAGE: report a failed check and count it; the script goes on.
fail() { echo "FAIL [$1]: $2" >&2; failures=$((failures + 1)); }

# die MESSAGE: report a failure after which nothing more can be checked; exit 1 now.
die() { echo "FAIL: $*" >&2; exit 1; }

# skip REASON: the test cannot run here; exit 77 (ctest: skipped).
skip() { echo "$CLI_NAME: SKIPPED: $*"; exit 77; }

# finish [MESSAGE]: the end of a script. Exit 1 with the number of failed checks if any
# failed; else print MESSAGE (default "NAME: all checks passed") and exit 0.
finish() {
  if ((failures > 0)); then
    echo "$CLI_NAME: $failures failure(s)" >&2
    exit 1
  fi
  echo "${1:-$CLI_NAME: all checks passed}"
  exit 0
}

# require COMMAND: a tool the checks need (python3, jq); its absence is a failure, exit 1.
require() { command -v "$1" >/dev/null || die "$1 is needed to check the outputs"; }

# asan_build: status 0 if BOUNCER is built with AddressSanitizer. Its entry point is in the
# binary either way: clang links the runtime statically, g++ dynamically.
asan_build() { grep -qa __asan_init "$BOUNCER"; }

# run NAME ARGS...: `bouncer ARGS` must exit 0; stdout goes to TMP/NAME.out, stderr to
# TMP/NAME.err. Returns 1 (after counting the failure) if it did not.
run() {
  local name=$1 rc=0
  shift
  "$BOUNCER" "$@" >"$TMP/$name.out" 2>"$TMP/$name.err" || rc=$?
  if [[ $rc -ne 0 ]]; then
    fail "$name" "exit status $rc (bouncer $*): $(head -c 500 "$TMP/$name.err")"
    return 1
  fi
  return 0
}

# refused [-E] [-t SECONDS] NAME PATTERN ARGS...: `bouncer ARGS` is refused as bad input:
# exit status 2, nothing on stdout, and on stderr exactly one newline-terminated line that
# starts with "bouncer" and matches PATTERN (grep's basic regex; -E: extended; "": any).
# -t: the run must also end within SECONDS. stdout and stderr stay in TMP/refused.out and
# TMP/refused.err (REFUSED_OUT, REFUSED_ERR) until the next call. Files the command must not
# have written: check them with `absent` or `empty_dir`.
REFUSED_OUT=$TMP/refused.out
REFUSED_ERR=$TMP/refused.err
refused() {
  local grep_mode=() limit=()
  while [[ $1 == -* ]]; do
    case $1 in
      -E) grep_mode=(-E); shift ;;
      -t) limit=(timeout "$2"); shift 2 ;;
      *) die "refused: unknown option $1" ;;
    esac
  done
  local name=$1 pattern=$2 rc=0
  shift 2
  "${limit[@]}" "$BOUNCER" "$@" >"$REFUSED_OUT" 2>"$REFUSED_ERR" || rc=$?
  local err lines
  err=$(head -c 300 "$REFUSED_ERR" | tr '\n' '|')
  lines=$(wc -l <"$REFUSED_ERR")
  if [[ $rc -ne 2 ]]; then
    fail "$name" "exit status $rc, expected 2 (bouncer $*): $err"
  fi
  if [[ $lines -ne 1 || $(wc -c <"$REFUSED_ERR") -ne $(head -n 1 "$REFUSED_ERR" | wc -c) ]]; then
    fail "$name" "expected exactly one newline-terminated line on stderr, got $lines: $err"
  elif [[ $(head -c 7 "$REFUSED_ERR") != bouncer ]]; then
    fail "$name" "the stderr line does not start with 'bouncer': $err"
  elif [[ -n $pattern ]] && ! grep -q "${grep_mode[@]}" -- "$pattern" "$REFUSED_ERR"; then
    fail "$name" "the stderr line does not match '$pattern': $err"
  fi
  if [[ -s $REFUSED_OUT ]]; then
    fail "$name" "something was written to stdout: $(head -c 200 "$REFUSED_OUT")"
  fi
  return 0
}

# absent NAME PATH...: none of the paths exists (a PATH may be a glob, expanded here).
absent() {
  local name=$1 path found
  shift
  for path in "$@"; do
    found=$(compgen -G "$path" | tr '\n' ' ' || true)
    [[ -z $found ]] || fail "$name" "left behind: $found"
  done
  return 0
}

# empty_dir NAME DIR: DIR holds nothing (no file, no hidden file).
empty_dir() {
  local left
  left=$(ls -A "$2" 2>&1) || true
  [[ -z $left ]] || fail "$1" "left behind in $2: $left"
  return 0
}

# outputs NAME PREFIX [EXT...]: the output set of a run with --out PREFIX: every PREFIX.EXT
# (default csv png json) exists and is not empty, and neither PREFIX.tiles nor a
# PREFIX.*.partial file is left.
outputs() {
  local name=$1 prefix=$2 ext
  shift 2
  (($# > 0)) || set -- csv png json
  for ext in "$@"; do [[ -s $prefix.$ext ]] || fail "$name" "missing $prefix.$ext"; done
  [[ ! -e $prefix.tiles ]] || fail "$name" "$prefix.tiles was left behind"
  absent "$name" "$prefix.*.partial"
}

# data FILE: a CSV's lines without the provenance comments (the header and the rows).
data() { grep -v '^#' "$1"; }

# rows FILE: a CSV's rows (no provenance comments, no header).
rows() { grep -v '^#' "$1" | tail -n +2; }

# jq_is NAME FILTER EXPECTED FILE: `jq -r FILTER FILE` prints EXPECTED.
jq_is() {
  local got
  got=$(jq -r "$2" "$4" 2>&1) || { fail "$1" "jq failed on $4: $got"; return 0; }
  [[ $got == "$3" ]] || fail "$1" "$2 = '$got', expected '$3'"
  return 0
}

# json_holds NAME EXPRESSION [FILE]: the python EXPRESSION is true of the JSON in FILE
# (default TMP/NAME.out, as written by `run NAME`), given as j; F is fractions.Fraction and
# inside(x, e) says that the exact rational x lies in the decimal enclosure e = [lo, hi].
json_holds() {
  python3 - "${3:-$TMP/$1.out}" "$2" <<'PY' || fail "$1" "check failed: $2"
import json, sys
from fractions import Fraction as F
j = json.load(open(sys.argv[1]))
def inside(x, e):
    return F(e[0]) <= F(x) <= F(e[1])
sys.exit(0 if eval("(" + sys.argv[2] + ")", {"j": j, "inside": inside, "F": F}) else 1)
PY
  return 0
}

# audited NAME FILE: `bouncer audit FILE` exits 0 and finds the result IDENTICAL (its
# output in TMP/audit.txt).
audited() {
  local rc=0
  "$BOUNCER" audit "$2" >"$TMP/audit.txt" 2>&1 || rc=$?
  [[ $rc -eq 0 ]] && grep -q IDENTICAL "$TMP/audit.txt" || fail "$1" "audit of $2: exit $rc: $(tail -c 300 "$TMP/audit.txt")"
  return 0
}
