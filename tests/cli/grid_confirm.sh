#!/usr/bin/env bash
# End-to-end: `--confirm` of `bouncer basin` and `bouncer scan` (issue 23): the starts of a
# sample classified again at mpfr:B and, where they differ, at mpfr:2B.
#   - an artefact: elastic a = 18 from (0.1, 10) is quasiperiodic in double for 40000 steps
#     and an accelerator mode at mpfr:256 and mpfr:512 (docs/guide/dynamics.md, bouncer classify). A 2 x 1
#     basin whose first cell centre is (0.1, 10) reports that start as an artefact, with
#     mpfr's class unbounded, in the CSV, the JSON (counts, fraction, the artefact's start)
#     and an artefact map; single-point classify of the same start says the same;
#   - all agree: at eps = 0.5, a = 12 every start goes to the eq. 5 family of fixed points
#     (a = 8(1+eps)/(p(1-eps)) with p = 2); every confirmed start is fixed in double and at
#     mpfr:256, for basin and for a scan whose only point is (12, 0.5) (dyadic: the same
#     parameters at every precision);
#   - a scan's artefact: eps = 7/8, a = 17 from (1/8, 18) settles on period 2 before step
#     5000 at mpfr:256 and mpfr:512, after it in double (transient_chaos): the scan's only
#     start is flagged, as single-point classify flags it;
#   - the sample: a 10 x 10 basin with --confirm-sample 4 confirms exactly the starts at
#     columns and rows 2 and 7 (stride 5, worked out by hand), with 1 and 2 threads alike;
#   - bouncer audit reruns a --confirm result bit for bit;
#   - bad --confirm / --confirm-sample values exit 2 with one line naming the option.
# Usage: bash grid_confirm.sh <bouncer-binary> <source-dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
cd "$TMP"
require python3

M12=(--model constant --eps 0.5 --a 12)
refused bits-low 'confirm: must be a number of bits in \[64, 1048576\]' basin "${M12[@]}" --grid 2x2 --confirm=10 --out bad
refused bits-text 'confirm: must be a number of bits' basin "${M12[@]}" --grid 2x2 --confirm=many --out bad
refused bits-scan 'confirm: must be a number of bits' scan --model constant --a-range 11:13 --eps-range 0.4:0.6 \
  --grid 2x2 --confirm=2000000 --out bad
refused sample-zero 'confirm-sample: must be a number of starts in \[1, 1e12\] or all' basin "${M12[@]}" --grid 2x2 --confirm --confirm-sample 0 --out bad
refused sample-alone 'confirm-sample: is only used with --confirm' basin "${M12[@]}" --grid 2x2 --confirm-sample 4 --out bad
refused with-certify 'confirm: is not used with --certify' basin "${M12[@]}" --grid 2x2 --certify --confirm --out bad
absent refused-files "bad*"

# --- The artefact: elastic a = 18, the start (0.1, 10) ------------------------------------------
E18=(--model elastic --a 18 --theta-range 0.05:0.25 --v-range 9.5:10.5 --grid 2x1 --transient 20000 --steps 20000)
run e18 basin "${E18[@]}" --confirm --threads 2 --quiet --out e18 && outputs e18 e18
[[ -s e18-artefacts.png ]] || fail e18 "no artefact map e18-artefacts.png"
run e18-classify classify --model elastic --a 18 --theta 0.1 --v 10 --transient 20000 --steps 20000 --json
run e18-classify2 classify --model elastic --a 18 --theta 0.2 --v 10 --transient 20000 --steps 20000 --json
python3 - <<'PY' || fail e18-content "see above"
import csv, json, sys
from clichecks import check, done
rows = list(csv.DictReader(l for l in open("e18.csv") if not l.startswith("#")))
check(list(rows[0].keys()) == ["theta", "v", "class", "period", "confirm", "check_class", "check_period", "differs_in"],
      f"columns {list(rows[0])}")
