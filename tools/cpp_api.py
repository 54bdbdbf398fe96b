#!/usr/bin/env python3
"""The C++ API reference (docs/reference/cpp.md) from the public headers lib/include/bouncer.

The headers are documented with plain `//` comments (which Doxygen ignores), so this reads
them itself: for each header, the comment it opens with, in Markdown with its layout kept
(blank comment lines are paragraph breaks; lines indented more than the comment's text are
list items when they start with a marker (`*`, `-`, `1.`, `(1)`) and text blocks otherwise:
formulas, aligned tables, examples), and then its public declarations at namespace scope
(classes, structs, enums, functions and function templates, constants, using-aliases,
concepts, macros), each as a C++ code block with the `//` comment directly above it. Class
bodies show their public members with their comments (function bodies and constructor
initializer lists cut, private and protected members left out). Left out: `namespace detail`
and `*_detail`, anonymous namespaces, `extern template` and explicit instantiations,
static_assert, forward declarations, #include / #pragma, macros the header #undefs again.

It is not a C++ parser: a small tokenizer (comments, strings, preprocessor lines) and brace
matching. A header it cannot follow still gets its opening comment (and a note), never a
crash of the documentation build. Plain python3, standard library only; used by
tools/gen_docs.py (cpp_api_page).

    tools/cpp_api.py HEADER...     print the Markdown of these headers' sections (a preview)
"""
import os
import re
import sys
import textwrap
import unicodedata

LAYERS = ["base", "scalar", "model", "analysis", "verify", "run", "io", "workflow"]


# ---------------------------------------------------------------- Markdown helpers

def md_escape(s):
    s = s.replace("\\", "\\\\")
    for ch in "`*_[]":
        s = s.replace(ch, "\\" + ch)
    return s.replace("<", "&lt;").replace(">", "&gt;")


def md_inline(text):
    """Prose from a comment: Markdown-escaped, except `code spans`, which stay code."""
    parts = text.split("`")
    if len(parts) % 2 == 0:  # an unpaired backtick: all text
        out = md_escape(text)
    else:
        out = "".join(md_escape(p) if i % 2 == 0 else f"`{p}`" for i, p in enumerate(parts))
    # what would start a block at the beginning of a paragraph: a heading, a list, a quote
    out = re.sub(r"^(#|[-+]\s|=)", r"\\\1", out)
    return re.sub(r"^(\d+)\.(\s)", r"\1\\.\2", out)


def slugify(text):
    """MkDocs' (Python-Markdown toc's) id for a heading of this plain text."""
    text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode("ascii")
    text = re.sub(r"[^\w\s-]", "", text).strip().lower()
    return re.sub(r"[-\s]+", "-", text)


class Anchors:
    """The ids the toc extension gives headings, in page order (duplicates get _1, _2, ...)."""

    def __init__(self):
        self.used = set()

    def add(self, plain):
        i = slugify(plain)
        while i in self.used or not i:
            m = re.match(r"^(.*)_([0-9]+)$", i)
            i = f"{m.group(1)}_{int(m.group(2)) + 1}" if m else i + "_1"
        self.used.add(i)
        return i


# ---------------------------------------------------------------- comments as Markdown

MARKER = re.compile(r"^(\*|-|\d{1,2}\.|\(\d{1,2}\)|\([a-z]\))(\s+)(?=\S)")


def _indent(line):
    return len(line) - len(line.lstrip(" "))


def _segments(block):
    """An indented block split into lists and text blocks: a line with a list marker starts
    a list, which goes on while its lines are indented more than the marker or start the
    next item at the marker's indentation; other lines are text (formulas, tables), up to
    a marker as little indented as the text's first line."""
    out = []
    for line in block:
        ind, marked = _indent(line), MARKER.match(line.strip(" ")) is not None
        if out:
            is_list, lines, ind0 = out[-1]
            if is_list and (ind > ind0 or (ind == ind0 and marked)):
                lines.append(line)
                continue
            if not is_list and not (marked and ind <= ind0):
                lines.append(line)
                continue
        out.append((marked, [line], ind))
    return [(is_list, lines) for is_list, lines, _ in out]


