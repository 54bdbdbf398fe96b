#!/usr/bin/env bash
# End-to-end: `bouncer orbit` streams in constant memory. 10^7 steps of the eq. 5 fixed point
# with --every 1000000 keep the process's peak resident memory below 50 MB, measured by GNU
# time (/usr/bin/time -v; tools/setup installs it: its absence is a failure, not a pass).
# Under AddressSanitizer (build-sanitize/) the bound says nothing (shadow memory and the
# quarantine of freed blocks are resident): exit 77, ctest's skipped.
# Usage: bash orbit_stream_memory.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
if asan_build; then skip "AddressSanitizer build (shadow memory and quarantine are resident)"; fi
/usr/bin/time -v true >/dev/null 2>&1 ||
  die "GNU time (/usr/bin/time -v) is missing: apt-get install time (tools/setup installs it)"
limit_kb=$((50 * 1024))
/usr/bin/time -v -o "$TMP/time" "$BOUNCER" orbit --model constant --a 24 --eps 0.5 --theta 0.25 --v 12 \
  --steps 10000000 --every 1000000 >"$TMP/out.csv" 2>"$TMP/err" || die "exit $?: $(head -c 300 "$TMP/err")"
[[ $(grep -vc '^#' "$TMP/out.csv") -eq 12 ]] || die "expected a header and 11 rows"
rss_kb=$(sed -n 's/^[[:space:]]*Maximum resident set size (kbytes): *\([0-9][0-9]*\)$/\1/p' "$TMP/time")
[[ -n $rss_kb ]] || die "no peak RSS in GNU time's report: $(cat "$TMP/time")"
(( rss_kb < limit_kb )) || die "peak resident memory $rss_kb kB >= $limit_kb kB for 10^7 steps (not streaming?)"
echo "orbit_stream_memory: peak resident memory $rss_kb kB (limit $limit_kb kB)"