first = rows[0]
check(float(first["theta"]) == 0.1 and float(first["v"]) == 10, f"first start {first['theta']}, {first['v']}")
check(first["class"] == "quasiperiodic", f"double's class {first['class']}")
check(first["confirm"] == "artefact" and first["check_class"] == "unbounded", f"confirmation {first}")
check(first["differs_in"] == "class", f"what differs {first}")
# (0.2, 10): unbounded at both precisions, period 0 in both: only differs_in says why it is an
# artefact; its words must be what single-point classify reports for the start at double and
# at mpfr:256 (growth kind, else the accelerator's period).
second = rows[1]
d2 = json.load(open("e18-classify2.out"))
k2 = d2["precision_check"]["checks"][0]
if d2["growth_kind"] != k2["growth_kind"]:
    want = f"growth kind {d2['growth_kind'] or 'none'} vs {k2['growth_kind'] or 'none'}"
else:
    want = f"accelerator period {d2['accelerator_period']} vs {k2['accelerator_period']}"
check(second["class"] == second["check_class"] == "unbounded" and second["confirm"] == d2["precision_check"]["verdict"] == "artefact",
      f"second start {second}")
check(second["differs_in"] == want, f"what differs at (0.2, 10): {second['differs_in']!r}, classify says {want!r}")
c = json.load(open("e18.json"))["summary"]["confirm"]
check(c["precisions"] == ["mpfr:256", "mpfr:512"], f"precisions {c['precisions']}")
check(c["sample"]["starts"] == 2 and c["confirmed"] == 2, f"sample {c['sample']}, confirmed {c['confirmed']}")
check(c["agrees"] + c["artefact"] + c["precision_dependent"] == 2 and c["artefact"] >= 1, f"counts {c}")
check(abs(c["confirmed_fraction"] - c["agrees"] / 2) < 1e-15, "confirmed fraction")
check(len(c["artefacts"]) == c["artefact"] and float(c["artefacts"][0]["theta"]) == 0.1 and float(c["artefacts"][0]["v"]) == 10,
      f"artefacts {c['artefacts']}")
check(c["artefacts"][0]["check_class"] == "unbounded", f"artefact {c['artefacts'][0]}")
check([a["differs_in"] for a in c["artefacts"]] == [r["differs_in"] for r in rows if r["confirm"] == "artefact"],
      f"the JSON's differs_in {c['artefacts']}")
# Single-point classify of the same start: the same verdict at the same precisions.
pc = json.load(open("e18-classify.out"))["precision_check"]
check(pc["verdict"] == "artefact", f"classify's verdict {pc['verdict']}")
check([k["precision"] for k in pc["checks"]] == ["mpfr:256", "mpfr:512"], "classify's precisions")
check(pc["checks"][0]["class"] == "unbounded", "classify at mpfr:256")
done()
PY
json_holds e18-provenance 'j["provenance"]["inputs"]["confirm"] in ("", "true")' e18.json

# --- All agree: eps = 0.5, a = 12, the eq. 5 family ------------------------------------------------
run a12 basin "${M12[@]}" --grid 4x3 --confirm --threads 2 --quiet --out a12 && outputs a12 a12
python3 - <<'PY' || fail a12-content "see above"
import csv, json, sys
from clichecks import check, done
rows = list(csv.DictReader(l for l in open("a12.csv") if not l.startswith("#")))
inside = [r for r in rows if r["class"] != "outside"]
check(len(rows) == 12 and len(inside) > 0, f"{len(rows)} rows, {len(inside)} inside")
for r in inside:
    check(r["class"] == "fixed" and r["period"] == "1", f"double at ({r['theta']}, {r['v']}): {r['class']} {r['period']}")
    check(r["confirm"] == "agrees" and r["check_class"] == "fixed" and r["check_period"] == "1", f"confirmation {r}")
for r in rows:
    if r["class"] == "outside":
        check(r["confirm"] == "", f"an outside start confirmed: {r}")
c = json.load(open("a12.json"))["summary"]["confirm"]
check(c["confirmed"] == len(inside) == c["agrees"] and c["artefact"] == 0 and c["precision_dependent"] == 0, f"counts {c}")
check(c["confirmed_fraction"] == 1 and c["artefacts"] == [], f"fraction {c['confirmed_fraction']}")
done()
PY

# A bare --confirm is recorded so that the result reruns from its provenance.
audited a12-audit a12.json

# The scan's only point is (a, eps) = (12, 0.5), 3 x 3 starts in its trapping region.
run s12 scan --model constant --a-range 11.5:12.5 --eps-range 0.25:0.75 --grid 1x1 --ics 3 --confirm --quiet --out s12 &&
  outputs s12 s12
