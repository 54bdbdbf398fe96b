#!/usr/bin/env bash
# End-to-end: `bouncer attractors` (every attractor at a parameter point).
#   - bad input exits 2 with one line naming the option, and writes nothing;
#   - at eps = 0.5, a = 24 (paper fig. basin2) PREFIX.csv/png/json are written and checked
#     by Python, independently of bouncer: the starts are the cell centres (2i+1)/(2N) of
#     the window; the CSV's attractor ids and the JSON agree (counts, shares, binomial
#     errors, shares summing to 1); the attractors are the eq. 5 fixed points at
#     v* = 4(1+eps)/(1-eps) = 12 (a family) and a sticking cycle through the release state
#     (1/2, 4), both certified, the printed points within 1e-12 of the certified enclosures;
#   - `bouncer audit` reruns PREFIX.json and finds it identical;
#   - --vary: each value's shares sum to 1 in the CSV and the JSON; periods 3 and 7 persist
#     as chains over a in 23.05..23.15 (veldep c = 1000); bad sweeps exit 2;
#   - elastic a = 18: the nine-branch accelerator mode (period 33, gain 9 x 8 = 72) is found,
#     the positive control of claims row 10b's search at a = 19;
#   - --vary's branches: the period-1 sticking cycle at eps = 1/4 appears between a = 22.1
#     and 22.25, tied to a certified border end whose enclosure holds 200/9 (exact fractions);
#   - without --out a readable summary names both; --help documents the options;
#   - starts too many for the memory available: exit 2 naming --starts (ulimit -v).
# Usage: bash attractors.sh <bouncer-binary> <source-dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
cd "$TMP"
require python3

M=(--model constant --eps 0.5 --a 24)
refused starts 'starts' attractors "${M[@]}" --starts 0x5 --out bad
refused starts-many 'starts' attractors "${M[@]}" --starts 8192x8192 --out bad
refused cells 'cells' attractors "${M[@]}" --cells 8x8 --out bad
refused sampling 'sampling' attractors "${M[@]}" --sampling sobol --out bad
refused recurrences 'recurrences' attractors "${M[@]}" --recurrences 0 --out bad
refused max-bits 'max-bits' attractors "${M[@]}" --max-bits 10 --out bad
refused max-bits-unused 'max-bits' attractors "${M[@]}" --no-certify --max-bits 128 --out bad
refused precision 'precision' attractors "${M[@]}" --precision interval:64 --out bad
refused elastic 'v-range' attractors --model elastic --a 19 --out bad
refused eps 'eps' attractors --model constant --eps 1.5 --a 24 --out bad
absent refused-files "bad.*"

run e05 attractors "${M[@]}" --starts 30x20 --threads 2 --quiet --out e05 && outputs e05 e05

python3 - <<'PY' || fail e05-content "see above"
import csv, json, math, sys
from fractions import Fraction as F
from clichecks import check, done

doc = json.load(open("e05.json"))
s = doc["summary"]
check(doc["provenance"]["command"] == "attractors", "provenance command")
rows = list(csv.DictReader(l for l in open("e05.csv") if not l.startswith("#")))
check(len(rows) == 600 == s["points"], f"{len(rows)} rows, points {s['points']}")
# The starts: cell centres of theta in [0, 1] (30) and v in the trapping window (20).
vlo, vhi = (F(x) for x in s["v_range"])
check(vhi == F(4 * (1 + 3 * F(1, 2)), 1 - F(1, 2)), f"v range top {vhi} is not 4(1+3eps)/(1-eps)")
for i, r in enumerate(rows):
    col, row = i % 30, i // 30
    check(float(r["theta"]) == float(F(2 * col + 1, 60)), f"row {i}: theta {r['theta']}")
    check(float(r["v"]) == float(vlo + (vhi - vlo) * F(2 * row + 1, 40)), f"row {i}: v {r['v']}")
atts = s["attractors"]
n = s["points_in_phase_space"]
count = {}
for r in rows:
    count[r["attractor"]] = count.get(r["attractor"], 0) + 1
total = s["undecided"]["fraction"]
for a in atts:
    k = count.get(str(a["id"]), 0)
    check(k == a["starts"], f"#{a['id']}: CSV has {k} starts, JSON {a['starts']}")
    p = k / n
    check(abs(a["fraction"] - p) < 1e-15, f"#{a['id']}: fraction {a['fraction']} != {p}")
    check(abs(a["fraction_stderr"] - math.sqrt(p * (1 - p) / n)) < 1e-15, f"#{a['id']}: stderr")
    total += a["fraction"]
