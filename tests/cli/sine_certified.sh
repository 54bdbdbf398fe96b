#!/usr/bin/env bash
# End-to-end: the certified commands on the sine wall (--wall sine), whose release phase
# theta_r = asin(a/(4 pi^2))/(2 pi) is irrational, so the release state is enclosed by the
# interval model rather than given as a decimal (verify/sticking.hpp, from_release).
#   certify-sticking: from the release state by default (inputs.start = "release"); at
#     eps = 0.5, a = 8 it sticks again at step 3 (the sticking cycle that certify-periodic
#     proves through the same release state), and double agrees; from a decimal start it
#     sticks first and says when; audit reruns it IDENTICAL.
#   certify-periodic: the period-3 sticking cycle through the release state (superstable),
#     and the stable period-1 focus at a = 30 (multipliers of modulus eps = 1/2 = sqrt(det)).
#   scan --certify: every cell is certified from the release state (JSON start "release"),
#     and a sample cell's class is certify-sticking's at the cell's exact parameters.
#   basin --certify: after a first sticking each orbit goes on from the release state, so
#     every certified sticking pixel has the release orbit's period (3 at a = 8).
#   continue: the stable period-1 branch ends in the fold at a_SN = 12 pi and has its period
#     doubling at the closed form a_PD = 4 pi^2 (1+eps)^2 / sqrt(4 (1+eps^2)^2 + pi^2 (1-eps^2)^2)
#     (computed here with Python's decimal module), which --certify's enclosure holds; the
#     fold's proof is refused (theta = 0, where the phase wraps); audit reruns it IDENTICAL.
#     The saddle branch ends below in a grazing; the sticking cycle's ends are the sticking
#     threshold and a grazing.
#   attractors: at eps = 0.5, a = 30 exactly two, the focus at the closed form (theta*, a/2),
#     cos 2 pi theta* = a (1-eps) / (4 pi (1+eps)), and the sticking cycle of period 1 through
#     the release state (theta_r, 2 pi cos 2 pi theta_r), theta_r = asin(a / 4 pi^2) / (2 pi),
#     both certified with enclosures holding the closed forms, shares summing to 1; at a = 8
#     the one attractor is the period-3 sticking cycle, certified; --vary a finds the focus's
#     period doubling at a_PD (certified) and its fold.
#   tongues --wall sine: the p = 1 row at eps = 1/2 has a_PD (as above) and a_SN = 12 pi, every
#     row a_PD < a_SN, audit reruns it IDENTICAL; a wall other than triangle or sine: exit 2.
#   bad input: certify-periodic --lift and certify-chaos still refuse the sine wall (exit 2).
# Usage: bash sine_certified.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3
cd "$TMP"
sine=(--model constant --wall sine --eps 0.5)

if run release certify-sticking "${sine[@]}" --a 8 --max-steps 200 --json; then
  json_holds release 'j["certified"] is True and j["outcome"] == "sticks" and j["period"] == 3'
  json_holds release 'j["inputs"]["start"] == "release" and "theta" not in j["inputs"] and j["inputs"]["wall"] == "sine"'
  json_holds release 'j["double_period"] == 3 and j["agrees"] is True'
fi
"$BOUNCER" certify-sticking "${sine[@]}" --a 8 --max-steps 200 --json --out release.json || fail release-out "exit $?"
audited release release.json
if run decimal certify-sticking "${sine[@]}" --a 8 --theta 0.3 --v 3 --max-steps 200 --json; then
  json_holds decimal 'j["certified"] is True and j["outcome"] == "sticks" and j["inputs"]["theta"] == "0.3"'
fi

if run cycle certify-periodic "${sine[@]}" --a 8 --period 3 --guess 0.0324764449261353,6.1528268841306 --json; then
  json_holds cycle 'j["certified"] is True and j["outcome"] == "through_release" and j["minimal_period"] == 3'
  json_holds cycle 'j["stability"] == "superstable" and j["events"][-1].startswith("sticking")'
fi
if run focus certify-periodic "${sine[@]}" --a 30 --period 1 --guess 0.1,15 --json; then
  json_holds focus 'j["certified"] is True and j["outcome"] == "isolated" and j["stability"] == "stable"'
  json_holds focus 'j["multipliers"]["kind"] == "complex" and inside("1/2", j["multipliers"]["modulus"])'
  json_holds focus 'inside("1/4", j["multipliers"]["det"]) and inside("15", j["points"][0]["v"])'
fi

"$BOUNCER" scan --model constant --wall sine --a-range 7.5:8.5 --eps-range 0.45:0.55 --grid 2x2 --transient 200 --steps 100 \
  --certify --max-bits 128 --quiet --out s || fail scan "exit $?"
