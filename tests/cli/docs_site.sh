#!/usr/bin/env bash
# The documentation site (mkdocs.yml, docs/), built as `tools/setup docs` builds it, in a copy:
#   - tools/gen_docs.py writes a reference page for every command `bouncer --help` lists, and
#     each page holds every option of that command's --help (read here with grep);
#   - mkdocs.yml's nav lists every generated reference page (a new command needs its line);
#   - the Python API page has a section for every name of bouncer.__all__, the C++ API page
#     one for every public header; that page (tools/cpp_api.py) against the headers, read
#     here line by line: every word of each header's opening comment, its formula and table
#     lines kept as lines, every type at namespace scope (outside detail namespaces) under a
#     heading, every one-line function declaration there in a C++ block followed by its
#     comment, no function bodies, ImpactMap's public members without
#     bodies; the check fails on a planted flattened formula and a dropped comment; a small
#     header by hand (what is shown, what is left out) and a broken one (its comment, a note);
#   - `mkdocs build --strict` succeeds (a warning, e.g. a link to a missing page, is an error);
#   - tools/check_site_links.py finds every internal link, anchor and file of the built site,
#     and no script, stylesheet or image loaded from the network (the site works offline);
#     and it does fail on a planted broken anchor and a planted missing file;
#   - headless Chromium renders the front page and a reference page (tools/screenshot_site.py:
#     the theme's navigation bar and text in each screenshot), where chromium is installed;
#   - README.md (the entry point, outside the site, read on GitHub) is under 200 lines and each
#     of its relative links names a file or directory of the repository.
# Exit 77 (skipped) when mkdocs is not installed (`tools/setup docs` installs it).
# Usage: bash docs_site.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
command -v mkdocs >/dev/null || skip "mkdocs is not installed (apt-get install mkdocs, or tools/setup docs)"
PY=python3; [[ -x /usr/bin/python3 ]] && PY=/usr/bin/python3

cp "$SRC/mkdocs.yml" "$TMP/"
cp -r "$SRC/docs" "$TMP/docs"
rm -rf "$TMP/docs/reference" "$TMP/docs/pictures"  # generated: made fresh below
"$PY" "$SRC/tools/gen_docs.py" --bouncer "$BOUNCER" --docs "$TMP/docs" >/dev/null || die "tools/gen_docs.py failed"