def _list_md(lines, nested):
    ind0 = _indent(lines[0])
    items = []  # (marker, [content lines], text column)
    for l in lines:
        if l.strip() and _indent(l) <= ind0:
            m = MARKER.match(l.strip(" "))
            col = ind0 + m.end()
            items.append((m.group(1), [" " * col + l.strip(" ")[m.end():]], col))
        else:
            items[-1][1].append(l)
    numbers = [re.sub(r"\D", "", mk) for mk, _, _ in items]
    ordered = all(numbers) and [int(n) for n in numbers] == list(range(1, len(items) + 1))
    out, prev_blocks = [], 0
    for k, (mk, content, col) in enumerate(items):
        body = _blocks_md(content, col, nested=True)
        lead = f"{k + 1}. " if ordered else ("- " if mk in "*-" else f"- {md_escape(mk)} ")
        if k > 0 and prev_blocks > 1 and out[-1] != "":
            out.append("")  # after an item of several blocks (else the next one joins its last paragraph)
        out.append(lead + (body[0] if body else ""))
        out += [("    " + b) if b else "" for b in body[1:]]
        prev_blocks = len(body)
    return out


def _blocks_md(lines, base, nested):
    """Markdown lines for comment lines (text after '//'), `base` the prose column. Top
    level: fenced text blocks; nested (inside a list item): indented code blocks (MkDocs'
    fenced_code does not work inside lists)."""
    out = []

    def emit(block):
        if out and out[-1] != "":
            out.append("")
        out.extend(block)

    prose = []
    i = 0
    while i <= len(lines):
        line = lines[i] if i < len(lines) else ""
        if i < len(lines) and line.strip() and _indent(line) <= base:
            prose.append(line.strip())
            i += 1
            continue
        if prose:
            emit([md_inline(" ".join(prose))])
            prose = []
        if i == len(lines):
            break
        if not line.strip():  # a blank comment line: a paragraph break
            i += 1
            continue
        j = i  # an indented block: up to the next blank line or prose line
        while j < len(lines) and lines[j].strip() and _indent(lines[j]) > base:
            j += 1
        for is_list, block in _segments(lines[i:j]):
            if is_list:
                emit(_list_md(block, nested))
            else:
                text = textwrap.dedent("\n".join(l.rstrip() for l in block)).split("\n")
                emit(["    " + t if t else "" for t in text] if nested else ["```text", *text, "```"])
        i = j
    return out


def comment_md(lines):
    """Markdown for a // comment block (its lines without the '//')."""
    lines = [l.expandtabs().rstrip() for l in lines]
    lines = [l for l in lines if not re.match(r"^\s*(clang-format (on|off)|NOLINT)", l)]
    while lines and not lines[0].strip():
        lines.pop(0)
    while lines and not lines[-1].strip():
        lines.pop()
    if not lines:
        return ""
    base = min(_indent(l) for l in lines if l.strip())
    return "\n".join(_blocks_md(lines, base, nested=False)) + "\n"


# ---------------------------------------------------------------- tokens

TOKEN = re.compile(r"""
  (?P<comment>//[^\n]*)
| (?P<block>/\*.*?\*/)
| (?P<pp>^[ \t]*\#(?:\\\n|[^\n])*)
| (?P<raw>R"(?P<delim>[^()\s\\]{0,16})\(.*?\)(?P=delim)")
| (?P<string>"(?:\\.|[^"\\\n])*")
| (?P<char>'(?:\\.|[^'\\\n])*')
| (?P<number>\.?\d(?:[eEpP][+-]|[\w.'])*)
| (?P<ident>[A-Za-z_]\w*)
| (?P<nl>\n)
| (?P<ws>[ \t\r\f\v]+)
| (?P<punct>::|->|.)
""", re.S | re.M | re.X)

TRIVIA = ("comment", "block", "pp", "nl", "ws")


class Tok:
    __slots__ = ("kind", "text", "line", "own_line", "blank")

    def __init__(self, kind, text, line):
        self.kind, self.text, self.line = kind, text, line
        self.own_line = False  # a comment with nothing but spaces before it on its line
        self.blank = False     # a newline ending a line of nothing but spaces


