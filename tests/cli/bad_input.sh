#!/usr/bin/env bash
# End-to-end: every kind of bad input to `bouncer orbit` (command line and scene file) must
#   - exit with status 2,
#   - print exactly one line on stderr, "bouncer: OPTION: ..." naming the option and what is
#     allowed (the range, the list of choices, or what is wrong with the scene),
#   - print nothing on stdout and leave no output file (nor a *.partial) behind.
# Usage: bash bad_input.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"

cases=0

# bad NAME LINE_REGEX ARGS... : run `bouncer ARGS... --out TMP/o/out.csv`, expect rejection.
# LINE_REGEX (grep -E) must match the single stderr line; it names the option and the range.
bad() {
  local name=$1 regex=$2
  shift 2
  cases=$((cases + 1))
  rm -rf "$TMP/o"
  mkdir "$TMP/o"
  refused -E "$name" "$regex" "$@" --out "$TMP/o/out.csv"
  empty_dir "$name" "$TMP/o"
}

M=(orbit --model constant --a 24 --eps 0.5)  # a valid model
IC=(--theta 0.25 --v 12)                      # a valid initial condition

# Sanity: the valid baseline runs and writes its file (else every case below is meaningless).
rc=0
"$BOUNCER" "${M[@]}" "${IC[@]}" --steps 1 --out "$TMP/ok.csv" >"$TMP/stdout" 2>"$TMP/stderr" || rc=$?
if [[ $rc -ne 0 || ! -s $TMP/ok.csv ]]; then
  die "baseline: the valid command failed (status $rc): $(cat "$TMP/stderr")"
fi

# --- gravity a > 0 (and <= 1e9)
bad "a=0" '^bouncer: a: .*> 0' orbit --model constant --a 0 --eps 0.5 "${IC[@]}"
bad "a=-1" '^bouncer: a: .*> 0' orbit --model constant --a -1 --eps 0.5 "${IC[@]}"
bad "a=1e10" '^bouncer: a: .*<= 1e9' orbit --model constant --a 1e10 --eps 0.5 "${IC[@]}"
# --- eps in [0, 1], decided exactly on the decimal
bad "eps=1.5" '^bouncer: eps: .*\[0, 1\]' orbit --model constant --a 24 --eps 1.5 "${IC[@]}"
bad "eps=-0.1" '^bouncer: eps: .*\[0, 1\]' orbit --model constant --a 24 --eps -0.1 "${IC[@]}"
bad "eps=1+1e-25" '^bouncer: eps: .*\[0, 1\]' orbit --model constant --a 24 --eps 1.0000000000000000000000001 "${IC[@]}"
bad "eps with elastic" '^bouncer: eps: .*constant' orbit --model elastic --a 24 --eps 0.5 "${IC[@]}"
# --- c > 0
bad "c=0" '^bouncer: c: .*> 0' orbit --model veldep --a 24 --c 0 "${IC[@]}"
bad "c=-2" '^bouncer: c: .*> 0' orbit --model veldep --a 24 --c -2 "${IC[@]}"
# --- NaN and infinities in every decimal option
for x in nan NaN inf -inf Infinity 1e999999999; do
  bad "a=$x" '^bouncer: a: .*finite' orbit --model constant --a="$x" --eps 0.5 "${IC[@]}"
  bad "eps=$x" '^bouncer: eps: .*finite' orbit --model constant --a 24 --eps="$x" "${IC[@]}"
  bad "c=$x" '^bouncer: c: .*finite' orbit --model veldep --a 24 --c="$x" "${IC[@]}"
  bad "theta=$x" '^bouncer: theta: .*finite' "${M[@]}" --theta="$x" --v 12
  bad "v=$x" '^bouncer: v: .*finite' "${M[@]}" --theta 0.25 --v="$x"
  bad "wall=asymmetric:$x" '^bouncer: wall: .*finite' "${M[@]}" "${IC[@]}" --wall "asymmetric:$x"
