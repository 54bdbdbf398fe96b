#!/usr/bin/env bash
# End-to-end: certify-sticking, certify-periodic's longest case, sweep and audit.
#   certify-sticking --json: the documented fields; period 1 above the analytic threshold
#     a >= 32/(1-eps) (eps = 0.5: a >= 64, derived in tests/test_sticking.cpp) and not 1
#     below it; --a-range: the theorem, pieces tiling the range, L = 0 above the threshold;
#   sweep --out PREFIX: PREFIX.json (rows with precision/bits/leaves_enclosure_at/answer,
#     implied_lyapunov), PREFIX.csv (provenance + one row per precision), PREFIX.png;
#   audit: exit 0 on fresh JSON, CSV and text results, 1 on a tampered result (with the
#     first difference named), 2 on a file that is not a result;
#   bad input: exit 2, one line on stderr, and no output file (nor *.partial) left.
# Usage: bash certify_commands.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3

# --- certify-sticking: fields, analytic threshold -----------------------------------------
if run above certify-sticking --eps 0.5 --a 64.5 --max-steps 200 --json; then
  json_holds above 'all(k in j for k in ["certified","period","bits","steps_checked","double_period","agrees","outcome","inputs","provenance","note"])'
  json_holds above 'j["certified"] is True and j["outcome"] == "sticks" and j["period"] == 1 and j["double_period"] == 1 and j["agrees"] is True'
  json_holds above 'j["inputs"]["a"] == "64.5" and j["inputs"]["eps"] == "0.5" and j["inputs"]["theta"] == "0.5" and j["inputs"]["v"] == "4"'
  json_holds above '"enclosed exactly" in j["note"] and j["provenance"]["command"] == "certify-sticking"'
  json_holds above 'isinstance(j["bits"], int) and j["bits"] >= 16 and j["steps_checked"] == 0'
fi
if run below certify-sticking --eps 0.5 --a 63.7 --max-steps 2000 --json; then
  json_holds below 'j["certified"] is True and j["period"] != 1 and j["steps_checked"] >= 1'
fi
if run paper certify-sticking --eps 0.96 --a 28.82 --max-steps 5000 --json; then
  json_holds paper 'j["certified"] is True and j["outcome"] in ("never_sticks", "no_sticking_within_max_steps") and j["period"] is None'
  json_holds paper 'j["double_period"] is None and j["agrees"] is True'
fi
if run range certify-sticking --eps 0.5 --a-range 64:70 --max-steps 200 --max-depth 3 --json; then
  json_holds range 'j["certified"] is True and j["uncertified_length"] == "0"'
  json_holds range 'j["theorem"].startswith("Theorem (computer-assisted). For every a in [64, 70] except a set of total length L = 0,")'
  json_holds range 'all(p["period"] == 1 for p in j["pieces"]) and j["pieces"][0]["a_lo"] == "64" and j["pieces"][-1]["a_hi"] == "70"'
  json_holds range 'all(j["pieces"][i]["a_hi"] == j["pieces"][i+1]["a_lo"] for i in range(len(j["pieces"]) - 1))'
fi
if run text certify-sticking --eps 0.5 --a 24 --max-steps 500; then
  grep -q '^# bouncer .* certify-sticking$' "$TMP/text.out" || fail text "no provenance line"
  grep -q '^outcome: sticks$' "$TMP/text.out" || fail text "no outcome line"
  grep -q '^note: Decimal inputs are enclosed exactly' "$TMP/text.out" || fail text "no decimal note"
fi

# --- certify-periodic, period 1096 ------------------------------------------------------------
# The stable period 1096 that `attractors` finds at veldep c = 1000, a = 21 (53% of a 32 x 32
# grid of starts): the composed P^1096 is undecided at its 689th step at every precision;
# multiple shooting (2192 unknowns) proves it at 64 bits in about 20 s. Agreement with
# double: the attractor search's double Newton multiplier (0.004581667845498367, from the
# composed Jacobian in double) lies in the enclosure of mu1 (from the Lohner-form product).
if run p1096 certify-periodic --model veldep --c 1000 --a 21 --period 1096 \
    --guess 2.4250358356353804e-05,22.812185821199588 --max-bits 64 --json; then
  json_holds p1096 'j["certified"] and j["krawczyk"]["formulation"] == "shooting" and j["minimal_period"] == 1096
               and j["stability"] == "stable" and len(j["points"]) == 1096 and j["double_distance"] is not None
               and j["double_distance"] < 1e-12 and inside("0.004581667845498367", j["multipliers"]["mu1"])'
fi

# --- sweep ----------------------------------------------------------------------------------
if run sweep sweep --model constant --eps 0.96 --a 31 --theta 0.5 --v 4 --steps 1500 --out "$TMP/sw"; then
  outputs sweep "$TMP/sw" json csv png
  cp "$TMP/sw.json" "$TMP/swj.out"
  json_holds swj '[r["precision"] for r in j["rows"]] == ["double","long","dd","quad","mpfr:64","mpfr:128","mpfr:256","mpfr:512","mpfr:1024","mpfr:2048","mpfr:4096"]'
  json_holds swj 'all(set(["precision","bits","leaves_enclosure_at","answer"]) <= set(r) for r in j["rows"]) and "implied_lyapunov" in j'
  json_holds swj 'j["reference"]["steps"] == 1500 and j["rows"][0]["leaves_enclosure_at"] is not None'
  # more bits never leave earlier than fewer bits of the same kind (mpfr rows)
  json_holds swj 'all((a["leaves_enclosure_at"] or 10**9) <= (b["leaves_enclosure_at"] or 10**9) for a, b in zip(j["rows"][4:], j["rows"][5:]))'
  head -c 8 "$TMP/sw.png" | od -An -tx1 | grep -q '89 50 4e 47' || fail sweep "PREFIX.png is not a PNG"
  grep -q '^precision,bits,leaves_enclosure_at,answer$' "$TMP/sw.csv" || fail sweep "CSV header"
  [[ $(grep -c '^mpfr:' "$TMP/sw.csv") -eq 7 ]] || fail sweep "CSV rows"
