#!/usr/bin/env bash
# End-to-end: `bouncer continue`.
#   - with --out, PREFIX.csv (provenance lines, a header, one parseable row per branch
#     point), PREFIX.json and PREFIX.png are written;
#   - the located end agrees with a hand-derived closed form: the period-1 sticking orbit
#     through the release state (1/2, 4) of the constant-eps model exists for
#     a >= 8((1+eps)/(1-eps))^2 (= 200/9 at eps = 1/4; derivation in
#     tests/test_continuation.cpp), so continued downwards it ends there at the sticking
#     threshold;
#   - the JSON summary carries the documented fields; `bouncer audit PREFIX.json` reruns it;
#   - each located end's error estimate: its widened bracket contains a* (the closed forms,
#     and the veldep period-7 ends' a* at mpfr:128), the text prints only its digits;
#   - a scene file gives the same result as the command line;
#   - --certify's certified one-sided bounds are consistent with the closed form; its fold and
#     period doubling enclosures hold the area identity's other multiplier (eps^2 per impact);
#   - bad input exits 2 with one line on stderr naming the option, nothing on stdout.
# Usage: bash continue_command.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"

# --- outputs and the closed-form sticking threshold ---------------------------------
"$BOUNCER" continue --model constant --eps 0.25 --a 26 --period 1 --guess 0.5,4 --range 20:31 \
  --out "$TMP/st" >"$TMP/st.txt"
outputs outputs "$TMP/st" csv json png
head -c 8 "$TMP/st.png" | od -An -c | grep -q 'P   N   G' || fail png "st.png is not a PNG"
grep -q '^# bouncer ' "$TMP/st.csv" || fail csv "no provenance comment lines"
# Header: the parameter first, then the documented columns; every row has as many cells.
# (one process: with pipefail, `grep | head -1` fails when head closes the pipe first)
header=$(awk '!/^#/ { print; exit }' "$TMP/st.csv")
[[ $header == a,stability,mu1_re,mu1_im,mu1_abs,mu2_re,mu2_im,mu2_abs,events,knot_distance,* ]] ||
  fail csv.header "header is '$header'"
ncol=$(awk -F, '{print NF}' <<<"$header")
bad=$(rows "$TMP/st.csv" | awk -F, -v n="$ncol" 'NF != n || $1 !~ /^[0-9.e+-]+$/ {c++} END {print c+0}')
[[ $bad == 0 ]] || fail csv.rows "$bad rows do not parse"
nrows=$(rows "$TMP/st.csv" | wc -l)
jq_is json.points '.summary.points' "$nrows" "$TMP/st.json"
jq_is json.command '.provenance.command' continue "$TMP/st.json"
jq_is json.fields '.summary | [has("start"), has("low"), has("high"), has("bifurcations")] | all' true "$TMP/st.json"
jq_is json.low.reason '.summary.low.reason' border "$TMP/st.json"
jq_is json.low.margin '.summary.low.margin' sticking_margin "$TMP/st.json"
# a* = 200/9 (hand-derived), to 1e-10 relative
jq_is json.low.astar '((.summary.low.param | tonumber) - 200/9 | fabs) < 200/9 * 1e-10' true "$TMP/st.json"
jq_is json.high.reason '.summary.high.reason' range_end "$TMP/st.json"
jq_is json.start.events '.summary.start.events' 'S0^' "$TMP/st.json"
grep -q '^low end:  period 1 ends at a\* = 22.22222222222' "$TMP/st.txt" || fail text "no located low end in the summary"
# Honest digits (issue 23): the widened bracket of the error estimate contains 200/9, the
# text prints a* with the digits it backs and "± R (estimate)", the JSON keeps the computed
# round-trip value beside it; a range end is the given value.
jq_is json.low.accuracy '.summary.low.accuracy' estimate "$TMP/st.json"
jq_is json.low.estimate '.summary.low.bracket_estimate | map(tonumber) | .[0] <= 200/9 and 200/9 <= .[1]' true "$TMP/st.json"
jq_is json.low.digits '.summary.low.a_star_digits | . >= 10 and . < 17' true "$TMP/st.json"
jq_is json.low.param_kept '.summary.low.param | tonumber | . > 22.2 and . < 22.3' true "$TMP/st.json"
jq_is json.high.accuracy '.summary.high.accuracy' given "$TMP/st.json"
backed=$(jq -r '.summary.low.a_star_backed + " ± " + .summary.low.a_star_plus_minus' "$TMP/st.json")
grep -qF "low end:  period 1 ends at a* = $backed (estimate) by" "$TMP/st.txt" || fail text.digits "the summary does not print '$backed (estimate)'"
# The rows are in increasing a and their sticking margin has the closed form
# sqrt(8a)(1+eps)/2 - a(1-eps)/2 (its distance to 0 is reported).
awk -F, -v OFS=, '!/^#/ && NR > 0 && $1 != "a" {
  a = $1; m = sqrt(8 * a) * 1.25 / 2 - a * 0.75 / 2; if (m < 0) m = -m
  col = 0; if ((m - $16) > 1e-9 || ($16 - m) > 1e-9) print "row a=" a ": " $16 " vs " m
  if (NR > 1 && a < last) print "not increasing at " a; last = a }' "$TMP/st.csv" >"$TMP/margins.txt"
