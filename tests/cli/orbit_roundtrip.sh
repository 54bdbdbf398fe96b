#!/usr/bin/env bash
# End-to-end: printed numbers round-trip. The impact map is deterministic and each printed
# theta/v reads back as exactly the same number at the same precision, so restarting from
# the printed state of row n and taking one step must print, character for character, the
# state of row n+1 of the original run. Checked for double, dd and mpfr:200 on orbits that go
# through impacts on both wall segments, indirect flights and sticking (release at (1/2, 4)).
# Usage: bash orbit_roundtrip.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3

# check NAME STEPS PRECISION MODEL-ARGS... -- THETA V
check() {
  local name=$1 steps=$2 precision=$3
  shift 3
  local model=()
  while [[ $1 != -- ]]; do model+=("$1"); shift; done
  shift
  local theta=$1 v=$2 rc=0
  "$BOUNCER" orbit "${model[@]}" --theta "$theta" --v "$v" --steps "$steps" --precision "$precision" \
    >"$TMP/$name.orig" 2>"$TMP/$name.err" || rc=$?
  if [[ $rc -ne 0 ]]; then
    fail "$name" "the original run exited $rc: $(cat "$TMP/$name.err")"
    return
  fi
  # Every state but the last, as the initial conditions of a one-step run (one orbit each).
  local thetas vs
  thetas=$(python3 -c 'import sys
rows=[l.split(",") for l in open(sys.argv[1]) if not l.startswith("#")][1:]
print(",".join(r[1] for r in rows[:-1]))' "$TMP/$name.orig")
  vs=$(python3 -c 'import sys
rows=[l.split(",") for l in open(sys.argv[1]) if not l.startswith("#")][1:]
print(",".join(r[2] for r in rows[:-1]))' "$TMP/$name.orig")
  rc=0
  "$BOUNCER" orbit "${model[@]}" --theta="$thetas" --v="$vs" --steps 1 --precision "$precision" \
    >"$TMP/$name.restart" 2>"$TMP/$name.err" || rc=$?
  if [[ $rc -ne 0 ]]; then
    fail "$name" "restarting from the printed states exited $rc: $(cat "$TMP/$name.err")"
    return
  fi
  python3 - "$TMP/$name.orig" "$TMP/$name.restart" "$name" "$steps" <<'PY' || fail "$name" "see above"
import sys
orig_f, restart_f, name, steps = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
def rows(f):
    L = [l.rstrip("\n").split(",") for l in open(f) if not l.startswith("#")]
    h = L[0]
    return [dict(zip(h, r)) for r in L[1:]]
orig = rows(orig_f)
restart = rows(restart_f)
bad = []
if [int(r["n"]) for r in orig] != list(range(steps + 1)):
    bad.append(f"original rows n = {[r['n'] for r in orig]}")
events = {r["event"] for r in orig}
# the next state of orbit i (restarted from row i) must be row i+1, as exact strings
nxt = {int(r["orbit"]): r for r in restart if r["n"] == "1"}
start = {int(r["orbit"]): r for r in restart if r["n"] == "0"}
if len(nxt) != steps:
    bad.append(f"{len(nxt)} restarted orbits took a step, expected {steps}")
for i in range(steps):
    a, b = orig[i + 1], nxt.get(i)
    s = start.get(i)
    if s is None or (s["theta"], s["v"]) != (orig[i]["theta"], orig[i]["v"]):
        bad.append(f"restart {i}: row 0 {s and (s['theta'], s['v'])} is not the printed state "
                   f"{(orig[i]['theta'], orig[i]['v'])} read back")
    if b is None or (b["theta"], b["v"], b["event"]) != (a["theta"], a["v"], a["event"]):
        bad.append(f"step {i}->{i+1}: restart gives {b and (b['theta'], b['v'], b['event'])}, "
                   f"original row {i+1} is {(a['theta'], a['v'], a['event'])}")
for x in bad[:10]:
    print(f"FAIL [{name}]:", x, file=sys.stderr)
if not bad:
    print(f"{name}: {steps} restarts reproduce the next row exactly (events: {', '.join(sorted(events))})")
sys.exit(1 if bad else 0)
PY
}

# eps = 0.5, a = 24 from (0.05, 10.5): chaotic transient, sticking at step 19, sticking cycle.
check double-default 30 double --model constant --a 24 --eps 0.5 -- 0.05 10.5
check mpfr200-default 30 mpfr:200 --model constant --a 24 --eps 0.5 -- 0.05 10.5
# eps = 0.96, a = 28.82 from the release state: long indirect flights, several periods.
check double-096 40 double --model constant --a 28.82 --eps 0.96 -- 0.5 4
check mpfr200-096 40 mpfr:200 --model constant --a 28.82 --eps 0.96 -- 0.5 4
# elastic, a = 19
check double-elastic 40 double --model elastic --a 19 -- 0.2125 28
check mpfr200-elastic 40 mpfr:200 --model elastic --a 19 -- 0.2125 28
# dd: a printed pair must read back as the same hi and lo (its digits span both words).
check dd-default 30 dd --model constant --a 24 --eps 0.5 -- 0.05 10.5
check dd-096 40 dd --model constant --a 28.82 --eps 0.96 -- 0.5 4
check dd-veldep 40 dd --model veldep --a 25 --c 1000 -- 0.1 5

finish "orbit_roundtrip.sh: printed states round-trip through the command line (double, dd, mpfr:200)"