def tokenize(text):
    toks, line, line_empty = [], 1, True
    pos = 0
    while pos < len(text):
        m = TOKEN.match(text, pos)
        kind = m.lastgroup if m.lastgroup != "delim" else "raw"
        t = Tok(kind, m.group(), line)
        if kind == "nl":
            t.blank = line_empty
            line_empty = True
        elif kind != "ws":
            t.own_line = line_empty
            line_empty = False
        toks.append(t)
        line += t.text.count("\n")
        pos = m.end()
    return toks


# ---------------------------------------------------------------- statements

class Stmt:
    def __init__(self, start, end, kind, body=None):
        self.start, self.end, self.kind, self.body = start, end, kind, body  # body: (open, close) token indices


HIDDEN_NAMESPACE = re.compile(r"^(detail|\w+_detail|)$")


class Header:
    def __init__(self, text):
        self.toks = tokenize(text)
        self.undefined = set(m.group(1) for m in re.finditer(r"^[ \t]*#\s*undef\s+(\w+)", text, re.M))

    # -- token helpers
    def text(self, i, j):
        return "".join(t.text for t in self.toks[i:j])

    def code(self, i, j):
        """The text of tokens i..j without comments and preprocessor lines, spaces collapsed."""
        return re.sub(r"\s+", " ", "".join(" " if t.kind in TRIVIA else t.text for t in self.toks[i:j])).strip()

    def next_code(self, i, end):
        while i < end and self.toks[i].kind in TRIVIA:
            i += 1
        return i

    def match_brace(self, i, end):
        depth = 0
        for j in range(i, end):
            t = self.toks[j]
            if t.kind == "punct":
                if t.text == "{":
                    depth += 1
                elif t.text == "}":
                    depth -= 1
                    if depth == 0:
                        return j
        raise ValueError(f"line {self.toks[i].line}: unmatched '{{'")

    def column(self, i):
        """Spaces before token i on its line."""
        col = 0
        k = i - 1
        while k >= 0 and self.toks[k].kind == "ws":
            col += len(self.toks[k].text.expandtabs())
            k -= 1
        return col

    # -- splitting a scope into statements
    def scan(self, i, end):
        """Yield ('trivia', index) and Stmt items of the token range [i, end)."""
        toks = self.toks
        while i < end:
            t = toks[i]
            if t.kind in TRIVIA:
                yield ("trivia", i)
                i += 1
                continue
            start, depth, body = i, 0, None
            kind = None
            if t.kind == "ident" and t.text in ("public", "private", "protected"):
                k = self.next_code(i + 1, end)
                if k < end and toks[k].text == ":":
                    yield Stmt(start, k + 1, "access")
                    i = k + 1
                    continue
            macro_call = t.kind == "ident" and re.fullmatch(r"[A-Z][A-Z0-9_]*", t.text) is not None
            while i < end:
                t = toks[i]
                if t.kind == "punct":
                    if t.text in "([":
                        depth += 1
                    elif t.text in ")]":
                        depth -= 1
                        if depth == 0 and macro_call:
                            k = i + 1
                            while k < end and toks[k].kind in ("ws", "comment", "block"):
                                k += 1
                            if k >= end or toks[k].kind == "nl":  # MACRO(...) alone on its line
                                kind = "macro_call"
                                i += 1
                                break
                    elif t.text == ";" and depth == 0:
                        i += 1
                        break
                    elif t.text == "{" and depth == 0:
                        close = self.match_brace(i, end)
                        kind = kind or self.classify(start, i)
                        if kind == "function" and body is None and self.init_colon(start, i) is not None:
                            k = i - 1
                            while k > start and toks[k].kind in TRIVIA:
                                k -= 1
                            if toks[k].kind == "ident" or toks[k].text == ">":  # a member initializer x{...}
                                i = close + 1
                                continue
                        if body is None:
                            body = (i, close)
                        i = close + 1
                        if kind in ("namespace", "extern", "function"):
                            break
                        continue
                    elif t.text == "}" and depth == 0:  # belongs to the enclosing scope
                        if i == start:  # a stray '}' (preprocessor branches?): passed over
                            i += 1
                            kind = "skip"
                        break
                macro_call = macro_call and (i == start or t.kind in ("ws", "nl") or depth > 0 or t.text == "(")
                i += 1
            yield Stmt(start, i, kind or self.classify(start, i), body)

    def classify(self, i, j):
        head = self.code(i, j)
        h = strip_template(head)
        if re.match(r"(inline\s+)?namespace\b", h):
            return "namespace"
        if re.match(r'extern\s*"C', h):
            return "extern"
        if head.startswith("template") and not h.startswith("concept") and not head.startswith("template <") \
                and not head.startswith("template<"):
            return "instantiation"
        if re.match(r"extern\s+template\b", h):
            return "instantiation"
        if re.match(r"(static_assert|using\s+namespace)\b", h) or h in ("", ";"):
            return "skip"
        if re.match(r"concept\b", h):
            return "concept"
        if re.match(r"(using|typedef)\b", h):
            return "alias"
        if re.match(r"(\[\[[^\]]*\]\]\s*)*(class|struct|union)\b", h):
            return "class"
        if re.match(r"enum\b", h):
            return "enum"
        before = h.split("(")[0]
        if "(" in top_level(h) and "=" not in top_level(before) or re.search(r"\boperator\b", before):
            return "function"
        return "variable"


