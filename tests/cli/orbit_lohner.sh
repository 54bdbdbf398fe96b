#!/usr/bin/env bash
# End-to-end: `bouncer orbit --precision interval:BITS --method lohner`.
#   - every row encloses the mpfr:512 orbit of the same exact decimals (theta, v, tau, and the
#     sticking columns), and the event, segment and period columns agree with it;
#   - on a chaotic elastic orbit at 64 bits, Lohner's sets stay certified more than twice as
#     long as iterated boxes (the wrapping effect that the method exists to remove);
#   - the fallback count is reported (csv comment line, json end.lohner_fallbacks);
#   - the scene key `method` works like the option;
#   - lohner with a point precision, or an unknown method: exit 2, one line naming `method`,
#     no output file.
# Usage: bash orbit_lohner.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3

# undecided_step FILE: the step at which the orbit stopped, or "none"
undecided_step() {
  local last
  last=$(grep '^# end: orbit 0' "$1")
  if [[ $last =~ undecided\ at\ step\ ([0-9]+) ]]; then echo "${BASH_REMATCH[1]}"; else echo none; fi
}

# encloses NAME INTERVAL-CSV REFERENCE-CSV
encloses() {
  python3 - "$2" "$3" "$1" <<'PY' || fail "$1" "see above"
import sys
from fractions import Fraction as F
def rows(f):
    L = [l.rstrip("\n").split(",") for l in open(f) if not l.startswith("#")]
    return [dict(zip(L[0], r)) for r in L[1:]]
iv, ref, name = rows(sys.argv[1]), rows(sys.argv[2]), sys.argv[3]
bad = [] if len(iv) == len(ref) and len(iv) > 1 else [f"{len(iv)} interval rows vs {len(ref)} reference rows"]
for a, b in zip(iv, ref):
    scal = ["theta", "v"] + (["tau"] if b["n"] != "0" else [])
    if b["event"] == "sticking":
        scal += ["stuck_theta", "stuck_v"]
    for k in scal:
        if not F(a[k + "_lo"]) <= F(b[k]) <= F(a[k + "_hi"]):
            bad.append(f"n={a['n']}: {k} [{a[k+'_lo']}, {a[k+'_hi']}] does not enclose mpfr:512 {b[k]}")
    for k in ("event", "periods", "segment", "corner", "sticking"):
        if a[k] != b[k]:
            bad.append(f"n={a['n']}: {k} is {a[k]!r}, the mpfr:512 orbit says {b[k]!r}")
for x in bad[:10]:
    print(f"FAIL [{name}]:", x, file=sys.stderr)
sys.exit(1 if bad else 0)
PY
}

# 1. Chaotic elastic orbit: Lohner against iterated boxes, and enclosure of the reference.
chaos=(--model elastic --a 19 --theta 0.1 --v 5)
"$BOUNCER" orbit "${chaos[@]}" --steps 1000 --precision interval:64 --method naive >"$TMP/naive.csv" 2>/dev/null
"$BOUNCER" orbit "${chaos[@]}" --steps 1000 --precision interval:64 --method lohner >"$TMP/lohner.csv" 2>/dev/null
# Interval runs default to Lohner's method, as the certified commands do.
"$BOUNCER" orbit "${chaos[@]}" --steps 1000 --precision interval:64 >"$TMP/default.csv" 2>/dev/null
cmp -s <(grep -v '^# invocation' "$TMP/default.csv" | grep -v '^# inputs') <(grep -v '^# invocation' "$TMP/lohner.csv" | grep -v '^# inputs') ||
  fail default "an interval run without --method is not the lohner run"
n_naive=$(undecided_step "$TMP/naive.csv")
n_lohner=$(undecided_step "$TMP/lohner.csv")
if [[ $n_naive == none || $n_lohner == none ]]; then
  fail chaos "both runs should stop undecided within 1000 steps at 64 bits (naive: $n_naive, lohner: $n_lohner)"
elif (( n_lohner <= 2 * n_naive )); then
  fail chaos "Lohner certified only to step $((n_lohner - 1)), iterated boxes to $((n_naive - 1))"
else
  echo "chaos: certified steps at 64 bits: naive $((n_naive - 1)), lohner $((n_lohner - 1))"
  "$BOUNCER" orbit "${chaos[@]}" --steps $((n_lohner - 1)) --precision mpfr:512 >"$TMP/chaos.ref" 2>/dev/null
  encloses chaos "$TMP/lohner.csv" "$TMP/chaos.ref"
fi
grep -Eq '^# lohner: orbit 0 [0-9]+ of [0-9]+ steps fell back to the interval box image$' "$TMP/lohner.csv" ||
  fail chaos "no '# lohner: orbit 0 K of N steps fell back ...' line"
grep -q '^# lohner:' "$TMP/naive.csv" && fail chaos "a naive run reports Lohner fallbacks"

# 2. Sticking orbits (constant restitution), every 7th row, from a scene with method = lohner.
cat >"$TMP/stick.toml" <<'EOF'
model = "constant"
a = "24"
eps = "0.5"
theta = "0.05"
v = "10.5"
steps = 300
every = 7
precision = "interval:128"
method = "lohner"
EOF
"$BOUNCER" orbit --scene "$TMP/stick.toml" >"$TMP/stick.csv" 2>"$TMP/stick.err" || fail stick "exit $?: $(cat "$TMP/stick.err")"
grep -q '^# end: orbit 0 completed 300 steps$' "$TMP/stick.csv" || fail stick "did not complete: $(grep '^# end' "$TMP/stick.csv")"
"$BOUNCER" orbit --scene "$TMP/stick.toml" --method naive >"$TMP/stick-naive.csv" 2>/dev/null
grep -q '^# lohner:' "$TMP/stick-naive.csv" && fail stick "--method naive on the command line did not override the scene"
"$BOUNCER" orbit --scene "$TMP/stick.toml" --precision mpfr:512 --method naive >"$TMP/stick.ref" 2>/dev/null
grep -q ',sticking,' "$TMP/stick.ref" || fail stick "the reference orbit has no sticking row to check"
encloses stick "$TMP/stick.csv" "$TMP/stick.ref"

# 3. json reports the fallback count.
"$BOUNCER" orbit "${chaos[@]}" --steps 20 --precision interval:64 --method lohner --format json >"$TMP/l.json" 2>/dev/null
python3 -c '
import json, sys
e = json.load(open(sys.argv[1]))["orbits"][0]["end"]
assert e["status"] == "completed" and e["steps_done"] == 20, e
assert isinstance(e["lohner_fallbacks"], int) and 0 <= e["lohner_fallbacks"] <= 20, e
' "$TMP/l.json" || fail json "end object without a valid lohner_fallbacks"

# 4. Bad input.
bad() {  # bad NAME ARGS...: exit 2, one line naming method, no output file
  local name=$1
  shift
  refused "bad-$name" method orbit "${chaos[@]}" --steps 3 "$@" --out "$TMP/bad-$name.csv"
  absent "bad-$name" "$TMP/bad-$name.csv" "$TMP/bad-$name.csv.partial"
}
bad point --precision mpfr:64 --method lohner
bad default-double --method lohner
bad unknown --precision interval:64 --method qr

finish "orbit_lohner.sh: Lohner interval orbits enclose the exact orbit and outlast iterated boxes"
