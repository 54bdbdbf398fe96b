#!/usr/bin/env bash
# End-to-end: the picture commands (bifurcation, portrait, basin, scan, merge) on tiny grids.
#   - each writes PREFIX.csv, PREFIX.png (a real PNG) and PREFIX.json (valid JSON with the
#     provenance), and removes its PREFIX.tiles/ when done;
#   - results are identical at 1 and 2 threads (double and MPFR), across shards joined by
#     `bouncer merge` (shared prefix or one prefix per shard), and after resuming;
#   - rows agree with facts known without the program (row counts, the phase-space
#     boundary v >= wall velocity, K x K initial conditions per scan point);
#   - bad input exits 2 and leaves no file behind.
# Usage: bash picture_commands.sh <bouncer-binary> <source-dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3
run_quiet() { run "$@" --quiet; }  # run_quiet NAME ARGS...: `run` with --quiet

# picture_outputs NAME PREFIX: `outputs` (the three files, no tiles or partial files left),
# and a PNG signature, a JSON with provenance.
picture_outputs() {
  local name=$1 p=$2
  outputs "$name" "$p"
  if [[ -s $p.png ]] && [[ $(head -c 8 "$p.png" | od -An -tx1 | tr -d ' \n') != 89504e470d0a1a0a ]]; then
    fail "$name" "$p.png does not start with the PNG signature"
  fi
  python3 - "$p.json" "$p.png" <<'PY' || fail "$name" "JSON or PNG text chunks invalid"
import json, struct, sys, zlib
d = json.load(open(sys.argv[1]))
assert d["provenance"]["tool"] == "bouncer", d
assert "summary" in d
# The PNG carries the provenance in a tEXt/zTXt chunk.
data = open(sys.argv[2], "rb").read()
pos, keys = 8, set()
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind in (b"tEXt", b"zTXt"):
        keys.add(body.split(b"\0", 1)[0].decode())
    pos += 12 + n
assert "bouncer:provenance" in keys and "Software" in keys, keys
PY
}

# --- bifurcation --------------------------------------------------------------------------
B="bifurcation --model constant --eps 0.96 --vary a --range 28:29 --transient 100 --record 30 --theta 0.1 --v 5"
run_quiet bif1 $B --samples 8 --threads 1 --out "$TMP/bif1" && picture_outputs bif1 "$TMP/bif1"
run_quiet bif2 $B --samples 8 --threads 2 --out "$TMP/bif2" && picture_outputs bif2 "$TMP/bif2"
[[ $(rows "$TMP/bif1.csv" | wc -l) -eq 240 ]] || fail bif "expected 8 x 30 = 240 rows, got $(rows "$TMP/bif1.csv" | wc -l)"
cmp -s <(grep -v '^#' "$TMP/bif1.csv") <(grep -v '^#' "$TMP/bif2.csv") || fail bif "1 and 2 threads differ"
# The parameter column runs through 28 .. 29 in 8 equal steps, each value 30 times.
python3 - "$TMP/bif1.csv" <<'PY' || fail bif "parameter column or sticking rows wrong"
import sys
rows = [l.split(",") for l in open(sys.argv[1]) if not l.startswith("#")][1:]
vals = sorted(set(float(r[0]) for r in rows))
assert len(vals) == 8 and abs(vals[0] - 28) < 1e-12 and abs(vals[-1] - 29) < 1e-12, vals
for k, x in enumerate(vals):
    assert abs(x - (28 + k / 7)) < 1e-12, (k, x)
for r in rows:
    th, v, s = float(r[2]), float(r[3]), int(r[4])
    assert 0 <= th < 1
    if s == 1:
        assert th == 0.5 and v == 4.0, r  # a sticking step ends at the release state
PY
# The sweep's model at a = 29 (last value, exact) is the model `bouncer orbit` builds from
# the decimal: the recorded rows are the orbit's steps 101..130.
"$BOUNCER" orbit --model constant --a 29 --eps 0.96 --theta 0.1 --v 5 --steps 130 >"$TMP/orbit29.stdout" ||
  fail orbit29 "bouncer orbit failed"
cmp -s <(grep -v '^#' "$TMP/bif1.csv" | awk -F, '$1 == "29" {print $2 "," $3 "," $4}') \
       <(grep -v '^#' "$TMP/orbit29.stdout" | awk -F, 'NR > 1 && $1 > 100 {print $1 "," $2 "," $3}') ||
  fail bif "rows at a = 29 differ from bouncer orbit --a 29"
[[ $(grep -v '^#' "$TMP/bif1.csv" | awk -F, '$1 == "29"' | wc -l) -eq 30 ]] || fail bif "expected 30 rows at a = 29"
run_quiet bifjson $B --samples 3 --json
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert d['summary']['rows']==90, d['summary']" "$TMP/bifjson.out" ||
  fail bifjson "--json summary on stdout"
