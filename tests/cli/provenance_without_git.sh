#!/usr/bin/env bash
# Provenance without git (cmake/BuildInfo.cmake): a source tree without git metadata (a
# tarball, a copy) is identified by "tree-sha256:<64 hex>" over its files; with git, by the
# 40-hex commit (+dirty-HASH16 for uncommitted changes, a hash of the diff). Checks: the binary's commit has exactly one of those two forms; a
# copy without .git gets the tree form, the same for two runs, and a different one after a
# one-byte change of a source file.
# Usage: bash provenance_without_git.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
form='^([0-9a-f]{40}(\+dirty-[0-9a-f]{16})?|tree-sha256:[0-9a-f]{64})$'

commit=$("$BOUNCER" --version | sed -n 's/.*(commit \(.*\))$/\1/p')
[[ $commit =~ $form ]] || fail version "commit '$commit' is neither a git commit nor a tree hash"

mkdir "$TMP/copy"
for d in CMakeLists.txt cmake lib tools proofs python tests data; do cp -r "$SRC/$d" "$TMP/copy/"; done
info() { cmake -DSRC="$TMP/copy" -DOUT="$TMP/$1.cpp" -DGIT= -DVERSION=0 -P "$SRC/cmake/BuildInfo.cmake" &&
         sed -n 's/.*info{"0", "\([^"]*\)".*/\1/p' "$TMP/$1.cpp"; }
first=$(info a)
second=$(info b)
[[ $first =~ ^tree-sha256:[0-9a-f]{64}$ ]] || fail tree "a copy without .git got '$first'"
[[ $first == "$second" ]] || fail stable "two runs on the same tree differ: $first vs $second"
echo "// one more byte" >>"$TMP/copy/lib/src/io/output.cpp"
third=$(info c)
[[ $third != "$first" && $third =~ ^tree-sha256: ]] || fail change "a changed source file kept the hash $first"

finish "provenance without git: all checks passed"
