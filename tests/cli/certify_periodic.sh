#!/usr/bin/env bash
# End-to-end: certify-periodic.
#   --json: an isolated orbit (constant eps = 0.8, a = 19, period 2) with det DP^2 enclosing
#     eps^4 = 0.4096 (area contraction, an invariant the certifier never uses), a family
#     (eq. 5 corrected: eps = 0.5, a = 24 encloses v* = 12, multipliers 1 and 1/4), a
#     parameter range (the pieces tile it), text output, --out and a scene;
#   audit: the JSON result reruns bit for bit;
#   bad input: exit 2, one line on stderr, no output file left.
# Usage: bash certify_periodic.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"

run iso certify-periodic --model constant --eps 0.8 --a 19 --period 2 --guess 0.944,-0.345 --json &&
  json_holds iso 'j["certified"] and j["outcome"] == "isolated" and j["minimal_period"] == 2 and j["stability"] == "unstable"
             and inside("0.4096", j["multipliers"]["det"]) and len(j["points"]) == 2 and j["provenance"]["command"] == "certify-periodic"
             and F(j["krawczyk"]["box"][0][0]) < F(j["krawczyk"]["image"][0][0]) and F(j["krawczyk"]["image"][0][1]) < F(j["krawczyk"]["box"][0][1])'

# Without --guess: Newton from a grid in the trapping region, then the same proof.
run search certify-periodic --model constant --eps 0.8 --a 19 --period 2 --json &&
  json_holds search 'j["certified"] and j["inputs"]["guess"] is None and inside("0.4096", j["multipliers"]["det"])'

run fam certify-periodic --model constant --eps 0.5 --a 24 --period 1 --guess 0.3,12 --json &&
  json_holds fam 'j["outcome"] == "family" and inside(24, j["family"]["parameter_at_theta"]) and inside(12, j["points"][0]["v"])
             and inside(1, j["multipliers"]["mu1"]) and inside(F(1, 4), j["multipliers"]["mu2"]) and j["family"]["given_parameter"] == "inside"'

run range certify-periodic --model constant --eps 0.8 --a-range 18.9:19.1 --period 2 --guess 0.944,-0.345 --json &&
  json_holds range 'j["certified"] and j["pieces"][0]["lo"] == "18.9" and j["pieces"][-1]["hi"] == "19.1"
               and all(F(a["hi"]) == F(b["lo"]) for a, b in zip(j["pieces"], j["pieces"][1:])) and "Theorem" in j["theorem"]'

# A long period: the stable period 100 of the veldep model (c = 1000, a = 19.5). Multiple
# shooting (every point an unknown, the default from period 12 on) proves it at 64 bits,
# stable, with the determinant equal to the product of the steps' (the composed form's own
# enclosure of it, at the precision it needs, must overlap); the composed P^100 alone is
# not certified at 128 bits (the interval evaluation of 100 composed steps widens the box
# by the product of their derivative norms).
P100=(--model veldep --c 1000 --a 19.5 --period 100 --guess 0.014057849515324,23.970073801684368)
run p100 certify-periodic "${P100[@]}" --json &&
  json_holds p100 'j["certified"] and j["krawczyk"]["formulation"] == "shooting" and j["bits"] == 64 and j["minimal_period"] == 100
              and j["stability"] == "stable" and len(j["points"]) == 100 and "multiple shooting" in j["statement"]
              and abs(F(j["multipliers"]["mu1"][0])) < 1 and F(j["multipliers"]["det"][0]) > 0'
run p100c certify-periodic "${P100[@]}" --formulation composed --max-bits 128 --json &&
  json_holds p100c 'not j["certified"] and j["outcome"] == "undecided" and [a["bits"] for a in j["attempts"]] == [64, 128]'
run p100c512 certify-periodic "${P100[@]}" --formulation composed --start-bits 512 --max-bits 512 --json &&
  json_holds p100c512 'j["certified"] and j["krawczyk"]["formulation"] == "composed" and j["minimal_period"] == 100'
python3 - "$TMP/p100.out" "$TMP/p100c512.out" <<'PY' || fail p100 "the shooting and composed certificates of the period 100 do not overlap"
import json, sys
from fractions import Fraction as F
s, c = (json.load(open(f)) for f in sys.argv[1:3])
def meets(x, y): return F(x[0]) <= F(y[1]) and F(y[0]) <= F(x[1])
assert meets(s["multipliers"]["det"], c["multipliers"]["det"]) and meets(s["multipliers"]["trace"], c["multipliers"]["trace"])
assert all(meets(p["theta"], q["theta"]) and meets(p["v"], q["v"]) for p, q in zip(s["points"], c["points"]))
PY