run_quiet bifcarry $B --samples 8 --carry --show v --out "$TMP/bifc" && picture_outputs bifcarry "$TMP/bifc"
run_quiet bifmpfr $B --samples 3 --precision mpfr:100 --out "$TMP/bifm" && picture_outputs bifmpfr "$TMP/bifm"

# --- portrait -----------------------------------------------------------------------------
run_quiet por portrait --model elastic --a 19 --theta 0.1,0.3 --v 10,12 --steps 200 --polar --out "$TMP/por" &&
  picture_outputs por "$TMP/por"
[[ $(rows "$TMP/por.csv" | wc -l) -eq 402 ]] || fail por "expected 2 x (1 + 200) rows"

# --- basin --------------------------------------------------------------------------------
BA="basin --model constant --a 24 --eps 0.5 --theta-range 0:1 --v-range 2:20 --transient 200 --steps 100"
run_quiet bas1 $BA --grid 8x6 --threads 1 --out "$TMP/bas1" && picture_outputs bas1 "$TMP/bas1"
run_quiet bas2 $BA --grid 8x6 --threads 2 --out "$TMP/bas2" && picture_outputs bas2 "$TMP/bas2"
cmp -s <(grep -v '^#' "$TMP/bas1.csv") <(grep -v '^#' "$TMP/bas2.csv") || fail basin "1 and 2 threads differ"
python3 - "$TMP/bas1.csv" <<'PY' || fail basin "grid rows, classes or the phase-space boundary wrong"
import sys
rows = [l.strip().split(",") for l in open(sys.argv[1]) if not l.startswith("#")][1:]
assert len(rows) == 48, len(rows)
classes = {"fixed", "periodic", "sticking", "quasiperiodic", "chaotic", "unbounded", "effective_sticking", "undecided", "outside"}
for th, v, c, q in rows:
    th, v = float(th), float(v)
    wall = 4 if th < 0.5 else -4  # triangle wall velocity (right-continuous at 1/2)
    assert c in classes, c
    assert (c == "outside") == (v < wall), (th, v, c)
# The paper's fixed points v* = 12 dominate at eps = 0.5, a = 24 (fig. basin2).
assert sum(c == "fixed" for _, _, c, _ in rows) > 0
PY
# MPFR at 2 threads = 1 thread.
run_quiet basm1 $BA --grid 4x3 --precision mpfr:128 --threads 1 --out "$TMP/basm1" && picture_outputs basm1 "$TMP/basm1"
run_quiet basm2 $BA --grid 4x3 --precision mpfr:128 --threads 2 --out "$TMP/basm2" && picture_outputs basm2 "$TMP/basm2"
cmp -s <(grep -v '^#' "$TMP/basm1.csv") <(grep -v '^#' "$TMP/basm2.csv") || fail basin-mpfr "1 and 2 threads differ"

# --- shards, merge, resume ----------------------------------------------------------------
run_quiet sh0 $BA --grid 8x6 --shard 0/2 --out "$TMP/sh"
[[ -e $TMP/sh.csv ]] && fail shard "a shard run wrote the final CSV"
[[ -d $TMP/sh.tiles ]] || fail shard "no tiles directory after a shard run"
rc=0; "$BOUNCER" merge "$TMP/sh" --quiet >/dev/null 2>"$TMP/merge-early.stderr" || rc=$?
[[ $rc -eq 2 ]] || fail merge "merge with missing tiles: exit $rc, expected 2"
[[ -e $TMP/sh.csv ]] && fail merge "merge with missing tiles wrote a CSV"
run_quiet sh1 $BA --grid 8x6 --shard 1/2 --out "$TMP/sh"
run_quiet merge merge "$TMP/sh" && picture_outputs merge "$TMP/sh"
cmp -s <(grep -v '^#' "$TMP/sh.csv") <(grep -v '^#' "$TMP/bas1.csv") || fail merge "merged shards differ from the whole run"
run_quiet pa $BA --grid 8x6 --shard 0/3 --out "$TMP/pa"
run_quiet pb $BA --grid 8x6 --shard 1/3 --out "$TMP/pb"
run_quiet pc $BA --grid 8x6 --shard 2/3 --out "$TMP/pc"
run_quiet merge3 merge --out "$TMP/m3" "$TMP/pa" "$TMP/pb" "$TMP/pc" && picture_outputs merge3 "$TMP/m3"
cmp -s <(grep -v '^#' "$TMP/m3.csv") <(grep -v '^#' "$TMP/bas1.csv") || fail merge3 "merged prefixes differ from the whole run"
# Resume: half the tiles exist (an interrupted run); the full run finishes from them.
run_quiet rs0 $BA --grid 8x6 --shard 0/2 --out "$TMP/rs"
run_quiet rs $BA --grid 8x6 --out "$TMP/rs" && picture_outputs resume "$TMP/rs"
cmp -s <(grep -v '^#' "$TMP/rs.csv") <(grep -v '^#' "$TMP/bas1.csv") || fail resume "resumed run differs"

