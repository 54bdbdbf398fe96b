#!/usr/bin/env bash
# End-to-end: `bouncer tongues` (fig. arnold), its CSV checked with exact rationals
# (Python fractions, independent of bouncer):
#   - every point satisfies a = 8(1+eps)/(p(1-eps)) exactly and lies in the window;
#   - theta_min = max(0, 1/2 - 2p eps/(1+eps)) and full = yes iff eps >= 1/(4p-1);
#   - every curve in the window has its switch point eps = 1/(4p-1), a = 16/(2p-1);
#   - the curves are ordered in p: curve p+1 lies above curve p (larger eps at equal a);
#   - PREFIX.csv/png/json written; bad options exit 2 with one line and no file;
#   - `bouncer audit` reproduces PREFIX.json and PREFIX.csv and finds a changed digit;
#   - `bouncer help tongues` documents the options; the scene file runs.
# Usage: bash tongues.sh <bouncer-binary> <source-dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
cd "$TMP"

"$BOUNCER" tongues --out t10 || fail t10 "exit $?"
"$BOUNCER" tongues --p-max 50 --a-range 0.5:100 --eps-range 0.01:0.99 --samples 40 --out t50 || fail t50 "exit $?"
for p in t10 t50; do outputs "$p" "$p"; done

python3 - <<'PY' || fail properties "see above"
import csv, json, sys
from fractions import Fraction as F
from clichecks import check, done

for name, pmax, (alo, ahi), (elo, ehi) in [("t10", 10, (0, 30), (0, 1)), ("t50", 50, (F("0.5"), 100), (F("0.01"), F("0.99")))]:
    rs = list(csv.DictReader(l for l in open(name + ".csv") if not l.startswith("#")))
    curves = {}
    for r in rs:
        p, a, e = int(r["p"]), F(r["a"]), F(r["eps"])
        check(1 <= p <= pmax, f"{name}: p = {p}")
        check(a == 8 * (1 + e) / (p * (1 - e)), f"{name}: p={p} ({a}, {e}) is off the curve")
        check(alo <= a <= ahi and elo <= e <= ehi, f"{name}: p={p} ({a}, {e}) outside the window")
        tmin = max(F(0), F(1, 2) - 2 * p * e / (1 + e))
        check(F(r["theta_min"]) == tmin, f"{name}: theta_min {r['theta_min']} != {tmin}")
        check((r["full"] == "yes") == (e >= F(1, 4 * p - 1)), f"{name}: full={r['full']} at p={p} eps={e}")
        check(float(r["a_double"]) == float(a) and float(r["eps_double"]) == float(e),  # Fraction -> float rounds to nearest
              f"{name}: double columns {r['a_double']}, {r['eps_double']}")
        curves.setdefault(p, []).append((a, e))
    for p in range(1, pmax + 1):
        sa, se = F(16, 2 * p - 1), F(1, 4 * p - 1)
        inside = alo < sa < ahi and elo < se < ehi
        check(((sa, se) in curves.get(p, [])) == inside, f"{name}: switch point of p={p} present={not inside}")
    # Ordering: for p < q, wherever both curves have points, at a_q >= a_p the eps of q is larger.
    for p in range(1, pmax):
        q = p + 1
        if p not in curves or q not in curves:
            continue
        for a, e in curves[q]:
            below = [ep for ap, ep in curves[p] if ap <= a]
            if below:
                check(max(below) < e, f"{name}: curve {q} not above curve {p} at a={float(a)}")
    s = json.load(open(name + ".json"))
    check(s["provenance"]["command"] == "tongues" and s["summary"]["points"] == len(rs), f"{name}: summary")
done()
PY

bad() {  # NAME OPTION-NAME ARGS...
  local name=$1 opt=$2
  shift 2
  refused "bad $name" "$opt" tongues "$@" --out "bad-$name"
  absent "bad $name" "bad-$name.csv" "bad-$name.png" "bad-$name.json"
}
bad pmax0 p-max --p-max 0
bad pmax51 p-max --p-max 51
bad pmaxtext p-max --p-max ten
bad arange a-range --a-range 5:5
bad arangeneg a-range --a-range -1:5
bad erange eps-range --eps-range 0:1.5
bad erangeform eps-range --eps-range 0.5
bad samples samples --samples 3

mkdir -p blocked.png
rc=0
"$BOUNCER" tongues --out blocked >blocked.out 2>blocked.err || rc=$?
[[ $rc -ne 0 ]] || fail "all-or-none" "exit 0 with a directory at PREFIX.png"
ls blocked.csv blocked.json >/dev/null 2>&1 && fail "all-or-none" "wrote the CSV or JSON without the PNG"

for f in t10.json t10.csv t50.json; do
  audited "audit $f" "$f"
done
sed 's/^1,8,0,1\/2,no,/1,8,0,1\/2,yes,/' t10.csv >tampered.csv
cmp -s t10.csv tampered.csv && fail "audit tamper" "no line changed"
rc=0
"$BOUNCER" audit tampered.csv >tampered.audit 2>&1 || rc=$?
[[ $rc -eq 1 ]] || fail "audit tamper" "exit $rc: $(cat tampered.audit)"

rc=0
"$BOUNCER" help tongues >help.txt 2>&1 || rc=$?
[[ $rc -eq 0 ]] || fail help "exit $rc"
for opt in p-max a-range eps-range samples out scene; do
  grep -qE -- "--$opt([[:space:]]|$)" help.txt || fail help "does not document --$opt"
done
"$BOUNCER" --scene "$SRC/data/scenes/picture-tongues-p10.toml" --out scene || fail scene "exit $?"
outputs scene scene

finish