mapfile -t cmds < <("$BOUNCER" --help | awk '/^Subcommands:/ {f = 1; next} f && /^  [a-z]/ {print $1} f && /^$/ {f = 0}')
((${#cmds[@]} >= 10)) || die "bouncer --help lists only ${#cmds[@]} commands"
for c in "${cmds[@]}"; do
  page=$TMP/docs/reference/$c.md
  [[ -f $page ]] || { fail "reference/$c.md" "not generated"; continue; }
  while read -r opt; do
    grep -qF -- "$opt" "$page" || fail "reference/$c.md" "does not document $opt"
  done < <("$BOUNCER" "$c" --help | grep -oE -- '^  (-[A-Za-z],)?--[a-z0-9-]+' | sed 's/^ *//; s/^-[A-Za-z],//')
  grep -qE -- "^ +- [a-z-]+: reference/$c\.md$" "$TMP/mkdocs.yml" || fail mkdocs.yml "the nav does not list reference/$c.md"
done
[[ -s $TMP/docs/claims.md ]] || fail claims.md "missing (committed; checked by cli.reproduce_claims_table)"
# The API pages: every public Python name (bouncer.__all__) has its section, every public
# header its own (both generated from the sources).
"$PY" - "$SRC" "$TMP/docs/reference" >"$TMP/api.log" 2>&1 <<'PY' || fail api "$(head -5 "$TMP/api.log")"
import ast, os, re, sys
src, ref = sys.argv[1], sys.argv[2]
init = ast.parse(open(os.path.join(src, "python/bouncer/__init__.py")).read())
names = [e.value for n in init.body if isinstance(n, ast.Assign) and getattr(n.targets[0], "id", "") == "__all__" for e in n.value.elts]
py = open(os.path.join(ref, "python.md")).read()
missing = [n for n in names if not re.search(rf"^## (class )?{re.escape(n)}(\(\))?$", py, re.M)]
cpp = open(os.path.join(ref, "cpp.md")).read()
headers = [os.path.relpath(os.path.join(d, f), os.path.join(src, "lib/include")) for d, _, fs in os.walk(os.path.join(src, "lib/include/bouncer")) for f in fs if f.endswith(".hpp")]
missing += [h for h in headers if f"### `{h}`" not in cpp]
if len(names) < 20 or len(headers) < 20 or missing:
    print(f"{len(names)} names, {len(headers)} headers; missing: {missing[:10]}")
    sys.exit(1)
PY

# The C++ API page against the headers (tests/cli/lib/check_cpp_page.py: every word of each
# opening comment, formula lines kept, types and one-line declarations with their comments,
# no function bodies, ImpactMap's public members) ...
CHECK_CPP=$SRC/tests/cli/lib/check_cpp_page.py
"$PY" "$CHECK_CPP" "$SRC" "$TMP/docs/reference" >"$TMP/cpp.log" 2>&1 || fail cpp.md "$(head -12 "$TMP/cpp.log")"
# ... and it can fail: the DoubleInterval header's first formula block run into its paragraph,
# the comment of certify_periodic left out
mkdir -p "$TMP/bad_ref"
"$PY" - "$TMP/docs/reference/cpp.md" "$TMP/bad_ref/cpp.md" <<'PY'
import re, sys
md = open(sys.argv[1], encoding="utf-8").read()
at = md.index("### `bouncer/scalar/interval_double.hpp`")
block = re.compile(r"\n\n```text\n(.*?)\n```\n", re.S).search(md, at)
md = md[:block.start()] + " " + " ".join(block.group(1).split()) + "\n" + md[block.end():]
md = re.sub(r"\nOne certification at one parameter value[^\n]*\n", "\n", md)
open(sys.argv[2], "w", encoding="utf-8").write(md)
PY
if "$PY" "$CHECK_CPP" "$SRC" "$TMP/bad_ref" >"$TMP/cpp_bad.log" 2>&1; then
  fail cpp.md "the check passes a page with a formula block run into prose and a comment left out"
fi
grep -q "interval_double.hpp: the indented comment line" "$TMP/cpp_bad.log" && grep -q "certify_periodic" "$TMP/cpp_bad.log" ||
  fail cpp.md "the check does not name the planted faults: $(head -5 "$TMP/cpp_bad.log")"
# A header tools/cpp_api.py cannot follow (an unmatched brace) still gets its comment; a
# small one, by hand: what is shown and what is left out.
printf '// Opening line.\n//\n// Second paragraph:\n//     x = 1 + 2\n//   * item one\n//     continued\n//   * item two\n#pragma once\n#include <vector>\nnamespace bouncer {\nnamespace detail {\ninline int hidden_fn() { return 1; }\n}\nnamespace {\nint anon_fn();\n}\n// A documented function.\nint visible_fn(int x);\nextern template class Foo<int>;\n// A struct.\nstruct S {\n  int a = 1;  // field a\n  void f() const { body_marker(); }\n\n private:\n  int secret_;\n};\n}  // namespace bouncer\n' >"$TMP/small.hpp"
"$PY" "$SRC/tools/cpp_api.py" "$TMP/small.hpp" >"$TMP/small.md" 2>&1 || fail cpp_api.py "exited $? on a small header: $(head -5 "$TMP/small.md")"
for want in 'Opening line.' 'x = 1 + 2' '- item one continued' '- item two' '#### `visible_fn()`' 'int visible_fn(int x);' \
            'A documented function.' '#### `S`' '  int a = 1;  // field a' '  void f() const;' 'A struct.'; do
  grep -qxF -- "$want" "$TMP/small.md" || fail cpp_api.py "the small header's page lacks the line '$want': $(head -40 "$TMP/small.md")"
done
for unwanted in hidden_fn anon_fn 'Foo<int>' body_marker secret_ private include pragma; do
  ! grep -qF -- "$unwanted" "$TMP/small.md" || fail cpp_api.py "the small header's page shows $unwanted"
done
printf '// Still documented.\nnamespace bouncer {\nstruct Broken {\n  int x;\n' >"$TMP/broken.hpp"
"$PY" "$SRC/tools/cpp_api.py" "$TMP/broken.hpp" >"$TMP/broken.md" 2>"$TMP/broken.err" || fail cpp_api.py "exited $? on a broken header"
grep -qx 'Still documented.' "$TMP/broken.md" && grep -q 'could not be read' "$TMP/broken.md" ||
  fail cpp_api.py "a header it cannot follow does not get its comment and a note: $(cat "$TMP/broken.md" "$TMP/broken.err")"

if ! (cd "$TMP" && mkdocs build --strict -q -d "$TMP/site") >"$TMP/mkdocs.log" 2>&1; then
  fail "mkdocs build --strict" "$(grep -E 'WARNING|ERROR|Error' "$TMP/mkdocs.log" | head -5)"
fi
[[ -f $TMP/site/index.html && -f $TMP/site/reference/orbit.html ]] || die "the site has no index.html or reference/orbit.html"
"$PY" "$SRC/tools/check_site_links.py" "$TMP/site" >"$TMP/links.log" 2>&1 || fail links "$(head -5 "$TMP/links.log")"
# It renders: headless Chromium screenshots of the front page and a reference page, checked
# for the navigation bar and text (tools/screenshot_site.py; 77: no chromium here, which
# `tools/setup docs` installs: said, not failed).
rc=0
"$PY" "$SRC/tools/screenshot_site.py" "$TMP/site" "$TMP/shots" >"$TMP/shots.log" 2>&1 || rc=$?
case $rc in
  0) ;;
  77) echo "docs_site: $(cat "$TMP/shots.log")" ;;
  *) fail screenshots "$(head -3 "$TMP/shots.log")" ;;
