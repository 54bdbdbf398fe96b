#!/usr/bin/env bash
# End-to-end: outputs under races, pipes, hostile inputs and scarce resources (issue 21;
# base/output.hpp, base/input.hpp). Each case is one of the audit's reproducing commands:
#   * two `orbit --out o.csv` at once: the second is refused at its start (exit 2, naming the
#     first's process), the first's file is whole and its own; two `trajectory` runs on one
#     prefix likewise, so no set mixes two runs;
#   * `orbit | head -1`: exit 1 (a failed write, not SIGPIPE's 141), nothing left behind;
#   * a FIFO at PREFIX.png is written through (its reader gets the PNG), never replaced;
#   * PREFIX.png a directory: exit 2 at once, before a long computation;
#   * a scene that is a FIFO, a scene with 40,000 nested dotted keys, a scene with a NUL byte,
#     a job.toml with either, a job.toml that adds `out = ...`: exit 2, one line, no crash;
#   * a tile that is a directory or a FIFO: exit 2, never a hang or "internal error";
#   * PREFIX.tiles a link to a directory holding a job.key: exit 2, that directory untouched;
#   * --tiles-from with a 300-character name, sweep and continue with --out DIR/: exit 2;
#   * worker threads that cannot be created: exit 1 with the reason, no PREFIX.tiles/ left;
#   * a grid larger than the memory the process may use (ulimit -v): exit 2 before any work.
# Usage: bash output_safety.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
cd "$TMP"
MODEL=(--model constant --eps 0.5 --a 24)
LONG_ORBIT=(orbit --model constant --eps 0.9 --a 28.82 --theta 0.1 --v 10 --steps 40000000 --every 1000000)
SLOW_BASIN=(basin --model constant --eps 0.5 --a 15 --grid 200x150 --transient 20000 --steps 2000 --threads 1 --quiet)

refused_soon() { refused -t 30 "$@"; }  # refused_soon NAME PATTERN ARGS...: refused within 30 s
wait_for() {  # wait_for PATH: until it exists (at most 30 s)
  for _ in $(seq 300); do [[ -e $1 ]] && return 0; sleep 0.1; done
  return 1
}

# --- Two writers of one path ------------------------------------------------------------------
"$BOUNCER" "${LONG_ORBIT[@]}" --out o.csv 2>first.err &
first=$!
wait_for o.csv.partial || fail race "the first run never staged its file"
refused_soon race "'o.csv' is in use by process $first " "${LONG_ORBIT[@]}" --out o.csv
wait "$first" || fail race "the first run failed: $(cat first.err)"
[[ $(grep -c '^# bouncer' o.csv) -eq 1 && $(grep -vc '^#' o.csv) -eq 42 ]] || fail race "o.csv is not one whole orbit"
grep -q "invocation: .*--out o.csv" o.csv || fail race "o.csv lacks its own provenance"
TRAJ=(trajectory --model constant --eps 0.5 --theta 0.3 --v 12 --periods 100 --samples 10000 --quiet)
"$BOUNCER" "${TRAJ[@]}" --a 19 --out t 2>/dev/null &
first=$!
"$BOUNCER" "${TRAJ[@]}" --a 24 --out t 2>second.err &
second=$!
rc1=0; wait "$first" || rc1=$?
rc2=0; wait "$second" || rc2=$?
if [[ $rc1 -eq 0 && $rc2 -eq 0 ]]; then  # one after the other: then the later set is whole
  :
elif [[ $rc1 -eq 0 || $rc2 -eq 0 ]]; then
  [[ $rc1 -eq 2 || $rc2 -eq 2 ]] || fail traj_race "exits $rc1 and $rc2: one must succeed, the other be refused (2)"
else
  fail traj_race "both runs failed: $rc1 $rc2"
fi
a_csv=$(sed -n 's/^# inputs:.* a=\([0-9.]*\) .*/\1/p' t.csv)
a_json=$(python3 -c 'import json,sys; print(json.load(open("t.json"))["provenance"]["inputs"]["a"])')
[[ -n $a_csv && $a_csv == "$a_json" ]] || fail traj_race "the CSV (a = $a_csv) and the JSON (a = $a_json) come from different runs"

# --- A closed pipe ----------------------------------------------------------------------------
set +o pipefail
"$BOUNCER" orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 1000000 2>pipe.err | head -1 >/dev/null
rc=${PIPESTATUS[0]}
set -o pipefail
[[ $rc -eq 1 ]] && grep -q "failed" pipe.err || fail pipe "exit $rc (expected 1, not 141): $(cat pipe.err)"
set +o pipefail
"$BOUNCER" basin "${MODEL[@]}" --grid 20x20 --transient 10 --steps 16 --quiet --out piped 2>pipe2.err | head -c 10 >/dev/null
set -o pipefail
compgen -G "piped*.partial" >/dev/null && fail pipe "staging files left: $(ls piped*)"

# --- Pictures: a FIFO is written through; a directory is refused before the work ----------------
mkfifo fifo.png
timeout 60 cat fifo.png >from-fifo.png &
reader=$!
timeout 60 "$BOUNCER" basin "${MODEL[@]}" --grid 8x6 --transient 10 --steps 16 --quiet --out fifo 2>fifo.err ||
  fail fifo_png "exit $?: $(cat fifo.err)"
