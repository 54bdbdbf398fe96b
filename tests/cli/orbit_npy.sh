#!/usr/bin/env bash
# End-to-end: `bouncer orbit --format npy` and the bytes of the CSV.
#   npy:  numpy.load reads PATH without bouncer: format 1.0, '<f8', C order, shape (rows, 16),
#         header padded to a multiple of 64 bytes; PATH.json beside it names the columns, the
#         shape, the codes of the text columns and each orbit's rows and end, with the run's
#         provenance;
#   same numbers: every numeric CSV cell, parsed as a double, equals the npy value bit for bit;
#         an empty CSV cell is NaN; the coded columns (event, wall, indirect, stick_wall,
#         passed_upward_turn) decode, with the sidecar's codes, to the CSV's text;
#   CSV bytes: every CSV data line is rebuilt independently from the npy values, each double
#         printed by this script's own implementation of std::to_chars' shortest form (the
#         shortest digits that round-trip, from Python's repr; printf %f or %e style,
#         whichever is shorter, %f on a tie; "-0"; an exponent of at least two digits), so
#         the CSV's number format is pinned by its specification, not by a saved output;
#   bad input: --format with an unknown value, npy with a precision whose numbers are not
#         doubles, npy without --out: exit 2, a one-line error naming the option and the
#         allowed values, and no file (nor .partial) left.
#   early stop: an orbit that stops at an undecided step leaves fewer rows than planned: the
#         header is rewritten to the rows written, the sidecar says where each orbit ends.
#   audit: `bouncer audit PATH.json` reruns the orbit and compares the sidecar and the data
#         PATH byte for byte (IDENTICAL, naming the data); one flipped bit in the data is
#         DIFFERENT at its row and column (exit 1); the data file given instead, the sidecar
#         under a name without .json, or the sidecar without its data: exit 2 and a
#         one-line error naming the sidecar or the data.
# Orbits: constant eps = 0.5, a = 10 from (0.3, 13) (sticking, with a ride through an upward
# turn, and direct flights) and from (0.05, 10.5); every step and every 7th; elastic
# a = 1e-300 (periods of 9e18, negative phase_bits, an overflow at step 1 of the second orbit).
# Usage: bash orbit_npy.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"

# numpy is the point of the format: the system Python (which has it here and in CI) first.
PY=""
for p in /usr/bin/python3 python3; do
  if command -v "$p" >/dev/null && "$p" -c 'import numpy' 2>/dev/null; then PY=$p; break; fi
done
[[ -n $PY ]] || skip "no python3 with numpy to read the .npy file"

M=(orbit --model constant --a 10 --eps 0.5 --theta 0.3,0.05 --v 13,10.5)

