#!/usr/bin/env bash
# End-to-end: files from strangers (docs/guide/security.md). audit and reproduce run only what
# bouncer itself would run, and write only where they own the place:
#   * the issue's reproducer: a two-line CSV naming command=reproduce and a manifest is
#     refused (exit 2, one line); nothing is run, no ./reproduction appears, the file the
#     manifest's --out named is untouched;
#   * a result recording merge, audit, or an input no result records (tiles-from, scene,
#     manifest, shard), or inputs bouncer refuses (a = -1), is refused with exit 2 before
#     any process starts;
#   * a claims.json made from another manifest is refused without --trust-manifest; with it,
#     a manifest command that names --out is still refused and nothing outside is written;
#   * a manifest whose ids hold "../", whose commands run reproduce or audit or choose
#     --out, or whose scenes are files, is refused (exit 2) by reproduce and by --check,
#     writing nothing; reproduce refuses to run inside reproduce;
#   * a crafted claims.json naming "../../x" as an output: reported as a difference, the
#     outside file never read;
#   * SIGKILL of reproduce or of audit leaves no child running (PR_SET_PDEATHSIG).
# Usage: bash trust_boundary.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
cd "$TMP"
VERSION=$("$BOUNCER" --version | awk '{print $2}')

claim() {  # claim ID RUN-ARRAY: one [[claim]] table
  cat <<EOF
[[claim]]
id = "$1"
row = "1"
text = "t"
paper = "p"
expected = "confirmed"
verdict = "v"
evidence = "e"
rerun = "r"
run = $2
checks = [["a", "==", 1]]
EOF
}

echo precious >victim
claim x '["bouncer", "orbit", "--model", "constant", "--a", "24", "--eps", "0.5", "--theta", "0.3", "--v", "12", "--out", "'"$TMP"'/victim"]' >evil.toml

# --- The issue's reproducer ---------------------------------------------------------------
printf '# bouncer 0.1.0 (commit x) reproduce\n# inputs: manifest=%s/evil.toml out=x\n' "$TMP" >r.csv
refused audit_reproduce_csv "records the command 'reproduce', which audit does not rerun" audit r.csv
[[ $(cat victim) == precious && ! -e reproduction && ! -e x ]] || fail audit_reproduce_csv "something was written: $(ls)"

# --- Results that record what bouncer never records ---------------------------------------
result() {  # result FILE COMMAND INPUTS: a CSV result header as bouncer writes one
  printf '# bouncer %s (commit x) %s\n# inputs: %s\nn,theta,v\n' "$VERSION" "$2" "$3" >"$1"
}
result merge.csv merge "prefix=p"
refused audit_merge "records the command 'merge'" audit merge.csv
result audit.csv audit "file=x"
refused audit_audit "records the command 'audit'" audit audit.csv
for key in tiles-from scene manifest shard keep-tiles; do
  result "$key.csv" orbit "model=constant a=24 eps=0.5 theta=0.3 v=12 $key=$TMP/victim"
  refused "audit_$key" "records the input '$key', which no bouncer result records" audit "$key.csv"
done
result bad.csv orbit "model=constant a=-1 eps=0.5 theta=0.3 v=12"
refused audit_bad_inputs "records inputs that bouncer refuses: a: " audit bad.csv
printf '{"provenance": {"command": "orbit", "inputs": {"model": "constant", "../out": "x"}}}\n' >key.json
refused audit_bad_key "records the input '../out'" audit key.json
printf '{"reproduce": {"mode": "quick"}, "claims": [1, "x", {"id": 7}]}\n' >mangled.json
mkdir mangled && cp mangled.json mangled/claims.json
refused audit_mangled "is not the claims.json of bouncer reproduce (an entry of 'claims' without a string 'id')" audit mangled
[[ $(cat victim) == precious ]] || fail results "the victim file changed"

# --- A reproduce directory from another manifest -------------------------------------------
mkdir foreign
printf '{"reproduce": {"mode": "quick", "manifest": "%s/evil.toml", "build": "x"}, "claims": []}\n' "$TMP" >foreign/claims.json
refused audit_foreign_manifest "not bouncer's built-in one; audit runs another manifest's commands only when told to (--trust-manifest" \
  audit foreign
rc=0; "$BOUNCER" audit --trust-manifest foreign >trusted.out 2>trusted.err || rc=$?
[[ $rc -eq 1 ]] && grep -q "the rerun of reproduce failed (exit status 2)" trusted.err || fail trusted "exit $rc: $(cat trusted.out trusted.err)"
[[ $(cat victim) == precious && ! -e reproduction ]] || fail trusted "something was written: $(ls)"

