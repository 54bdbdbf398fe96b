#!/usr/bin/env bash
# End-to-end: scenes.
#   - data/scenes/default.toml runs: two orbits, as many steps as the scene says, table format,
#     the scene's exact decimals in the provenance, orbit 0 at the fixed point (0.25, 12);
#   - command-line options override scene values (--steps 3 -> rows 0..3; --format; a list
#     --theta/--v replaces the scene's list; a bad scene value overridden by a good one is fine);
#   - a scene with theta/v lists runs several orbits (orbit column), each starting at its IC;
#   - scene keys every/out work like the options;
#   - every orbit scene in data/scenes/ runs (the eps = 0.96 scene prints n = 0, 100, ..., 2000);
#   - a scene name with a typo is refused with "did you mean NAME?" naming the built-in scene.
# Usage: bash orbit_scene.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
SCENES=$SRC/data/scenes
DEFAULT=$SCENES/default.toml
[[ -f $DEFAULT ]] || die "no default scene at $DEFAULT"

out() { data "$TMP/$1.out"; }  # header + rows of the output of `run NAME`
# (pipelines here always read their input to the end: with pipefail, `| head` or `| grep -q`
# could fail the pipeline through SIGPIPE)

# ---- the default scene as docs/guide/install.md runs it
if run default orbit --scene "$DEFAULT"; then
  steps=$(sed -n 's/^steps *= *\([0-9][0-9]*\).*/\1/p' "$DEFAULT")
  [[ -n $steps ]] || fail default "cannot read 'steps' from $DEFAULT"
  for o in 0 1; do
    grep -q "^# end: orbit $o completed $steps steps$" "$TMP/default.out" ||
      fail default "no '# end: orbit $o completed $steps steps' line"
  done
  grep -q '^# inputs: .*\ba=24\b.*\beps=0\.5\b.*\bmodel=constant\b' "$TMP/default.out" ||
    fail default "the provenance does not record the scene's a=24 eps=0.5 model=constant"
  read -r -a hdr < <(out default | awk 'NR == 1')
  [[ ${hdr[0]} == n && ${hdr[1]} == theta && ${hdr[2]} == v ]] ||
    fail default "the table header starts '${hdr[*]:0:3}'"
  # orbit 0 rows: the fixed point (0.25, 12); rows number steps+1 per orbit
  nrows=$(out default | tail -n +2 | wc -l)
  [[ $nrows -eq $((2 * (steps + 1))) ]] || fail default "$nrows rows, expected $((2 * (steps + 1)))"
  off=$(out default | awk -v last=$((steps + 2)) 'NR >= 2 && NR <= last { d = $2 - 0.25; e = $3 - 12; if (d*d > 1e-24 || e*e > 1e-24) print }')
  [[ -z $off ]] || fail default "orbit 0 left the fixed point (0.25, 12): $off"
fi

# ---- command line overrides the scene
if run override orbit --scene "$DEFAULT" --steps 3 --format csv; then
  got=$(out override | tail -n +2 | awk -F, '{ printf "%s:%s ", $NF, $1 }')
  [[ $got == "0:0 0:1 0:2 0:3 1:0 1:1 1:2 1:3 " ]] || fail override "--steps 3: rows (orbit:n) are $got"
  [[ $(out override | awk 'NR == 1') == n,theta,v,* ]] || fail override "--format csv did not override the scene's table"
  grep -q '^# inputs: .*\bsteps=3\b' "$TMP/override.out" || fail override "the provenance does not record steps=3"
fi
if run override_ic orbit --scene "$DEFAULT" --theta 0.3 --v 12 --steps 4 --format csv; then
  # one orbit now; (0.3, 12) is also on the fixed-point family theta* in (0, 1/2), v* = 12
  orbits=$(out override_ic | tail -n +2 | cut -d, -f15 | sort -u | tr '\n' ' ')
  [[ $orbits == "0 " ]] || fail override_ic "--theta/--v should replace the scene's lists: orbits $orbits"
  off=$(out override_ic | tail -n +2 | awk -F, '{ d = $2 - 0.3; e = $3 - 12; if (d*d > 1e-24 || e*e > 1e-24) print }')
  [[ -z $off ]] || fail override_ic "(0.3, 12) is a fixed point at eps = 0.5, a = 24 but moved: $off"
fi
sed 's/^eps = .*/eps = "1.5"/' "$DEFAULT" >"$TMP/bad-eps.toml"
grep -q '^eps = "1.5"$' "$TMP/bad-eps.toml" || fail setup "could not write a scene with eps = 1.5"
rc=0
"$BOUNCER" orbit --scene "$TMP/bad-eps.toml" --steps 1 >/dev/null 2>&1 || rc=$?
[[ $rc -eq 2 ]] || fail override_bad "a scene with eps = 1.5 must be rejected (status $rc)"
run override_bad orbit --scene "$TMP/bad-eps.toml" --eps 0.5 --steps 1 ||
  fail override_bad "--eps 0.5 on the command line should override the scene's bad eps"

