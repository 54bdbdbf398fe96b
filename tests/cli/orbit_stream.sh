#!/usr/bin/env bash
# End-to-end: `bouncer orbit` streams. 10^7 steps of the fixed point (0.25, 12) at eps = 0.5,
# a = 24 (paper eq. 5) with --every 1000000 print exactly 11 rows (n = 0, 10^6, ..., 10^7),
# every one still at the fixed point. (That memory does not grow with the steps:
# orbit_stream_memory.sh.)
# Usage: bash orbit_stream.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"

ARGS=(orbit --model constant --a 24 --eps 0.5 --theta 0.25 --v 12 --steps 10000000 --every 1000000)
rc=0
"$BOUNCER" "${ARGS[@]}" >"$TMP/out.csv" 2>"$TMP/err" || rc=$?
[[ $rc -eq 0 ]] || die "exit status $rc: $(head -c 500 "$TMP/err")"

ns=$(rows "$TMP/out.csv" | cut -d, -f1 | tr '\n' ' ')
want="0 1000000 2000000 3000000 4000000 5000000 6000000 7000000 8000000 9000000 10000000 "
[[ $ns == "$want" ]] || fail rows "rows n = $ns; expected $want"
grep -q '^# end: orbit 0 completed 10000000 steps$' "$TMP/out.csv" ||
  fail end "no '# end: orbit 0 completed 10000000 steps' line: $(tail -n 1 "$TMP/out.csv")"
# Every printed state is still the fixed point (eigenvalues 1 and eps^2: no drift beyond rounding).
off=$(rows "$TMP/out.csv" |
  awk -F, '{ d = $2 - 0.25; if (d < 0) d = -d; e = $3 - 12; if (e < 0) e = -e; if (d > 1e-9 || e > 1e-9) print "n=" $1 " theta=" $2 " v=" $3 }')
[[ -z $off ]] || fail drift "the fixed point (0.25, 12) drifted: $off"
finish "orbit_stream.sh: 10^7 steps streamed as 11 rows"