def strip_template(head):
    """The head without its leading `template <...>` (all of them)."""
    while True:
        m = re.match(r"template\s*<", head)
        if not m:
            return head
        depth, k = 0, m.end() - 1
        for k in range(m.end() - 1, len(head)):
            if head[k] in "<(":
                depth += 1
            elif head[k] in ">)":
                depth -= 1
                if depth == 0:
                    break
        head = head[k + 1:].lstrip()


def top_level(s, angles=False):
    """s with everything inside parentheses, brackets and braces removed (the opening one
    kept as a mark); angles: template arguments <...> removed too (not for operator<)."""
    out, depth, angle = [], 0, 0
    for ch in s:
        if angles and depth == 0 and ch == "<":
            angle += 1
        elif angles and depth == 0 and ch == ">" and angle > 0:
            angle -= 1
        elif angle > 0:
            continue
        elif ch in "([{":
            if depth == 0:
                out.append(ch)
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif depth == 0:
            out.append(ch)
    return "".join(out)


def decl_name(kind, head):
    h = strip_template(head)
    if kind == "macro":
        m = re.match(r"#\s*define\s+(\w+)", h)
        return m.group(1) if m else ""
    if kind in ("class", "enum"):
        h = re.sub(r"\[\[[^\]]*\]\]|alignas\s*\([^)]*\)", " ", h)
        m = re.match(r"(?:enum\s+(?:class|struct)?|class|struct|union|enum)\s*(\w+)", h)
        return m.group(1) if m else ""
    if kind == "alias":
        m = re.match(r"using\s+(\w+)", h)
        if m:
            return m.group(1)
        m = re.search(r"(\w+)\s*;?\s*$", h)
        return m.group(1) if m else ""
    if kind == "concept":
        m = re.match(r"concept\s+(\w+)", h)
        return m.group(1) if m else ""
    if kind == "function":
        m = re.search(r"\boperator\b\s*(\(\s*\)|\[\s*\]|[^(]+?)\s*\(", h)
        if m:  # operator<<, operator(), operator bool
            op = m.group(1)
            return "operator" + (" " + op if op[0].isalnum() else re.sub(r"\s+", "", op))
        for m in re.finditer(r"((?:\w+\s*::\s*)*~?\w+)\s*\(", top_level(h, angles=True)):
            if m.group(1) not in ("decltype", "noexcept", "requires", "alignas", "throw", "__attribute__"):
                return re.sub(r"\s+", "", m.group(1))
        return ""
    m = re.match(r"([^=({;\[]*?)(\w+)\s*(?:\[[^\]]*\]\s*)*(?:=|\{|;|$)", top_level(h).rstrip(";").strip() + ";")
    return m.group(2) if m else ""


# ---------------------------------------------------------------- declarations

class Entry:
    def __init__(self, kind, name, code, comment, line, end_line=None):
        self.kind, self.name, self.code, self.comment, self.line = kind, name, code, comment, line
        self.end_line = line if end_line is None else end_line  # its last line in the header


def comment_text(tok):
    return tok.text[2:] if tok.kind == "comment" else re.sub(r"^/\*+|\*+/$", "", tok.text)


