#!/usr/bin/env bash
# End-to-end: `bouncer periodic`, `bouncer lyapunov` and `bouncer classify`.
#   - the JSON summary parses and carries the documented fields and the provenance;
#   - the values agree with independent truth: the eq. 5 fixed point v* = 12 at a = 24,
#     eps = 0.5 with multipliers {1, eps^2}; sticking gives lambda = -inf and class
#     sticking; the period-2 orbit of a = 19, eps = 0.9 has lambda = log(0.9);
#   - a scene file gives the same result as the command line;
#   - bad input exits 2 with one line on stderr naming the option, nothing on stdout.
# Usage: bash analysis_commands.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"

# --- periodic -------------------------------------------------------------------------
"$BOUNCER" periodic --model constant --a 24 --eps 0.5 --period 1 --guess 0.3,11.5 --json >"$TMP/p.json"
jq_is periodic.parse '.converged' true "$TMP/p.json"
jq_is periodic.fields '[has("points"), has("multipliers"), has("provenance")] | all' true "$TMP/p.json"
jq_is periodic.command '.provenance.command' periodic "$TMP/p.json"
jq_is periodic.v '(.points[0][1] | tonumber) - 12 | fabs < 1e-12' true "$TMP/p.json"
jq_is periodic.mu1 '(.multipliers[0][0] | tonumber) - 1 | fabs < 1e-12' true "$TMP/p.json"
jq_is periodic.mu2 '(.multipliers[1][0] | tonumber) - 0.25 | fabs < 1e-12' true "$TMP/p.json"
# Points round-trip: the MPFR run prints more digits than a double holds.
"$BOUNCER" periodic --model constant --a 19 --eps 0.9 --period 2 --precision mpfr:200 --json >"$TMP/p2.json"
jq_is periodic.mpfr '.converged and (.points | length) == 2 and .complex_pair' true "$TMP/p2.json"
jq_is periodic.digits '(.points[0][0] | length) > 40' true "$TMP/p2.json"
# long double and quad: the eq. 5 fixed point (v* = 12, multipliers 1 and eps^2 = 1/4) and
# the classification of a sticking orbit (period 3, see test_classify) in every point type.
for prec in long quad; do
  "$BOUNCER" periodic --model constant --a 24 --eps 0.5 --period 1 --guess 0.3,11.5 --precision $prec --json >"$TMP/p_$prec.json"
  jq_is periodic.$prec.v '(.points[0][1] | tonumber) - 12 | fabs < 1e-15' true "$TMP/p_$prec.json"
  jq_is periodic.$prec.mu2 '(.multipliers[1][0] | tonumber) - 0.25 | fabs < 1e-15' true "$TMP/p_$prec.json"
  jq_is periodic.$prec.precision '.provenance.precision' $prec "$TMP/p_$prec.json"
  "$BOUNCER" classify --model constant --a 20 --eps 0.3 --theta 0.3 --v 9 --precision $prec --json >"$TMP/c_$prec.json"
  jq_is classify.$prec '[.class, .period] | @text' '["sticking",3]' "$TMP/c_$prec.json"
done
jq_is periodic.modulus '(.multiplier_moduli[0] - 0.81) | fabs < 1e-12' true "$TMP/p2.json"
jq_is periodic.bits '.provenance.bits' 200 "$TMP/p2.json"
# Text output names the same fields.
"$BOUNCER" periodic --model constant --a 24 --eps 0.5 --period 1 --guess 0.3,11.5 >"$TMP/p.txt"
grep -q '^converged: true$' "$TMP/p.txt" || fail periodic.text "no 'converged: true' line"
grep -q '^# bouncer ' "$TMP/p.txt" || fail periodic.text "no provenance comment lines"

# --- lyapunov -------------------------------------------------------------------------
"$BOUNCER" lyapunov --model constant --a 30 --eps 0.3 --theta 0.3 --v 9 --transient 10 --steps 100 --json \
  >"$TMP/l1.json" 2>/dev/null
jq_is lyapunov.sticking '.lambda' -inf "$TMP/l1.json"
jq_is lyapunov.contracted '.contracted' true "$TMP/l1.json"
"$BOUNCER" lyapunov --model constant --a 19 --eps 0.9 --theta 0.17 --v 14.1 --transient 500 --steps 4000 --json \
  >"$TMP/l2.json"
