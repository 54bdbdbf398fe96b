#!/usr/bin/env bash
# End-to-end: `bouncer certify-chaos` (issue 26) as a user runs it.
#   proved: the velocity-dependent model at c = 1000, a = 27: `certified: true`, a bound
#         h_top >= x with 0 < x < 0.2 (a lower bound; bouncer's Lyapunov exponent there is
#         about 0.11 per collision), the saddle of period 2 with multipliers about -2.87 and
#         -0.27 (as `bouncer periodic --period 2` finds them), every covering proved, the h-sets
#         disjoint, and the Arb replay valid; --json says the same in JSON.
#   files: --out PREFIX writes PREFIX.json (a certificate that `check-certificate` finds VALID
#         in a separate process, and that `audit` reruns bit for bit), PREFIX.png and
#         PREFIX-covering.png (PNGs with provenance); the statement says what is not proved.
#   tampered: the certificate with one h-set's centre moved is NOT VALID (exit 1).
#   not proved: a = 20 (a stable period-2 focus, no saddle of period 1..4): `certified: false`,
#         the reason, exit 0, and no file written under --out.
#   bad input: --bits 5, --max-period 0, --model constant without --eps, an unknown option:
#         exit 2 with one line naming the option.
# Usage: bash certify_chaos.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
cd "$TMP"

V=(certify-chaos --model veldep --c 1000)
"$BOUNCER" "${V[@]}" --a 27 --out v27 >v27.txt || fail proved "exit $?"
grep -q "^certified: true$" v27.txt || fail proved "not certified: $(grep -v '^#' v27.txt | head -3)"
grep -q "^replay.valid: true$" v27.txt || fail proved "the Arb replay is not valid"
grep -q "^disjoint: true$" v27.txt || fail proved "h-sets not disjoint"
grep -q "Not proved: that the attractor is this set" v27.txt || fail proved "the statement does not say what is not proved"
grep -q "proved: false" v27.txt && fail proved "a covering of the report is not proved"
python3 - v27.txt <<'PY' || fail proved "see above"
import sys
kv = dict(l.rstrip("\n").split(": ", 1) for l in open(sys.argv[1]) if ": " in l and not l.startswith("#"))
bound = float(kv["entropy.bound_double"])
assert 0 < bound < 0.2, bound
assert kv["saddle.period"] == "2", kv["saddle.period"]
assert abs(float(kv["saddle.lambda_u"]) + 2.87) < 0.01 and abs(float(kv["saddle.lambda_s"]) + 0.27) < 0.01
assert float(kv["entropy.bound"]) == bound or kv["entropy.bound"].startswith(kv["entropy.bound_double"][:10])
PY
for f in v27.json v27.png v27-covering.png; do [[ -s $f ]] || fail files "$f missing"; done
for f in v27.png v27-covering.png; do
  [[ $(head -c 8 "$f" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] || fail files "$f is not a PNG"
  grep -aq "certify-chaos" "$f" || fail files "$f has no provenance"
done
ls v27*.partial >/dev/null 2>&1 && fail files "staging files left"
"$BOUNCER" check-certificate v27.json >check.txt || fail replay "check-certificate: exit $?: $(cat check.txt)"
grep -q "VALID: v27.json" check.txt || fail replay "not VALID: $(cat check.txt)"
"$BOUNCER" audit v27.json >audit.txt || fail audit "exit $?: $(cat audit.txt)"
grep -q "IDENTICAL" audit.txt || fail audit "$(cat audit.txt)"

# The same through --json.
"$BOUNCER" "${V[@]}" --a 27 --json >v27j.json || fail json "exit $?"
python3 - v27j.json <<'PY' || fail json "see above"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["certified"] is True and d["replay"]["valid"] is True, d["statement"]
assert 0 < d["entropy"]["bound_double"] < 0.2
assert all(c["proved"] for c in d["coverings"]) and d["hsets"] >= 3
assert d["provenance"]["command"] == "certify-chaos"
PY

# One h-set moved: the replay rejects it.
python3 - <<'PY'
import json
d = json.load(open("v27.json"))
p, q = d["sets"][3]["centre"][1].split("/") if "/" in d["sets"][3]["centre"][1] else (d["sets"][3]["centre"][1], "1")
d["sets"][3]["centre"][1] = f"{int(p) + int(q) // 1000}/{q}"  # v moved by 1e-3
json.dump(d, open("moved.json", "w"))
PY
status=0
"$BOUNCER" check-certificate moved.json >moved.txt || status=$?
[[ $status == 1 ]] || fail tampered "exit $status: $(cat moved.txt)"
grep -q "NOT VALID" moved.txt || fail tampered "$(cat moved.txt)"

# No saddle: not proved, and why; nothing written.
"$BOUNCER" "${V[@]}" --a 20 --out v20 >v20.txt || fail not-proved "exit $?"
grep -q "^certified: false$" v20.txt || fail not-proved "$(grep -v '^#' v20.txt | head -2)"
grep -q "no saddle periodic orbit found" v20.txt || fail not-proved "no reason: $(grep statement v20.txt)"
ls v20* 2>/dev/null | grep -v v20.txt && fail not-proved "files written without a proof"

# refused NAME PATTERN ARGS...: exit 2, one line, nothing written.
refused() {
  local name=$1 pattern=$2
  shift 2
  local status=0
  "$BOUNCER" "$@" >out.txt 2>err.txt || status=$?
  [[ $status == 2 ]] || fail "$name" "exit $status, expected 2: $(cat err.txt)"
  [[ $(wc -l <err.txt) == 1 ]] || fail "$name" "not one line: $(cat err.txt)"
  grep -q -- "$pattern" err.txt || fail "$name" "no '$pattern' in: $(cat err.txt)"
}
refused bits "bits: must be an integer in \[32, 4096\]" "${V[@]}" --a 27 --bits 5
refused max-period "max-period: must be an integer in \[1, 8\]" "${V[@]}" --a 27 --max-period 0
refused eps "eps: is required" certify-chaos --model constant --a 27
refused unknown "certify-chaos" "${V[@]}" --a 27 --bitz 64

finish