class Reader(Header):
    """The entries (declarations and free-standing comments) of one header."""

    def entries(self):
        out = []
        self.namespace(0, len(self.toks), False, out, "")
        return out

    def namespace(self, i, end, hidden, out, prefix):
        """The entries of a namespace's body; prefix: its qualifier ("" in bouncer)."""
        pending = []   # own-line comment lines not yet attached
        last = None    # (entry, line of its last token)
        for item in self.scan(i, end):
            if isinstance(item, tuple):
                t = self.toks[item[1]]
                if t.kind in ("comment", "block"):
                    if t.own_line:
                        pending += comment_text(t).split("\n")
                    elif last and last[1] == t.line and last[0] is not None:
                        last[0].code += "  " + t.text  # a trailing comment: in the code block
                elif t.kind == "nl" and t.blank:
                    if pending and not hidden:
                        out.append(Entry("note", "", "", pending, t.line))
                    pending = []
                elif t.kind == "pp":
                    m = re.match(r"\s*#\s*define\s+(\w+)", t.text)
                    if m and not hidden and (m.group(1) in self.undefined or m.group(1).startswith("_")):
                        if pending:  # a local macro (#undef-ed again): its comment, as a note
                            out.append(Entry("note", "", "", pending, t.line))
                    elif m and not hidden:
                        e = Entry("macro", m.group(1), t.text.strip(), pending, t.line, t.line + t.text.count("\n"))
                        out.append(e)
                        last = (e, t.line + t.text.count("\n"))
                    pending = []
                continue
            s = item
            if s.kind in ("namespace", "extern") and s.body is None:  # namespace a = b; (an alias)
                pending = []
                continue
            if s.kind in ("namespace", "extern"):
                name = re.sub(r"^(inline\s+)?namespace\s*", "", self.code(s.start, s.body[0])) if s.kind == "namespace" else "x"
                if pending and not hidden and s.kind == "namespace" and not HIDDEN_NAMESPACE.match(name):
                    out.append(Entry("note", "", "", pending, self.toks[s.start].line))
                pending = []
                inner = prefix if s.kind == "extern" else prefix + name + "::"
                if not prefix and name.startswith("bouncer"):
                    inner = name[len("bouncer"):].lstrip(":") + "::" if name != "bouncer" else ""
                self.namespace(s.body[0] + 1, s.body[1], hidden or bool(HIDDEN_NAMESPACE.match(name.split("::")[-1])),
                               out, inner)
                last = None
                continue
            e = None if hidden else self.entry(s, pending)
            if e is not None:
                e.name = prefix + e.name if e.name else e.name
                out.append(e)
            last = (e, self.toks[s.end - 1].line)
            pending = []
        if pending and not hidden:
            out.append(Entry("note", "", "", pending, 0))

    def entry(self, s, comment):
        if s.kind in ("skip", "instantiation", "macro_call"):
            return None
        head_end = s.body[0] if s.body else s.end
        head = self.code(s.start, head_end)
        if s.kind in ("class", "enum") and s.body is None:
            return None  # a forward declaration
        if s.kind == "function" and s.body is not None:
            code = self.signature(s.start, s.body[0])
        elif s.kind == "class":
            code = self.text(s.start, s.body[0]) + "{" + self.members(s.body[0] + 1, s.body[1], self.is_struct(head)) \
                + self.text(s.body[1], s.end)
        else:
            code = self.text(s.start, s.end)
        code = textwrap.dedent(" " * self.column(s.start) + code.rstrip()).strip("\n")
        code = re.sub(r"[ \t]+\n", "\n", code)
        last = self.toks[s.end - 1]
        return Entry(s.kind, decl_name(s.kind, head), code, comment, self.toks[s.start].line,
                     last.line + last.text.count("\n"))

    @staticmethod
    def is_struct(head):
        return re.match(r"(\[\[[^\]]*\]\]\s*)*(struct|union)\b", strip_template(head)) is not None

    def init_colon(self, i, body_open):
        """The ':' of a constructor's initializer list in the head i..body_open, or None."""
        depth, seen_params = 0, False
        for k in range(i, body_open):
            t = self.toks[k]
            if t.kind != "punct":
                continue
            if t.text in "([":
                depth += 1
            elif t.text in ")]":
                depth -= 1
                seen_params = seen_params or (depth == 0 and t.text == ")")
            elif t.text == ":" and depth == 0 and seen_params:
                return k
        return None

    def signature(self, i, body_open):
        """A function's text up to its body, without a constructor's initializer list."""
        colon = self.init_colon(i, body_open)
        return self.text(i, body_open if colon is None else colon).rstrip() + ";"

    def drop(self, out, i, j):
        for k in range(i, j):
            out[k] = ""

    def drop_ws_before(self, out, k):
        k -= 1
        while k >= 0 and self.toks[k].kind in ("ws", "nl"):
            out[k] = ""
            k -= 1

    def mark_members(self, i, end, public, out):
        """Mark in `out` (token index -> replacement text) what a class body's rendering
        leaves out: private and protected members, function bodies (replaced by ';'),
        initializer lists, static_asserts, friend classes, preprocessor lines, and the
        comments directly above what is left out."""
        visible = public
        pending = []        # own-line comments since the last blank line or member
        dropped_line = -1   # the last line of the last member left out
        for item in self.scan(i, end):
            if isinstance(item, tuple):
                k = item[1]
                t = self.toks[k]
                if t.kind in ("comment", "block"):
                    if t.own_line:
                        pending.append(k)
                        if not visible:
                            out[k] = ""
                    elif not visible or t.line == dropped_line:
                        out[k] = ""
                elif t.kind == "nl" and t.blank:
                    pending = []
                elif t.kind == "pp":
                    out[k] = ""
                continue
            s = item
            head = self.code(s.start, s.body[0] if s.body else s.end)
            if s.kind == "access":
                visible = self.toks[s.start].text == "public"
                keep = visible
            else:
                keep = visible and s.kind not in ("skip", "instantiation", "macro_call") \
                    and not re.match(r"friend\s+(class|struct)\b", head)
            if not keep:
                self.drop(out, s.start, s.end)
                for k in pending:
                    out[k] = ""
                dropped_line = self.toks[s.end - 1].line
            elif s.kind == "function" and s.body is not None:
                colon = self.init_colon(s.start, s.body[0])
                cut = s.body[0] if colon is None else colon
                self.drop(out, cut, s.body[1] + 1)
                self.drop_ws_before(out, cut)
                out[s.body[1]] = ";"
            elif s.kind == "class" and s.body is not None:
                self.mark_members(s.body[0] + 1, s.body[1], self.is_struct(head), out)
            pending = []

    def members(self, i, end, public):
        """A class body's text (between its braces) as the page shows it."""
        out = {}
        self.mark_members(i, end, public, out)
        lines, cur, had, kept = [], [], False, False
        for k in range(i, end):
            t = self.toks[k]
            txt = out.get(k, t.text)
            if t.kind == "nl":
                if txt == "":  # a line break before a cut body: the ';' joins its line
                    continue
                if not had or kept:  # a line whose every token was left out disappears
                    lines.append("".join(cur).rstrip())
                cur, had, kept = [], False, False
                continue
            if t.kind != "ws":
                had = True
                kept = kept or txt != ""
            cur.append(txt)
        text = "\n".join(lines) + "\n" + "".join(cur)
        text = re.sub(r"\n{3,}", "\n\n", text)
        text = re.sub(r"^\n\n+", "\n", text)
        return re.sub(r"\n\n+([ \t]*)$", r"\n\1", text)


