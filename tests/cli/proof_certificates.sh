#!/usr/bin/env bash
# End-to-end: the computer-assisted proofs (proofs/*.cpp) and their certificates.
#   * `--json` prints one valid JSON object with the documented keys, in order (proof, claim,
#     method, bits, mode, notes, subclaims [name, paper, verdict, statement, evidence],
#     seconds, verdict, statement); `proof` is the program's own name, `bits` the default
#     precision (64 for sticking_period, else 128) or the --bits given, `mode` default;
#   * the overall verdict is the one derived by hand in each proof's header (docs/claims.md),
#     every sub-claim is settled (no "not proved"), and the exit status is 0;
#   * the text certificate says the same: its verdict/statement lines and its sub-claim
#     verdicts equal the JSON fields (two output paths, one content);
#   * bad --bits (abc, 0, 99999999, 1.5, empty) is refused by every proof: exit 2, nothing on
#     stdout, one line on stderr naming --bits and its range [16, 1048576].
# Usage: bash proof_certificates.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
PROOFS="$(dirname "$BOUNCER")/../proofs"

# Overall verdicts established in the proof headers (and the claims table, docs/claims.md).
declare -A VERDICT=(
  [elastic_period2]=refuted [fixed_point_family]=corrected [inelastic_period2]=corrected
  [sticking_period]=refuted [trapping_region]=corrected [veldep_collapse]=refuted
  [veldep_fixed_points]=corrected [horseshoes]=confirmed)
# Proofs fast enough (< 0.2 s) to run a second time for the text certificate.
QUICK=" elastic_period2 fixed_point_family inelastic_period2 veldep_fixed_points "

check_json() {  # check_json NAME FILE BITS VERDICT [TEXT-FILE]
  python3 - "$@" <<'EOF'
import json, sys
name, path, bits, verdict = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
text = sys.argv[5] if len(sys.argv) > 5 else None
errors = []
try:
    with open(path) as f:
        j = json.load(f)
except ValueError as e:
    print(f"not valid JSON: {e}"); sys.exit(1)
keys = ["proof", "claim", "method", "bits", "mode", "notes", "subclaims", "seconds", "verdict", "statement"]
if list(j) != keys: errors.append(f"keys {list(j)}, expected {keys}")
else:
    if j["proof"] != name: errors.append(f"proof {j['proof']!r}")
    if j["bits"] != bits or not isinstance(j["bits"], int): errors.append(f"bits {j['bits']!r}, expected {bits}")
    if j["mode"] != "default": errors.append(f"mode {j['mode']!r}")
    if not isinstance(j["seconds"], (int, float)) or j["seconds"] < 0: errors.append(f"seconds {j['seconds']!r}")
    for k in ("claim", "method", "statement"):
        if not isinstance(j[k], str) or not j[k]: errors.append(f"{k} empty or not text")
    if not all(isinstance(n, str) for n in j["notes"]): errors.append("notes not all text")
    if j["verdict"] != verdict: errors.append(f"verdict {j['verdict']!r}, expected {verdict!r}")
    subs = j["subclaims"]
    if not subs: errors.append("no sub-claims")
    for s in subs:
        if list(s) != ["name", "paper", "verdict", "statement", "evidence"]: errors.append(f"sub-claim keys {list(s)}"); continue
        if s["verdict"] not in ("confirmed", "refuted", "corrected"): errors.append(f"sub-claim {s['name']}: {s['verdict']}")
        if not s["statement"]: errors.append(f"sub-claim {s['name']}: settled without a statement")
        if not all(isinstance(e, str) and e for e in s["evidence"]): errors.append(f"sub-claim {s['name']}: evidence not all text")
    if text:
        lines = open(text).read().splitlines()
        want = [f"==== CERTIFICATE proof.{name} ====", f"verdict: {j['verdict']}", f"statement: {j['statement']}"]
        want += [f"-- sub-claim {s['name']}: {s['verdict']}" for s in subs]
        want += [f"   * {e}" for s in subs for e in s["evidence"]]
        missing = [w for w in want if w not in lines]
        if missing: errors.append(f"text certificate lacks {missing[0][:120]!r}")
if errors:
    print("; ".join(errors)[:600]); sys.exit(1)
EOF
}

for name in "${!VERDICT[@]}"; do
  prog="$PROOFS/proof_$name"
  if [[ ! -x $prog ]]; then fail "$name" "no proof program at $prog"; continue; fi
  bits=128; [[ $name == sticking_period ]] && bits=64
  rc=0; "$prog" --json >"$TMP/$name.json" 2>"$TMP/$name.err" || rc=$?
  [[ $rc -eq 0 ]] || fail "$name" "--json exit $rc: $(head -c 300 "$TMP/$name.err")"
  textfile=()
  if [[ $QUICK == *" $name "* ]]; then
    rc=0; "$prog" >"$TMP/$name.txt" 2>"$TMP/$name.err" || rc=$?
    [[ $rc -eq 0 ]] || fail "${name}_text" "exit $rc: $(head -c 300 "$TMP/$name.err")"
    textfile=("$TMP/$name.txt")
  fi
  msg=$(check_json "$name" "$TMP/$name.json" "$bits" "${VERDICT[$name]}" "${textfile[@]}") || fail "${name}_json" "$msg"

  for bad in abc 0 99999999 1.5 ""; do
    rc=0; "$prog" --bits "$bad" >"$TMP/out" 2>"$TMP/err" || rc=$?
    [[ $rc -eq 2 ]] || fail "${name}_bits_$bad" "exit $rc, expected 2"
    [[ ! -s "$TMP/out" ]] || fail "${name}_bits_$bad" "something was written to stdout"
    [[ $(wc -l <"$TMP/err") -eq 1 ]] || fail "${name}_bits_$bad" "expected one line on stderr: $(head -c 300 "$TMP/err" | tr '\n' '|')"
    grep -q -- '--bits' "$TMP/err" && grep -q '16' "$TMP/err" && grep -q '1048576' "$TMP/err" ||
      fail "${name}_bits_$bad" "message lacks --bits and its range: $(head -c 300 "$TMP/err")"
  done
done

# --bits is honoured: the certificate records the precision asked for (a quick proof).
rc=0; "$PROOFS/proof_veldep_fixed_points" --json --bits 160 >"$TMP/b160.json" 2>"$TMP/err" || rc=$?
[[ $rc -eq 0 ]] || fail bits_160 "exit $rc: $(head -c 300 "$TMP/err")"
msg=$(check_json veldep_fixed_points "$TMP/b160.json" 160 corrected) || fail bits_160 "$msg"

finish "proof certificates: all checks passed"
