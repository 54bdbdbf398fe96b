#!/usr/bin/env bash
# End-to-end: `bouncer orbit` streams. 10^7 steps of the fixed point (0.25, 12) at eps = 0.5,
# a = 24 (paper eq. 5) with --every 1000000 print exactly 11 rows (n = 0, 10^6, ..., 10^7),
# every one still at the fixed point. (That memory does not grow with the steps:
# orbit_stream_memory.sh.)
# Usage: bash orbit_stream.sh <bouncer-binary> <source-dir>
set -euo pipefail
BOUNCER=${1:?usage: bash orbit_stream.sh <bouncer-binary> <source-dir>}
SRC=${2:?usage: bash orbit_stream.sh <bouncer-binary> <source-dir>}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

ARGS=(orbit --model constant --a 24 --eps 0.5 --theta 0.25 --v 12 --steps 10000000 --every 1000000)
rc=0
"$BOUNCER" "${ARGS[@]}" >"$TMP/out.csv" 2>"$TMP/err" || rc=$?
if [[ $rc -ne 0 ]]; then
  echo "FAIL: exit status $rc: $(head -c 500 "$TMP/err")" >&2
  exit 1
fi

failures=0
ns=$(grep -v '^#' "$TMP/out.csv" | tail -n +2 | cut -d, -f1 | tr '\n' ' ')
want="0 1000000 2000000 3000000 4000000 5000000 6000000 7000000 8000000 9000000 10000000 "
if [[ $ns != "$want" ]]; then
  echo "FAIL: rows n = $ns; expected $want" >&2
  failures=$((failures + 1))
fi
grep -q '^# end: orbit 0 completed 10000000 steps$' "$TMP/out.csv" || {
  echo "FAIL: no '# end: orbit 0 completed 10000000 steps' line: $(tail -n 1 "$TMP/out.csv")" >&2
  failures=$((failures + 1))
}
# Every printed state is still the fixed point (eigenvalues 1 and eps^2: no drift beyond rounding).
off=$(grep -v '^#' "$TMP/out.csv" | tail -n +2 |
  awk -F, '{ d = $2 - 0.25; if (d < 0) d = -d; e = $3 - 12; if (e < 0) e = -e; if (d > 1e-9 || e > 1e-9) print "n=" $1 " theta=" $2 " v=" $3 }')
if [[ -n $off ]]; then
  echo "FAIL: the fixed point (0.25, 12) drifted: $off" >&2
  failures=$((failures + 1))
fi
if [[ $failures -ne 0 ]]; then exit 1; fi
echo "orbit_stream.sh: 10^7 steps streamed as 11 rows"
