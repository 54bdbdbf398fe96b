#!/usr/bin/env bash
# End-to-end: outputs never replace what they should not and never fail silently
# (lib/include/bouncer/base/output.hpp, docs/guide/orbit.md, "Exit status and outputs").
#   * stdout on a full device (/dev/full): exit 1, one line, for every kind of command;
#   * --out /dev/full: exit 1, no PATH.partial left; --out /dev/null: written through, the
#     device stays a device; --out a named pipe: written through (its reader gets the data);
#   * --out a symlink to a regular file: refused (exit 2), link and target unchanged; a
#     symlink to a device is written through;
#   * --out a directory or DIR/: exit 2, naming --out, nothing written;
#   * more than 1e8 rows without --force: exit 2 before anything is written;
#   * a path with a space is quoted on the "# inputs:" line and audit reruns it.
# Usage: bash output_edges.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
MODEL=(--model constant --eps 0.5 --a 24)

expect() {  # expect NAME STATUS ARGS... (stdout to /dev/full unless --out is given)
  local name=$1 want=$2 rc=0
  shift 2
  "$BOUNCER" "$@" >/dev/full 2>"$TMP/$name.err" || rc=$?
  [[ $rc -eq $want ]] || fail "$name" "exit $rc, expected $want: $(head -c 300 "$TMP/$name.err")"
  [[ $(wc -l <"$TMP/$name.err") -eq 1 ]] || fail "$name" "expected one line on stderr, got: $(head -c 300 "$TMP/$name.err")"
}
expect orbit 1 orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 10
expect orbit_long 1 orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 100000000 --every 2
expect sticking 1 certify-sticking --eps 0.5 --a 10
expect periodic_certified 1 certify-periodic "${MODEL[@]}" --period 1 --guess 0.3,12
expect periodic 1 periodic "${MODEL[@]}" --period 1 --guess 0.3,12
expect classify 1 classify "${MODEL[@]}" --theta 0.3 --v 12
expect lyapunov 1 lyapunov "${MODEL[@]}" --theta 0.2 --v 7
expect sweep 1 sweep "${MODEL[@]}" --theta 0.5 --v 4 --steps 100 --json
"$BOUNCER" orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 5 --format json --out "$TMP/r.json" 2>/dev/null
expect audit 1 audit "$TMP/r.json"
expect basin 1 basin "${MODEL[@]}" --grid 3x3 --v-range 4:20 --transient 10 --steps 16 --json --quiet

# --out on devices, pipes and links.
rc=0; "$BOUNCER" orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 10 --out /dev/full 2>"$TMP/full.err" || rc=$?
[[ $rc -eq 1 && ! -e /dev/full.partial ]] || fail out_full "exit $rc: $(cat "$TMP/full.err")"
"$BOUNCER" orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 10 --out /dev/null || fail out_null "exit $?"
[[ -c /dev/null ]] || fail out_null "/dev/null is no longer a character device"
mkfifo "$TMP/pipe"
cat "$TMP/pipe" >"$TMP/from-pipe" &
reader=$!
"$BOUNCER" orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 10 --out "$TMP/pipe" || fail out_fifo "exit $?"
wait $reader
[[ -p "$TMP/pipe" ]] || fail out_fifo "the pipe was replaced"
grep -q '^10,' "$TMP/from-pipe" || fail out_fifo "the reader did not get the orbit"
# A link to a regular file is refused (it may have been planted to point anywhere): exit 2,
# naming --out, the link and its target as they were. A link to a device is written through.
echo old >"$TMP/target"
ln -s "$TMP/target" "$TMP/link"
refused out_link '^bouncer: out: .* is a symbolic link' orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 10 --out "$TMP/link"
[[ -L "$TMP/link" && $(cat "$TMP/target") == old && ! -e "$TMP/link.partial" ]] || fail out_link "the link or its target changed"
ln -s /dev/null "$TMP/null-link"
"$BOUNCER" orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 10 --out "$TMP/null-link" || fail out_link "link to /dev/null: exit $?"
[[ -L "$TMP/null-link" && -c /dev/null ]] || fail out_link "the link to /dev/null was replaced"

# Unbounded output is refused before anything is written (--force overrides; not run here).
refused huge '^bouncer: steps: would print' orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 10000000000 --out "$TMP/huge.csv"
absent huge "$TMP/huge.csv"

# A path with a space round-trips through the "# inputs:" line: audit reruns it.
mkdir "$TMP/with space"
"$BOUNCER" orbit "${MODEL[@]}" --theta 0.3 --v 12 --steps 5 --out "$TMP/with space/o.csv" || fail space "orbit exit $?"
grep -q "out=\"$TMP/with space/o.csv\"" "$TMP/with space/o.csv" || fail space "the inputs line does not quote the path"
audited space "$TMP/with space/o.csv"

