#!/usr/bin/env python3
"""The C++ API page (docs/reference/cpp.md, written by tools/gen_docs.py with tools/cpp_api.py)
against the headers, read here line by line, not with cpp_api.py's tokenizer:
  - each header has its section, and its opening comment keeps every word, in order; the
    comment's indented lines that are not list items (formulas, tables) stay lines;
  - every type at namespace scope (struct, class, enum, using alias at column 0, outside
    detail and anonymous namespaces: brace depth counted here) has a heading;
  - every one-line function declaration there is in a C++ block of its header's section,
    followed (before the next heading) by the words of the comment directly above it;
  - no C++ block holds a function body (no `return` outside comments);
  - certify_periodic: its heading, its declaration, then its comment; ImpactMap: its class
    with its public members and their comments, no private members or bodies; the
    DoubleInterval header's opening comment in paragraphs, its `a + b` table in a text block,
    its slow paths as a list; names of detail namespaces absent.

    check_cpp_page.py SOURCE-DIR REFERENCE-DIR     exit 0: all hold (a summary line);
                                                   1: the problems, one a line
Used by tests/cli/docs_site.sh (which also checks that it fails on planted faults).
"""
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

n_decls = n_commented = n_types = 0
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
        t = re.match(r"(?:(?:struct|class|union|enum(?: class)?) (\w+)[^;]*\{|using (\w+) =)", l)
        if hidden_at is None and depth == 1 and t:  # a type at namespace scope: a heading names it
            n_types += 1
            if not re.search(rf"^#### .*`(\w+::)*{t.group(1) or t.group(2)}`", sec, re.M):  # a nested namespace qualifies it
                problems.append(f"{h}:{k + 1}: {t.group(1) or t.group(2)} has no heading in its section")
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
if n_decls < 150 or n_commented < 80 or n_types < 100 or problems:
    print(f"{n_types} types, {n_decls} one-line declarations ({n_commented} with a comment) checked; {len(problems)} problems:")
    print("\n".join(problems[:20]))
    sys.exit(1)
print(f"cpp.md: {len(headers)} headers, {n_types} types with their headings, {n_decls} one-line declarations ({n_commented} with a comment) in C++ blocks followed by their comments")