def top_comment(text):
    """The comment a header opens with (its lines without '//') and the rest of the text."""
    lines = text.split("\n")
    k = 0
    while k < len(lines) and not lines[k].strip():
        k += 1
    comment = []
    while k < len(lines) and lines[k].lstrip().startswith("//"):
        comment.append(lines[k].lstrip()[2:])
        k += 1
    return comment, "\n".join(lines[k:])


# ---------------------------------------------------------------- the page

KIND_WORD = {"function": "()"}  # after the name in headings and the index


def header_section(path, rel, anchors, level=3):
    """Markdown for one header: its heading, opening comment, index and declarations."""
    text = open(path, encoding="utf-8").read()
    comment, rest = top_comment(text)
    out = []
    anchor = anchors.add(rel)
    out.append(f"\n{'#' * level} `{rel}`\n\n")
    out.append(comment_md(comment) if comment else "(no opening comment)\n")
    try:
        entries = Reader(rest).entries()
    except Exception as e:  # any header it cannot follow: its comment, and this note
        print(f"gen_docs: {rel}: declarations not read ({e})", file=sys.stderr)
        out.append(f"\n*The declarations of this header could not be read by tools/cpp_api.py ({md_escape(str(e))}); "
                   "see the header itself.*\n")
        return anchor, "".join(out), 0
    # Declarations the header writes as one block under one comment (no blank line between,
    # no comment of their own) are one code block; consecutive declarations of one name
    # (overloads) share a heading.
    blocks = []
    for e in entries:
        prev = blocks[-1][-1] if blocks else None
        if prev is not None and e.kind != "note" and prev.kind != "note" and not e.comment \
                and e.line == prev.end_line + 1:
            blocks[-1].append(e)
        else:
            blocks.append([e])
    groups = []  # (names, [blocks])
    for b in blocks:
        names = None if b[0].kind == "note" else list(dict.fromkeys(
            e.name + KIND_WORD.get(e.kind, "") for e in b if e.name)) or ["(unnamed)"]
        if names and groups and groups[-1][0] == names and len(names) == 1:
            groups[-1][1].append(b)
        else:
            groups.append((names, [b]))
    ids = [None if names is None else anchors.add(" · ".join(names)) for names, _ in groups]
    index = [f"[`{name}`](#{i})" for (names, _), i in zip(groups, ids) if names for name in names]
    if index:
        out.append("\n**Declares:** " + " · ".join(index) + "\n")
    n = 0
    for (names, group), i in zip(groups, ids):
        if names is None:
            doc = comment_md(group[0][0].comment)
            if doc:
                out.append("\n" + doc)
            continue
        out.append("\n#### " + " · ".join(f"`{name}`" for name in names) + "\n")
        for block in group:
            n += len(block)
            code = "\n".join(e.code for e in block)
            out.append(f"\n```cpp\n{code}\n```\n")
            doc = comment_md(block[0].comment)
            if doc:
                out.append("\n" + doc)
    return anchor, "".join(out), n


