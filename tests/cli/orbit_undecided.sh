#!/usr/bin/env bash
# End-to-end: an interval orbit at a low bit count must stop at an undecided step, and that
# is a result, not an error:
#   - exit status 0, output written (also with --out, atomically);
#   - the final line is "# end: orbit 0 undecided at step N: REASON (...)";
#   - stderr says "stopped at step N: REASON (not certified at 20 bits ...)";
#   - exactly N rows, n = 0..N-1, and each encloses the mpfr:256 orbit of the same decimals;
#   - json: end.status "undecided", end.steps_done = N-1.
# Orbits: the default scene's chaotic transient (eps = 0.5, a = 24, from (0.05, 10.5)) and an
# elastic orbit at a = 19; at 20 bits neither can stay certified for 2000 steps.
# Usage: bash orbit_undecided.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3

check() {  # check NAME MODEL-ARGS... : theta/v included in the args
  local name=$1 rc=0
  shift
  "$BOUNCER" orbit "$@" --steps 2000 --precision interval:20 >"$TMP/$name.csv" 2>"$TMP/$name.err" || rc=$?
  if [[ $rc -ne 0 ]]; then
    fail "$name" "an undecided orbit is a result: expected exit 0, got $rc: $(cat "$TMP/$name.err")"
    return
  fi
  local last n reason
  last=$(tail -n 1 "$TMP/$name.csv")
  if [[ ! $last =~ ^#\ end:\ orbit\ 0\ undecided\ at\ step\ ([0-9]+):\ (.+)\ \( ]]; then
    fail "$name" "the final line does not say 'undecided at step N: REASON': $last"
    return
  fi
  n=${BASH_REMATCH[1]}
  reason=${BASH_REMATCH[2]}
  [[ ${#reason} -ge 10 ]] || fail "$name" "the reason is too short to name anything: '$reason'"
  if (( n < 2 || n > 2000 )); then fail "$name" "undecided at step $n, outside 2..2000"; fi
  grep -q 'completed' "$TMP/$name.csv" && fail "$name" "the output also claims completion"
  if [[ $(wc -l <"$TMP/$name.err") -ne 1 ]] ||
     ! grep -qF "stopped at step $n: $reason (not certified at 20 bits" "$TMP/$name.err"; then
    fail "$name" "stderr should say 'stopped at step $n: $reason (not certified at 20 bits ...)', got: $(cat "$TMP/$name.err")"
  fi
  # rows n = 0..N-1 exactly
  local ns
  ns=$(grep -v '^#' "$TMP/$name.csv" | tail -n +2 | cut -d, -f1 | tr '\n' ' ')
  [[ $ns == "$(seq -s ' ' 0 $((n - 1))) " ]] || fail "$name" "undecided at step $n but rows are n = $ns"
  # the certified rows enclose a high-precision orbit of the same exact decimals
  local rc2=0
  "$BOUNCER" orbit "$@" --steps $((n - 1)) --precision mpfr:256 >"$TMP/$name.ref" 2>/dev/null || rc2=$?
  [[ $rc2 -eq 0 ]] || { fail "$name" "the mpfr:256 reference run failed"; return; }
  python3 - "$TMP/$name.csv" "$TMP/$name.ref" "$name" <<'PY' || fail "$name" "see above"
import sys
from fractions import Fraction as F
def rows(f):
    L = [l.rstrip("\n").split(",") for l in open(f) if not l.startswith("#")]
    return [dict(zip(L[0], r)) for r in L[1:]]
iv, ref, name = rows(sys.argv[1]), rows(sys.argv[2]), sys.argv[3]
bad = [f"{len(iv)} interval rows vs {len(ref)} reference rows"] if len(iv) != len(ref) else []
for a, b in zip(iv, ref):
    for k in ("theta", "v"):
        if not F(a[k + "_lo"]) <= F(b[k]) <= F(a[k + "_hi"]):
            bad.append(f"n={a['n']}: {k} [{a[k+'_lo']}, {a[k+'_hi']}] does not enclose mpfr:256 {b[k]}")
for x in bad[:10]:
    print(f"FAIL [{name}]:", x, file=sys.stderr)
sys.exit(1 if bad else 0)
PY
  # --out: the undecided result is written, atomically
  mkdir -p "$TMP/o"
  rc=0
  "$BOUNCER" orbit "$@" --steps 2000 --precision interval:20 --out "$TMP/o/$name.csv" >/dev/null 2>&1 || rc=$?
  [[ $rc -eq 0 && -s $TMP/o/$name.csv && ! -e $TMP/o/$name.csv.partial ]] ||
    fail "$name" "with --out: status $rc, file written: $([[ -s $TMP/o/$name.csv ]] && echo yes || echo no), partial left: $([[ -e $TMP/o/$name.csv.partial ]] && echo yes || echo no)"
  # json
  rc=0
  "$BOUNCER" orbit "$@" --steps 2000 --precision interval:20 --format json >"$TMP/$name.json" 2>/dev/null || rc=$?
  python3 -c '
import json, sys
d = json.load(open(sys.argv[1])); n = int(sys.argv[2])
o = d["orbits"][0]; e = o["end"]
assert e["status"] == "undecided", e
assert e["steps_done"] == n - 1, (e, n)
assert len(o["rows"]) == n, (len(o["rows"]), n)
assert "undecided at step %d" % n in e["message"], e
' "$TMP/$name.json" "$n" || fail "$name" "json (status $rc) does not report the same undecided step $n"
  echo "$name: undecided at step $n ($reason)"
}

# Iterated boxes (--method naive) lose this sticking orbit to the wrapping effect; Lohner's
# method (the default for interval runs) carries it through all 2000 steps at 20 bits,
# since every sticking episode releases at a state that does not depend on the input.
check default-sticking-naive --model constant --a 24 --eps 0.5 --theta 0.05 --v 10.5 --method naive
"$BOUNCER" orbit --model constant --a 24 --eps 0.5 --theta 0.05 --v 10.5 --steps 2000 --precision interval:20 \
  >"$TMP/lohner-sticking.csv" 2>/dev/null
[[ $(tail -n 1 "$TMP/lohner-sticking.csv") == "# end: orbit 0 completed 2000 steps" ]] ||
  fail lohner-sticking "the default (lohner) run did not complete: $(tail -n 1 "$TMP/lohner-sticking.csv")"
check elastic-19 --model elastic --a 19 --theta 0.1 --v 7

finish "orbit_undecided.sh: low-precision interval orbits stop at an undecided step and say so"