check(abs(total - 1) < 1e-12, f"shares sum to {total}")
check(count.get("undecided", 0) == s["undecided"]["starts"], "undecided count")
kinds = sorted(a["kind"] for a in atts)
check(kinds == ["family", "sticking"], f"kinds {kinds}")
vstar = 4 * (1 + 0.5) / (1 - 0.5)
for a in atts:
    c = a["certificate"]
    check(c is not None and c["certified"], f"#{a['id']} not certified: {c}")
    if a["kind"] == "family":
        check(a["period"] == 1 and c["outcome"] == "family", f"family: {a['period']}, {c['outcome']}")
        for th, v in a["points"]:
            check(abs(float(v) - vstar) <= 1e-12 * vstar, f"family point v = {v}, v* = {vstar}")
            check(0 < float(th) < 0.5, f"family point theta = {th}")
        check(abs(a["multipliers"][0]["modulus"] - 1) < 1e-9 and abs(a["multipliers"][1]["modulus"] - 0.25) < 1e-9,
              f"family multipliers {a['multipliers']}")
    else:
        check(F(a["points"][0][0]) == F(1, 2) and F(a["points"][0][1]) == 4, f"sticking cycle starts at {a['points'][0]}")
        check(c["outcome"] == "through_release" and a["period"] == len(a["points"]), f"sticking: {c['outcome']}")
    # The printed (double) points lie within 1e-12 of the certificate's exact enclosures.
    def off(x, lohi):
        lo, hi = F(lohi[0]), F(lohi[1])
        return max(lo - F(x), F(x) - hi, 0)
    if a["kind"] != "family":
        for (th, v), box in zip(a["points"], c["points"]):
            check(off(th, box["theta"]) < F(1, 10**12) and off(v, box["v"]) < F(1, 10**12),
                  f"point ({th}, {v}) is far from its certified box {box}")
done()
PY

# The result is reproducible from its provenance (the starts run in fixed batches).
audited e05-audit e05.json

run text attractors "${M[@]}" --starts 12x12 --no-certify
grep -q "family of fixed points" "$TMP/text.out" || fail text "no family in: $(cat "$TMP/text.out")"
grep -q "sticking cycle" "$TMP/text.out" || fail text "no sticking cycle in: $(cat "$TMP/text.out")"
grep -q "^# bouncer" "$TMP/text.out" || fail text "no provenance lines"

# --vary: the attractors across a parameter, chained value to value.
V=(--model veldep --c 1000 --vary a)
refused range-alone 'range' attractors "${M[@]}" --range 23:24 --out bad
refused values 'values' attractors "${V[@]}" --range 23:23.2 --values 1 --out bad
refused vary-eps 'vary' attractors "${V[@]}" --vary eps --range 0.1:0.2 --out bad
refused vary-range 'range' attractors "${V[@]}" --out bad
run sweep attractors "${V[@]}" --range 23.05:23.15 --values 3 --starts 16x16 --no-certify --quiet --out sw && outputs sweep sw
python3 - <<'PY' || fail sweep-content "see above"
import csv, json, sys
from fractions import Fraction as F
from clichecks import check, done
s = json.load(open("sw.json"))["summary"]
check(s["vary"] == "a" and s["values"] == ["23.05", "23.1", "23.15"], f"values {s['values']}")
rows = list(csv.DictReader(l for l in open("sw.csv") if not l.startswith("#")))
for k, v in enumerate(s["values"]):
    share = [F(r["fraction"]) for r in rows if r["a"] == v]
    check(abs(sum(share) - 1) < F(1, 10**12), f"a = {v}: shares sum to {float(sum(share))}")
    inchains = [c["fraction"][k] for c in s["chains"] if c["fraction"][k] is not None]
    check(abs(sum(inchains) + s["undecided_fraction"][k] - 1) < 1e-12, f"a = {v}: chain shares")
periods = {c["period"] for c in s["chains"] if all(f is not None for f in c["fraction"])}
check({3, 7} <= periods, f"periods 3 and 7 should persist over 23.05..23.15: {periods}")
done()
PY

