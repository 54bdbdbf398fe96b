#!/usr/bin/env bash
# End-to-end: exponent curves, `bouncer lyapunov --vary`.
#   - the curve's exponent at a value is bit for bit that of the single-point command at
#     that value and start (same function; the value printed round-trip is the same double,
#     and make_model builds the same model from it), for exact and inexact values and for
#     the given start and a spread start;
#   - the CSV is the same at 1 and 2 threads and after shards joined by `bouncer merge`;
#   - the summary counts every row once; PNG and JSON are written;
#   - bad input exits 2 with one line on stderr and no file.
# Usage: bash lyapunov_curve.sh <bouncer-binary> <source-dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3

# Veldep, c = 1000 (the paper's fig. lyapunov_one model), short windows; 7 values over
# [20, 30] (20 + 10k/6: most of them not exact decimals) x 2 starts.
C="lyapunov --model veldep --c 1000 --vary a --range 20:30 --samples 7 --ics 2 --theta 0.3 --v 6 --transient 300 --steps 1500"
"$BOUNCER" $C --threads 1 --quiet --out "$TMP/t1" 2>"$TMP/t1.err" || fail curve.run "exit $? ($(head -c 300 "$TMP/t1.err"))"
"$BOUNCER" $C --threads 2 --quiet --out "$TMP/t2" || fail curve.run2 "exit $?"
# The classifier options reach the rows: eps = 0.96, a = 28 from (1/2, 4) is chaotic around
# step 5000 and on a 2-cycle from step 10155 (test_classify), so the row is transient_chaos
# with the re-check (20 x 500 steps) and chaotic without it.
T="lyapunov --model constant --eps 0.96 --vary a --range 28:28.5 --samples 2 --theta 0.5 --v 4 --transient 0 --steps 5000 --quiet"
"$BOUNCER" $T --out "$TMP/t3" || fail curve.classify_opts "exit $?"
"$BOUNCER" $T --recheck-factor 0 --out "$TMP/t4" || fail curve.classify_opts "exit $?"
[[ $(data "$TMP/t3.csv" | grep '^28,' | cut -d, -f7,8) == "transient_chaos,2" ]] || fail curve.recheck "a = 28: $(data "$TMP/t3.csv" | grep '^28,')"
[[ $(data "$TMP/t4.csv" | grep '^28,' | cut -d, -f7,8) == "chaotic,0" ]] || fail curve.recheck_off "a = 28: $(data "$TMP/t4.csv" | grep '^28,')"
outputs curve.files "$TMP/t1"
cmp -s <(data "$TMP/t1.csv") <(data "$TMP/t2.csv") || fail curve.threads "CSV differs between 1 and 2 threads"

# Shards of the same job, joined by merge, give the same rows.
"$BOUNCER" $C --quiet --shard 0/2 --out "$TMP/sh" || fail curve.shard "shard 0 exit $?"
"$BOUNCER" $C --quiet --shard 1/2 --out "$TMP/sh" || fail curve.shard "shard 1 exit $?"
"$BOUNCER" merge "$TMP/sh" --quiet || fail curve.merge "exit $?"
cmp -s <(data "$TMP/t1.csv") <(data "$TMP/sh.csv") || fail curve.merge "merged CSV differs"

python3 - "$TMP/t1.csv" "$TMP/t1.json" <<'PY' || fail curve.content "rows or summary wrong"
import json, sys
lines = [l.rstrip("\n").split(",") for l in open(sys.argv[1]) if not l.startswith("#")]
head, rows = lines[0], lines[1:]
assert head == ["value", "ic", "theta0", "v0", "lambda", "stderr", "class", "period"], head
assert len(rows) == 14, len(rows)
vals = sorted(set(float(r[0]) for r in rows))
assert len(vals) == 7 and vals[0] == 20 and vals[-1] == 30, vals
assert all(abs(v - (20 + 10 * k / 6)) < 1e-12 for k, v in enumerate(vals)), vals
assert all(r[2:4] == ["0.3", "6"] for r in rows if r[1] == "0"), rows
d = json.load(open(sys.argv[2]))["summary"]
assert sum(d["classes"].values()) == 14, d["classes"]
assert len(d["values"]) == 7
for v in d["values"]:
    lam = [float(r[4]) for r in rows if r[0] == v["value"]]
    assert v["max_lambda"] == max(lam), (v, lam)
