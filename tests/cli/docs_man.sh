#!/usr/bin/env bash
# Man pages and bash completion, generated from the help by tools/gen_docs.py (the CMake
# target bouncer_man builds and installs the same files):
#   - every command that `bouncer --help` lists has bouncer-CMD.1, and bouncer.1 exists;
#   - each page renders with `MANWIDTH=80 man --warnings -l` without a warning, its NAME line
#     is "bouncer-CMD - <the command's description>", and every option and positional that
#     `bouncer CMD --help` prints appears in the rendered page (read from the help here with
#     grep, not with the generator's parser); bouncer.1 names every command;
#   - the warning check can fail: a page with an unknown escape does give a warning;
#   - the completion script, sourced in bash: `bouncer <TAB>` offers every command,
#     `bouncer cert<TAB>` exactly the three certify- commands, `bouncer orbit --<TAB>`
#     every option of orbit's help, `bouncer orbit --precision <TAB>` the precisions,
#     `bouncer help <TAB>` the commands, `bouncer orbit --a <TAB>` nothing (a number);
#   - where the build has made them (target bouncer_man), `cmake --install --component man`
#     puts every page where `man -w bouncer-CMD` finds it, identical to the help's, and the
#     completion in share/bash-completion/completions.
# Exit 77 (skipped) when man (man-db) or groff is missing.
# Usage: bash docs_man.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
command -v man >/dev/null && command -v groff >/dev/null || skip "man (man-db) or groff is not installed"
PY=python3; [[ -x /usr/bin/python3 ]] && PY=/usr/bin/python3

"$PY" "$SRC/tools/gen_docs.py" --bouncer "$BOUNCER" --man "$TMP/man" --completion "$TMP/bouncer.bash" >/dev/null ||
  die "tools/gen_docs.py failed"
