#!/usr/bin/env bash
# The documentation's pictures (data/pictures/, copied into the site by tools/gen_docs.py)
# are drawn by `bouncer reproduce --pictures`:
#   * every picture README.md or a page of docs/ shows exists (data/pictures/NAME.png in the
#     README, pictures/NAME.png relative to the page in docs/), and every data/pictures/*.png is a file of a
#     [[picture]] entry of data/paper/manifest.toml (the Python example's figure aside: its
#     script draws it), and every entry's files are in data/pictures/;
#   * each committed PNG records (tEXt "Source") the command of its entry as reproduce runs
#     it: the same words, the scene under DIR/scenes/, --out DIR/pictures/NAME --quiet: the
#     picture was regenerated from the manifest, not drawn by hand with other options;
#   * `reproduce --pictures --only` draws one picture into DIR/pictures/, its report
#     references only existing files, and `bouncer audit DIR` finds it identical;
#   * --pictures with --quick is refused (exit 2), and so is a paper item in --only.
# Usage: bash readme_pictures.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"

python3 - "$SRC" <<'PY' || fail committed "see above"
import os, re, struct, sys, tomllib
src = sys.argv[1]
m = tomllib.load(open(os.path.join(src, "data/paper/manifest.toml"), "rb"))
pics = m.get("picture", [])
errors = []
files = {f: p for p in pics for f in p.get("files", [p["name"] + ".png"])}
shown = 0
pages = [os.path.join(src, "README.md")] + [os.path.join(d, f) for d, _, fs in os.walk(os.path.join(src, "docs"))
                                            for f in fs if f.endswith(".md")]
for page in pages:
    text = open(page, encoding="utf-8").read()
    for ref in re.findall(r"\]\(((?:\.\./)*(?:data/)?pictures/[A-Za-z0-9_.-]+\.png)\)", text):
        shown += 1
        name = os.path.basename(ref)
        if not os.path.isfile(os.path.join(src, "data/pictures", name)):
            errors.append(f"{os.path.relpath(page, src)} shows {ref}, which is not in data/pictures/")
        elif page.endswith("README.md") and ref != "data/pictures/" + name:
            errors.append(f"README.md shows {ref}: write data/pictures/{name}")
        elif not page.endswith("README.md") and os.path.normpath(os.path.join(os.path.dirname(page), ref)) != os.path.join(src, "docs", "pictures", name):
            errors.append(f"{os.path.relpath(page, src)} shows {ref}, which is not docs/pictures/{name} from there")
if shown < 10:
    errors.append(f"only {shown} pictures shown in README.md and docs/: is the pattern still right?")
committed = sorted(f for f in os.listdir(os.path.join(src, "data/pictures")) if f.endswith(".png"))
for f in committed:
    if f not in files and not f.startswith("python-"):
        errors.append(f"data/pictures/{f} is no [[picture]] entry's file")
for f in files:
    if f not in committed:
        errors.append(f"[[picture]] {files[f]['name']}: data/pictures/{f} missing")
def source_of(path):
    d = open(path, "rb").read()
    i = 8
    while i < len(d):
        n, = struct.unpack(">I", d[i:i + 4])
        t, c = d[i + 4:i + 8], d[i + 8:i + 8 + n]
        if t == b"tEXt" and c.startswith(b"Source\0"):
            return c[7:].decode()
        i += 12 + n
    return None
for f, p in files.items():
    path = os.path.join(src, "data/pictures", f)
    if not os.path.isfile(path):
        continue
    s = source_of(path)
    if s is None:
        errors.append(f"data/pictures/{f}: no Source in its PNG"); continue
    words = s.split()
    expected = p["command"][1:]
    got = words[1:]
    # the scene is read from DIR/scenes/NAME.toml, the output goes to DIR/pictures/NAME
    norm = []
    for k, w in enumerate(got):
        if k > 0 and got[k - 1] == "--scene":
            w = "data/scenes/" + os.path.basename(w)
        if k > 0 and got[k - 1] == "--out":
            w = ("pictures/" + os.path.basename(w)) if os.path.basename(os.path.dirname(w)) == "pictures" else w
        norm.append(w)
    want = expected + ["--out", "pictures/" + p["name"], "--quiet"]
    if norm != want:
        errors.append(f"data/pictures/{f} was drawn by `{' '.join(got)}`, not by reproduce --pictures (`{' '.join(want)}`)")
if errors:
    print("\n".join(errors)); sys.exit(1)
PY

D=$TMP/r
"$BOUNCER" reproduce --pictures --only tongues-p10 --out "$D" 2> "$TMP/err" || fail run "exit $?: $(cat "$TMP/err")"
[ -s "$D/pictures/tongues-p10.png" ] || fail run "pictures/tongues-p10.png missing"
[ -s "$D/scenes/picture-tongues-p10.toml" ] || fail run "the built-in scene was not written to DIR/scenes/"
cmp -s "$D/scenes/picture-tongues-p10.toml" "$SRC/data/scenes/picture-tongues-p10.toml" ||
  fail run "the built-in scene differs from data/scenes/picture-tongues-p10.toml (rebuild)"
for r in $(grep -o '](pictures/[^)]*)' "$D/report.md" | sed 's/^](//; s/)$//') $(grep -o 'src="[^"]*"' "$D/report.html" | sed 's/^src="//; s/"$//'); do
  [ -f "$D/$r" ] || fail report "references $r, which does not exist"
done
grep -q 'tongues-p10' "$D/report.md" || fail report "report.md does not name the picture"
grep -q '## Claims' "$D/report.md" && fail report "a pictures report has a claims section"
"$BOUNCER" audit "$D" > "$TMP/audit" 2>&1 || fail audit "exit $?: $(cat "$TMP/audit")"

refused bad-quick 'pictures' reproduce --pictures --quick --out "$TMP/x"
refused bad-only "unknown item 'fig:basin1'" reproduce --pictures --only fig:basin1 --out "$TMP/y"

finish "ok: the pictures of README and docs/ drawn by reproduce --pictures; one redrawn and audited"