esac

# the link checker can fail: a missing anchor, a missing picture
mkdir -p "$TMP/bad/sub"
printf '<html><body><h1 id="top">x</h1><a href="sub/b.html#nowhere">b</a><img src="pic.png"></body></html>' >"$TMP/bad/index.html"
printf '<html><body><a href="../index.html#top">a</a></body></html>' >"$TMP/bad/sub/b.html"
"$PY" "$SRC/tools/check_site_links.py" "$TMP/bad" >"$TMP/bad.log" 2>&1 && fail check_site_links "passes a site with broken links"
grep -q "no id 'nowhere'" "$TMP/bad.log" || fail check_site_links "does not report the missing anchor: $(cat "$TMP/bad.log")"
grep -q "pic.png does not exist" "$TMP/bad.log" || fail check_site_links "does not report the missing picture: $(cat "$TMP/bad.log")"
lines=$(wc -l <"$SRC/README.md")
((lines < 200)) || fail README "$lines lines: the README is the entry point, keep it under 200 (the rest belongs in docs/)"
"$PY" - "$SRC" >"$TMP/readme.log" 2>&1 <<'PY' || fail README "$(cat "$TMP/readme.log")"
import os, re, sys
src = sys.argv[1]
text = open(os.path.join(src, "README.md"), encoding="utf-8").read()
text = re.sub(r"```.*?```", "", text, flags=re.S)
bad = []
links = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", text)
for target in links:
    if re.match(r"[a-z]+:", target):
        continue
    if not os.path.exists(os.path.join(src, target)):
        bad.append(target)
if bad or len(links) < 10:
    sys.exit(f"README.md links to missing files: {bad}" if bad else f"only {len(links)} links in README.md")
PY
finish "docs_site: ${#cmds[@]} reference pages; $(tail -1 "$TMP/cpp.log"); mkdocs --strict builds; $(tail -1 "$TMP/links.log" | sed 's/^check_site_links: //')"
