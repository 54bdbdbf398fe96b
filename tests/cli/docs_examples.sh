#!/usr/bin/env bash
# The numbers the documentation quotes are what the tool prints (tools/check_docs_examples.py):
#   - every example marked `<!-- run -->` in README.md and docs/ (a ```sh block with one
#     bouncer command, then a ```text block with its output) is rerun and its output equals
#     the quote, after the documented normalisation (commit hashes, `# time:` numbers, the
#     temporary directory; `...` lines stand for left-out lines); each is fast (CPU limit);
#   - the README quotes at least 3 examples and the docs at least 5 more;
#   - the check can fail: in a copy of every file, one digit of every quote is changed (the
#     last digit of its last line holding one, outside commit hashes and time lines), and the checker
#     must then report exactly one mismatch per example; a marker without its blocks and a
#     marked command that is not bouncer are refused.
# Under AddressSanitizer (the sanitized build) the CPU limits are 5 times larger.
# Usage: bash docs_examples.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
PY=python3; [[ -x /usr/bin/python3 ]] && PY=/usr/bin/python3
CHECK=$SRC/tools/check_docs_examples.py
# 5 s per example: the guideline of 2.5 s (the slowest, continue --certify, takes 2.1 s here and
# took 3.2 s on the CI machine) with a margin for a loaded machine; 20 s for all of them.
limits=(--max-cpu 5 --max-total 20)  # the defaults, spelled out
grep -qa AddressSanitizer "$BOUNCER" && limits=(--max-cpu 25 --max-total 100)

# 1. the committed documentation
"$PY" "$CHECK" --bouncer "$BOUNCER" --root "$SRC" "${limits[@]}" >"$TMP/ok.log" 2>&1 ||
  fail quotes "$(cat "$TMP/ok.log")"
n_readme=$(grep -c '^<!-- run' "$SRC/README.md" || true)
((n_readme >= 3)) || fail README "only $n_readme marked examples (want the quick examples, at least 3)"
n_docs=$(grep -rc '^<!-- run' "$SRC/docs" --include='*.md' | awk -F: '{s += $2} END {print s + 0}')
((n_docs >= 5)) || fail docs "only $n_docs marked examples in docs/"
# the last line is `check_docs_examples: N examples ...` or `... K problem(s) in N examples`
checked=$(grep -E '^check_docs_examples: ' "$TMP/ok.log" | grep -oE '[0-9]+ examples' | grep -oE '[0-9]+' || echo 0)
((checked == n_readme + n_docs)) || fail count "the checker ran $checked examples, the files mark $((n_readme + n_docs))"

# 2. a changed digit in every quote is found
mkdir -p "$TMP/planted"
"$PY" - "$SRC" "$TMP/planted" <<'PY'
import os, re, sys
src, out = sys.argv[1:3]
files = [os.path.join(src, "README.md")] + [os.path.join(d, f) for d, _, fs in os.walk(os.path.join(src, "docs"))
                                            if "reference" not in os.path.relpath(d, src).split(os.sep)
                                            for f in fs if f.endswith(".md")]
k = 0
for path in files:
    lines = open(path, encoding="utf-8").read().split("\n")
    if not any(l.startswith("<!-- run") for l in lines):
        continue
    i = 0
    while i < len(lines):
        if lines[i].startswith("<!-- run"):
            j = i + 1
            blocks = 0
            while blocks < 2:            # skip the ```sh block, find the ```text block
                if lines[j].startswith("```") and lines[j].strip() != "```":
                    blocks += 1
                j += 1
            start = j
            while lines[j].strip() != "```":
                j += 1
            body = range(start, j)
            def digits(line):  # digits outside `(commit ...)` in a line that is not `# time:`
                if line.strip() == "..." or line.startswith("# time:"):
                    return []
                cut = re.sub(r"\(commit [^)]*\)", lambda c: " " * len(c.group()), line)
                return list(re.finditer(r"\d", cut))
            cands = [n for n in body if digits(lines[n])]
            if not cands:
                sys.exit(f"{path}:{i + 1}: a quote without a digit to change")
            n = cands[-1]
            m = digits(lines[n])[-1]
            d = str((int(m.group()) + 1) % 10)
            lines[n] = lines[n][:m.start()] + d + lines[n][m.end():]
            k += 1
            i = j
        i += 1
    name = os.path.relpath(path, src).replace(os.sep, "__")
    open(os.path.join(out, name), "w", encoding="utf-8").write("\n".join(lines))
open(os.path.join(out, "COUNT"), "w").write(str(k))
PY
planted=$(cat "$TMP/planted/COUNT")
rc=0
"$PY" "$CHECK" --bouncer "$BOUNCER" --root "$SRC" "${limits[@]}" "$TMP"/planted/*.md >"$TMP/planted.log" 2>&1 || rc=$?
((rc == 1)) || fail planted "the checker exited $rc on $planted planted digits, not 1"
found=$(grep -c 'prints something else than the quote' "$TMP/planted.log" || true)
((found == planted && planted == n_readme + n_docs)) ||
  fail planted "$found mismatches reported for $planted planted digits in $((n_readme + n_docs)) examples: $(head -20 "$TMP/planted.log")"

# 3. malformed markers are refused
printf '# x\n\n<!-- run -->\n```sh\nbouncer --version\n```\n\nno output block\n' >"$TMP/bad1.md"
printf '# x\n\n<!-- run -->\n```sh\nls /\n```\n\n```text\nbin\n```\n' >"$TMP/bad2.md"
rc=0; "$PY" "$CHECK" --bouncer "$BOUNCER" --root "$SRC" "$TMP/bad1.md" >"$TMP/bad1.log" 2>&1 || rc=$?
((rc == 1)) && grep -q 'not followed by a ```text block' "$TMP/bad1.log" || fail markers "a marker without an output block: exit $rc, $(cat "$TMP/bad1.log")"
rc=0; "$PY" "$CHECK" --bouncer "$BOUNCER" --root "$SRC" "$TMP/bad2.md" >"$TMP/bad2.log" 2>&1 || rc=$?
((rc == 1)) && grep -q 'must be one `bouncer ...` command' "$TMP/bad2.log" || fail markers "a marked command that is not bouncer: exit $rc, $(cat "$TMP/bad2.log")"

finish "docs_examples: $(tail -1 "$TMP/ok.log" | sed 's/^check_docs_examples: //'); $found of $planted planted digits found"