fi
if run sweepj sweep --model constant --eps 0.5 --a 24 --theta 0.5 --v 4 --steps 100 --json; then
  json_holds sweepj 'len(j["rows"]) == 11 and all(r["answer"].startswith("sticks at step 4") for r in j["rows"])'
  json_holds sweepj 'all(r["class"] is None and r["lambda"] is None for r in j["rows"])'  # sticking: no classification
fi
# A chaotic elastic orbit: no sticking, no period, so each row classifies what its precision
# sees. From 512 bits on the runs are the same orbit through all 1500 steps (they agree to
# far below double), so they must agree on a chaotic class and on one positive exponent.
if run sweepc sweep --model elastic --a 19 --theta 0.1 --v 5 --steps 1000 --json; then
  json_holds sweepc 'all(r["class"] is not None and "over 500 more steps: " + r["class"] in r["answer"] for r in j["rows"])'
  json_holds sweepc 'all(r["class"] == "chaotic" and r["lambda"] > 0.01 for r in j["rows"][7:])'
  json_holds sweepc 'max(r["lambda"] for r in j["rows"][7:]) - min(r["lambda"] for r in j["rows"][7:]) < 1e-9'
fi
if run sweepw sweep --model elastic --a 19 --theta 0.1 --v 5 --steps 300 --classify-steps 100 --json; then
  json_holds sweepw 'any(r["class"] for r in j["rows"]) and all("over 100 more steps: " in r["answer"] for r in j["rows"] if r["class"])'
fi

# --- audit ----------------------------------------------------------------------------------
audit_rc() { local rc=0; "$BOUNCER" audit "$1" >"$TMP/audit.out" 2>"$TMP/audit.err" || rc=$?; echo $rc; }
"$BOUNCER" certify-sticking --eps 0.5 --a 24 --max-steps 500 --json --out "$TMP/c.json"
"$BOUNCER" certify-sticking --eps 0.5 --a 24 --max-steps 500 --out "$TMP/c.txt"
for f in "$TMP/c.json" "$TMP/c.txt" "$TMP/sw.json" "$TMP/sw.csv"; do
  [[ -f $f ]] || { fail audit "missing $f"; continue; }
  rc=$(audit_rc "$f"); [[ $rc -eq 0 ]] || fail audit "exit $rc on a fresh result $f: $(cat "$TMP/audit.out")"
done
sed 's/"period": 4/"period": 5/' "$TMP/c.json" >"$TMP/tampered.json"
rc=$(audit_rc "$TMP/tampered.json")
[[ $rc -eq 1 ]] || fail audit "tampered JSON: exit $rc, expected 1"
grep -q 'first difference at period' "$TMP/audit.out" || fail audit "tampered JSON: difference not named: $(cat "$TMP/audit.out")"
sed 's/^mpfr:4096,4096,\([0-9]*\),/mpfr:4096,4096,7,/' "$TMP/sw.csv" >"$TMP/tampered.csv"
sed -i 's/^double,53,[0-9]*,/double,53,1,/' "$TMP/tampered.csv"
rc=$(audit_rc "$TMP/tampered.csv")
[[ $rc -eq 1 ]] || fail audit "tampered CSV: exit $rc, expected 1"
echo 'precision,bits' >"$TMP/not_a_result.csv"
rc=$(audit_rc "$TMP/not_a_result.csv"); [[ $rc -eq 2 ]] || fail audit "non-result: exit $rc, expected 2"
echo '{"rows": []}' >"$TMP/not_a_result.json"
rc=$(audit_rc "$TMP/not_a_result.json"); [[ $rc -eq 2 ]] || fail audit "JSON without provenance: exit $rc, expected 2"
rc=$(audit_rc "$TMP/does_not_exist"); [[ $rc -eq 2 ]] || fail audit "missing file: exit $rc, expected 2"

# --- bad input: exit 2, no files --------------------------------------------------------------
bad() {  # bad NAME ARGS... : must exit 2 with one stderr line and leave no TMP/bad_NAME*
  local name=$1
  shift
  refused "bad $name" "" "$@"
  absent "bad $name" "$TMP/bad_$name*"
}
bad eps certify-sticking --eps 1.5 --a 24 --json --out "$TMP/bad_eps.json"
bad law certify-sticking --model elastic --a 24 --out "$TMP/bad_law.json"
bad range certify-sticking --eps 0.5 --a-range 30:20 --out "$TMP/bad_range.json"
bad both certify-sticking --eps 0.5 --a 24 --a-range 20:30 --out "$TMP/bad_both.json"
bad bits certify-sticking --eps 0.5 --a 24 --max-bits 8 --out "$TMP/bad_bits.json"
bad steps sweep --model constant --eps 0.5 --a 24 --theta 0.5 --v 4 --steps 0 --out "$TMP/bad_steps"
bad theta sweep --model constant --eps 0.5 --a 24 --theta 1.5 --v 4 --steps 10 --out "$TMP/bad_theta"
bad tol sweep --model constant --eps 0.5 --a 24 --theta 0.5 --v 4 --tolerance -1 --out "$TMP/bad_tol"
bad csteps sweep --model constant --eps 0.5 --a 24 --theta 0.5 --v 4 --classify-steps 7 --out "$TMP/bad_csteps"

finish