# MPI ranks as shards: tests/cli/mpi_ranks.sh (skipped, visibly, where MPI is not built in).

# --- scan ---------------------------------------------------------------------------------
run_quiet scan scan --model constant --a-range 18:26 --eps-range 0.4:0.9 --grid 3x2 --ics 2 --transient 100 --steps 64 \
  --max-period 16 --out "$TMP/scan" && picture_outputs scan "$TMP/scan"
python3 - "$TMP/scan.csv" <<'PY' || fail scan "rows or counts wrong"
import sys
lines = [l.strip().split(",") for l in open(sys.argv[1]) if not l.startswith("#")]
head, rows = lines[0], lines[1:]
assert head[:2] == ["a", "eps"] and head[-1] == "total", head
assert len(rows) == 6, len(rows)
for r in rows:
    counts = list(map(int, r[2:-1]))
    assert sum(counts) == int(r[-1]) == 4, r  # 2 x 2 initial conditions per point
    assert 18 < float(r[0]) < 26 and 0.4 < float(r[1]) < 0.9, r
# cell centres: a in {18+8/6, 22, 26-8/6}, eps in {0.525, 0.775}
a = sorted(set(round(float(r[0]), 9) for r in rows)); e = sorted(set(round(float(r[1]), 9) for r in rows))
assert a == [round(18 + 8 / 6, 9), 22.0, round(26 - 8 / 6, 9)] and e == [0.525, 0.775], (a, e)
PY
run_quiet scanjson scan --model veldep --a-range 20:26 --c-range 500:1500 --grid 2x2 --ics 2 --transient 50 --steps 32 \
  --max-period 8 --json
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert sum(d['summary']['totals'].values())==16" \
  "$TMP/scanjson.out" || fail scanjson "--json totals"

# --- scenes in data/scenes run as they are (short settings) ----------------------------------
for scene in "$SRC"/data/scenes/picture-*.toml; do
  [[ -e $scene ]] || continue
  cmd=$(sed -n 's/^command = "\(.*\)"/\1/p' "$scene")
  name=$(basename "$scene" .toml)
  extra=()
  # The newcomer's global search (161 values, 4-6 minutes) runs here on a slice of its range:
  # the scene's own settings otherwise (tests/cli/attractors.sh checks what it finds).
  [[ $name == picture-attractors-veldep-c1000-a15-31 ]] && extra=(--range 22.9:23.3 --values 5 --starts 12x12)
  run_quiet "$name" "$cmd" --scene "$scene" "${extra[@]}" --out "$TMP/$name" && picture_outputs "$name" "$TMP/$name"
done

# --- bad input: exit 2, one line on stderr, no files -------------------------------------
bad() {  # bad NAME ARGS...
  local name=$1
  shift
  rm -rf "$TMP/bad"
  mkdir "$TMP/bad"
  refused "bad:$name" "" "$@"
  empty_dir "bad:$name" "$TMP/bad"
}
O="--out $TMP/bad/o"
bad range-order bifurcation --model constant --eps 0.96 --range 29:28 --theta 0.1 --v 5 $O
bad vary-eps-elastic bifurcation --model elastic --a 19 --vary eps --range 0.1:0.2 --theta 0.1 --v 5 $O
bad samples-zero $B --samples 0 $O
bad interval $B --precision interval:64 $O
bad shard-range $B --shard 2/2 $O
bad shard-no-out $B --shard 0/2
bad threads-zero $B --threads 0 $O
bad eps-range-above-1 bifurcation --model constant --a 24 --vary eps --range 0.5:1.5 --theta 0.1 --v 5 $O
bad below-wall portrait --model constant --a 24 --eps 0.5 --theta 0.1 --v 1 $O
bad grid-zero $BA --grid 0x5 $O
bad grid-form $BA --grid 5 $O
bad theta-range basin --model constant --a 24 --eps 0.5 --theta-range 0:2 --v-range 4:10 $O
bad no-v-range basin --model elastic --a 24 --grid 4x4 $O  # constant and veldep default to the trapping region
bad max-period $BA --grid 8x6 --max-period 400 $O
# A prefix the file system cannot name (found by tools/fuzz_input.py: it was an internal error).
bad out-too-long $B --out "$TMP/bad/$(printf 'x%.0s' {1..300})"
bad out-tiles-too-long $B --out "$TMP/bad/$(printf 'x%.0s' {1..252})"
bad basin-interval basin --model constant --a 24 --eps 0.5 --v-range 4:10 --precision interval:64 $O
bad scan-elastic scan --model elastic --a-range 18:20 --eps-range 0.1:0.2 $O
bad scan-eps-1 scan --model constant --a-range 18:20 --eps-range 0.5:1 $O
bad scan-a-given scan --model constant --a 19 --a-range 18:20 --eps-range 0.5:0.6 $O
bad merge-nothing merge "$TMP/bad/nothing"
bad unknown-option $BA --grid 8x6 --colour red $O

finish
