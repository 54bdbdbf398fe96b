#!/usr/bin/env bash
# The paper manifest against the paper's LaTeX source: data/paper/figure-labels.txt equals
# the .tex's \label{fig:...} in order, and every panel's caption is the .tex caption of its
# figure. The .tex is not in the repository (it is the paper's, not ours): give it with
# $BOUNCER_PAPER_TEX, or it is looked for beside the checkout (../shared/paper/); without it
# this test exits 77 (ctest: skipped, visibly) instead of passing.
# Usage: bash reproduce_manifest_tex.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
TEX=${BOUNCER_PAPER_TEX:-$SRC/../shared/paper/langer-miller-2014.tex}
[[ -f $TEX ]] || skip "the paper's .tex is not here (set BOUNCER_PAPER_TEX=PATH to check against it)"
python3 - "$SRC/data/paper/manifest.toml" "$SRC/data/paper/figure-labels.txt" "$TEX" <<'PY'
import re, sys, tomllib
manifest, labels_file, tex = sys.argv[1:4]
m = tomllib.load(open(manifest, "rb"))
labels = [l.strip() for l in open(labels_file) if l.strip() and not l.startswith("#")]
panels = [p for p in m.get("panel", []) if "twin_of" not in p and "beside" not in p]
errors = []
src = open(tex, encoding="utf-8").read()
tex_labels = re.findall(r"\\label\{(fig:[^}]*)\}", src)
if tex_labels != labels:
    errors.append(f"figure-labels.txt differs from the .tex labels: {tex_labels}")
captions = 0
for fig in re.findall(r"\\begin\{figure\}(.*?)\\end\{figure\}", src, re.S):
    cap = re.search(r"\\caption\{(.*)\}\s*\\label\{(fig:[^}]*)\}", fig, re.S)
    if not cap:
        continue
    for p in panels:
        if p["figure"] == cap.group(2):
            captions += 1
            if p["caption"] != cap.group(1).strip():
                errors.append(f"{p['label']}: caption differs from the .tex")
if captions == 0:
    errors.append("no panel's caption was compared (the .tex has no captioned figures?)")
if errors:
    print("FAIL:\n  " + "\n  ".join(errors)); sys.exit(1)
print(f"ok: {len(labels)} labels and {captions} panel captions equal the .tex's")
PY