[[ ! -s $TMP/margins.txt ]] || fail csv.margin "$(head -3 "$TMP/margins.txt")"

# --- audit reruns it ------------------------------------------------------------------
audited audit "$TMP/st.json"

# --- JSON on stdout, and a scene ------------------------------------------------------
"$BOUNCER" continue --model constant --eps 0.25 --a 26 --period 1 --guess 0.5,4 --range 24:33.5 --json >"$TMP/k.json"
jq_is knot.reason '.summary.high.reason' border "$TMP/k.json"
jq_is knot.astar '((.summary.high.param | tonumber) - 32 | fabs) < 32e-10' true "$TMP/k.json"
jq_is knot.knot '.summary.high.knot' 0 "$TMP/k.json"
jq_is knot.estimate '.summary.high.bracket_estimate | map(tonumber) | .[0] <= 32 and 32 <= .[1]' true "$TMP/k.json"
# --quiet is accepted (as by every picture command) and changes nothing but the invocation.
"$BOUNCER" continue --model constant --eps 0.25 --a 26 --period 1 --guess 0.5,4 --range 24:33.5 --json --quiet >"$TMP/kq.json" ||
  fail quiet "exit $?"
cmp -s <(jq -S 'del(.provenance)' "$TMP/k.json") <(jq -S 'del(.provenance)' "$TMP/kq.json") || fail quiet "--quiet changed the result"
cat >"$TMP/scene.toml" <<'EOF'
command = "continue"
model = "constant"
a = "26"
eps = "0.25"
period = 1
guess = ["0.5", "4"]
range = "24:33.5"
EOF
"$BOUNCER" continue --scene "$TMP/scene.toml" --json >"$TMP/ks.json"
jq_is scene.same '.summary.high.param' "$(jq -r .summary.high.param "$TMP/k.json")" "$TMP/ks.json"
# The example scene of docs/guide/dynamics.md runs (shortened range: the test stays fast).
"$BOUNCER" continue --scene "$SRC/data/scenes/continue-veldep-period7.toml" --json >"$TMP/v7.json"
jq_is scene.v7 '.summary.start.stability != null and .summary.period == 7' true "$TMP/v7.json"
# Its ends: the double bracket lies within the location's tolerance (2^-44 |a*|) of a* as
# located at mpfr:128 (docs/guide/dynamics.md) and enclosed by Krawczyk (test_border_collision),
# and the widened brackets contain a*.
jq_is v7.low.near '.summary.low.bracket | map(tonumber) | .[0] - 2e-12 <= 27.720561305445859 and 27.720561305445859 <= .[1] + 2e-12' true "$TMP/v7.json"
jq_is v7.low.estimate '.summary.low.bracket_estimate | map(tonumber) | .[0] <= 27.720561305445859 and 27.720561305445859 <= .[1]' true "$TMP/v7.json"
jq_is v7.high.estimate '.summary.high.bracket_estimate | map(tonumber) | .[0] <= 28.761251769269447 and 28.761251769269447 <= .[1]' true "$TMP/v7.json"

# --- --certify: the certified one-sided bounds agree with the closed form -------------
# Low end: the orbit is proved to exist on [c, ...], so a* <= c must hold for a* = 200/9;
# high end: a* >= c for a* = 32. Both bounds within 1e-4 of a*.
"$BOUNCER" continue --model constant --eps 0.25 --a 26 --period 1 --guess 0.5,4 --range 20:33.5 --certify \
  --json >"$TMP/cert.json"
jq_is certify.low '(.summary.low.certified.certified_to | tonumber) as $c | $c >= 200/9 and $c - 200/9 < 1e-4' true "$TMP/cert.json"
jq_is certify.high '(.summary.high.certified.certified_to | tonumber) as $c | $c <= 32 and 32 - $c < 1e-4' true "$TMP/cert.json"
jq_is certify.input '.provenance.inputs.certify' true "$TMP/cert.json"
# The error estimate's widened brackets contain the two-sided certified enclosures.
jq_is certify.estimate '[.summary.low, .summary.high] | map(.certified.two_sided.estimate_contains) | all' true "$TMP/cert.json"