# The elastic model (claims rows 10 and 10b): at a = 18 the search must find the nine-branch
# accelerator mode, or its finding nothing at a = 19 says nothing. Truth from the map by hand
# (docs/claims.md, row 10): a long flight returns v + 2u = v + 8, so a mode whose phases cycle
# through 9 branches gains 9 x 8 = 72 per period; its period is 33. The starts: theta =
# 1/32, the 16 v cell centres of [5, 150] (the column theta = 1/32 of row 10b's 16 x 16 check).
run elastic18 attractors --model elastic --a 18 --theta-range 0:0.0625 --v-range 5:150 --starts 1x16 --no-certify \
  --max-steps 20000 --lyapunov-steps 10000 --json
python3 - "$TMP/elastic18.out" <<'PY' || fail elastic18 "see above"
import json, sys
s = json.load(open(sys.argv[1]))["summary"]
modes = [a for a in s["attractors"] if a["kind"] == "accelerator"]
assert len(modes) == 1, [(a["kind"], a["period"]) for a in s["attractors"]]
m = modes[0]
assert m["period"] == 33 and abs(m["gain_per_period"] - 72) < 1e-3, (m["period"], m["gain_per_period"])
assert "9 phase branches" in m["evidence"] and m["starts"] >= 1, m["evidence"]
PY
# --vary hands each periodic chain to `continue`: at eps = 1/4 the period-1 sticking cycle
# through (1/2, 4) exists exactly for 200/9 <= a < 32 (test_continuation.cpp's header), so
# over a = 22.1, 22.25, 22.4 it appears between the first two values, tied to its branch's
# low border end, certified on both sides with an enclosure holding 200/9 (checked with
# exact fractions); text, JSON and the figure agree; --no-branches leaves them out.
refused no-branches-alone 'no-branches' attractors "${M[@]}" --no-branches --out bad
run ends attractors --model constant --eps 0.25 --vary a --range 22.1:22.4 --values 3 --starts 12x12 --no-certify --threads 2 --quiet --out st && outputs ends st
python3 - <<'PY' || fail ends-content "see above"
import json, sys
from fractions import Fraction as F
from clichecks import check, done
s = json.load(open("st.json"))["summary"]
st = [c for c in s["chains"] if c["kind"] == "sticking" and c["period"] == 1]
check(len(st) == 1, f"one period-1 sticking chain: {[(c['kind'], c['period']) for c in s['chains']]}")
c = st[0]
check(c["fraction"][0] is None and c["fraction"][1] is not None, f"present at {c['fraction']}")
check(len(c["ends"]) == 1, f"ends {c['ends']}")
e = c["ends"][0]
check(e["appears"] and e["between"] == ["22.1", "22.25"] and e["explained"], f"end {e}")
ev = e["event"] or {}
check(ev.get("kind") == "border" and ev.get("end") == "low", f"event {ev}")
# --no-certify proves no orbit, but the ends are proved only with certify: not here.
check(ev.get("certified") is False, f"certified without certificates: {ev}")
check(s["branches"] and s["branches"][c["branch"]]["period"] == 1, "the chain's branch")
done()
PY
run ends-cert attractors --model constant --eps 0.25 --vary a --range 22.1:22.4 --values 3 --starts 12x12 --threads 2 --quiet --out sc && outputs ends-cert sc
python3 - <<'PY' || fail ends-cert-content "see above"
import json, sys
from fractions import Fraction as F
s = json.load(open("sc.json"))["summary"]
c = [c for c in s["chains"] if c["kind"] == "sticking" and c["period"] == 1][0]
ev = c["ends"][0]["event"]
lo, hi = (F(x) for x in ev["enclosure"])
ok = ev["certified"] and lo <= F(200, 9) <= hi and hi - lo < F(1, 10**25)
if not ok:
    print("FAIL: enclosure", ev, file=sys.stderr)
sys.exit(0 if ok else 1)
PY
# The chains, branches and ties do not depend on the number of threads.
run ends-one attractors --model constant --eps 0.25 --vary a --range 22.1:22.4 --values 3 --starts 12x12 --no-certify --threads 1 --quiet --out s1 && outputs ends-one s1
python3 - <<'PY' || fail ends-threads "see above"
import json, sys
a, b = (json.load(open(f))["summary"] for f in ("st.json", "s1.json"))
key = lambda s: [(c["kind"], c["period"], c["present"], c.get("branch"), [e["sentence"] for e in c.get("ends", [])]) for c in s["chains"]]
if key(a) != key(b) or [x["span"] for x in a["branches"]] != [x["span"] for x in b["branches"]]:
    print("FAIL: 2 threads", key(a), "\n1 thread", key(b), file=sys.stderr)
    sys.exit(1)
