#!/usr/bin/env bash
# End-to-end: the figure font missing (hidden by a bind mount in a private mount namespace).
# A picture command with --out exits 1 (an output failure) with one line naming the Debian
# package, before any work and with no file; sweep likewise; a run without --out draws
# nothing and does not need the font. Exit 77 (ctest: skipped) where no mount namespace can
# be made (unshare -m needs root or CAP_SYS_ADMIN).
# Usage: bash missing_font.sh <bouncer-binary> <source-dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
FONT=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
[[ -e $FONT ]] || die "$FONT missing (apt-get install fonts-dejavu-core)"
unshare -m true 2>/dev/null || skip "no private mount namespace here (unshare -m needs root or CAP_SYS_ADMIN)"
BASIN=(basin --model constant --a 24 --eps 0.5 --v-range 2:20 --grid 24x16 --transient 100 --steps 64 --quiet)
hidden() { unshare -m bash -c 'mount --bind /dev/null "$0" && exec "$@"' "$FONT" "$@"; }
rc=0
hidden "$BOUNCER" "${BASIN[@]}" --out "$TMP/nofont" 2>"$TMP/nofont.err" || rc=$?
[[ $rc -eq 1 ]] || fail nofont "exit $rc, expected 1"
[[ $(wc -l <"$TMP/nofont.err") -eq 1 ]] && grep -q "fonts-dejavu-core" "$TMP/nofont.err" ||
  fail nofont "expected one line naming fonts-dejavu-core: $(head -c 300 "$TMP/nofont.err")"
written=$(compgen -G "$TMP/nofont*" | grep -v 'nofont.err$' || true)
[[ -z $written ]] || fail nofont "something was written: $written"
rc=0
hidden "$BOUNCER" sweep --model constant --eps 0.5 --a 24 --theta 0.5 --v 4 --steps 10 --out "$TMP/nofont_sw" >/dev/null 2>&1 || rc=$?
[[ $rc -eq 1 ]] || fail nofont-sweep "exit $rc, expected 1"
hidden "$BOUNCER" "${BASIN[@]}" >/dev/null 2>"$TMP/nofont2.err" || fail nofont-stdout "a run without --out failed: $(head -c 300 "$TMP/nofont2.err")"
finish