PY

# Exact agreement with single-point runs: value k = 0 (exact), 1 (20 + 10/6, inexact), 3
# and 6, for both starts (one python process: its start-up is slow on a busy machine).
python3 - "$BOUNCER" "$TMP/t1.csv" <<'PY' || fail curve.single "curve and single-point exponents differ"
import json, subprocess, sys
rows = [l.rstrip("\n").split(",") for l in open(sys.argv[2]) if not l.startswith("#")][1:]
picks = rows[0:2] + rows[2:4] + rows[6:8] + rows[12:14]
assert len(picks) == 8
bad = []
for r in picks:
    out = subprocess.run([sys.argv[1], "lyapunov", "--model", "veldep", "--c", "1000", "--a", r[0], "--theta", r[2],
                          "--v", r[3], "--transient", "300", "--steps", "1500", "--json"],
                         capture_output=True, text=True, check=True).stdout
    single = float(json.loads(out)["lambda"])
    if single != float(r[4]):  # bit for bit: the same double
        bad.append((r[0], r[2], r[3], r[4], repr(single)))
assert not bad, bad
PY

# The single-point command is unchanged by the curve options it now shares.
"$BOUNCER" lyapunov --model veldep --a 27 --c 1000 --theta 0.3 --v 6 --transient 200 --steps 1000 >"$TMP/one.txt" ||
  fail single.run "exit $?"
grep -q '^lambda: ' "$TMP/one.txt" || fail single.text "no 'lambda:' line"

# Bad input: exit 2, one line on stderr, nothing written.
bad() {  # bad NAME ARGS...
  local name=$1
  shift
  refused "bad.$name" "" "$@" --quiet
  absent "bad.$name" "$TMP/bad_out*"
  rm -rf "$TMP"/bad_out*
}
O="--out $TMP/bad_out"
bad vary-eps-veldep lyapunov --model veldep --c 1000 --vary eps --range 0.1:0.2 --samples 3 $O
bad vary-c-constant lyapunov --model constant --eps 0.5 --vary c --range 10:20 --samples 3 $O
bad vary-unknown lyapunov --model veldep --c 1000 --vary b --range 20:30 --samples 3 $O
bad range-a-zero lyapunov --model veldep --c 1000 --vary a --range 0:30 --samples 3 $O
bad range-eps-above-1 lyapunov --model constant --vary eps --range 0.5:1.5 --a 20 --samples 3 $O
bad range-reversed lyapunov --model veldep --c 1000 --vary a --range 30:20 --samples 3 $O
bad range-missing lyapunov --model veldep --c 1000 --vary a --samples 3 $O
bad samples-0 lyapunov --model veldep --c 1000 --vary a --range 20:30 --samples 0 $O
bad ics-0 lyapunov --model veldep --c 1000 --vary a --range 20:30 --samples 3 --ics 0 $O
bad steps-0 lyapunov --model veldep --c 1000 --vary a --range 20:30 --samples 3 --steps 0 $O
bad theta-1 lyapunov --model veldep --c 1000 --vary a --range 20:30 --samples 3 --theta 1 --v 6 $O
bad v-below-wall lyapunov --model veldep --c 1000 --vary a --range 20:30 --samples 3 --theta 0.1 --v 3 $O
bad out-without-vary lyapunov --model veldep --a 27 --c 1000 --theta 0.3 --v 6 $O
bad recheck-without-vary lyapunov --model veldep --a 27 --c 1000 --theta 0.3 --v 6 --recheck-factor 0 $O
bad recheck-negative lyapunov --model veldep --c 1000 --vary a --range 20:30 --samples 3 --recheck-factor -1 $O
bad interval lyapunov --model veldep --c 1000 --vary a --range 20:30 --samples 3 --precision interval:64 $O

finish
