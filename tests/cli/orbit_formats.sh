#!/usr/bin/env bash
# End-to-end: the output formats of `bouncer orbit`.
#   csv:   provenance comment lines (version + commit, precision with bits, libraries,
#          compiler flags with -ffp-contract=off, the decimal note), header n,theta,v,...
#          (interval: n,theta_lo,theta_hi,v_lo,v_hi,...), row n=0 = the initial condition,
#          every row as many fields as the header, a final "# end:" line per orbit;
#   json:  parses; provenance / columns / orbits[].rows / orbits[].end;
#   table: aligned rows with the same numbers as csv;
#   --out: writes the same content to the file atomically (no *.partial left, old file replaced);
#   --every K: rows n % K == 0 plus the last step, identical to those rows of --every 1.
# Usage: bash orbit_formats.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3

M=(orbit --model constant --a 24 --eps 0.5)
IC=(--theta 0.05,0.25 --v 10.5,12)

# ---------------------------------------------------------------- csv, double and mpfr
run csv "${M[@]}" "${IC[@]}" --steps 3 || true
run csv_mpfr "${M[@]}" "${IC[@]}" --steps 3 --precision mpfr:100 || true
run csv_interval "${M[@]}" "${IC[@]}" --steps 3 --precision interval:64 || true

python3 - "$TMP" <<'PY' || fail csv "see above"
import sys, re
from fractions import Fraction
tmp = sys.argv[1]
bad = []
def check(name, precision_line, interval, decimals_re):
    lines = open(f"{tmp}/{name}.out").read().split("\n")
    assert lines[-1] == "", f"{name}: output does not end with a newline"
    lines = lines[:-1]
    comments = [l for l in lines if l.startswith("#")]
    data = [l for l in lines if not l.startswith("#")]
    def has(pattern, what):
        if not any(re.search(pattern, c) for c in comments):
            bad.append(f"{name}: no provenance line with {what} (/{pattern}/)")
    # The two forms of the build's identity (cmake/BuildInfo.cmake): a git commit (with a
    # hash of the diff when dirty), or a hash of the source tree where there is no git.
    has(r"^# bouncer \d+\.\d+\.\d+ \(commit ([0-9a-f]{40}(\+dirty-[0-9a-f]{16})?|tree-sha256:[0-9a-f]{64})\) orbit$",
        "version and commit")
    has(r"^# invocation: .*orbit", "the invocation")
    has(r"^# inputs: .*\ba=24\b.*\beps=0\.5\b.*\btheta=0\.05,0\.25\b.*\bv=10\.5,12\b", "the exact inputs")
    has("^# precision: " + re.escape(precision_line), f"precision '{precision_line}'")
    has(r"^# libraries: .*boost \d.*mpfr \d.*mpfi \d.*gmp \d", "library versions")
    has(r"^# compiler: .*-ffp-contract=off", "compiler flags with -ffp-contract=off")
    has(decimals_re, "the decimal note")
    if any(re.search(r"-f{2}ast-math|-O[f]ast", c) for c in comments):  # (pattern spelled so that it does not match itself)
        bad.append(f"{name}: built with fast math: " + next(c for c in comments if "fast" in c))
    header = data[0].split(",")
    want = ["n", "theta_lo", "theta_hi", "v_lo", "v_hi"] if interval else ["n", "theta", "v"]
    if header[:len(want)] != want:
        bad.append(f"{name}: header starts {header[:len(want)]}, expected {want}")
        return
    if "orbit" not in header or "event" not in header:
        bad.append(f"{name}: header lacks 'event' or 'orbit': {header}")
        return
    rows = [dict(zip(header, r.split(","))) for r in data[1:]]
    for r, raw in zip(rows, data[1:]):
        if len(raw.split(",")) != len(header):
            bad.append(f"{name}: row has {len(raw.split(','))} fields, header {len(header)}: {raw}")
    # Two orbits, rows n = 0..3 each, in order.
    got = [(r["orbit"], r["n"]) for r in rows]
    want_rows = [(str(o), str(n)) for o in range(2) for n in range(4)]
    if got != want_rows:
        bad.append(f"{name}: (orbit, n) of the rows are {got}, expected {want_rows}")
        return
    for o, (th, v) in enumerate([("0.05", "10.5"), ("0.25", "12")]):
        r0 = next(r for r in rows if r["orbit"] == str(o) and r["n"] == "0")
        if r0["event"] != "start":
            bad.append(f"{name}: row 0 of orbit {o} has event {r0['event']!r}, expected 'start'")
        for key, dec in (("theta", th), ("v", v)):
            exact = Fraction(dec)
            if interval:
                lo, hi = Fraction(r0[key + "_lo"]), Fraction(r0[key + "_hi"])
                if not lo <= exact <= hi:
                    bad.append(f"{name}: row 0 [{lo}, {hi}] does not enclose {key} = {dec}")
                if exact.denominator & (exact.denominator - 1) and not lo < hi:
                    bad.append(f"{name}: {key} = {dec} is not dyadic but its enclosure is a point")
            else:
                x = Fraction(r0[key])
                # the initial condition is the input decimal rounded to the working precision
                tol = Fraction(1, 2**52) if name == "csv" else Fraction(1, 2**99)
                if abs(x - exact) > tol * max(1, abs(exact)):
                    bad.append(f"{name}: row 0 {key} = {r0[key]}, expected the input {dec}")
    ends = [l for l in lines if l.startswith("# end:")]
    want_ends = ["# end: orbit 0 completed 3 steps", "# end: orbit 1 completed 3 steps"]
    if ends != want_ends:
        bad.append(f"{name}: end lines {ends}, expected {want_ends}")
    # The fixed point (0.25, 12) of eq. 5 stays put (orbit 1).
    for r in rows:
        if r["orbit"] == "1":
            if interval:
                ok = Fraction(r["theta_lo"]) <= Fraction(1, 4) <= Fraction(r["theta_hi"]) and \
                     Fraction(r["v_lo"]) <= 12 <= Fraction(r["v_hi"])
            else:
                ok = abs(float(r["theta"]) - 0.25) < 1e-12 and abs(float(r["v"]) - 12) < 1e-12
            if not ok:
                bad.append(f"{name}: the fixed point (0.25, 12) moved at row {r['n']}: {r}")