jq_is lyapunov.fields '[has("lambda"), has("stderr"), has("steps")] | all' true "$TMP/l2.json"
jq_is lyapunov.logeps '(.lambda - (0.9 | log)) | fabs < 2e-3' true "$TMP/l2.json"
jq_is lyapunov.steps '.steps' 4000 "$TMP/l2.json"

# --- classify -------------------------------------------------------------------------
"$BOUNCER" classify --model constant --a 24 --eps 0.5 --theta 0.3 --v 11.5 --json >"$TMP/c1.json"
jq_is classify.fixed '.class + " " + (.period | tostring)' "fixed 1" "$TMP/c1.json"
"$BOUNCER" classify --model constant --a 24 --eps 0.1 --theta 0.5 --v 4 --json >"$TMP/c2.json"
jq_is classify.sticking '.class + " " + (.period | tostring)' "sticking 1" "$TMP/c2.json"
"$BOUNCER" classify --model elastic --a 16 --theta 0.25 --v 8 --transient 1000 --steps 200 --json >"$TMP/c3.json"
jq_is classify.unbounded '.class' unbounded "$TMP/c3.json"
"$BOUNCER" classify --model constant --a 19 --eps 0.9 --theta 0.17 --v 14.1 --precision mpfr:128 --json >"$TMP/c4.json"
jq_is classify.periodic '.class + " " + (.period | tostring)' "periodic 2" "$TMP/c4.json"
# A chaotic window re-checked much later (eps = 0.96, a = 28: period 2 from step 10155, see
# test_classify TransientChaosIsRecheckedAndSettles); --recheck-factor 0 keeps the window's label.
"$BOUNCER" classify --model constant --a 28 --eps 0.96 --theta 0.5 --v 4 --json >"$TMP/c6.json"
jq_is classify.transient_chaos '.class + " " + .settled_class + " " + (.period | tostring)' "transient_chaos periodic 2" "$TMP/c6.json"
jq_is classify.settled_at '.settled_at > 5500' true "$TMP/c6.json"
"$BOUNCER" classify --model constant --a 28 --eps 0.96 --theta 0.5 --v 4 --recheck-factor 0 --json >"$TMP/c7.json"
jq_is classify.recheck_off '.class' chaotic "$TMP/c7.json"
# basin uses the same rule, point by point (each basin label is classify's at that point),
# and --recheck-factor 0 brings back the window-only labels there too.
"$BOUNCER" basin --model constant --a 28 --eps 0.96 --v-range 4:40 --grid 4x3 --quiet >"$TMP/b.csv"
"$BOUNCER" basin --model constant --a 28 --eps 0.96 --v-range 4:40 --grid 4x3 --recheck-factor 0 --quiet >"$TMP/b0.csv"
grep -q ',transient_chaos,' "$TMP/b.csv" || fail basin.recheck "no transient_chaos point in the basin"
grep -q ',transient_chaos,' "$TMP/b0.csv" && fail basin.recheck_off "transient_chaos with --recheck-factor 0"
while IFS=, read -r theta v cls period; do
  got=$("$BOUNCER" classify --model constant --a 28 --eps 0.96 --theta "$theta" --v "$v" --json | jq -r '.class + "," + (.period | tostring)')
  [[ $got == "$cls,$period" ]] || fail basin.same_rule "($theta, $v): basin $cls,$period, classify $got"
done < <(grep -v '^#' "$TMP/b.csv" | tail -n +2 | grep -E 'transient_chaos|chaotic' | head -4)
# Accelerator mode: the exact orbit v_n = 8(n + 1), theta = 1/4 of a = 16.
jq_is classify.accelerator '[.growth_kind, .accelerator_period, .phase_branches] | @text' '["accelerator",1,1]' "$TMP/c3.json"
# A higher precision checks the answer: the exact orbit above agrees at once; elastic a = 18
# from (0.1, 10) is quasiperiodic in double and the period-33 accelerator mode at mpfr:256
# and mpfr:512 (issue 23), so double's class is named an artefact; --no-confirm skips it.
jq_is classify.confirm_agrees '.precision_check | [.verdict, (.checks | length), .checks[0].precision] | @text' \
  '["agrees",1,"mpfr:256"]' "$TMP/c3.json"
