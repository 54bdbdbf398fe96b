#!/usr/bin/env bash
# Runs examples/library/grids.cpp in a temporary directory and checks what it wrote: the row
# counts of its three CSVs, valid class names, and that its basin is, row for row, the
# command line's `bouncer basin` of the same request (the library and the CLI are one code).
set -euo pipefail
example=$1 bouncer=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
"$example"
fail=0
check() { if ! eval "$2"; then echo "example.library_grids: $1" >&2; fail=1; fi; }
check "basin.csv has 40 x 30 rows" '[ "$(wc -l < basin.csv)" -eq 1200 ]'
check "scan.csv has 12 x 8 rows" '[ "$(wc -l < scan.csv)" -eq 96 ]'
check "certified.csv has 6 x 6 rows" '[ "$(wc -l < certified.csv)" -eq 36 ]'
check "basin classes are class names" \
  '! cut -d, -f3 basin.csv | grep -vqxE "fixed|periodic|sticking|quasiperiodic|chaotic|unbounded|effective_sticking|undecided|transient_chaos|outside"'
check "certified classes are certified class names" \
  '! cut -d, -f3 certified.csv | grep -vqxE "sticking|fixed|periodic|no_sticking|not_trapped|undecided|outside"'
check "scan counts are whole numbers in [0, 16]" '! cut -d, -f3 scan.csv | awk "\$1 !~ /^[0-9]+$/ || \$1 > 16" | grep -q .'
"$bouncer" basin --model constant --a 24 --eps 0.5 --grid 40x30 --quiet | grep -v '^#' | tail -n +2 | cut -d, -f1-3 > cli.csv
check "the library's basin is the CLI's, row for row" 'cmp -s basin.csv cli.csv'
[ "$fail" -eq 0 ] && echo "example.library_grids: all checks passed"
exit "$fail"