def page(src, version):
    root = os.path.join(src, "lib", "include", "bouncer")
    anchors = Anchors()
    anchors.add("C++ API")
    intro = (f"# C++ API\n\n*Generated from the headers by tools/gen_docs.py ({version}).* The library "
             "(`find_package(bouncer)` or `pkg-config bouncer`; [Using the library from CMake](../guide/cmake.md)) "
             "is layered: each layer includes only the ones before it (tests/check_layers.py checks; what each "
             "holds: [Layout and development](../guide/development.md)). "
             "One section per public header: the comment it opens with, then its declarations at namespace "
             "scope, each with the comment above it in the header (class bodies with their public members; "
             "`detail` namespaces, private members and function bodies left out).\n")
    layers = LAYERS + sorted(d for d in os.listdir(root) if os.path.isdir(os.path.join(root, d)) and d not in LAYERS)
    sections, contents, total = [], [], 0
    n_headers = 0
    for layer in layers:
        d = os.path.join(root, layer)
        if not os.path.isdir(d):
            continue
        headers = sorted(os.path.join(dp, f) for dp, _, fs in os.walk(d) for f in fs if f.endswith(".hpp"))
        if not headers:
            continue
        layer_id = anchors.add(layer)
        body, links = [], []
        for h in headers:
            rel = os.path.relpath(h, os.path.join(src, "lib", "include"))
            anchor, md, n = header_section(h, rel, anchors)
            total += n
            n_headers += 1
            body.append(md)
            links.append(f"[`{os.path.relpath(h, d)[:-4]}`](#{anchor})")
        sections.append(f"\n## {layer}\n\n" + " · ".join(links) + "\n" + "".join(body))
        contents.append(f"- [{layer}](#{layer_id}): " + ", ".join(links))
    summary = f"\n{n_headers} headers, {total} declarations.\n\n" + "\n".join(contents) + "\n"
    return intro + summary + "".join(sections)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__.split("\n\n")[-1])
    anchors = Anchors()
    for h in sys.argv[1:]:
        print(header_section(h, h, anchors)[1])


if __name__ == "__main__":
    main()
