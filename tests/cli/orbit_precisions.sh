#!/usr/bin/env bash
# End-to-end: the precisions agree, and intervals enclose.
# On the default scene (eps = 0.5, a = 24; orbit 0 = the fixed point (0.25, 12) of the
# paper's eq. 5, orbit 1 = a chaotic transient from (0.05, 10.5)) over 10 steps:
#   - double, long, dd and quad agree with mpfr:256 to 1e-12, 1e-15, 1e-26, 1e-28 (same events);
#   - interval:256 encloses the mpfr:256 state at every row and stays narrow (< 1e-60);
#   - the fixed point is exact: interval:256 encloses (0.25, 12) itself at every row
#     (the exact decimal orbit IS the fixed point), and mpfr:256 stays within 1e-70 of it.
# Usage: bash orbit_precisions.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3
SCENE=$SRC/data/scenes/default.toml
[[ -f $SCENE ]] || die "no default scene at $SCENE"

for p in double long dd quad mpfr:256 interval:256; do
  rc=0
  "$BOUNCER" orbit --scene "$SCENE" --theta 0.25,0.05 --v 12,10.5 --steps 10 --every 1 --format csv \
    --precision "$p" >"$TMP/$p.csv" 2>"$TMP/$p.err" || rc=$?
  [[ $rc -eq 0 ]] || die "$p: exit status $rc: $(cat "$TMP/$p.err")"
done

python3 - "$TMP" <<'PY'
import sys
from fractions import Fraction as F
tmp = sys.argv[1]
def rows(p):
    L = [l.rstrip("\n").split(",") for l in open(f"{tmp}/{p}.csv") if not l.startswith("#")]
    h = L[0]
    return [dict(zip(h, r)) for r in L[1:]]
def phase_diff(a, b):
    d = abs(a - b) % 1
    return min(d, 1 - d)
ref = rows("mpfr:256")
bad = []
if [(r["orbit"], r["n"]) for r in ref] != [(str(o), str(n)) for o in range(2) for n in range(11)]:
    bad.append(f"mpfr:256 rows are not orbits 0,1 x n = 0..10: {[(r['orbit'], r['n']) for r in ref]}")
for p, tol in (("double", F(1, 10**12)), ("long", F(1, 10**15)), ("dd", F(1, 10**26)), ("quad", F(1, 10**28))):
    worst = F(0)
    for a, b in zip(rows(p), ref):
        if (a["orbit"], a["n"], a["event"]) != (b["orbit"], b["n"], b["event"]):
            bad.append(f"{p} vs mpfr:256: row {(a['orbit'], a['n'], a['event'])} vs {(b['orbit'], b['n'], b['event'])}")
            continue
        dt = phase_diff(F(a["theta"]), F(b["theta"]))
        dv = abs(F(a["v"]) - F(b["v"]))
        worst = max(worst, dt, dv)
        if dt > tol or dv > tol:
            bad.append(f"{p} vs mpfr:256 at orbit {a['orbit']} n={a['n']}: theta {a['theta']} vs {b['theta']}, v {a['v']} vs {b['v']} (tolerance {float(tol):g})")
    print(f"{p} vs mpfr:256: largest difference {float(worst):.3g}")
iv = rows("interval:256")
if len(iv) != len(ref):
    bad.append(f"interval:256 has {len(iv)} rows, mpfr:256 {len(ref)}")
for a, b in zip(iv, ref):
    if (a["orbit"], a["n"], a["event"]) != (b["orbit"], b["n"], b["event"]):
        bad.append(f"interval:256 row {(a['orbit'], a['n'], a['event'])} vs mpfr:256 {(b['orbit'], b['n'], b['event'])}")
        continue
    for k in ("theta", "v"):
        lo, hi, x = F(a[k + "_lo"]), F(a[k + "_hi"]), F(b[k])
        if not lo <= x <= hi:
            bad.append(f"interval:256 orbit {a['orbit']} n={a['n']}: {k} [{a[k+'_lo']}, {a[k+'_hi']}] does not enclose mpfr:256 {b[k]}")
        if hi - lo > F(1, 10**60):
            bad.append(f"interval:256 orbit {a['orbit']} n={a['n']}: {k} enclosure is {float(hi - lo):.3g} wide")
    if a["orbit"] == "0":  # the exact fixed point
        if not (F(a["theta_lo"]) <= F(1, 4) <= F(a["theta_hi"]) and F(a["v_lo"]) <= 12 <= F(a["v_hi"])):
            bad.append(f"interval:256 n={a['n']}: the enclosure does not contain the fixed point (0.25, 12): {a}")
        if abs(F(b["theta"]) - F(1, 4)) > F(1, 10**70) or abs(F(b["v"]) - 12) > F(1, 10**70):
            bad.append(f"mpfr:256 n={b['n']}: left the fixed point (0.25, 12): ({b['theta']}, {b['v']})")
for x in bad[:20]:
    print("FAIL:", x, file=sys.stderr)
if bad:
    print(f"orbit_precisions.sh: {len(bad)} disagreement(s)", file=sys.stderr)
    sys.exit(1)
print("orbit_precisions.sh: double/long/quad agree with mpfr:256; interval:256 encloses it and the exact fixed point")
PY
