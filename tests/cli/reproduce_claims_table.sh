#!/usr/bin/env bash
# The claims table (docs/claims.md, the documentation's Claims page, committed so that it can
# be read on GitHub) is generated, not hand-kept: the block between
# <!-- claims:begin ... --> and <!-- claims:end --> must equal `bouncer reproduce --claims-table`
# (printed from data/paper/manifest.toml, compiled into the binary). Also: the table has one
# row per claim of the manifest, every row has the five columns, and the manifest's expected
# verdict word appears in the row's verdict cell. The README's one-sentence summary (after its
# `<!-- claims-summary ... -->` marker: "N claims of the paper: K confirmed, ...") states the
# number of claims and of each expected verdict of the manifest.
# Usage: bash reproduce_claims_table.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
"$BOUNCER" reproduce --claims-table > "$TMP/generated.md"
python3 - "$SRC/docs/claims.md" "$TMP/generated.md" "$SRC/data/paper/manifest.toml" "$SRC/README.md" <<'PY'
import collections, re, sys, tomllib
page, generated, manifest, readme = sys.argv[1:5]
text = open(page, encoding="utf-8").read()
begin = [m.end() for m in re.finditer(r"<!-- claims:begin[^>]*-->\n", text)]
end = [m.start() for m in re.finditer(r"<!-- claims:end -->", text)]
if len(begin) != 1 or len(end) != 1 or end[0] < begin[0]:
    sys.exit("FAIL: docs/claims.md must hold exactly one claims:begin ... claims:end block")
block = text[begin[0]:end[0]]
gen = open(generated, encoding="utf-8").read()
if block != gen:
    import difflib
    sys.stdout.writelines(difflib.unified_diff(block.splitlines(True), gen.splitlines(True), "docs/claims.md block", "generated"))
    sys.exit("FAIL: the claims block of docs/claims.md differs from `bouncer reproduce --claims-table`; paste the generated table")
m = tomllib.load(open(manifest, "rb"))
rows = [l for l in gen.splitlines() if l.startswith("| ") and not l.startswith("| # ")]
if len(rows) != len(m["claim"]):
    sys.exit(f"FAIL: {len(rows)} table rows for {len(m['claim'])} claims")
for row, claim in zip(rows, m["claim"]):
    cells = [c.strip() for c in re.split(r"(?<!\\)\|", row)[1:-1]]
    if len(cells) != 5:
        sys.exit(f"FAIL: row {claim['row']} has {len(cells)} cells, not 5")
    if cells[0] != claim["row"]:
        sys.exit(f"FAIL: row {cells[0]} is not claim {claim['row']}")
    if claim["expected"] not in cells[2].replace("*", ""):
        sys.exit(f"FAIL: row {claim['row']}: verdict cell {cells[2]!r} does not say {claim['expected']!r}")
text = open(readme, encoding="utf-8").read()
m2 = re.search(r"<!-- claims-summary[^>]*-->\n(.*?)\n\n", text, re.S)
if not m2:
    sys.exit("FAIL: README.md has no <!-- claims-summary --> paragraph")
summary = " ".join(m2.group(1).split())
n = re.search(r"(\d+) claims of the paper", summary)
if not n or int(n.group(1)) != len(m["claim"]):
    sys.exit(f"FAIL: the README's claims summary does not say '{len(m['claim'])} claims of the paper': {summary[:120]}")
counts = collections.Counter(c["expected"] for c in m["claim"])
for word in ("confirmed", "corrected", "refuted", "not reproduced", "consistent"):
    said = re.search(r"(\d+) " + word + r"\b", summary)
    if not said or int(said.group(1)) != counts.get(word, 0):
        sys.exit(f"FAIL: the README's claims summary should say '{counts.get(word, 0)} {word}': {summary[:200]}")
if sum(counts.values()) != len(m["claim"]) or set(counts) - {"confirmed", "corrected", "refuted", "not reproduced", "consistent"}:
    sys.exit(f"FAIL: expected verdicts outside the five words: {dict(counts)}")
print(f"ok: docs/claims.md claims block = generated table ({len(rows)} claims); README summary = manifest counts")
PY