try:
    check("csv", "double (53 significand bits)", False, r"^# decimals: .*rounded.*double")
    check("csv_mpfr", "mpfr:100 (100 significand bits)", False, r"^# decimals: .*rounded.*mpfr:100")
    check("csv_interval", "interval:64 (64 significand bits)", True, r"^# decimals: .*enclos.*exact")
except Exception as e:
    bad.append(f"checking csv output raised {type(e).__name__}: {e}")
for b in bad:
    print("FAIL [csv]:", b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY

# ---------------------------------------------------------------- json
run json "${M[@]}" "${IC[@]}" --steps 3 --format json || true
run json_interval orbit --model elastic --a 19 --theta 0.1 --v 7 --steps 2000 --precision interval:20 --format json || true
python3 - "$TMP" <<'PY' || fail json "see above"
import sys, json
tmp = sys.argv[1]
bad = []
def load(name):
    with open(f"{tmp}/{name}.out") as f:
        return json.load(f)
try:
    d = load("json")
    for k in ("provenance", "columns", "orbits"):
        if k not in d:
            bad.append(f"json: no top-level '{k}' (keys {list(d)})")
    p = d["provenance"]
    for k in ("version", "commit", "command", "inputs", "precision", "bits", "decimals", "libraries", "compiler", "flags"):
        if k not in p:
            bad.append(f"json: provenance lacks '{k}'")
    if p.get("precision") != "double" or p.get("bits") != 53:
        bad.append(f"json: provenance precision/bits {p.get('precision')}/{p.get('bits')}, expected double/53")
    if "-ffp-contract=off" not in p.get("flags", ""):
        bad.append(f"json: flags lack -ffp-contract=off: {p.get('flags')}")
    if p.get("inputs", {}).get("a") != "24" or p.get("inputs", {}).get("theta") != "0.05,0.25":
        bad.append(f"json: provenance inputs do not hold the exact input texts: {p.get('inputs')}")
    cols = d["columns"]
    if cols[:3] != ["n", "theta", "v"]:
        bad.append(f"json: columns start {cols[:3]}")
    if len(d["orbits"]) != 2:
        bad.append(f"json: {len(d['orbits'])} orbits, expected 2")
    for i, o in enumerate(d["orbits"]):
        rows = o["rows"]
        if [r[0] for r in rows] != ["0", "1", "2", "3"]:
            bad.append(f"json: orbit {i} rows n = {[r[0] for r in rows]}")
        if any(len(r) != len(cols) for r in rows):
            bad.append(f"json: orbit {i} has a row whose length differs from the columns")
        e = o.get("end", {})
        if e.get("status") != "completed" or e.get("steps_done") != 3:
            bad.append(f"json: orbit {i} end = {e}")
    th = [float(r[1]) for r in d["orbits"][0]["rows"]]
    if abs(th[0] - 0.05) > 1e-17:
        bad.append(f"json: first theta {th[0]}, expected 0.05")
    # same numbers as the csv run
    csv = [l.split(",") for l in open(f"{tmp}/csv.out") if not l.startswith("#")][1:]
    flat = [r for o in d["orbits"] for r in o["rows"]]
    if [r[:3] for r in flat] != [[c.strip() for c in r[:3]] for r in csv]:
        bad.append("json: n/theta/v differ from the csv output of the same run")
    di = load("json_interval")
    cols = di["columns"]
    if cols[:5] != ["n", "theta_lo", "theta_hi", "v_lo", "v_hi"]:
        bad.append(f"json interval: columns start {cols[:5]}")
    e = di["orbits"][0]["end"]
    if e.get("status") != "undecided" or len(di["orbits"][0]["rows"]) != e.get("steps_done", -2) + 1:
        bad.append(f"json interval: end {e} does not match {len(di['orbits'][0]['rows'])} rows")
    if "enclos" not in di["provenance"].get("decimals", ""):
        bad.append(f"json interval: decimal note does not say inputs are enclosed: {di['provenance'].get('decimals')}")
except Exception as ex:
    bad.append(f"json output does not parse or lacks a part: {type(ex).__name__}: {ex}")
for b in bad:
    print("FAIL [json]:", b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY

# ---------------------------------------------------------------- table
run table "${M[@]}" "${IC[@]}" --steps 3 --format table || true
python3 - "$TMP" <<'PY' || fail table "see above"
import sys
tmp = sys.argv[1]
bad = []
lines = [l.rstrip("\n") for l in open(f"{tmp}/table.out")]
if not any(l.startswith("# bouncer ") for l in lines):
    bad.append("table: no provenance lines")
data = [l.split() for l in lines if not l.startswith("#")]
if data[0][:3] != ["n", "theta", "v"]:
    bad.append(f"table: header starts {data[0][:3]}")
csv = [l.split(",") for l in open(f"{tmp}/csv.out") if not l.startswith("#")][1:]
if [r[:4] for r in data[1:]] != [r[:4] for r in csv]:
    bad.append(f"table: n/theta/v/event differ from the csv run:\n{data[1:]}\n{csv}")
for b in bad:
    print("FAIL [table]:", b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY

# ---------------------------------------------------------------- --out
mkdir "$TMP/o"
echo "old content" >"$TMP/o/orbit.csv"
if run out "${M[@]}" "${IC[@]}" --steps 3 --out "$TMP/o/orbit.csv"; then
  [[ -s $TMP/out.out ]] && fail "out" "with --out, something went to stdout: $(head -c 200 "$TMP/out.out")"
  left=$(cd "$TMP/o" && ls -A)
  [[ $left == "orbit.csv" ]] || fail "out" "the --out directory holds '$left', expected only orbit.csv (no .partial)"
  # same content as the stdout run, apart from the invocation/inputs lines that name --out
  if ! diff <(grep -v -e '^# invocation:' -e '^# inputs:' "$TMP/o/orbit.csv") \
            <(grep -v -e '^# invocation:' -e '^# inputs:' "$TMP/csv.out") >"$TMP/diff"; then
    fail "out" "the file differs from the stdout output: $(head -c 500 "$TMP/diff")"
  fi
  grep -q '^# inputs: .*out=' "$TMP/o/orbit.csv" || fail "out" "the inputs line does not record out="
fi
# unwritable destination: status 2, one line naming 'out', nothing left behind
refused "out unwritable" '^bouncer: out: ' "${M[@]}" "${IC[@]}" --out "$TMP/o/no-such-dir/x.csv"
[[ ! -e $TMP/o/no-such-dir ]] || fail "out unwritable" "a directory was created"
[[ $(cd "$TMP/o" && ls -A) == "orbit.csv" ]] || fail "out unwritable" "files left: $(ls -A "$TMP/o")"

# ---------------------------------------------------------------- --every
run every1 "${M[@]}" --theta 0.05 --v 10.5 --steps 25 || true
run every7 "${M[@]}" --theta 0.05 --v 10.5 --steps 25 --every 7 || true
run every30 "${M[@]}" --theta 0.05 --v 10.5 --steps 25 --every 30 || true
run every5 "${M[@]}" --theta 0.05 --v 10.5 --steps 25 --every 5 || true
python3 - "$TMP" <<'PY' || fail every "see above"
import sys
tmp = sys.argv[1]
bad = []
def rows(name):
    return [l.rstrip("\n") for l in open(f"{tmp}/{name}.out") if not l.startswith("#")][1:]
full = {r.split(",")[0]: r for r in rows("every1")}
if sorted(map(int, full)) != list(range(26)):
    bad.append(f"every 1: rows n = {sorted(map(int, full))}")
for k, want in ((7, [0, 7, 14, 21, 25]), (30, [0, 25]), (5, [0, 5, 10, 15, 20, 25])):
    got = rows(f"every{k}")
    ns = [int(r.split(",")[0]) for r in got]
    if ns != want:
        bad.append(f"every {k}: rows n = {ns}, expected {want}")
    for r in got:
        if full.get(r.split(",")[0]) != r:
            bad.append(f"every {k}: row differs from the --every 1 run: {r}")
for b in bad:
    print("FAIL [every]:", b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY

finish "orbit_formats.sh: csv, json, table, --out and --every behave"
