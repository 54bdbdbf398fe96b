#!/usr/bin/env bash
# End-to-end: `bouncer orbit` streams. 10^7 steps of the fixed point (0.25, 12) at eps = 0.5,
# a = 24 (paper eq. 5) with --every 1000000 print exactly 11 rows (n = 0, 10^6, ..., 10^7),
# every one still at the fixed point, and the process's peak resident memory stays below
# 50 MB (memory must not grow with the number of steps). The peak RSS is measured with GNU
# time (/usr/bin/time -v); without it that part is skipped with a message.
# Usage: bash orbit_stream.sh <bouncer-binary> <source-dir>
set -euo pipefail
BOUNCER=${1:?usage: bash orbit_stream.sh <bouncer-binary> <source-dir>}
SRC=${2:?usage: bash orbit_stream.sh <bouncer-binary> <source-dir>}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

ARGS=(orbit --model constant --a 24 --eps 0.5 --theta 0.25 --v 12 --steps 10000000 --every 1000000)
limit_kb=$((50 * 1024))
rss_kb=""
rc=0
# (ASan is linked statically by clang, the sanitized build's compiler, dynamically by g++:
# its entry point in the binary tells either.)
if grep -qa __asan_init "$BOUNCER"; then
  # build-sanitize/ (`tools/setup sanitize`): ASan's shadow memory and its quarantine of freed
  # blocks are part of the resident set, so the 50 MB bound says nothing about streaming there.
  echo "orbit_stream.sh: AddressSanitizer build: peak memory NOT checked (shadow memory and quarantine)"
  "$BOUNCER" "${ARGS[@]}" >"$TMP/out.csv" 2>"$TMP/err" || rc=$?
elif [[ -x /usr/bin/time ]] && /usr/bin/time -v true >/dev/null 2>&1; then
  /usr/bin/time -v -o "$TMP/time" "$BOUNCER" "${ARGS[@]}" >"$TMP/out.csv" 2>"$TMP/err" || rc=$?
  rss_kb=$(sed -n 's/^[[:space:]]*Maximum resident set size (kbytes): *\([0-9][0-9]*\)$/\1/p' "$TMP/time")
else
  echo "orbit_stream.sh: GNU time (/usr/bin/time -v) not available: peak memory NOT checked (apt-get install time)"
  "$BOUNCER" "${ARGS[@]}" >"$TMP/out.csv" 2>"$TMP/err" || rc=$?
fi
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
if [[ -n $rss_kb ]]; then
  if (( rss_kb >= limit_kb )); then
    echo "FAIL: peak resident memory $rss_kb kB >= $limit_kb kB for 10^7 steps (not streaming?)" >&2
    failures=$((failures + 1))
  else
    echo "orbit_stream.sh: peak resident memory $rss_kb kB (limit $limit_kb kB)"
  fi
elif [[ -e $TMP/time ]]; then
  echo "FAIL: could not read the peak RSS from GNU time's report: $(cat "$TMP/time")" >&2
  failures=$((failures + 1))
fi

if [[ $failures -ne 0 ]]; then exit 1; fi
echo "orbit_stream.sh: 10^7 steps streamed as 11 rows"