# ---- a scene with theta/v lists: several orbits
cat >"$TMP/multi.toml" <<'TOML'
# three initial conditions, one of them on the downward segment
command = "orbit"
model = "constant"
a = "24"
eps = "0.5"
theta = ["0.25", "0.1", "0.75"]
v = ["12", "7.3", "-2"]
steps = 5
format = "csv"
TOML
if run multi orbit --scene "$TMP/multi.toml"; then
  got=$(out multi | tail -n +2 | awk -F, '$1 == 0 { printf "%s:%s:%s ", $NF, $2, $3 }')
  [[ $got == "0:0.25:12 1:0.1:7.3 2:0.75:-2 " ]] || fail multi "rows n=0 (orbit:theta:v) are $got"
  got=$(out multi | tail -n +2 | cut -d, -f15 | uniq -c | awk '{ printf "%s:%s ", $2, $1 }')
  [[ $got == "0:6 1:6 2:6 " ]] || fail multi "rows per orbit (orbit:count) are $got, expected 6 each"
  [[ $(grep -c '^# end: orbit [012] completed 5 steps$' "$TMP/multi.out") -eq 3 ]] || fail multi "not three '# end' lines"
fi

# ---- scene keys every / out
mkdir "$TMP/o"
{ grep -v -e '^steps' -e '^format' "$TMP/multi.toml"; echo 'steps = 10'; echo 'every = 4'; echo "out = \"$TMP/o/multi.csv\""; } >"$TMP/every-out.toml"
if run every_out orbit --scene "$TMP/every-out.toml"; then
  [[ ! -s $TMP/every_out.out ]] || fail every_out "with out in the scene, output went to stdout"
  if [[ -s $TMP/o/multi.csv ]]; then
    got=$(grep -v '^#' "$TMP/o/multi.csv" | tail -n +2 | awk -F, '$NF == 0 { printf "%s ", $1 }')
    [[ $got == "0 4 8 10 " ]] || fail every_out "every = 4 of 10 steps gave rows n = $got"
  else
    fail every_out "the scene's out file $TMP/o/multi.csv was not written"
  fi
  [[ $(ls -A "$TMP/o") == multi.csv ]] || fail every_out "left in the out directory: $(ls -A "$TMP/o")"
fi

# ---- every orbit scene in data/scenes/ runs (2 steps), and the scenes named by the task
for scene in "$SCENES"/*.toml; do
  grep -q '^command *= *"orbit"' "$scene" || continue
  name=$(basename "$scene" .toml)
  run "scene-$name" orbit --scene "$scene" --steps 2 || continue
  grep -q '^# end: orbit 0 completed 2 steps$' "$TMP/scene-$name.out" || fail "scene-$name" "did not complete 2 steps"
done
if [[ -f $SCENES/orbit-sticking-096.toml ]]; then
  if run sticking orbit --scene "$SCENES/orbit-sticking-096.toml"; then
    got=$(out sticking | tail -n +2 | cut -d, -f1 | tr '\n' ' ')
    [[ $got == "$(seq -s ' ' 0 100 2000) " ]] || fail sticking "rows n = $got, expected 0, 100, ..., 2000"
    [[ $(out sticking | awk 'NR == 2') == 0,0.5,4,start,* ]] || fail sticking "row 0 is not the release state (0.5, 4)"
    grep -q '^# inputs: .*\ba=28\.82\b.*\beps=0\.96\b' "$TMP/sticking.out" || fail sticking "inputs are not a=28.82 eps=0.96"
    below=$(out sticking | tail -n +2 | awk -F, '{ u = ($2 < 0.5) ? 4 : -4; if ($3 < u - 1e-9) print "n=" $1 " theta=" $2 " v=" $3 }')
    [[ -z $below ]] || fail sticking "states below the wall velocity: $below"
  fi
else
  fail sticking "data/scenes/orbit-sticking-096.toml is missing"
fi
if [[ -f $SCENES/orbit-elastic-fermi.toml ]]; then
  if run fermi orbit --scene "$SCENES/orbit-elastic-fermi.toml"; then
    grep -q '^# inputs: .*\ba=19\b.*\bmodel=elastic\b' "$TMP/fermi.out" || fail fermi "inputs are not a=19 model=elastic"
    grep -q '^# end: orbit 0 completed [0-9]* steps$' "$TMP/fermi.out" || fail fermi "did not complete: $(tail -n 1 "$TMP/fermi.out")"
    # every printed state is a post-impact state: v >= the wall velocity u(theta) (+4 on
    # [0, 1/2), -4 on [1/2, 1)), else the particle would be inside the wall
    below=$(out fermi | tail -n +2 | awk -F, '{ u = ($2 < 0.5) ? 4 : -4; if ($3 < u - 1e-9) print "n=" $1 " theta=" $2 " v=" $3 }')
    [[ -z $below ]] || fail fermi "states below the wall velocity: $below"
  fi
else
  fail fermi "data/scenes/orbit-elastic-fermi.toml is missing"
fi

# ---- a scene name with a typo: refused with the built-in scene it most likely means (issue
# 24), for every scene of data/scenes/ (one letter dropped from the middle of its name, as a
# name and as the checkout path), writing nothing
for scene in "$SCENES"/*.toml; do
  name=$(basename "$scene" .toml)
  name=${name#picture-}
  cmd=$(sed -n 's/^command *= *"\([a-z-]*\)".*/\1/p' "$scene")
  [[ -n $cmd ]] || cmd=orbit
  half=$((${#name} / 2))
  typo=${name:0:half}${name:half+1}
  refused "typo-$name" "'$typo' not found.*(did you mean $name?)" "$cmd" --scene "$typo" --out "$TMP/typo/o"
  refused "typo-path-$name" "(did you mean $name?)" "$cmd" --scene "data/scenes/$typo.toml" --out "$TMP/typo/o"
done
[[ ! -e $TMP/typo ]] || fail typo "a refused scene left output: $(ls -R "$TMP/typo")"
refused typo-far "'no-such-scene-at-all' not found$" orbit --scene no-such-scene-at-all

finish "orbit_scene.sh: scenes run, lists give several orbits, command line overrides, typos get a suggestion"