PY
run ends-text attractors --model constant --eps 0.25 --vary a --range 22.1:22.4 --values 3 --starts 12x12 --threads 2 --quiet
grep -q "appears at a in (22.1, 22.25): border collision at a\* = 22.2222.* certified \[22.2222" "$TMP/ends-text.out" ||
  fail ends-text "no certified appearance in: $(cat "$TMP/ends-text.out")"
run no-branches attractors --model constant --eps 0.25 --vary a --range 22.1:22.4 --values 3 --starts 12x12 --no-branches --quiet --out nb
python3 -c "import json,sys; s=json.load(open('nb.json'))['summary']; sys.exit(0 if s['branches'] is None and all('ends' not in c for c in s['chains']) else 1)" ||
  fail no-branches "branches written with --no-branches"
# One attractor split by the matching: the velocity-dependent period 4 at c = 1000 moves more
# than the match distance between a = 20.4, 20.5, 20.6, 20.7, so without branches it is four
# chains; its continued branch spans [20.4, 20.7] with no event, so with branches the four are
# one chain, joined by the branch at each of the three steps. Independent of the sweep:
# `continue` from the period-4 orbit at 20.4 reaches the range's end with no event.
V4=(attractors --model veldep --c 1000 --vary a --range 20.4:20.7 --values 4 --starts 16x16 --no-certify --quiet)
run split-nb "${V4[@]}" --no-branches --out sp0
run split "${V4[@]}" --out sp1
python3 - <<'PY' || fail split-chains "see above"
import json
from clichecks import check, done
p4 = lambda f: [c for c in json.load(open(f))["summary"]["chains"] if c["period"] == 4]
without, merged = p4("sp0.json"), p4("sp1.json")
check(len(without) == 4 and all(len([x for x in c["fraction"] if x is not None]) == 1 for c in without),
      f"without branches: four one-value chains of period 4, got {[c['present'] for c in without]}")
check(len(merged) == 1 and merged[0]["present"] == "20.4..20.7", f"with branches: one chain, got {[c['present'] for c in merged]}")
check(merged and merged[0]["joined_by_branch"] == [["20.4", "20.5"], ["20.5", "20.6"], ["20.6", "20.7"]],
      f"joined at each step, got {merged and merged[0]['joined_by_branch']}")
check(merged and merged[0]["ends"] == [], f"no appearance or disappearance inside the range, got {merged and merged[0]['ends']}")
done()
PY
run split-point attractors --model veldep --c 1000 --a 20.4 --starts 16x16 --quiet --json
guess=$(python3 -c "import json; s=json.load(open('$TMP/split-point.out'))['summary']; print(','.join([a['points'][0] for a in s['attractors'] if a['period'] == 4][0]))")
run split-continue continue --model veldep --c 1000 --a 20.4 --period 4 --guess "$guess" --range 20.4:20.7 --json
python3 -c "import json,sys; s=json.load(open('$TMP/split-continue.out'))['summary']; sys.exit(0 if s['high']['reason'] == 'range_end' and not s['bifurcations'] else 1)" ||
  fail split-continue "the period-4 branch does not reach a = 20.7 without an event: $(head -c 400 "$TMP/split-continue.out")"
# Memory: a request whose starts would not fit in the memory available (here a 1.5 GB
# address space, ulimit -v) is refused at once, naming --starts; not under AddressSanitizer,
# which reserves terabytes of address space (tests/cli/output_safety.sh).
if ! asan_build; then
  rc=0
  (ulimit -v 1500000; timeout 30 "$BOUNCER" attractors "${M[@]}" --starts 2000x2000 --out mem 2>mem.err) || rc=$?
  [[ $rc -eq 2 && $(wc -l <mem.err) -eq 1 ]] &&
    grep -q "starts: this request of 4000000 starts and 262144 cells needs about .* GB of memory, more than .*give fewer --starts" mem.err ||
    fail memory "exit $rc: $(head -c 300 mem.err)"
  absent memory-files "mem.*[^r]"
fi

run help attractors --help
for opt in starts sampling cells recurrences attractor-steps hits max-steps precision out no-certify vary range values no-branches; do
  grep -q -- "--$opt" "$TMP/help.out" || fail help "does not document --$opt"
done
finish