"$BOUNCER" basin "${sine[@]}" --a 8 --grid 4x3 --transient 200 --steps 100 --certify --max-bits 128 --quiet --out b \
  || fail basin "exit $?"
python3 - "$BOUNCER" <<'PY' || fail properties "see above"
import csv, json, subprocess, sys
bouncer = sys.argv[1]
from clichecks import check, done
def rows(name):
    return list(csv.DictReader(l for l in open(name + ".csv") if not l.startswith("#")))
js = json.load(open("s.json"))["summary"]
check(js["certified"] is True and js["start"] == "release", "scan: certified from the release: %s" % js.get("start"))
cells = rows("s")
check(len(cells) == 4, "scan: 4 cells, got %d" % len(cells))
decided = [c for c in cells if c["class"] not in ("undecided", "outside")]
check(len(decided) > 0, "scan: no certified cell")
for c in decided[:2]:
    out = subprocess.run([bouncer, "certify-sticking", "--model", "constant", "--wall", "sine", "--a", c["a"], "--eps", c["eps"],
                          "--max-steps", "300", "--max-bits", "4096", "--json"], capture_output=True, text=True)
    h = json.loads(out.stdout)
    if c["class"] == "sticking":
        check(h["outcome"] == "sticks" and str(h["period"]) == c["period"], "scan cell %s: %s vs %s" % (c, h["outcome"], h["period"]))
b = rows("b")
stick = [r for r in b if r["class"] == "sticking"]
check(len(stick) > 0, "basin: no certified sticking pixel")
check(all(r["period"] == "3" for r in stick), "basin: sticking periods %s (the release orbit's is 3)" % {r["period"] for r in stick})
done()
PY

if run branch continue "${sine[@]}" --a 30 --period 1 --guess 0.1,15 --vary a --range 20:39 --certify --json; then
  python3 - "$TMP/branch.out" <<'PY' || fail branch "see above"
import json, sys
from decimal import Decimal as D, getcontext
from clichecks import check, done
getcontext().prec = 60
pi = D("3.14159265358979323846264338327950288419716939937510582097494")
e = D("0.5")
a_pd = 4 * pi * pi * (1 + e) ** 2 / (4 * (1 + e * e) ** 2 + pi * pi * (1 - e * e) ** 2).sqrt()
a_sn = 4 * pi * (1 + e) / (1 - e)
s = json.load(open(sys.argv[1]))["summary"]
check(s["low"]["reason"] == "range_end", "low end: %s" % s["low"]["reason"])
check(s["high"]["reason"] == "fold" and abs(D(s["high"]["param"]) - a_sn) < D("1e-8"), "high end: %s at %s" % (s["high"]["reason"], s["high"]["param"]))
check(s["high"]["certified"]["certified"] is False and "wraps" in s["high"]["certified"]["statement"], "the fold's proof is refused with the reason")
pd = s["bifurcations"]
check(len(pd) == 1 and pd[0]["kind"] == "period_doubling", "one period doubling: %s" % [b["kind"] for b in pd])
enc = pd[0]["certified"]["enclosure"]
check(pd[0]["certified"]["certified"] is True and D(enc[0]) <= a_pd <= D(enc[1]), "a_PD %s in %s" % (a_pd, enc))
done()
PY
fi
"$BOUNCER" continue "${sine[@]}" --a 30 --period 1 --guess 0.1,15 --vary a --range 20:39 --out branch || fail branch-out "exit $?"
audited branch branch.json
if run saddle continue "${sine[@]}" --a 30 --period 1 --guess 0.896,15 --vary a --range 5:39 --json; then
  json_holds saddle 'j["summary"]["low"]["reason"] == "border" and j["summary"]["low"]["margin"] == "clearance" and "grazes the wall at theta" in j["summary"]["low"]["detail"]'
  json_holds saddle 'j["summary"]["high"]["reason"] == "fold" and j["summary"]["start"]["stability"] == "unstable"'
fi
if run stuck continue "${sine[@]}" --a 8 --period 3 --guess 0.5,3 --vary a --range 4:20 --json; then
  json_holds stuck 'j["summary"]["low"]["margin"] == "sticking_margin" and j["summary"]["high"]["margin"] == "clearance"'
  json_holds stuck 'abs(j["summary"]["high"]["graze_theta"] - 0.40998) < 1e-3 and "graze_theta" not in j["summary"]["low"]'
fi

if run att30 attractors "${sine[@]}" --a 30 --cells 64x64 --json; then
  python3 - "$TMP/att30.out" <<'PY' || fail att30 "see above"