# --- Manifests that ask for too much --------------------------------------------------------
manifest_refused() {  # manifest_refused NAME PATTERN: the manifest NAME.toml, by reproduce and by --check
  refused "$1_run" "$2" reproduce --manifest "$1.toml" --out "$1.dir"
  refused "$1_check" "$2" reproduce --check --manifest "$1.toml"
  [[ ! -e "$1.dir" && $(cat victim) == precious ]] || fail "$1" "something was written"
}
cp evil.toml out.toml
manifest_refused out "claim x: command gives --out: reproduce chooses where each command writes"
claim "../escape" '["proof_elastic_period2"]' >escape.toml
manifest_refused escape "claim ../escape: an id must be a safe file name"
claim self '["bouncer", "reproduce", "--manifest", "'"$TMP"'/self.toml"]' >self.toml
manifest_refused self "command runs 'reproduce': a manifest runs only"
claim aud '["bouncer", "audit", "r.csv"]' >aud.toml
manifest_refused aud "command runs 'audit'"
claim scene '["bouncer", "orbit", "--scene", "'"$TMP"'/s.toml"]' >scene.toml
manifest_refused scene "is not a scene of data/scenes/ (built in)"
claim proof '["proof_elastic_period2", "--out", "x"]' >proof.toml
manifest_refused proof "a proof program takes only --full, --json and --bits N"
rc=0; BOUNCER_IN_REPRODUCE=1 "$BOUNCER" reproduce --only elastic-period2 --out nested >/dev/null 2>nested.err || rc=$?
[[ $rc -eq 2 && ! -e nested ]] && grep -q "runs no reproduce inside another" nested.err || fail nested "exit $rc: $(cat nested.err)"
python3 -c "print('schema = 1\n' + '.'.join(['k'] * 40000) + ' = 1')" >deep.toml
manifest_refused deep "nested more than 32 deep"

# --- A crafted claims.json: its file names stay inside the directory -------------------------
mkdir crafted
cat >crafted/claims.json <<EOF
{"reproduce": {"mode": "quick", "only": ["elastic-period2"], "manifest": "data/paper/manifest.toml (built in)", "build": "x"},
 "claims": [{"id": "elastic-period2", "status": "reproduced", "verdict": "v", "checks": [], "output": "../../../../../../etc/passwd"}],
 "panels": [{"label": "fig:x", "status": "done", "files": ["panels/../../victim.csv"]}]}
EOF
rc=0; "$BOUNCER" audit crafted >crafted.out 2>crafted.err || rc=$?
[[ $rc -eq 1 ]] || fail crafted "exit $rc, expected 1: $(cat crafted.out crafted.err)"
grep -q "'../../../../../../etc/passwd': not a file of a reproduce directory" crafted.out || fail crafted "the path is not named: $(cat crafted.out)"
grep -q "root:" crafted.out && fail crafted "the outside file was read into the report"

# --- SIGKILL leaves no child running ---------------------------------------------------------
children_of() { pgrep -P "$1" | tr '\n' ' ' || true; }
wait_children() {  # wait_children PID N: until PID has N children (at most 10 s)
  for _ in $(seq 100); do
    [[ $(wc -w <<<"$(children_of "$1")") -ge $2 ]] && return 0
    sleep 0.1
  done
  return 1
}
killed() {  # killed NAME N COMMAND...: start it, wait for N children, SIGKILL it: every child ends within 5 s
  local name=$1 n=$2 pid kids p
  shift 2
  "$BOUNCER" "$@" >/dev/null 2>&1 &
  pid=$!
  wait_children "$pid" "$n" || fail "$name" "it did not start its $n children"
  kids=$(children_of "$pid")
  kill -KILL "$pid"
  wait "$pid" 2>/dev/null || true
  for p in $kids; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    if kill -0 "$p" 2>/dev/null; then
      fail "$name" "child $p still running after its parent was killed"
      kill -KILL "$p" 2>/dev/null || true
    fi
  done
}
killed kill_reproduce 2 reproduce --manifest "$SRC/tests/data/reproduce-slow-manifest.toml" --jobs 2 --out killed
result long.csv orbit "model=constant a=20 eps=0.5 theta=0.1 v=5 steps=2000000000 every=1000000000"
# A killed audit cannot remove its private directory (SIGKILL runs no clean-up): it is made
# under TMPDIR, here the test's own directory, so that nothing is left in /tmp.
mkdir -p "$TMP/audit-tmp"
TMPDIR="$TMP/audit-tmp" killed kill_audit 1 audit long.csv
compgen -G "$TMP/audit-tmp/bouncer-audit-*" > /dev/null || fail kill_audit "the audit's private directory was not under TMPDIR"

finish "trust boundary: all checks passed"
