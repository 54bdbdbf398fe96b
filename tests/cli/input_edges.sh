#!/usr/bin/env bash
# End-to-end: inputs that are not what they seem get bouncer's own one-line message and
# exit status 2 (tools/command_line.hpp):
#   * an unknown command names the commands, with a did-you-mean;
#   * an unknown option names the command's help, with a did-you-mean (--epsilon -> --eps);
#   * `--opt=` with no value is refused (it used to take the next option as its value);
#   * a 100,000-character value is cut and a newline in a value is escaped: one short line;
#   * a word that is not valid UTF-8 is refused, its bytes shown as \xNN;
#   * a directory given as a scene is refused; a bad --range is blamed on --range;
#   * a theta that rounds to 1 in the chosen precision is refused (not wrapped);
#   * --version works on every command; a proof program refuses --bits abc;
#   * `bouncer help CMD` and `bouncer --scene FILE` (the scene's command) work.
# Usage: bash input_edges.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"

short_refusal() {  # short_refusal NAME PATTERN ARGS... : refused (-E), with a line of at most 500 characters
  refused -E "$@"
  [[ $(wc -c <"$REFUSED_ERR") -le 500 ]] || fail "$1" "the error line is $(wc -c <"$REFUSED_ERR") characters long"
}
M=(--model constant --eps 0.5 --a 24)
short_refusal unknown_command "unknown command 'orbti' \(did you mean 'orbit'\?\); commands: orbit, " orbti
short_refusal unknown_option "orbit: unknown option '--epsilon' \(did you mean --eps\?\)" orbit --epsilon 0.5 --a 24
short_refusal empty_value "^bouncer: steps: '--steps=' gives no value" orbit "${M[@]}" --theta 0.3 --v 12 --steps= --json
long=$(printf 'x%.0s' $(seq 1 100000))
short_refusal long_value "characters cut" orbit "${M[@]}" --theta "$long" --v 12
short_refusal newline "\\\\n" orbit "${M[@]}" --theta $'0.3\nsecond line' --v 12
# A word that is not UTF-8 cannot be recorded in a JSON provenance: refused up front (it
# was an internal error when the JSON was written; found by tests/fuzz/fuzz_command_line).
short_refusal not_utf8 "^bouncer: out: the value 'o\\\\xffn.json' is not valid UTF-8" orbit "${M[@]}" --theta 0.3 --v 12 --steps 2 --format json --out $'o\xffn.json'
short_refusal not_utf8_overlong "the argument '--theta=\\\\xc0\\\\xb0' is not valid UTF-8" orbit "${M[@]}" $'--theta=\xc0\xb0' --v 12
short_refusal theta_rounds_to_1 "theta: .* rounds to 1" orbit "${M[@]}" --theta 0.99999999999999999999 --v 12
"$BOUNCER" orbit "${M[@]}" --theta 0.99999999999999999999 --v 12 --precision mpfr:256 >/dev/null ||
  fail theta_mpfr "the same theta at 256 bits (it does not round to 1 there) was refused"
mkdir "$TMP/scene.toml"
short_refusal scene_dir "scene: .* is a directory" orbit --scene "$TMP/scene.toml"
short_refusal range_blame "^bouncer: range:" bifurcation --model constant --eps 0.5 --range x:30 --samples 3
short_refusal range_blame_lyapunov "^bouncer: range:" lyapunov --model constant --eps 0.5 --vary a --range x:30 --samples 3
for cmd in orbit certify-sticking certify-periodic certify-chaos check-certificate sweep audit periodic continue lyapunov classify bifurcation portrait basin scan trajectory tongues merge; do
  rc=0
  out=$("$BOUNCER" "$cmd" --version 2>&1) || rc=$?
  [[ $rc -eq 0 && $out =~ commit ]] || fail "version_$cmd" "exit $rc: ${out:0:200}"
done

# Extra values and missing values get bouncer's message naming the option, not CLI11's
# "The following argument was not expected: 0.6", which names none.
short_refusal extra_value "orbit: unexpected value '0.6' after --eps" orbit --model constant --a 24 --eps 0.5 0.6 --theta 0.1 --v 10
short_refusal missing_value "^bouncer: grid: --grid needs a value" basin "${M[@]}" --grid
short_refusal missing_value_mid "^bouncer: steps: --steps needs a value" orbit "${M[@]}" --steps --theta 0.1 --v 10

# `bouncer help CMD` is `bouncer CMD --help`; `bouncer --scene FILE` runs the scene's command.
for cmd in orbit basin merge; do
  cmp -s <("$BOUNCER" help "$cmd") <("$BOUNCER" "$cmd" --help) || fail "help_$cmd" "bouncer help $cmd differs from bouncer $cmd --help"
done
short_refusal help_unknown "unknown command 'orbti' \(did you mean 'orbit'\?\)" help orbti
printf 'command = "orbit"\nmodel = "constant"\neps = "0.5"\na = "24"\ntheta = "0.3"\nv = "12"\nsteps = 5\n' >"$TMP/run.toml"
cmp -s <("$BOUNCER" --scene "$TMP/run.toml" --steps 3 | grep -v '^# invocation') \
  <("$BOUNCER" orbit --scene "$TMP/run.toml" --steps 3 | grep -v '^# invocation') ||
  fail scene_dispatch "bouncer --scene FILE did not run the scene's command with the same result"
printf 'model = "constant"\n' >"$TMP/nocommand.toml"
short_refusal scene_no_command "scene: .* has no command" --scene "$TMP/nocommand.toml"
short_refusal scene_missing "scene: .* not found" --scene "$TMP/missing.toml"
short_refusal scene_dispatch_dir "scene: .* is a directory" --scene "$TMP"

# Defaults consistent across commands: basin, like scan, defaults --v-range to the trapping
# region [4, 4(1+3eps)/(1-eps)] (eps = 1/2: exactly 20); elastic has none and needs it.
v_range=$("$BOUNCER" basin "${M[@]}" --grid 4x4 --transient 10 --steps 16 --json --quiet | python3 -c 'import json,sys; print(json.load(sys.stdin)["summary"]["v_range"])')
[[ $v_range == "['4', '20']" ]] || fail basin_v_range "default v range $v_range, expected ['4', '20']"
short_refusal basin_elastic "v-range: is needed for --model elastic" basin --model elastic --a 24 --grid 4x4

# Proof programs parse their options with CLI11: --bits abc used to run at 16 bits.
PROOF="$(dirname "$BOUNCER")/../proofs/proof_veldep_collapse"
if [[ -x $PROOF ]]; then
  for bad in abc 5; do
    rc=0; "$PROOF" --bits "$bad" >/dev/null 2>"$TMP/proof.err" || rc=$?
    [[ $rc -eq 2 ]] && grep -q -- '--bits' "$TMP/proof.err" || fail "proof_bits_$bad" "exit $rc: $(head -c 200 "$TMP/proof.err")"
  done
else
  fail proof_bits "no proof program at $PROOF"
fi

finish "input edges: all checks passed"