done
# --- theta in [0, 1)
bad "theta=1" '^bouncer: theta: .*\[0, 1\)' "${M[@]}" --theta 1 --v 12
bad "theta=-0.1" '^bouncer: theta: .*\[0, 1\)' "${M[@]}" --theta=-0.1 --v 12
bad "theta list" '^bouncer: theta: .*\[0, 1\)' "${M[@]}" --theta 0.25,1.5 --v 12,12
# --- v at least the wall velocity at theta (u = +4 on [0,1/2), -4 on [1/2,1)), and <= 1e15
bad "theta=0.25 v=3.9" '^bouncer: v: .*>= the wall velocity 4' "${M[@]}" --theta 0.25 --v 3.9
bad "theta=0.5 v=-4.1" '^bouncer: v: .*>= the wall velocity -4' "${M[@]}" --theta 0.5 --v=-4.1
bad "theta=0 v=3.99" '^bouncer: v: .*>= the wall velocity 4' "${M[@]}" --theta 0 --v 3.99
bad "v=1e16" '^bouncer: v: .*<= 1e15' "${M[@]}" --theta 0.25 --v 1e16
bad "theta/v lengths" '^bouncer: v: .*as many values as theta' "${M[@]}" --theta 0.25,0.1 --v 12
# --- unknown choices
bad "model=foo" '^bouncer: model: .*allowed: elastic, constant, veldep' orbit --model foo --a 24 "${IC[@]}"
bad "wall=foo" '^bouncer: wall: .*allowed: triangle' "${M[@]}" "${IC[@]}" --wall foo
bad "wall=asymmetric:1.5" '^bouncer: wall: .*0 < R < 1' "${M[@]}" "${IC[@]}" --wall asymmetric:1.5
bad "downward-sticking=foo" '^bouncer: downward-sticking: .*allowed: paper, impact' "${M[@]}" "${IC[@]}" --downward-sticking foo
bad "precision=float" '^bouncer: precision: .*16 <= BITS <= 1048576' "${M[@]}" "${IC[@]}" --precision float
bad "format=xml" '^bouncer: format: .*allowed: csv, json, table' "${M[@]}" "${IC[@]}" --format xml
# --- bits outside [16, 1048576] or not a whole number
for p in mpfr:8 mpfr:15 interval:0 interval:15 mpfr:99999999 interval:1048577 mpfr:abc mpfr: mpfr:-20 mpfr:1e3 mpfr:64.5; do
  bad "precision=$p" '^bouncer: precision: .*16 <= BITS <= 1048576' "${M[@]}" "${IC[@]}" --precision "$p"
done
# --- integers: steps >= 0, every >= 1
bad "steps=-1" '^bouncer: steps: .*integer in \[0, ' "${M[@]}" "${IC[@]}" --steps=-1
bad "steps=1.5" '^bouncer: steps: .*integer in \[0, ' "${M[@]}" "${IC[@]}" --steps 1.5
bad "steps=nan" '^bouncer: steps: .*integer in \[0, ' "${M[@]}" "${IC[@]}" --steps nan
bad "every=0" '^bouncer: every: .*integer in \[1, ' "${M[@]}" "${IC[@]}" --every 0
bad "every=-3" '^bouncer: every: .*integer in \[1, ' "${M[@]}" "${IC[@]}" --every=-3
# --- missing required options
bad "missing model" '^bouncer: model: .*required' orbit --a 24 --eps 0.5 "${IC[@]}"
bad "missing a" '^bouncer: a: .*required' orbit --model constant --eps 0.5 "${IC[@]}"
bad "missing eps" '^bouncer: eps: .*required' orbit --model constant --a 24 "${IC[@]}"
bad "missing c" '^bouncer: c: .*required' orbit --model veldep --a 24 "${IC[@]}"
bad "missing theta" '^bouncer: theta: .*required' "${M[@]}" --v 12
bad "missing v" '^bouncer: v: .*required' "${M[@]}" --theta 0.25
# --- unknown command-line option (CLI11 parse error, also status 2)
bad "unknown option" '^bouncer: .*--bogus' "${M[@]}" "${IC[@]}" --bogus 3