# --- --certify proves folds and period doublings ---------------------------------------
# eps = 0.9: the period-11 orbit ends going down at a fold, and the period-2 orbit has a
# period doubling at a* ~ 15.78. The constant-eps map contracts area by eps^2 per impact, so
# at the fold the other multiplier is det DP^11 = 0.9^22 and at the period doubling it is
# -0.9^4: both inside the certified enclosures (compared as exact fractions).
"$BOUNCER" continue --model constant --eps 0.9 --a 12.5 --period 11 --guess 0.04780185758554826,34.63889719838767 \
  --range 12:13 --certify --json >"$TMP/fold.json"
"$BOUNCER" continue --model constant --eps 0.9 --a 19 --period 2 --guess 0.1678819228862684,14.143149884133248 \
  --range 12:21 --certify --json >"$TMP/pd.json"
python3 - "$TMP/fold.json" "$TMP/pd.json" <<'PY' || fail certify.smooth "see above"
import json, sys
from fractions import Fraction as F
from clichecks import check, done
fold = json.load(open(sys.argv[1]))["summary"]["low"]
check(fold["reason"] == "fold", f"low end {fold['reason']}")
c = fold.get("certified", {})
lo, hi = (F(x) for x in c.get("other_multiplier") or ["1", "0"])
check(c.get("certified") and lo <= F(9, 10) ** 22 <= hi, f"fold: other multiplier {c.get('other_multiplier')} vs 0.9^22")
a_lo, a_hi = (F(x) for x in c.get("enclosure") or ["1", "0"])
check(a_lo <= F(fold["param"]) + F(1, 10**9) and F(fold["param"]) - F(1, 10**9) <= a_hi, f"fold enclosure {c.get('enclosure')} vs {fold['param']}")
check(c.get("estimate_contains") is True, "the fold's widened bracket contains the enclosure")
bif = json.load(open(sys.argv[2]))["summary"]["bifurcations"]
check(len(bif) == 1 and bif[0]["kind"] == "period_doubling", f"bifurcations {bif}")
pc = bif[0].get("certified", {}) if bif else {}
lo, hi = (F(x) for x in pc.get("other_multiplier") or ["1", "0"])
check(pc.get("certified") and lo <= -F(9, 10) ** 4 <= hi, f"period doubling: other multiplier {pc.get('other_multiplier')} vs -0.9^4")
done()
PY

# --- a doubling end: the period 62 (veldep, c = 1000) born at a period-31 orbit's doubling --
# (tests/test_border_collision.cpp proves it; here the JSON and the sentence say so)
"$BOUNCER" continue --model veldep --c 1000 --a 28.7 --period 62 --guess 0.02863575971809439,15.428624909128757 \
  --range 28.699:28.701 --json > "$TMP/p62.json" 2> "$TMP/p62.err" || fail doubling.run "exit $?: $(tail -n 3 "$TMP/p62.err")"
jq_is doubling.reason '.summary.low.reason' doubling "$TMP/p62.json"
jq_is doubling.mother '.summary.low.mother_period' 31 "$TMP/p62.json"
jq_is doubling.beyond '.summary.low.beyond.newton_orbit_relation' mother "$TMP/p62.json"
jq_is doubling.sentence '.summary.low.sentence | test("by the period doubling it is born from")' true "$TMP/p62.json"

# --- bad input: exit 2, one line naming the option, nothing on stdout -----------------
bad_input() {  # bad_input NAME FIELD ARGS...
  local name=$1 field=$2
  shift 2
  refused "bad.$name" "$field" continue "$@"
}
OK=(--model constant --eps 0.25 --a 26 --period 1 --guess 0.5,4)
bad_input no-period period --model constant --eps 0.25 --a 26 --guess 0.5,4 --range 20:31
bad_input no-guess guess --model constant --eps 0.25 --a 26 --period 1 --range 20:31
bad_input no-range range "${OK[@]}"
bad_input vary-eps vary --model veldep --c 1000 --a 26 --period 1 --guess 0.5,4 --vary eps --range 0.1:0.2
bad_input vary-c vary "${OK[@]}" --vary c --range 1:2
bad_input vary-x vary "${OK[@]}" --vary b --range 1:2
bad_input range-eps range --model constant --eps 0.5 --a 26 --period 1 --guess 0.5,4 --vary eps --range 0.2:1.5
bad_input range-a range "${OK[@]}" --range -1:30
bad_input start-outside a "${OK[@]}" --range 27:30
bad_input guess-inside guess --model constant --eps 0.25 --a 26 --period 1 --guess 0.25,1 --range 20:31
bad_input period-0 period --model constant --eps 0.25 --a 26 --period 0 --guess 0.5,4 --range 20:31
bad_input precision precision "${OK[@]}" --range 20:31 --precision interval:64
bad_input step step "${OK[@]}" --range 20:31 --step 20
[[ ! -e $TMP/none.csv ]] || fail bad.files "a file was written"

finish