for every in 1 7; do
  run "csv$every" "${M[@]}" --steps 300 --every "$every" || true
  run "npy$every" "${M[@]}" --steps 300 --every "$every" --format npy --out "$TMP/o$every.npy" || true
  [[ -s $TMP/npy$every.out ]] && fail "npy$every" "--format npy --out printed on stdout: $(head -c 200 "$TMP/npy$every.out")"
  ls "$TMP"/*.partial >/dev/null 2>&1 && fail "npy$every" "a .partial file was left: $(ls "$TMP"/*.partial)"
done
# An orbit that stops early (overflow at step 1 in double: a = 1e-300 makes the flight from
# v = 1e15 infinite): fewer rows than the header first named, so the header is rewritten.
E=(orbit --model elastic --a 1e-300 --theta 0.2,0.5 --v 5,1e15 --steps 5)
run csvE "${E[@]}" || true
run npyE "${E[@]}" --format npy --out "$TMP/oE.npy" || true

"$PY" - "$TMP" <<'PY' || fail npy "see above"
import json, math, struct, sys
from decimal import Decimal
import numpy as np

tmp = sys.argv[1]
bad = []
COLUMNS = ["n", "theta", "v", "event", "tau", "periods", "segment", "wall", "corner", "indirect",
           "stick_wall", "passed_upward_turn", "stuck_theta", "stuck_v", "phase_bits", "orbit"]
CSV_HEADER = "n,theta,v,event,tau,periods,segment,wall,corner,flight,sticking,stuck_theta,stuck_v,phase_bits,orbit"


def bits(x):
    return struct.pack("<d", x)


def shortest(x):
    """std::to_chars(first, last, double) without a format: the shortest round-trip digits
    (Python's repr finds the same digits), printed as printf's %f or %e would print them,
    whichever has fewer characters (%f on a tie)."""
    if x == 0:
        return "-0" if math.copysign(1.0, x) < 0 else "0"
    sign = "-" if x < 0 else ""
    d = Decimal(repr(abs(x))).normalize()  # value = DIGITS x 10^exponent, no trailing zeros
    t = d.as_tuple()
    digits = "".join(map(str, t.digits))
    point = len(digits) + t.exponent  # value = 0.DIGITS x 10^point
    E = point - 1  # scientific exponent
    sci = digits[0] + ("." + digits[1:] if len(digits) > 1 else "") + "e" + ("-" if E < 0 else "+") + "%02d" % abs(E)
    if point >= len(digits):
        # An integer: libstdc++ (as MSVC's to_chars) prints its exact value in %f style, not
        # the shortest digits padded with zeros (5.741739999449888e+19 -> 57417399994498883584).
        fixed = str(int(abs(x)))
    elif point > 0:
        fixed = digits[:point] + "." + digits[point:]
    else:
        fixed = "0." + "0" * (-point) + digits
    out = fixed if len(fixed) <= len(sci) else sci
    assert float(out) == abs(x), (x, out)
    return sign + out


# The formatter itself against cases whose text is known from the C++ standard's rule.
for x, want in [(0.5, "0.5"), (4.0, "4"), (-0.0, "-0"), (1e-05, "1e-05"), (0.0001, "1e-04"),
                (0.00012, "0.00012"), (1e15, "1e+15"), (123456.0, "123456"), (1e22, "1e+22"),
                (0.1 + 0.2, "0.30000000000000004"), (-2.5e-300, "-2.5e-300"), (12.0, "12"),
                (5.741739999449888e+19, "57417399994498883584")]:
    if shortest(x) != want:
        bad.append(f"the test's own formatter: {x!r} -> {shortest(x)}, expected {want}")

kept = {every: 1 + len([n for n in range(1, 301) if n % every == 0 or n == 300]) for every in (1, 7)}
# run name -> each orbit's (orbit, first_row, rows, status, steps_done)
RUNS = {
    1: [(0, 0, kept[1], "completed", 300), (1, kept[1], kept[1], "completed", 300)],
    7: [(0, 0, kept[7], "completed", 300), (1, kept[7], kept[7], "completed", 300)],
    "E": [(0, 0, 6, "completed", 5), (1, 6, 1, "undecided", 0)],
}
for every, want_orbits in RUNS.items():
    path = f"{tmp}/o{every}.npy"
    raw = open(path, "rb").read()
    if raw[:8] != b"\x93NUMPY\x01\x00":
        bad.append(f"every {every}: not an .npy format 1.0 file: {raw[:8]!r}")
        continue
    hlen = struct.unpack("<H", raw[8:10])[0]
    if (10 + hlen) % 64 != 0:
        bad.append(f"every {every}: data start at byte {10 + hlen}, not a multiple of 64")
    a = np.load(path, allow_pickle=False)
    side = json.load(open(path + ".json"))
    if a.dtype != np.dtype("<f8") or a.ndim != 2 or not a.flags["C_CONTIGUOUS"]:
        bad.append(f"every {every}: dtype {a.dtype}, ndim {a.ndim}: expected C-order <f8 of 2 dimensions")
        continue
    if side.get("columns") != COLUMNS:
        bad.append(f"every {every}: sidecar columns {side.get('columns')}, expected {COLUMNS}")
    if list(a.shape) != side.get("shape") or a.shape[1] != len(COLUMNS):
        bad.append(f"every {every}: shape {a.shape}, sidecar says {side.get('shape')}")
        continue
    if side.get("npy") != f"o{every}.npy" or side.get("dtype") != "<f8":
        bad.append(f"every {every}: sidecar npy/dtype {side.get('npy')!r} {side.get('dtype')!r}")
    prov = side.get("provenance", {})
    if "orbit" not in json.dumps(prov) or "eps" not in json.dumps(prov):
        bad.append(f"every {every}: the sidecar's provenance lacks the command or its inputs: {json.dumps(prov)[:300]}")
    codes = side["codes"]

    csv_lines = open(f"{tmp}/csv{every}.out").read().split("\n")
    data = [l for l in csv_lines if l and not l.startswith("#")]
    if data[0] != CSV_HEADER:
        bad.append(f"every {every}: CSV header {data[0]!r}")
    rows = [l.split(",") for l in data[1:]]
    header = data[0].split(",")
    if len(rows) != a.shape[0]:
        bad.append(f"every {every}: {len(rows)} CSV rows, {a.shape[0]} npy rows")
        continue
    # Rows each orbit should have: the start and steps n % every == 0 or n == 300.
    orbits = side.get("orbits", [])
    if [(o["orbit"], o["first_row"], o["rows"], o["status"], o["steps_done"]) for o in orbits] != want_orbits:
        bad.append(f"every {every}: sidecar orbits {orbits}, expected {want_orbits}")
    if every == "E" and "overflow" not in orbits[-1].get("reason", ""):
        bad.append(f"every {every}: the undecided orbit's reason is not the overflow: {orbits[-1]}")

    col = {c: i for i, c in enumerate(COLUMNS)}
    def dec(name, value):
        return "" if math.isnan(value) else codes[name][str(int(value))]
    seen = set()
    for k, (r, x) in enumerate(zip(rows, a)):
        cell = dict(zip(header, r))
        # 1. numbers: bit for bit; empty cells are NaN
        for name in ["n", "theta", "v", "tau", "periods", "segment", "corner", "stuck_theta", "stuck_v",
                     "phase_bits", "orbit"]:
            got = x[col[name]]
            if cell[name] == "":
                if not math.isnan(got):
                    bad.append(f"every {every} row {k}: {name} is empty in the CSV, {got!r} in the npy")
            elif bits(float(cell[name])) != bits(got):
                bad.append(f"every {every} row {k}: {name} {cell[name]} in the CSV, {got!r} in the npy")
        # 2. codes
        if dec("event", x[col["event"]]) != cell["event"]:
            bad.append(f"every {every} row {k}: event {cell['event']!r}, npy code {x[col['event']]}")
        if dec("wall", x[col["wall"]]) != cell["wall"]:
            bad.append(f"every {every} row {k}: wall {cell['wall']!r}, npy code {x[col['wall']]}")
        if dec("indirect", x[col["indirect"]]) != cell["flight"]:
            bad.append(f"every {every} row {k}: flight {cell['flight']!r}, npy code {x[col['indirect']]}")
        stick = dec("stick_wall", x[col["stick_wall"]])
        passed = x[col["passed_upward_turn"]]
        if stick and passed == 1:
            stick += ":paper"  # the default --downward convention
        if stick != cell["sticking"]:
            bad.append(f"every {every} row {k}: sticking {cell['sticking']!r}, npy {stick!r}")
        seen.add(cell["event"] + ("/" + cell["sticking"] if cell["sticking"] else "") + "/" + cell["flight"])
        # 3. the CSV line, rebuilt from the npy row by the specification of the format
        def num(name, integer=False):
            v = x[col[name]]
            return "" if math.isnan(v) else (str(int(v)) if integer else shortest(v))
        sticking = stick
        want = ",".join([num("n", True), num("theta"), num("v"), dec("event", x[col["event"]]), num("tau"),
                         num("periods", True), num("segment", True), dec("wall", x[col["wall"]]),
                         num("corner", True), dec("indirect", x[col["indirect"]]), sticking,
                         num("stuck_theta"), num("stuck_v"), num("phase_bits", True), num("orbit", True)])
        if want != data[1 + k]:
            bad.append(f"every {every} row {k}: CSV line\n    {data[1 + k]}\n  expected from the npy values\n    {want}")
    if every == 1:
        for needed in ["start", "sticking/down:paper", "impact/direct"]:
            if not any(s.startswith(needed) for s in seen):
                bad.append(f"the orbit no longer has a row of kind {needed!r} (seen: {sorted(seen)})")

for b in bad[:30]:
    print("FAIL:", b, file=sys.stderr)
sys.exit(1 if bad else 0)
PY

# ---------------------------------------------------------------- audit of an npy orbit
audited audit_npy "$TMP/o7.npy.json"
grep -qF "and its npy data '$TMP/o7.npy'" "$TMP/audit.txt" || fail audit_npy "the verdict does not name the data: $(cat "$TMP/audit.txt")"
mkdir -p "$TMP/tamper" && cp "$TMP/o7.npy" "$TMP/o7.npy.json" "$TMP/tamper/"
# One bit of row 3's v (column 2 of 16 float64 values after the header) flipped.
"$PY" - "$TMP/tamper/o7.npy" <<'PY'
import sys
p = sys.argv[1]
d = bytearray(open(p, "rb").read())
start = 10 + int.from_bytes(d[8:10], "little")
d[start + (3 * 16 + 2) * 8] ^= 1
open(p, "wb").write(bytes(d))
PY
rc=0
"$BOUNCER" audit "$TMP/tamper/o7.npy.json" >"$TMP/tamper.txt" 2>&1 || rc=$?
[[ $rc -eq 1 ]] && grep -q "DIFFERENT: first difference at .*o7.npy (npy data): byte [0-9]* differs (row 3, column v)" "$TMP/tamper.txt" ||
  fail audit_tamper "exit $rc: $(tail -c 300 "$TMP/tamper.txt")"
refused audit_data "o7.npy' is the data of an npy orbit; audit its provenance '.*o7.npy.json' beside it" audit "$TMP/o7.npy"
cp "$TMP/o7.npy.json" "$TMP/tamper/sidecar"
refused audit_name "sidecar' is the provenance of an npy orbit.*ending in .json" audit "$TMP/tamper/sidecar"
rm "$TMP/tamper/o7.npy"
refused audit_nodata "its data '.*tamper/o7.npy' cannot be read" audit "$TMP/tamper/o7.npy.json"

# ---------------------------------------------------------------- bad input: exit 2, no files
bad_input() {  # bad_input NAME OPTION-NAME ALLOWED-PATTERN ARGS...
  local name=$1 option=$2 allowed=$3 rc=0
  shift 3
  mkdir -p "$TMP/bad_$name"
  "$BOUNCER" "${M[@]}" --steps 5 "$@" >"$TMP/bad_$name/stdout" 2>"$TMP/bad_$name.err" || rc=$?
  [[ $rc -eq 2 ]] || fail "bad_$name" "expected exit 2, got $rc"
  [[ $(wc -l <"$TMP/bad_$name.err") -eq 1 ]] || fail "bad_$name" "not a one-line error: $(cat "$TMP/bad_$name.err")"
  grep -q "^bouncer: $option: .*$allowed" "$TMP/bad_$name.err" ||
    fail "bad_$name" "the error does not name $option and /$allowed/: $(cat "$TMP/bad_$name.err")"
  local left
  left=$(cd "$TMP/bad_$name" && ls -A | grep -v '^stdout$' || true)
  [[ -z $left ]] || fail "bad_$name" "files left: $left"
  [[ ! -s $TMP/bad_$name/stdout ]] || fail "bad_$name" "printed: $(head -c 200 "$TMP/bad_$name/stdout")"
}
bad_input npz format "allowed: csv, json, table, npy" --format npz --out "$TMP/bad_npz/o.npz"
bad_input NPY format "allowed: csv, json, table, npy" --format NPY --out "$TMP/bad_NPY/o.npy"
bad_input mpfr format "needs --precision double.*allowed.*csv, json, table" --format npy --precision mpfr:100 \
  --out "$TMP/bad_mpfr/o.npy"
bad_input long format "needs --precision double" --format npy --precision long --out "$TMP/bad_long/o.npy"
bad_input interval format "needs --precision double" --format npy --precision interval:double \
  --out "$TMP/bad_interval/o.npy"
bad_input noout out "give --out PATH" --format npy
# A device or directory: PATH.json would be written beside it (/dev/null.json among the devices).
mkdir -p "$TMP/adir"
bad_input dir out "must name a regular file" --format npy --out "$TMP/adir"
[[ ! -e /dev/null.json ]] || { rm -f /dev/null.json; fail dev_null "wrote /dev/null.json"; }
bad_input devnull out "must name a regular file" --format npy --out /dev/null
[[ ! -e /dev/null.json ]] || { rm -f /dev/null.json; fail dev_null "wrote /dev/null.json"; }

finish