"$BOUNCER" classify --model elastic --a 18 --theta 0.1 --v 10 --transient 20000 --steps 20000 --json >"$TMP/c6.json"
jq_is classify.artefact '[.class, .precision_check.verdict, .precision_check.checks[1].precision, .precision_check.checks[0].accelerator_period] | @text' \
  '["quasiperiodic","artefact","mpfr:512",33]' "$TMP/c6.json"
# after capture the mode grows by gain/period per step (72/33), not by the wander's rate
jq_is classify.after_capture '.precision_check.checks[0] | (.growth_per_step - .accelerator_gain / 33 | fabs) < 0.01' true "$TMP/c6.json"
"$BOUNCER" classify --model elastic --a 16 --theta 0.25 --v 8 --no-confirm --json >"$TMP/c7.json"
jq_is classify.no_confirm 'has("precision_check")' false "$TMP/c7.json"
refused classify.confirm_bits "confirm-bits" classify --model elastic --a 16 --theta 0.25 --v 8 --confirm-bits 10
# Scene file = command line.
cat >"$TMP/scene.toml" <<'TOML'
command = "classify"
model = "constant"
a = "24"
eps = "0.5"
theta = "0.3"
v = "11.5"
TOML
"$BOUNCER" classify --scene "$TMP/scene.toml" --json >"$TMP/c5.json"
jq_is classify.scene '.class + " " + .evidence' "$(jq -r '.class + " " + .evidence' "$TMP/c1.json")" "$TMP/c5.json"

# --- bad input: exit 2, one line naming the option, nothing on stdout ------------------
refused -E periodic.noperiod 'period' periodic --model constant --a 24 --eps 0.5
refused -E periodic.period0 'period.*\[1, 100\]' periodic --model constant --a 24 --eps 0.5 --period 0
refused -E periodic.guess 'guess' periodic --model constant --a 24 --eps 0.5 --period 1 --guess 0.3
refused -E periodic.guessbelow 'guess' periodic --model constant --a 24 --eps 0.5 --period 1 --guess 0.3,1
refused -E periodic.precision 'precision.*allowed: double, long, dd, quad, mpfr:BITS' periodic --model constant --a 24 --eps 0.5 --period 1 --precision interval:64
refused -E lyapunov.theta 'theta' lyapunov --model elastic --a 20 --theta 1.5 --v 9
refused -E lyapunov.steps 'steps' lyapunov --model elastic --a 20 --theta 0.3 --v 9 --steps 0
refused -E lyapunov.precision 'precision.*allowed' lyapunov --model elastic --a 20 --theta 0.3 --v 9 --precision interval:128
refused -E lyapunov.a ' a: |^bouncer: a' lyapunov --model elastic --a -1 --theta 0.3 --v 9
refused -E classify.v 'v' classify --model elastic --a 20 --theta 0.3
refused -E classify.maxperiod 'max-period' classify --model elastic --a 20 --theta 0.3 --v 9 --steps 100 --max-period 64
refused -E classify.transient 'transient.*\[0, 10000000000\]' classify --model elastic --a 20 --theta 0.3 --v 9 --transient -1
# classify, basin and scan share one validation of the classifier window: the same errors,
# and a short window without --max-period takes max-period = steps/2 instead of failing.
refused -E basin.maxperiod 'max-period.*steps/2 \(50\)' basin --model constant --a 24 --eps 0.5 --v-range 4:12 --grid 4x4 --steps 100 --max-period 60
refused -E scan.transient 'transient' scan --model constant --a-range 18:26 --eps-range 0.4:0.9 --grid 2x2 --transient -1
"$BOUNCER" classify --model constant --a 24 --eps 0.5 --theta 0.3 --v 11.5 --steps 100 --json >"$TMP/cshort.json" 2>&1 &&
  python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["max_period"] == 50 and j["class"] == "fixed", j' "$TMP/cshort.json" ||
  fail classify.short "--steps 100 without --max-period: $(head -c 300 "$TMP/cshort.json")"
refused -E classify.precision 'precision.*allowed' classify --model elastic --a 20 --theta 0.3 --v 9 --precision interval:64
refused -E classify.eps 'eps' classify --model elastic --a 20 --eps 0.5 --theta 0.3 --v 9
refused -E classify.recheck 'recheck-factor.*\[0, 1000\]' classify --model elastic --a 20 --theta 0.3 --v 9 --recheck-factor -1
refused -E basin.recheck 'recheck-factor' basin --model constant --a 24 --eps 0.5 --v-range 4:12 --grid 4x4 --recheck-factor x

finish
