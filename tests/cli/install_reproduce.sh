#!/usr/bin/env bash
# An install that stands alone (issue 24): `cmake --install` into a temporary prefix, then the
# installed bouncer, run from a directory with no checkout and no build tree in reach,
#   * finds its proof programs in PREFIX/libexec/bouncer (relative to its own binary, never
#     through PATH): `reproduce --check` refuses none of the manifest's commands;
#   * reproduces the claims: `reproduce --quick --only SUBSET` with every claim a proof
#     program settles (all seven), two claims and a panel of bouncer's own commands (the
#     manifest's --scene commands, the documentation pictures', are validated by --check). The
#     subset, not the whole --quick run, keeps this test short (measured in
#     docs/guide/install.md; the whole run takes minutes: tools/setup run does it);
#   * prints rerun commands that work from the install (PREFIX/libexec/bouncer/proof_NAME,
#     no checkout-relative build/proofs/, a built-in scene by name, not data/scenes/NAME.toml),
#     and they do run;
#   * reads scenes by name (--scene bifurcation-eps096, --scene default), by the
#     checkout's path (data/scenes/NAME.toml) and by the installed file's path.
# Usage: bash install_reproduce.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require jq
build=$(cd "$(dirname "$BOUNCER")/.." && pwd)
cmake --install "$build" --prefix "$TMP/p" >/dev/null
P="$TMP/p/bin/bouncer"
[[ -x $P ]] || die "cmake --install put no bin/bouncer"

# Every proof program of proofs/ is installed, executable, in libexec/bouncer.
for src in "$SRC"/proofs/*.cpp; do
  name=proof_$(basename "$src" .cpp)
  [[ -x $TMP/p/libexec/bouncer/$name ]] || fail proofs "$name is not in PREFIX/libexec/bouncer"
done
for f in share/bouncer/paper/manifest.toml share/bouncer/scenes/default.toml lib/pkgconfig/bouncer.pc; do
  [[ -f $TMP/p/$f ]] || fail files "cmake --install did not install $f"
done

# Away from the checkout: an empty directory, and a PATH with nothing of bouncer's on it.
mkdir "$TMP/elsewhere"
cd "$TMP/elsewhere"
export PATH=/usr/bin:/bin

# --check: every command of the manifest validates, the proof programs found.
"$P" reproduce --check > check.txt 2> check.err || fail check "exit $?: $(grep -v ': ok' check.txt | head -n 5)"
grep -q ' 0 refused$' check.txt || fail check "$(tail -n 1 check.txt)"
grep -q 'proof binary found' check.txt || fail check "no proof program was checked"

# --quick: every proof program's claim, two claims and a panel of bouncer's own commands.
proof_claims=$(python3 -c '
import sys, tomllib
m = tomllib.load(open(sys.argv[1], "rb"))
print(",".join(c["id"] for c in m["claim"] if c["run"][0].startswith("proof_")))' "$SRC/data/paper/manifest.toml")
[[ $(tr ',' '\n' <<<"$proof_claims" | wc -l) -ge 7 ]] || die "the manifest lists only '$proof_claims' as proof claims"
only="$proof_claims,sticking-thresholds,basin-fixed-points,fig:sticking"
if "$P" reproduce --quick --only "$only" --out "$TMP/r" > run.out 2> run.err; then :; else
  fail quick "exit $?: $(tail -n 5 run.err)"
fi
n=$(tr ',' '\n' <<<"$only" | grep -vc '^fig:')
jq_is quick-claims '[.claims[] | select(.status == "reproduced")] | length' "$n" "$TMP/r/claims.json"
jq_is quick-panels '[.panels[] | select(.status != "done")] | length' 0 "$TMP/r/claims.json"
grep -q "$n of $n claims reproduced" run.err || fail quick "summary: $(grep 'claims reproduced' run.err)"

# The reports name the installed proof programs, never the checkout's build/proofs/.
grep -l 'build/proofs' "$TMP/r/report.md" "$TMP/r/report.html" "$TMP/r/claims.json" &&
  fail rerun "a report names build/proofs/"
libexec=$(cd "$TMP/p/libexec/bouncer" && pwd -P)
grep -q "$libexec/proof_elastic_period2" "$TMP/r/report.md" || fail rerun "report.md does not name $libexec/proof_elastic_period2"
cmd=$(jq -r '.claims[] | select(.id == "elastic-period2") | .command' "$TMP/r/claims.json")
[[ $cmd == "$libexec/proof_elastic_period2 --json" ]] || fail rerun "elastic-period2's command is '$cmd'"
# shellcheck disable=SC2086  # the command's words
$cmd > cert.json || fail rerun "the printed command '$cmd' failed"
jq_is rerun-cert '.verdict' "$(jq -r .verdict "$TMP/r/claims/elastic-period2.json")" cert.json
jq_is rerun-claim '.claim' "$(jq -r .claim "$TMP/r/claims/elastic-period2.json")" cert.json

# The claims' rerun commands work from here too: a built-in scene by its name (never the
# checkout's data/scenes/ path), and the one that needs a build tree of the sources says so.
grep -l -- '--scene data/scenes/' "$TMP/r/report.md" "$TMP/r/report.html" "$TMP/r/claims.json" &&
  fail rerun "a report names a scene by the checkout's path"
rerun=$(jq -r '.claims[] | select(.id == "basin-fixed-points") | .rerun' "$TMP/r/claims.json")
[[ $rerun == *"--scene "* ]] || fail rerun "basin-fixed-points' rerun names no scene: $rerun"
words=$(sed 's/^`bouncer //; s/`.*$//' <<<"$rerun")
# shellcheck disable=SC2086  # the command's words
"$P" $words --quiet > /dev/null || fail rerun "the printed rerun '$rerun' failed from the install"
out=$(grep -o -- '--out [^ ]*' <<<"$words" | cut -d' ' -f2)
[[ -n $out && -s $out.csv ]] || fail rerun "the printed rerun '$rerun' wrote no $out.csv"
rerun=$(jq -r '.claims[] | select(.id == "sticking-thresholds") | .rerun' "$TMP/r/claims.json")
[[ $rerun == *'`ctest --test-dir build '*'` (in a build tree of the sources)'* ]] ||
  fail rerun "sticking-thresholds' ctest rerun does not say it needs a build tree: $rerun"

# Scenes by name, by the checkout's path and by the installed path; a name that is no scene
# is still "not found" for the option.
"$P" --scene default --steps 2 > by-name.txt || fail scene "--scene default: exit $?"
"$P" orbit --scene data/scenes/default.toml --steps 2 > by-path.txt || fail scene "--scene data/scenes/default.toml: exit $?"
"$P" orbit --scene "$TMP/p/share/bouncer/scenes/default.toml" --steps 2 > installed.txt ||
  fail scene "the installed scene file: exit $?"
cmp -s <(data by-name.txt) <(data by-path.txt) || fail scene "by name and by path differ"
cmp -s <(data by-name.txt) <(data installed.txt) || fail scene "built in and installed differ"
"$P" bifurcation --scene bifurcation-eps096 --samples 5 --transient 10 --record 5 --out bif --quiet ||
  fail scene "--scene bifurcation-eps096: exit $?"
[[ -s bif.csv ]] || fail scene "--scene bifurcation-eps096 wrote no bif.csv"
BOUNCER=$P refused scene-missing "scene.*no-such-scene" orbit --scene no-such-scene
finish