[[ -s s12-artefacts.png ]] || fail s12 "no artefact map s12-artefacts.png"
python3 - <<'PY' || fail s12-content "see above"
import csv, json, sys
rows = list(csv.DictReader(l for l in open("s12.csv") if not l.startswith("#")))
r = rows[0]
ok = len(rows) == 1 and float(r["a"]) == 12 and float(r["eps"]) == 0.5
inside = int(r["total"]) - int(r["outside"])
ok = ok and int(r["fixed"]) == inside > 0
ok = ok and int(r["confirm_agrees"]) == inside and r["confirm_artefact"] == "0" and r["confirm_precision_dependent"] == "0"
c = json.load(open("s12.json"))["summary"]["confirm"]
ok = ok and c["sample"]["points"] == 1 and c["sample"]["starts"] == 9 and c["agrees"] == inside and c["artefacts"] == []
if not ok:
    print("FAIL: scan at (12, 0.5):", r, c, file=sys.stderr)
sys.exit(0 if ok else 1)
PY

# --- A scan's artefact: eps = 7/8, a = 17 (dyadic), the start (1/8, 18) -----------------------------
# A chaotic transient ends on the period-2 orbit: at mpfr:256 and mpfr:512 before step 5000
# (periodic), in double after it (transient_chaos, settling on periodic): the 53-bit orbit
# leaves the true one within about a hundred steps, the 256- and 512-bit ones track it past
# its capture. The scan's only point, its only start, is that start (theta 0:1/4, v 17:19);
# single-point classify of the same start says the same.
run s17 scan --model constant --a-range 16.5:17.5 --eps-range 0.85:0.9 --grid 1x1 --ics 1 --theta-range 0:0.25 \
  --v-range 17:19 --confirm --quiet --out s17 && outputs s17 s17
[[ -s s17-artefacts.png ]] || fail s17 "no artefact map s17-artefacts.png"
run s17-classify classify --model constant --eps 0.875 --a 17 --theta 0.125 --v 18 --json
python3 - <<'PY' || fail s17-content "see above"
import csv, json
from clichecks import check, done
r = list(csv.DictReader(l for l in open("s17.csv") if not l.startswith("#")))[0]
check(float(r["a"]) == 17 and float(r["eps"]) == 0.875 and r["total"] == "1", f"the point {r}")
check(r["transient_chaos"] == "1" and r["confirm_artefact"] == "1", f"double's class and the verdict {r}")
c = json.load(open("s17.json"))["summary"]["confirm"]
check(c["artefact"] == 1 and c["artefacts"] == [{"a": "17", "eps": "0.875", "theta": "0.125", "v": "18"}], f"artefacts {c}")
pc = json.load(open("s17-classify.out"))
check(pc["class"] == "transient_chaos" and pc["precision_check"]["verdict"] == "artefact", f"classify {pc['class']}, {pc['precision_check']['verdict']}")
check([k["class"] for k in pc["precision_check"]["checks"]] == ["periodic", "periodic"], f"checks {pc['precision_check']['checks']}")
done()
PY

# --- The sample: 10 x 10 starts, at most 4 confirmed --------------------------------------------------
for t in 1 2; do
  run sample$t basin "${M12[@]}" --grid 10x10 --transient 200 --steps 50 --confirm --confirm-sample 4 --threads $t --quiet --out sample$t
done
cmp -s <(data sample1.csv) <(data sample2.csv) || fail sample-threads "1 and 2 threads give different rows"
python3 - <<'PY' || fail sample-content "see above"
import csv, json, sys
rows = list(csv.DictReader(l for l in open("sample1.csv") if not l.startswith("#")))
confirmed = sorted((i % 10, i // 10) for i, r in enumerate(rows) if r["confirm"])
want = [(2, 2), (2, 7), (7, 2), (7, 7)]
outside = {(i % 10, i // 10) for i, r in enumerate(rows) if r["class"] == "outside"}
s = json.load(open("sample1.json"))["summary"]["confirm"]["sample"]
ok = confirmed == [p for p in want if p not in outside] and s["stride"] == 5 and s["starts"] == 4 and s["requested"] == 4
if not ok:
    print("FAIL: confirmed", confirmed, "sample", s, file=sys.stderr)
sys.exit(0 if ok else 1)
PY

finish "grid --confirm: all checks passed"