# Text output: key: value lines with the provenance comment header.
run text certify-periodic --model constant --eps 0.8 --a 19 --period 2 --guess 0.944,-0.345 &&
  { grep -q '^certified: true$' "$TMP/text.out" && grep -q '^# bouncer .* certify-periodic$' "$TMP/text.out" &&
    grep -q '^krawczyk.box: \[\[' "$TMP/text.out"; } || fail text "text output lacks its fields"

# --out, audit, scene.
run out certify-periodic --model constant --eps 0.8 --a 19 --period 2 --guess 0.944,-0.345 --json --out "$TMP/r.json"
[[ -s "$TMP/r.json" && ! -s "$TMP/out.out" ]] || fail out "--out did not write the file (or also wrote stdout)"
audited audit "$TMP/r.json"
# One more digit after the 17th of a number parses to the same double: audit compares the
# text, so it must see the edit.
python3 - "$TMP/r.json" "$TMP/r-edited.json" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
m = re.search(r'"double_distance": (-?[0-9.]+)(e-?[0-9]+)?', s)
assert m, "no double_distance number"
edited = '"double_distance": ' + m.group(1) + "1" + (m.group(2) or "")
assert float(edited.split(": ")[1]) == float(m.group(0).split(": ")[1]), "the edit must not change the double"
open(sys.argv[2], "w").write(s.replace(m.group(0), edited))
PY
rc=0; "$BOUNCER" audit "$TMP/r-edited.json" >"$TMP/audit2.out" 2>&1 || rc=$?
[[ $rc -eq 1 ]] && grep -q "DIFFERENT: first difference at double_distance" "$TMP/audit2.out" ||
  fail audit_digits "an edit beyond double precision passed: exit $rc, $(cat "$TMP/audit2.out")"
cat > "$TMP/scene.toml" <<'TOML'
command = "certify-periodic"
model = "constant"
eps = "0.5"
a = "24"
period = 1
guess = ["0.3", "12"]
TOML
run scene certify-periodic --scene "$TMP/scene.toml" --json && json_holds scene 'j["outcome"] == "family"'

# Accelerator ladders (--lift): a = 16 is one, a = 19 is not.
run ladder certify-periodic --model elastic --a 16 --period 1 --guess 0.25,8 --lift 8 --json &&
  json_holds ladder 'j["certified"] and j["outcome"] == "accelerator_mode" and j["gain_per_impact"] == "8" and j["first_flight_periods"] == "1"'
run noladder certify-periodic --model elastic --a 19 --period 1 --guess 0.25,9.5 --lift 8 --json &&
  json_holds noladder 'not j["certified"] and j["outcome"] == "not_a_ladder" and "16/19" in j["statement"]'

# Bad input: exit 2, one line naming the option, no file.
bad() {  # bad NAME EXPECTED-WORD ARGS...
  local name=$1 word=$2
  shift 2
  refused "$name" "$word" certify-periodic "$@" --out "$TMP/bad.json"
  absent "$name" "$TMP/bad.json" "$TMP/bad.json.partial"
}
bad no_period period --model constant --eps 0.5 --a 24
bad period_range period --model constant --eps 0.5 --a 24 --period 0
bad both a-range --model constant --eps 0.5 --a 24 --a-range 1:2 --period 1
bad two_ranges range --model constant --eps 0.5 --a-range 1:2 --eps-range 0.1:0.2 --period 1
bad eps_veldep eps-range --model veldep --c 10 --a 3 --eps-range 0.1:0.2 --period 1
bad reversed a-range --model constant --eps 0.5 --a-range 2:1 --period 1
bad family_range family --model constant --eps 0.5 --a-range 1:2 --period 1 --family on
bad family_word family --model constant --eps 0.5 --a 24 --period 1 --family maybe
bad formulation_word formulation --model constant --eps 0.5 --a 24 --period 1 --formulation both
bad guess guess --model constant --eps 0.5 --a 24 --period 1 --guess 0.3
bad inside_wall guess --model constant --eps 0.5 --a 24 --period 1 --guess 0.3,-10
bad bits max-bits --model constant --eps 0.5 --a 24 --period 1 --max-bits 5
bad lift_model lift --model constant --eps 0.5 --a 16 --period 1 --guess 0.25,8 --lift 8
bad lift_period lift --model elastic --a 16 --period 2 --guess 0.25,8 --lift 8
bad lift_guess lift --model elastic --a 16 --period 1 --lift 8
bad lift_value lift --model elastic --a 16 --period 1 --guess 0.25,8 --lift x

finish