# Directories: exit 2, nothing written.
mkdir "$TMP/dir"
for args in "orbit ${MODEL[*]} --theta 0.3 --v 12 --steps 10 --out $TMP/dir" \
            "orbit ${MODEL[*]} --theta 0.3 --v 12 --steps 10 --out $TMP/dir/" \
            "basin ${MODEL[*]} --grid 3x3 --v-range 4:20 --transient 10 --steps 16 --quiet --out $TMP/dir/" \
            "certify-periodic ${MODEL[*]} --period 1 --guess 0.3,12 --out $TMP/dir"; do
  # shellcheck disable=SC2086
  refused out_dir '^bouncer: out:' $args
  [[ -z "$(ls -A "$TMP/dir")" ]] || fail out_dir "files written into the directory: $(ls -A "$TMP/dir")"
done

# A folder without write permission: exit 1 (the output failed, not the input), one line
# naming the path, never "internal error", for a plain output and for a grid job alike.
# As root permissions do not apply, so the check runs as nobody (setpriv, util-linux, part of
# every Debian system), with a copy of the binary nobody can execute wherever the build is.
as_user=()
RUN_AS=$BOUNCER
if [[ $(id -u) -eq 0 ]]; then
  as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
  cp "$BOUNCER" "$TMP/bouncer-copy" && chmod 755 "$TMP/bouncer-copy"
  RUN_AS=$TMP/bouncer-copy
fi
mkdir -p "$TMP/ro" && chmod 755 "$TMP" && chmod 555 "$TMP/ro"
"${as_user[@]}" "$RUN_AS" --version >/dev/null 2>&1 || fail read_only "cannot run the binary as an unprivileged user"
"${as_user[@]}" test -w "$TMP/ro" && fail read_only "the folder is writable: the check would prove nothing"
for args in "orbit ${MODEL[*]} --theta 0.3 --v 12 --steps 10 --out $TMP/ro/o.csv" \
            "basin ${MODEL[*]} --grid 4x4 --transient 10 --steps 16 --quiet --out $TMP/ro/b"; do
  rc=0
  # shellcheck disable=SC2086
  "${as_user[@]}" "$RUN_AS" $args >/dev/null 2>"$TMP/ro.err" || rc=$?
  [[ $rc -eq 1 && $(wc -l <"$TMP/ro.err") -eq 1 ]] && grep -q 'Permission denied' "$TMP/ro.err" &&
    ! grep -q 'internal error' "$TMP/ro.err" || fail read_only "exit $rc for '${args%% *}': $(head -c 300 "$TMP/ro.err")"
done
[[ -z "$(ls -A "$TMP/ro")" ]] || fail read_only "something was written: $(ls -A "$TMP/ro")"

# A full disk in the middle of an output set (RLIMIT_FSIZE of 4 KB, SIGXFSZ ignored: the
# 0.9 KB CSV fits, the 8 KB PNG does not): exit 1 and no file of the set, never a CSV
# without its PNG and JSON (it used to leave PREFIX.csv).
rc=0
(trap '' XFSZ; ulimit -f 4; "$BOUNCER" basin "${MODEL[@]}" --grid 4x4 --transient 10 --steps 16 --quiet \
  --out "$TMP/set" 2>"$TMP/set.err") || rc=$?
[[ $rc -eq 1 && $(wc -l <"$TMP/set.err") -eq 1 ]] || fail output_set "exit $rc: $(head -c 300 "$TMP/set.err")"
for ext in csv png json csv.partial png.partial json.partial; do
  [[ ! -e "$TMP/set.$ext" ]] || fail output_set "set.$ext was left behind"
done

# SIGTERM during a long orbit: the .partial file is removed, nothing else is left, and the
# process ends by the signal (143). (Grid jobs: tests/cli/grid_edges.sh.)
"$BOUNCER" orbit --model constant --eps 0.9 --a 28.82 --theta 0.1 --v 10 --steps 50000000 \
  --out "$TMP/long.csv" 2>"$TMP/long.err" &
pid=$!
for _ in $(seq 300); do [[ -s "$TMP/long.csv.partial" ]] && break; sleep 0.1; done
[[ -s "$TMP/long.csv.partial" ]] || fail sigterm "the orbit never started writing"
kill -TERM "$pid"
rc=0
wait "$pid" || rc=$?
[[ $rc -eq 143 ]] || fail sigterm "exit $rc, expected 143"
[[ ! -e "$TMP/long.csv.partial" && ! -e "$TMP/long.csv" ]] || fail sigterm "a partial or cut-off orbit was left"
grep -q "interrupted by SIGTERM; partial files removed" "$TMP/long.err" || fail sigterm "message: $(head -c 300 "$TMP/long.err")"

finish "output edges: all checks passed"