import json, sys
from decimal import Decimal as D, getcontext
from clichecks import check, done
getcontext().prec = 50
pi = D("3.14159265358979323846264338327950288419716939937510582097494")
def acos_or_asin(x, asin):  # by bisection on cos (decimal has no trigonometry)
    def cos(t):  # Taylor series of cos(t), |t| <= 2
        s, term, k = D(1), D(1), 0
        while abs(term) > D("1e-45"):
            k += 2
            term *= -t * t / (k * (k - 1))
            s += term
        return s
    lo, hi = D(0), pi / 2 if asin else pi
    for _ in range(170):
        mid = (lo + hi) / 2
        if (cos(pi / 2 - mid) < x) if asin else (cos(mid) > x):
            lo = mid
        else:
            hi = mid
    return lo, cos
a, e = D(30), D("0.5")
t_star = acos_or_asin(a * (1 - e) / (4 * pi * (1 + e)), False)[0] / (2 * pi)
t_r, cos = acos_or_asin(a / (4 * pi * pi), True)
t_r /= 2 * pi
v_r = 2 * pi * cos(2 * pi * t_r)
s = json.load(open(sys.argv[1]))["summary"]
atts = s["attractors"]
check(len(atts) == 2, "two attractors, got %d" % len(atts))
check(abs(sum(x["fraction"] for x in atts) + s["undecided"]["fraction"] - 1) < 1e-12, "the shares sum to 1")
def holds(enc, x):
    return D(enc[0]) <= x <= D(enc[1])
for x in atts:
    c = x["certificate"]
    check(c["certified"] is True, "%s certified" % x["name"])
    p = c["points"][0]
    if x["kind"] == "sticking":
        check(x["period"] == 1 and c["outcome"] == "through_release", "the sticking cycle has period 1 through the release")
        check(holds(p["theta"], t_r) and holds(p["v"], v_r), "the release state %s holds (%s, %s)" % (p, t_r, v_r))
    else:
        check(x["period"] == 1 and c["stability"] == "stable", "the other is the stable fixed point: %s" % x["name"])
        check(holds(p["theta"], t_star) and holds(p["v"], a / 2), "the focus %s holds (%s, 15)" % (p, t_star))
done()
PY
fi
if run att8 attractors "${sine[@]}" --a 8 --cells 32x32 --json; then
  json_holds att8 'len(j["summary"]["attractors"]) == 1 and j["summary"]["attractors"][0]["kind"] == "sticking" and j["summary"]["attractors"][0]["period"] == 3 and j["summary"]["attractors"][0]["certificate"]["certified"] is True'
fi
if run sweep attractors "${sine[@]}" --a 20 --vary a --range 20:38 --values 4 --cells 48x48 --json; then
  # a_PD = 25.856565883105104434161963729485610166... (the closed form, as in the branch check above)
  json_holds sweep 'any(e["kind"] == "period_doubling" and e["certified"] is True and inside("25.8565658831051044341619637294856101663", e["enclosure"]) for b in j["summary"]["branches"] for e in b["events"])'
  json_holds sweep 'any(e["kind"] == "fold" and abs(float(e["param"]) - 37.69911184307752) < 1e-8 for b in j["summary"]["branches"] for e in b["events"])'
fi

if "$BOUNCER" tongues --wall sine --p-max 3 --samples 601 --out tongues --quiet; then
  python3 - <<'PY' || fail tongues "see above"
import csv
from decimal import Decimal as D, getcontext
from clichecks import check, done
getcontext().prec = 50
rows = list(csv.DictReader(l for l in open("tongues.csv") if not l.startswith("#")))
check(len(rows) == 3 * 599, "599 rows per curve (eps = 0 and 1 left out): %d" % len(rows))
check(all(D(r["a_pd"]) < D(r["a_sn"]) for r in rows), "a_PD < a_SN on every row")
half = [r for r in rows if r["p"] == "1" and r["eps"] == "1/2"]
check(len(half) == 1, "a p = 1 row at eps = 1/2")
check(abs(D(half[0]["a_pd"]) - D("25.8565658831051044341619637294856101663")) < D("1e-35"), "a_PD %s" % half[0]["a_pd"])
check(abs(D(half[0]["a_sn"]) - D("37.6991118430775188615517205993540346102")) < D("1e-35"), "a_SN %s" % half[0]["a_sn"])
done()
PY
  audited tongues tongues.json
else
  fail tongues "exit $?"
fi
refused tongues-wall "wall" tongues --wall sawtooth

refused lift "wall" certify-periodic --model elastic --wall sine --a 16 --period 1 --guess 0.1,8 --lift 8
refused chaos "wall" certify-chaos "${sine[@]}" --a 20
finish