mapfile -t cmds < <("$BOUNCER" --help | awk '/^Subcommands:/ {f = 1; next} f && /^  [a-z]/ {print $1} f && /^$/ {f = 0}')
((${#cmds[@]} >= 10)) || die "bouncer --help lists only ${#cmds[@]} commands"

render() {  # FILE -> rendered text in $TMP/out; any warning (groff's default set, then all) fails
  MANWIDTH=80 man --warnings=w -l "$1" >/dev/null 2>"$TMP/err" || fail "$1" "man -l exited $?"
  MANWIDTH=80 man --warnings -l "$1" >"$TMP/out" 2>>"$TMP/err" || fail "$1" "man -l exited $?"
  if [[ -s $TMP/err ]]; then fail "$(basename "$1")" "man --warnings: $(head -c 300 "$TMP/err")"; fi
}
# the rendered page has hyphenated / justified words; compare with spaces squeezed, no hyphen breaks
flat() { tr -s ' \n' ' ' <"$TMP/out" | sed 's/‐ //g; s/- //g'; }

[[ -f $TMP/man/bouncer.1 ]] || fail bouncer.1 "not written"
render "$TMP/man/bouncer.1"
top=$(flat)
for c in "${cmds[@]}"; do
  [[ $top == *" $c "* ]] || fail bouncer.1 "does not name the command $c"
  page=$TMP/man/bouncer-$c.1
  [[ -f $page ]] || { fail "bouncer-$c.1" "missing"; continue; }
  render "$page"
  text=$(flat)
  desc=$("$BOUNCER" "$c" --help | sed -n 1p)
  name_line=$(awk '/^NAME/ {getline; print; exit}' "$TMP/out" | tr -s ' ' | sed 's/^ *//')
  [[ $name_line == "bouncer-$c - "* ]] || fail "bouncer-$c.1" "NAME line is '$name_line'"
  first_words=$(echo "$desc" | cut -d' ' -f1-3)
  [[ $text == *"$first_words"* ]] || fail "bouncer-$c.1" "does not give the description '$desc'"
  while read -r opt; do
    [[ $text == *"$opt"* ]] || fail "bouncer-$c.1" "does not document $opt"
  done < <("$BOUNCER" "$c" --help | grep -oE -- '^  (-[A-Za-z],)?--[a-z0-9-]+|^  [a-z]+ ' | sed 's/^ *//; s/^-[A-Za-z],//; s/ $//')
done

# the warning checks themselves can fail: an unknown macro (the default set), an unknown escape (all)
printf '.TH BAD 1\n.SH NAME\nbad \\- a broken page\n.XYZ foo\n' >"$TMP/bad.1"
MANWIDTH=80 man --warnings -l "$TMP/bad.1" >/dev/null 2>"$TMP/bad.err" || true
[[ -s $TMP/bad.err ]] || fail "man --warnings" "gives no warning for an unknown macro: the check above proves nothing"
printf '.TH BAD 1\n.SH NAME\nbad \\- a broken escape \\q\n' >"$TMP/bad2.1"
MANWIDTH=80 man --warnings=w -l "$TMP/bad2.1" >/dev/null 2>"$TMP/bad2.err" || true
[[ -s $TMP/bad2.err ]] || fail "man --warnings=w" "gives no warning for an unknown escape: the check above proves nothing"

# completion
complete_words() {  # WORDS... (the last is the word being completed)
  bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); _bouncer; printf "%s\n" "${COMPREPLY[@]}"' \
    _ "$TMP/bouncer.bash" "$@"
}
offered=$(complete_words bouncer "")
for c in "${cmds[@]}" help; do
  grep -qx -- "$c" <<<"$offered" || fail completion "bouncer <TAB> does not offer $c"
done
[[ $(complete_words bouncer cert | sort | tr '\n' ' ') == "certify-chaos certify-periodic certify-sticking " ]] ||
  fail completion "bouncer cert<TAB> offers '$(complete_words bouncer cert | tr '\n' ' ')'"
offered=$(complete_words bouncer orbit --)
while read -r opt; do
  grep -qx -- "$opt" <<<"$offered" || fail completion "bouncer orbit --<TAB> does not offer $opt"
done < <("$BOUNCER" orbit --help | grep -oE -- '^  (-[A-Za-z],)?--[a-z0-9-]+' | sed 's/^ *//; s/^-[A-Za-z],//')
offered=$(complete_words bouncer orbit --precision "")
for p in double long dd quad interval:double; do
  grep -qx -- "$p" <<<"$offered" || fail completion "bouncer orbit --precision <TAB> does not offer $p"
done
offered=$(complete_words bouncer help "")
grep -qx orbit <<<"$offered" || fail completion "bouncer help <TAB> does not offer orbit"
[[ -z $(complete_words bouncer orbit --a "") ]] || fail completion "bouncer orbit --a <TAB> offers words for a number"
# the build's pages (CMake target bouncer_man), installed: `man bouncer-CMD` finds each in
# PREFIX/share/man/man1, the same bytes as generated above; the completion beside it
build=$(cd "$(dirname "$BOUNCER")/.." && pwd)
if [[ -f $build/tools/man.stamp && -f $build/cmake_install.cmake ]]; then
  cmake --install "$build" --component man --prefix "$TMP/inst" >/dev/null || fail install "cmake --install --component man failed"
  for page in bouncer "${cmds[@]/#/bouncer-}"; do
    found=$(MANPATH=$TMP/inst/share/man man -w "$page" 2>/dev/null || true)
    [[ $found == "$TMP/inst/share/man/man1/$page.1" ]] || { fail install "man -w $page gives '$found'"; continue; }
    cmp -s "$found" "$TMP/man/$page.1" || fail install "the installed $page.1 differs from the help's (stale build?)"
  done
  cmp -s "$TMP/inst/share/bash-completion/completions/bouncer" "$TMP/bouncer.bash" ||
    fail install "share/bash-completion/completions/bouncer is missing or differs from the help's"
else
  echo "docs_man: the target bouncer_man is not built in $build: the installed pages are not checked"
fi
finish "docs_man: ${#cmds[@]} commands: man pages render without warnings and document every option; completion offers commands and options"
