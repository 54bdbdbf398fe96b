#!/usr/bin/env bash
# End-to-end: `bouncer audit` supports every kind of result bouncer writes, or refuses it up
# front with exit 2 and what to do instead.
#   * every command's text/CSV and JSON outputs, on stdout or as PREFIX.csv / PREFIX.json,
#     reproduce (exit 0), and a one-digit edit of a number in each is found (exit 1): a
#     basin JSON used to give a false DIFFERENT (rerun without --out), and the JSON of
#     periodic, lyapunov and classify could not be audited at all (rerun without --json);
#   * a PNG and a proof certificate are refused with exit 2, naming what to audit instead.
# Usage: bash audit_kinds.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
cd "$TMP"

# audited_and_tampered FILE: exit 0 and IDENTICAL; then the same file with one digit of its
# last number-bearing data line changed must be DIFFERENT (exit 1).
audited_and_tampered() {
  local f=$1 rc=0
  audited "$f" "$f"
  # Tamper: change the last digit 1-8 on the last line (outside the provenance) that has one.
  local tampered="tampered-$f"
  awk '{ lines[NR] = $0 }
       END {
         for (i = NR; i >= 1 && !done; --i)
           if (lines[i] !~ /^#/ && lines[i] !~ /provenance|commit|version|invocation|seconds/)
             for (j = length(lines[i]); j >= 1; --j) {
               d = substr(lines[i], j, 1)
               if (d ~ /[1-8]/ && substr(lines[i], j - 1, 1) ~ /[0-9.]/) {
                 lines[i] = substr(lines[i], 1, j - 1) (d + 1) substr(lines[i], j + 1)
                 done = 1
                 break
               }
             }
         for (i = 1; i <= NR; ++i) print lines[i]
       }' "$f" >"$tampered"
  if cmp -s "$f" "$tampered"; then fail "$f" "found no digit to change"; return; fi
  "$BOUNCER" audit "$tampered" >"$tampered.audit" 2>&1 || rc=$?
  [[ $rc -eq 1 ]] && grep -q "DIFFERENT" "$tampered.audit" ||
    fail "$f" "a changed digit was not found (exit $rc): $(tail -c 300 "$tampered.audit")"
}

S=(--model constant --eps 0.8 --a 24 --theta 0.1 --v 10)
"$BOUNCER" orbit "${S[@]}" --steps 10 >orbit.csv
"$BOUNCER" orbit "${S[@]}" --steps 10 --format json >orbit.json
"$BOUNCER" certify-sticking --eps 0.5 --a 24 >sticking.txt
"$BOUNCER" certify-sticking --eps 0.5 --a 24 --json >sticking.json
"$BOUNCER" certify-periodic --model elastic --a 24 --period 1 --json >cperiodic.json
"$BOUNCER" periodic --model elastic --a 24 --period 1 >periodic.txt
"$BOUNCER" periodic --model elastic --a 24 --period 1 --json >periodic.json
"$BOUNCER" lyapunov "${S[@]}" --steps 2000 --json >lyapunov.json
"$BOUNCER" classify "${S[@]}" --json >classify.json
"$BOUNCER" sweep "${S[@]}" --steps 10 --json >sweep.json
"$BOUNCER" basin --model constant --eps 0.5 --a 24 --grid 16x12 --out basin --quiet --format png,pdf,svg
"$BOUNCER" bifurcation --model constant --eps 0.5 --range 20:24 --samples 8 --transient 100 --record 20 --theta 0.1 --v 10 --out bif --quiet
"$BOUNCER" scan --model constant --a-range 20:24 --eps-range 0.4:0.6 --grid 6x4 --out scan --quiet
"$BOUNCER" lyapunov --model constant --eps 0.5 --vary a --range 20:24 --samples 4 --steps 300 --transient 50 --out curve --quiet
"$BOUNCER" trajectory --model constant --eps 0.5 --a 24 --theta 0.5 --v 4 --periods 4 --samples 40 --out traj
"$BOUNCER" tongues --p-max 3 --samples 20 --out tongues
for f in traj.json traj.csv tongues.json tongues.csv orbit.csv orbit.json sticking.txt sticking.json cperiodic.json periodic.txt periodic.json lyapunov.json \
  classify.json sweep.json basin.json basin.csv bif.json scan.json curve.csv; do
  audited_and_tampered "$f"
done

# Refused up front: exit 2, one line naming what to audit or rerun instead.
for pic in basin.png basin.pdf basin.svg; do refused "$pic" "audit the PREFIX.json or PREFIX.csv" audit "$pic"; done
printf '{"proof": "elastic_period2", "claim": "eq. (33)", "verdict": "proved"}\n' >certificate.json
refused certificate.json "proof_elastic_period2 --json" audit certificate.json

finish "audit_kinds: every result kind reproduces and a changed digit is found; pictures and certificates refused"
