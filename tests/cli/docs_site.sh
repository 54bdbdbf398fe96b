#!/usr/bin/env bash
# The documentation site (mkdocs.yml, docs/), built as `tools/setup docs` builds it, in a copy:
#   - tools/gen_docs.py writes a reference page for every command `bouncer --help` lists, and
#     each page holds every option of that command's --help (read here with grep);
#   - mkdocs.yml's nav lists every generated reference page (a new command needs its line);
#   - the Python API page has a section for every name of bouncer.__all__, the C++ API page
#     one for every public header; that page (tools/cpp_api.py) against the headers, read
#     here line by line: every word of each header's opening comment, its formula and table
#     lines kept as lines, every one-line declaration at namespace scope (outside detail
#     namespaces) in a C++ block followed by its comment, ImpactMap's public members without
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

# The C++ API page (tools/cpp_api.py) against the headers, read here line by line: each
# header's opening comment keeps every word in order, and its indented lines (formulas,
# tables) stay lines; every one-line function declaration at namespace scope outside detail
# namespaces is in a C++ block of its header's section, followed by the comment above it;
# certify_periodic and ImpactMap (public members, no bodies or private parts) and the
# DoubleInterval header (paragraphs, a formula block, a list) as expected.
cat >"$TMP/check_cpp.py" <<'PY'
# The C++ API page against the headers, read here line by line (not with tools/cpp_api.py):
import html, os, re, sys
src, ref = sys.argv[1], sys.argv[2]
inc = os.path.join(src, "lib/include")
cpp = open(os.path.join(ref, "cpp.md"), encoding="utf-8").read()
headers = sorted(os.path.relpath(os.path.join(d, f), inc) for d, _, fs in os.walk(os.path.join(inc, "bouncer"))
                 for f in fs if f.endswith(".hpp"))
problems = []
def words(text):  # the words of a text, without Markdown's code fences and escapes
    return re.findall(r"[A-Za-z0-9]+", html.unescape(re.sub(r"^```\w*$", "", text, flags=re.M)))

def section(h):  # the page's text for header h: from its heading to the next header's
    start = cpp.find(f"### `{h}`")
    if start < 0:
        return None
    m = re.compile(r"^#{2,3} ", re.M).search(cpp, start + 4)
    return cpp[start:m.start() if m else len(cpp)]

def contains(seq, sub):
    n = len(sub)
    return any(seq[k:k + n] == sub for k in range(len(seq) - n + 1))

n_decls = n_commented = 0
for h in headers:
    text = open(os.path.join(inc, h), encoding="utf-8").read()
    lines = text.split("\n")
    sec = section(h)
    if sec is None:
        problems.append(f"{h}: no section")
        continue
    # 1. the opening comment, every word in order (nothing lost), before the declarations;
    #    its indented lines (formulas, tables) kept as lines, not run into a paragraph
    top = []
    for l in lines:
        if not l.startswith("//"):
            break
        top.append(l[2:])
    intro = sec.split("\n**Declares:**")[0].split("\n#### ")[0]
    if not contains(words(intro), words("\n".join(top))):
        problems.append(f"{h}: the opening comment's words are not all in its section, in order")
    page_lines = {l.strip() for l in sec.split("\n")}
    run_is_list = False  # a run of lines indented more than the text: a list if its first has a marker
    for l in top:
        indented = re.match(r"^ {2,}\S", l) is not None
        if not indented:
            run_is_list = False
            continue
        if not run_is_list and re.match(r"^\s*([*-]|\d+\.|\(\d+\))\s", l):
            run_is_list = True
        if not run_is_list and l.strip() not in page_lines:
            problems.append(f"{h}: the indented comment line {l.strip()[:60]!r} is not a line of the page")
    # 2. one-line function declarations at namespace scope (column 0, outside detail
    #    namespaces: brace depth counted here), each in a C++ block, followed by the words
    #    of the comment directly above it before the next declaration's heading
    depth, hidden_at = 0, None
    for k, l in enumerate(lines):
        code = re.sub(r'//.*|"(\\.|[^"\\])*"|\'(\\.|[^\'\\])*\'', "", l)
        m = re.match(r"namespace\s+(\w*)\s*\{", code.strip())
        if m and hidden_at is None and (m.group(1) == "detail" or m.group(1).endswith("_detail") or m.group(1) == ""):
            hidden_at = depth
        if (hidden_at is None and depth == 1 and re.match(r"[A-Za-z_][\w:<>,*& ]* [*&]?~?\w+\(.*\);$", l)
                and not re.match(r"(static_assert|using|return|template|extern|friend|typedef)\b", l)):
            n_decls += 1
            at = sec.find("\n" + l.strip() + "\n")
            block_start = sec.rfind("```cpp\n", 0, at + 1)
            if at < 0 or block_start < 0 or "```\n" in sec[block_start + 7:at + 1]:
                problems.append(f"{h}:{k + 1}: {l.strip()[:60]!r} is not in a C++ block of its section")
                continue
            comment = []
            j = k - 1
            while j >= 0 and lines[j].startswith("//"):
                comment.insert(0, lines[j][2:])
                j -= 1
            if comment and j >= 0 and lines[j].strip() != "" and not lines[j].rstrip().endswith(("{", "}", ";")):
                comment = []  # e.g. the line before is a template head: not a one-line declaration's comment
            if comment:
                n_commented += 1
                after = sec[at:]
                nxt = re.search(r"^#{3,4} ", after, re.M)
                if not contains(words(after[:nxt.start()] if nxt else after), words("\n".join(comment))):
                    problems.append(f"{h}:{k + 1}: the comment above {l.strip()[:50]!r} does not follow it")
        depth += code.count("{") - code.count("}")
        if hidden_at is not None and depth <= hidden_at:
            hidden_at = None
