#!/usr/bin/env bash
# End-to-end: grid jobs (picture commands with --out PREFIX) trust nothing they find.
#   * a second run on a prefix in use exits 2 and names the process that holds it; the
#     shards of one job run side by side, and merge to the whole run's numbers;
#   * SIGTERM removes every .partial file, keeps the finished tiles, says how to resume,
#     and ends by the signal (status 143); the rerun resumes and gives the same numbers;
#   * a saved tile edited by hand (bad checksum) or from another build is recomputed, and
#     the run says so; the outputs are those of a clean run;
#   * a missing --out folder, and a merge with missing tiles, exit 2 and create nothing.
# Usage: bash grid_edges.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
on_exit 'kill $(jobs -p) 2>/dev/null || true'
cd "$TMP"

JOB=(basin --model constant --eps 0.5 --a 24 --quiet)
SMALL=(--grid 48x32)
LONG=(--grid 200x150 --threads 1)

# Reference: a clean run of the small job.
"$BOUNCER" "${JOB[@]}" "${SMALL[@]}" --out ref

# --- A prefix in use ---------------------------------------------------------------------
wait_for_tiles() {  # wait_for_tiles DIR N: until DIR holds N finished tiles (at most ~60 s)
  for _ in $(seq 600); do
    [[ $(find "$1" -name 'tile-*' ! -name '*.partial' 2>/dev/null | wc -l) -ge $2 ]] && return 0
    sleep 0.1
  done
  return 1
}
"$BOUNCER" "${JOB[@]}" "${LONG[@]}" --out busy 2>busy.err &
holder=$!
wait_for_tiles busy.tiles 1 || fail lock "the long run saved no tile"
refused lock "in use by process $holder " "${JOB[@]}" "${LONG[@]}" --out busy
rc=0
"$BOUNCER" "${JOB[@]}" "${LONG[@]}" --out busy --shard 1/2 >/dev/null 2>shard.err || rc=$?
[[ $rc -eq 2 ]] || fail lock "a shard run on a prefix a whole run holds: exit $rc, expected 2"

# --- SIGTERM: partial files removed, tiles kept, resume -------------------------------------
kill -TERM "$holder"
rc=0
wait "$holder" || rc=$?
[[ $rc -eq 143 ]] || fail sigterm "exit $rc, expected 143 (ended by SIGTERM)"
grep -q "interrupted by SIGTERM; partial files removed; finished tiles are kept in busy.tiles/: run the same command again to resume" busy.err ||
  fail sigterm "message: $(head -c 300 busy.err)"
[[ -z $(find . -name '*.partial') ]] || fail sigterm "partial files left: $(find . -name '*.partial' | head -3)"
[[ ! -e busy.csv && ! -e busy.png && ! -e busy.json ]] || fail sigterm "an output was written by the interrupted run"
kept=$(find busy.tiles -name 'tile-*' | wc -l)
[[ $kept -ge 1 ]] || fail sigterm "no finished tile was kept"

# --- Shards side by side, then merge -----------------------------------------------------
"$BOUNCER" "${JOB[@]}" "${SMALL[@]}" --out sh --shard 0/2 --threads 1 &
s0=$!
"$BOUNCER" "${JOB[@]}" "${SMALL[@]}" --out sh --shard 1/2 --threads 1 &
s1=$!
rc0=0 rc1=0
wait $s0 || rc0=$?
wait $s1 || rc1=$?
[[ $rc0 -eq 0 && $rc1 -eq 0 ]] || fail shards "two shards of one job side by side: exit $rc0 and $rc1"
"$BOUNCER" merge sh --quiet || fail shards "merge failed"
cmp -s <(data ref.csv) <(data sh.csv) || fail shards "merged shards differ from the whole run"

# --- Tiles that cannot be trusted are recomputed ---------------------------------------------
"$BOUNCER" "${JOB[@]}" "${SMALL[@]}" --out t --keep-tiles
[[ -f t.tiles/tile-000001 && -f t.tiles/tile-000002 ]] || fail tiles "expected kept tiles"
# Hand edit: one digit of the first item of tile 1 changed, the checksum left as it was.
python3 - t.tiles/tile-000001 <<'EOF'
import re, sys
p = sys.argv[1]
s = open(p).read()
i = s.index("\nitem ") + 1
j = s.index("\n", i) + 1            # start of the first item's text
m = re.search(r"[1-8]", s[j:])
k = j + m.start()
open(p, "w").write(s[:k] + str(int(s[k]) + 1) + s[k + 1:])
EOF
# Another build: the build line changed and the checksum recomputed (FNV-1a 64).
python3 - t.tiles/tile-000002 <<'EOF'
import re, sys
p = sys.argv[1]
s = open(p).read()
s = re.sub(r"\nbuild [0-9a-f]+\n", "\nbuild 0123456789abcdef\n", s, count=1)
body = s[: s.rindex("end ")]
h = 14695981039346656037
for b in body.encode():
    h = ((h ^ b) * 1099511628211) % (1 << 64)
open(p, "w").write(body + "end %016x\n" % h)
EOF
"$BOUNCER" "${JOB[@]}" "${SMALL[@]}" --out t 2>t.err || fail tiles "the rerun failed: $(head -c 300 t.err)"
grep -q "2 saved tile(s) in t.tiles/ recomputed: 1 from another build, 1 with a bad checksum (damaged or edited)" t.err ||
  fail tiles "the rerun did not say which tiles it recomputed: $(head -c 300 t.err)"
cmp -s <(data ref.csv) <(data t.csv) || fail tiles "outputs differ from a clean run"

# --- Nothing is created on bad input ---------------------------------------------------------
rc=0
"$BOUNCER" "${JOB[@]}" "${SMALL[@]}" --out nodir/x 2>err || rc=$?
[[ $rc -eq 2 && ! -e nodir ]] || fail create "--out into a missing folder: exit $rc, nodir $( [[ -e nodir ]] && echo created || echo absent)"
"$BOUNCER" "${JOB[@]}" "${SMALL[@]}" --out part --shard 0/2 --quiet >/dev/null
rc=0
"$BOUNCER" merge part --out elsewhere 2>err || rc=$?
[[ $rc -eq 2 ]] || fail create "merge with missing tiles: exit $rc, expected 2"
[[ ! -e elsewhere.tiles && ! -e elsewhere.csv ]] || fail create "merge with missing tiles created outputs or folders"
grep -q "tiles are missing" err || fail create "merge message: $(head -c 300 err)"

# --- Resume after the interrupt ------------------------------------------------------------
"$BOUNCER" "${JOB[@]}" "${LONG[@]}" --out busy 2>resume.err || fail resume "the resumed run failed: $(head -c 300 resume.err)"
[[ -f busy.csv && -f busy.png && -f busy.json ]] || fail resume "the resumed run wrote no outputs"
"$BOUNCER" "${JOB[@]}" --grid 200x150 --out clean
cmp -s <(data clean.csv) <(data busy.csv) || fail resume "the resumed run differs from a clean run"

finish "grid_edges: lock, SIGTERM cleanup and resume, shards, untrusted tiles, nothing created on bad input"