wait "$reader" || fail fifo_png "the reader failed"
[[ -p fifo.png ]] || fail fifo_png "the FIFO was replaced"
[[ $(head -c 4 from-fifo.png | tail -c 3) == PNG ]] || fail fifo_png "the reader did not get a PNG"
mkdir dir.png
start=$SECONDS
refused_soon png_dir "out: 'dir.png' is a directory" "${SLOW_BASIN[@]}" --out dir
[[ $((SECONDS - start)) -lt 10 && ! -e dir.csv && ! -e dir.tiles ]] || fail png_dir "not refused at once, or files left"

# --- Hostile scenes and job files ---------------------------------------------------------------
mkfifo fifo.toml
refused_soon scene_fifo "scene: 'fifo.toml' is a named pipe" orbit --scene fifo.toml
python3 -c "print('command = \"orbit\"\n' + '.'.join(['k'] * 40000) + ' = 1')" >deep.toml
refused_soon scene_deep "scene: 'deep.toml' line 2: tables or arrays nested more than 32 deep" --scene deep.toml
refused_soon scene_deep_cmd "nested more than 32 deep" orbit --scene deep.toml
printf 'command = "orbit"\nmodel = "constant"\na = "24\0junk"\n' >nul.toml
refused_soon scene_nul "scene: 'nul.toml' line 3: contains a NUL byte" orbit --scene nul.toml
BASIN=(basin "${MODEL[@]}" --grid 4x3 --transient 10 --steps 16 --quiet)
"$BOUNCER" "${BASIN[@]}" --shard 0/2 --out job
cp job.tiles/job.toml job.toml.orig
{ cat job.toml.orig; echo "out = \"$TMP/elsewhere\""; } >job.tiles/job.toml
refused_soon merge_out "job.toml' names 'out', which is not part of a job" merge job
[[ ! -e elsewhere.csv ]] || fail merge_out "merge wrote where job.toml said"
python3 -c "print('command = \"basin\"\n' + '.'.join(['k'] * 40000) + ' = 1')" >job.tiles/job.toml
refused_soon merge_deep "nested more than 32 deep" merge job
cp job.toml.orig job.tiles/job.toml

# --- Tiles that are not files, and a tile directory that is a link -----------------------------
"$BOUNCER" "${BASIN[@]}" --shard 0/2 --out tdir
mkdir tdir.tiles/tile-000001
refused_soon tile_dir "tile-000001' is a directory, not a regular file" "${BASIN[@]}" --out tdir
refused_soon tile_dir_merge "tile-000001' is a directory" merge tdir
"$BOUNCER" "${BASIN[@]}" --shard 0/2 --out tfifo
mkfifo tfifo.tiles/tile-000001
refused_soon tile_fifo "tile-000001' is a named pipe" "${BASIN[@]}" --out tfifo
refused_soon tile_fifo_merge "tile-000001' is a named pipe" merge tfifo
mkdir precious
echo key >precious/job.key
echo keep >precious/notes.txt
ln -s precious linked.tiles
refused_soon tiles_link "linked.tiles' is a symbolic link" "${BASIN[@]}" --out linked
[[ -e precious/notes.txt && -e precious/job.key && $(ls precious | wc -l) -eq 2 ]] || fail tiles_link "the linked directory changed: $(ls precious)"

# --- Names the file system cannot hold; directories given as prefixes ----------------------------
long=$(printf 'x%.0s' $(seq 300))
refused_soon tiles_from_long "tiles-from: a name in" "${BASIN[@]}" --out tl --tiles-from "$long"
mkdir d
refused_soon sweep_dir "out: 'd/' is a directory" sweep "${MODEL[@]}" --theta 0.5 --v 4 --steps 10 --out d/
refused_soon continue_dir "out: 'd/' is a directory" continue "${MODEL[@]}" --period 1 --guess 0.5,4 --range 23:25 --out d/
[[ -z $(ls -A d) ]] || fail prefix_dir "hidden files written: $(ls -A d)"

# --- Threads and memory ----------------------------------------------------------------------------
# Both checks limit the address space (ulimit -v); AddressSanitizer reserves terabytes of
# shadow address space at start, so under it (build-sanitize/) they cannot run at all.
if asan_build; then
  echo "output_safety: AddressSanitizer build: the thread and memory limits (ulimit -v) NOT checked"
else
rc=0
(ulimit -v 2000000; "$BOUNCER" basin "${MODEL[@]}" --grid 512x512 --threads 400 --quiet --out thr 2>thr.err) || rc=$?
[[ $rc -eq 1 && $(wc -l <thr.err) -eq 1 ]] && grep -q "cannot start worker thread .*give fewer --threads" thr.err ||
  fail threads "exit $rc: $(head -c 300 thr.err)"
[[ ! -e thr.tiles && ! -e thr.csv ]] || fail threads "files left: $(ls thr* 2>/dev/null)"
rc=0
(ulimit -v 4000000; timeout 30 "$BOUNCER" basin "${MODEL[@]}" --grid 8192x8192 --out mem 2>mem.err) || rc=$?
[[ $rc -eq 2 && $(wc -l <mem.err) -eq 1 ]] && grep -q "grid: this job of 67108864 items needs about .* GB .* give --force" mem.err ||
  fail memory "exit $rc: $(head -c 300 mem.err)"
[[ ! -e mem.tiles && ! -e mem.csv ]] || fail memory "files left"
fi

finish "output safety: all checks passed"