# 3. specific: certify_periodic and ImpactMap as declarations with their comments; the
#    DoubleInterval header in paragraphs, a formula block and a list; detail names absent
pc = section("bouncer/verify/periodic_certify.hpp") or ""
if not re.search(r"#### `certify_periodic\(\)`\n\n```cpp\nPeriodicCertificate certify_periodic\(const PeriodicQuestion& q\);\n```\n\nOne certification at one parameter value", pc):
    problems.append("certify_periodic: not a heading, its declaration and then its comment")
im = section("bouncer/model/impact_map.hpp") or ""
m = re.search(r"#### `ImpactMap`\n\n```cpp\n(template <class T>\nclass ImpactMap \{.*?\n\};)\n```", im, re.S)
if not m:
    problems.append("ImpactMap: no heading with the class's declaration")
else:
    body = m.group(1)
    for want in ["// One step. Throws Undecided when a branch cannot be decided (intervals, NaN).\n  StepResult<T> step(const State<T>& s) const;",
                 "explicit ImpactMap(Model<T> model);", "struct Collapse {"]:
        if want not in body:
            problems.append(f"ImpactMap: the class body lacks {want[:50]!r}")
    for unwanted in ["m_;", "zero_", "private:", "{ return", "static_assert", "void ride("]:
        if unwanted in body:
            problems.append(f"ImpactMap: the class body shows {unwanted!r} (private members or function bodies)")
di = section("bouncer/scalar/interval_double.hpp") or ""
intro = di.split("\n**Declares:**")[0]
paragraphs = [p for p in intro.split("\n\n")[1:] if p and not p.startswith(("```", "- ", "#"))]
if len(paragraphs) < 6 or "```text\na + b:  TwoSum" not in intro or intro.count("\n- ") < 4:
    problems.append(f"interval_double.hpp: {len(paragraphs)} paragraphs, want >= 6, the a + b table in a text block and 4 list items")
# no function bodies: no `return` in the code of any C++ block (comments aside)
for b in re.findall(r"```cpp\n(.*?)\n```", cpp, re.S):
    for l in b.split("\n"):
        if re.search(r"\breturn\b", re.sub(r"//.*", "", l)):
            problems.append(f"a function body in a C++ block: {l.strip()[:60]!r}")
for name in ["next_up", "round_to", "PointGuards", "contract_detail", "interval_double_detail::"]:
    if re.search(rf"^#### .*{name}", cpp, re.M) or re.search(rf"^\S*{name}\b.*\(", cpp, re.M):
        problems.append(f"{name}: from a detail namespace, but on the page")
if n_decls < 150 or n_commented < 80 or problems:
    print(f"{n_decls} one-line declarations ({n_commented} with a comment) checked; {len(problems)} problems:")
    print("\n".join(problems[:20]))
    sys.exit(1)
print(f"cpp.md: {len(headers)} headers, {n_decls} one-line declarations ({n_commented} with a comment) in C++ blocks followed by their comments")
PY
"$PY" "$TMP/check_cpp.py" "$SRC" "$TMP/docs/reference" >"$TMP/cpp.log" 2>&1 || fail cpp.md "$(head -12 "$TMP/cpp.log")"
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
if "$PY" "$TMP/check_cpp.py" "$SRC" "$TMP/bad_ref" >"$TMP/cpp_bad.log" 2>&1; then
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