# --- malformed scene files
S=$TMP/scenes
mkdir -p "$S"
good_scene() {
  cat <<'TOML'
command = "orbit"
model = "constant"
a = "24"
eps = "0.5"
theta = "0.25"
v = "12"
steps = 2
TOML
}
good_scene >"$S/good.toml"
rc=0
"$BOUNCER" orbit --scene "$S/good.toml" >/dev/null 2>"$TMP/stderr" || rc=$?
[[ $rc -eq 0 ]] || fail "good scene" "the valid scene was rejected (status $rc): $(cat "$TMP/stderr")"

{ good_scene; echo 'steps = [3'; } >"$S/syntax.toml"
bad "scene: bad TOML syntax" '^bouncer: scene: .*syntax\.toml.*line [0-9]+' orbit --scene "$S/syntax.toml"
{ good_scene; echo 'a = = "3"'; } >"$S/syntax2.toml"
bad "scene: bad TOML syntax 2" '^bouncer: scene: .*syntax2\.toml.*line [0-9]+' orbit --scene "$S/syntax2.toml"
{ good_scene; echo 'foo = "1"'; } >"$S/unknown.toml"
bad "scene: unknown key" "^bouncer: scene: .*unknown key 'foo'" orbit --scene "$S/unknown.toml"
{ good_scene; printf '[extra]\nx = 1\n'; } >"$S/table.toml"
bad "scene: unknown table" "^bouncer: scene: .*unknown key 'extra'" orbit --scene "$S/table.toml"
good_scene | sed 's/^a = "24"$/a = 28.82/' >"$S/float.toml"
grep -q '^a = 28.82$' "$S/float.toml" || fail "setup" "float.toml not written as intended"
bad "scene: TOML float a = 28.82" '^bouncer: a: .*string' orbit --scene "$S/float.toml"
good_scene | sed 's/^eps = "0.5"$/eps = 0.5/' >"$S/float-eps.toml"
bad "scene: TOML float eps = 0.5" '^bouncer: eps: .*string' orbit --scene "$S/float-eps.toml"
good_scene | sed 's/^a = "24"$/a = inf/' >"$S/float-inf.toml"
bad "scene: TOML float a = inf" '^bouncer: a: .*string' orbit --scene "$S/float-inf.toml"
good_scene | sed 's/^a = "24"$/a = nan/' >"$S/float-nan.toml"
bad "scene: TOML float a = nan" '^bouncer: a: .*string' orbit --scene "$S/float-nan.toml"
good_scene | sed 's/^theta = "0.25"$/theta = [0.25]/' >"$S/float-list.toml"
bad "scene: TOML float in a list" '^bouncer: theta: .*string' orbit --scene "$S/float-list.toml"
good_scene | sed 's/^a = "24"$/a = "nan"/' >"$S/nan-string.toml"
bad "scene: a = \"nan\"" '^bouncer: a: .*finite' orbit --scene "$S/nan-string.toml"
good_scene | sed 's/^a = "24"$/a = "1e999999999"/' >"$S/huge-string.toml"
bad "scene: a = \"1e999999999\"" '^bouncer: a: .*finite' orbit --scene "$S/huge-string.toml"
good_scene | sed 's/^eps = "0.5"$/eps = "1.5"/' >"$S/eps-range.toml"
bad "scene: eps out of range" '^bouncer: eps: .*\[0, 1\]' orbit --scene "$S/eps-range.toml"
good_scene | sed 's/^a = "24"$/a = ["24", "25"]/' >"$S/list.toml"
bad "scene: list for a single value" '^bouncer: a: .*one value' orbit --scene "$S/list.toml"
good_scene | sed 's/^command = "orbit"$/command = "diagram"/' >"$S/command.toml"
bad "scene: wrong command" "^bouncer: scene: .*not 'orbit'" orbit --scene "$S/command.toml"
good_scene | sed 's/^steps = 2$/steps = -2/' >"$S/steps.toml"
bad "scene: steps < 0" '^bouncer: steps: .*integer in \[0, ' orbit --scene "$S/steps.toml"
good_scene | sed '/^model = /d' >"$S/nomodel.toml"
bad "scene: missing model" '^bouncer: model: .*required' orbit --scene "$S/nomodel.toml"
bad "scene: file does not exist" '^bouncer: scene: .*not found' orbit --scene "$S/does-not-exist.toml"

finish "bad_input.sh: all $cases bad-input cases rejected with status 2, one line, no output file"
