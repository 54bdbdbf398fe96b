#!/usr/bin/env python3
"""Convert the ITF1788 interval test suite into bouncer's test vectors.

ITF1788 (https://github.com/oheim/ITF1788, "Interval Test Framework for IEEE Std
1788-2015") holds test cases for interval arithmetic on binary64 ends in its own small
language, in the files itl/*.itl:

    testcase minimal_add_test {
        add [1.0, 2.0] [1.0, 2.0] = [2.0, 4.0];
        ...
    }

This script reads those files (from a directory, or straight from a git directory of the
repository with --git-dir) and writes ONE plain-text file,
tests/data/itf1788/vectors.txt, that tests/test_itf1788.cpp reads. Only the operations
that bouncer's interval types (DoubleInterval, Mpfi) provide are kept:

    add sub mul div neg recip sqrt exp log abs    (arithmetic; recip x = 1 / x)
    convexHull intersection                       (hull, intersect)
    subset isMember precedes strictPrecedes       (contains, contains(point), Tr::le, Tr::lt)
    isCommonInterval                              (Tr::is_finite)

Conventions of ITF1788 kept here (see docs/scalars.md and its code generators,
itf1788/plugins/*/callbacks.py):
  * Every numeric literal is a binary64 number: the generators paste it into the target
    language as a floating-point literal (C++: verbatim; Octave: hex forms turned into 18
    significant digits), so it denotes the double nearest to it, for operands and expected
    results alike. The literals of the kept cases are almost all exact doubles; the few
    that are not (0.1, 2.1, 3e300, ...) are read round-to-nearest, as ITF1788 does, and
    counted in the output's header.
  * A test "op args = result" without "<=" asks for the tightest result: the smallest
    interval of doubles containing the exact result (the kept cases have no "tight <=
    accurate" pairs and no "signal" clauses; any that appear are skipped and counted).
  * [empty] is the empty set, [entire] the whole real line; [nai] (not an interval) and
    decorated intervals ([a, b]_com, ...) have no counterpart in bouncer's types: cases
    with them are skipped and counted (every decorated case of these operations repeats
    a bare one).

Output format, one case per line (blank lines and lines starting with '#' are comments):

    <op> <operand>... = <expected> @ <source file>:<testcase>

with intervals written [lo,hi] (C99 hexadecimal floats as printed by Python's
float.hex(), exact; 'inf' and '-inf'), [empty], numbers as hex floats (or 'nan'), and
booleans 'true' / 'false'. [entire] is written [-inf,inf].

Licences: the ITF1788 framework is Apache-2.0 (its LICENSE), but each .itl file carries
its own notice: libieeep1788_*.itl are Apache-2.0; mpfi.itl, fi_lib.itl and c-xsc.itl
(converted from GNU MPFI, FI_LIB and C-XSC) are LGPL-2.1-or-later; the others use the
FSF all-permissive notice. The output's header names the licence of every source file
the cases come from and reproduces their copyright lines; the licence texts are
tests/data/itf1788/LICENSE.Apache-2.0 and LICENSE.LGPL-2.1 (the repository's LICENSE and
COPYING.LESSER). --exclude-lgpl leaves the LGPL-licensed files out (732 cases instead of
1545 at commit b6ee1e24d209: lower kMinCases in tests/test_itf1788.cpp to match).

Usage (regenerating the committed file):

    git clone https://github.com/oheim/ITF1788 /tmp/ITF1788
    python3 tools/itf1788_convert.py --git-dir /tmp/ITF1788/.git \\
        -o tests/data/itf1788/vectors.txt

Plain python3, standard library only.
"""

import argparse
import collections
import os
import re
import subprocess
import sys
import textwrap
from fractions import Fraction

SOURCE_URL = "https://github.com/oheim/ITF1788"

# ITF1788 operation -> number of operands and the kind of its result.
OPERATIONS = {
    "add": (2, "interval"),
    "sub": (2, "interval"),
    "mul": (2, "interval"),
    "div": (2, "interval"),
    "neg": (1, "interval"),
    "recip": (1, "interval"),
    "sqrt": (1, "interval"),
    "exp": (1, "interval"),
    "log": (1, "interval"),
    "abs": (1, "interval"),
    "convexHull": (2, "interval"),
    "intersection": (2, "interval"),
    "subset": (2, "bool"),
    "isMember": (2, "bool"),  # number, interval
    "precedes": (2, "bool"),
    "strictPrecedes": (2, "bool"),
    "isCommonInterval": (1, "bool"),
}

LICENCES = {
    "apache": "Apache-2.0",
    "lgpl": "LGPL-2.1-or-later",
    "permissive": "FSF all-permissive",
}

# One token of a statement: an interval literal (maybe decorated), a string, an array, or
# a run of other characters.
TOKEN = re.compile(r'\[[^\]]*\](?:_[A-Za-z]+)?|"[^"]*"|\{[^}]*\}|[^\s\[\]{}"]+')
HEX_FLOAT = re.compile(r"([+-]?)0[xX]([0-9a-fA-F]*)(?:\.([0-9a-fA-F]*))?(?:[pP]([+-]?\d+))?[fFlLuU]*$")
DEC_FLOAT = re.compile(r"([+-]?)(\d*)(?:\.(\d*))?(?:[eE]([+-]?\d+))?[fFlLuU]*$")


class Skip(Exception):
    """A case this converter does not keep; the message is the counted reason."""


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"#\*.*?\*#", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", " ", text)
    text = re.sub(r"#[^\n]*", " ", text)
    return text


def header_comment(text):
    m = re.match(r"\s*/\*(.*?)\*/", text, flags=re.S)
    return m.group(1) if m else ""


def licence_of(name, text):
    head = header_comment(text)
    if "Apache License" in head:
        return "apache"
    if "GNU Lesser General Public" in head:
        return "lgpl"
    if "Copying and distribution of this file" in head:
        return "permissive"
    raise SystemExit("%s: no licence notice recognised in its header" % name)


def copyright_lines(text):
    """The Copyright lines of a file's header comment, with their indented continuations."""
    out, in_block = [], False
    for raw in header_comment(text).splitlines():
        if raw.strip().startswith("Copyright"):
            out.append(raw.strip())
            in_block = True
        elif in_block and raw.startswith("    ") and raw.strip():
            out[-1] += " " + raw.strip()
        else:
            in_block = False
    return out


def testcases(text):
    """(name, body) of each testcase block; bodies may hold {...} arrays."""
    pos = 0
    head = re.compile(r"testcase\s+([A-Za-z0-9_.\-]+)\s*\{")
    while True:
        m = head.search(text, pos)
        if not m:
            return
        depth, i = 1, m.end()
        while depth:
            if i >= len(text):
                raise SystemExit("unterminated testcase %s" % m.group(1))
            depth += {"{": 1, "}": -1}.get(text[i], 0)
            i += 1
        yield m.group(1), text[m.end():i - 1]
        pos = i


def exact_value(lit):
    """The exact rational value of a numeric literal, or +-inf / nan as strings."""
    s = lit.strip()
    low = s.lower()
    if re.fullmatch(r"[+-]?infinity[fl]?", low):
        return "-inf" if low.startswith("-") else "inf"
    if re.fullmatch(r"nan[fl]?", low):
        return "nan"
    m = HEX_FLOAT.match(s)
    if m and (m.group(4) is not None or m.group(3) is None):
        sign, whole, frac, exp = m.groups()
        frac = frac or ""
        if not whole and not frac:
            raise Skip("malformed number %r" % lit)
        v = Fraction(int((whole or "0") + frac, 16), 16 ** len(frac)) * Fraction(2) ** int(exp or 0)
        return -v if sign == "-" else v
    m = DEC_FLOAT.match(s)
    if m and (m.group(2) or m.group(3)):
        sign, whole, frac, exp = m.groups()
        frac = frac or ""
        v = Fraction(int((whole or "0") + frac), 10 ** len(frac)) * Fraction(10) ** int(exp or 0)
        return -v if sign == "-" else v
    raise Skip("unrecognised number %r" % lit)


def nearest_double(v, negative_zero=False):
    """The binary64 number nearest to the exact value v (ties to even), as a float."""
    if isinstance(v, str):
        return float(v)
    if v == 0:
        return -0.0 if negative_zero else 0.0
    # Fraction -> float is correctly rounded (round half to even) in CPython; check it
    # against the neighbours anyway, so that a wrong conversion cannot pass unseen.
    f = float(v)
    if f not in (float("inf"), float("-inf")):
        err = abs(Fraction(f) - v)
        for g in (nextafter(f, 1), nextafter(f, -1)):
            if g not in (float("inf"), float("-inf")) and abs(Fraction(g) - v) < err:
                raise SystemExit("float(%s) is not the nearest double" % v)
    return f


def nextafter(x, direction):
    import math
    return math.nextafter(x, math.inf if direction > 0 else -math.inf)


class Stats:
    def __init__(self):
        self.kept = collections.Counter()           # (file, op)
        self.skipped = collections.Counter()        # reason
        self.inexact = []                           # (file, testcase, literal)


def number(lit, ctx, stats):
    v = exact_value(lit)
    neg_zero = lit.strip().startswith("-")
    f = nearest_double(v, neg_zero)
    if not isinstance(v, str) and Fraction(f) != v:
        stats.inexact.append((ctx, lit.strip()))
    return f


def fmt_double(f):
    if f != f:
        return "nan"
    if f in (float("inf"), float("-inf")):
        return "inf" if f > 0 else "-inf"
    return f.hex()


def interval(tok, ctx, stats):
    if not tok.startswith("["):
        raise Skip("operand is not an interval")
    if re.search(r"\]_[A-Za-z]+$", tok):
        raise Skip("decorated interval (bouncer's types have no decorations)")
    inner = tok[1:-1].strip()
    low = inner.lower()
    if low in ("empty", "emptyf"):
        return "[empty]"
    if low in ("entire", "entiref"):
        return "[-inf,inf]"
    if low in ("nai", "naif"):
        raise Skip("[nai] (not an interval: no counterpart)")
    parts = [p.strip() for p in inner.split(",")]
    if len(parts) == 1:
        parts = parts * 2
    if len(parts) != 2:
        raise Skip("malformed interval %r" % tok)
    lo, hi = (number(p, ctx, stats) for p in parts)
    if not lo <= hi or lo == float("inf") or hi == float("-inf"):
        raise Skip("interval literal %r is not a valid interval" % tok)
    return "[%s,%s]" % (fmt_double(lo), fmt_double(hi))


def convert_statement(stmt, ctx, stats):
    toks = TOKEN.findall(stmt)
    if not toks:
        return None
    op = toks[0]
    if op not in OPERATIONS:
        return None
    if "signal" in toks:
        raise Skip("case with a 'signal' clause")
    if "<=" in toks:
        raise Skip("'tight <= accurate' case")
    if "=" not in toks:
        raise Skip("malformed statement")
    eq = toks.index("=")
    args, outs = toks[1:eq], toks[eq + 1:]
    nargs, kind = OPERATIONS[op]
    if len(args) != nargs or len(outs) != 1:
        raise Skip("unexpected arity in %r" % stmt.strip())
    written = []
    for i, a in enumerate(args):
        if op == "isMember" and i == 0:
            if a.startswith("["):
                raise Skip("malformed isMember")
            written.append(fmt_double(number(a, ctx, stats)))
        else:
            written.append(interval(a, ctx, stats))
    out = outs[0]
    if kind == "bool":
        if out not in ("true", "false"):
            raise Skip("boolean operation with a non-boolean result")
        result = out
    else:
        result = interval(out, ctx, stats)
    return "%s %s = %s" % (op, " ".join(written), result)


def read_sources(args):
    """[(file name, text)] of the .itl files, and a description of where they came from."""
    files = []
    if args.git_dir:
        rev = subprocess.run(["git", "--git-dir", args.git_dir, "rev-parse", args.rev + "^{commit}"],
                             check=True, capture_output=True, text=True).stdout.strip()
        names = subprocess.run(["git", "--git-dir", args.git_dir, "ls-tree", "--name-only", rev, "itl/"],
                               check=True, capture_output=True, text=True).stdout.split()
        for name in sorted(names):
            if name.endswith(".itl"):
                text = subprocess.run(["git", "--git-dir", args.git_dir, "show", "%s:%s" % (rev, name)],
                                      check=True, capture_output=True, text=True).stdout
                files.append((os.path.basename(name), text))
        origin = "%s commit %s" % (SOURCE_URL, rev)
    else:
        for name in sorted(os.listdir(args.itl_dir)):
            if name.endswith(".itl"):
                with open(os.path.join(args.itl_dir, name), encoding="utf-8") as fh:
                    files.append((name, fh.read()))
        origin = "%s (%s%s)" % (SOURCE_URL, args.itl_dir, ", commit " + args.commit if args.commit else "")
    if not files:
        raise SystemExit("no .itl files found")
    return files, origin


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("--git-dir", help="git directory of a clone of oheim/ITF1788")
    src.add_argument("--itl-dir", help="directory holding the .itl files")
    ap.add_argument("--rev", default="HEAD", help="revision to read with --git-dir (default HEAD)")
    ap.add_argument("--commit", help="the commit the --itl-dir files come from (recorded in the header)")
    ap.add_argument("--exclude-lgpl", action="store_true", help="leave out the LGPL-licensed .itl files")
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()

    files, origin = read_sources(args)
    stats = Stats()
    lines = []
    used = []  # (file, licence, copyright lines)
    for name, text in files:
        lic = licence_of(name, text)
        if args.exclude_lgpl and lic == "lgpl":
            continue
        body = strip_comments(text)
        n_before = len(lines)
        for tc, block in testcases(body):
            for stmt in block.split(";"):
                if not stmt.strip():
                    continue
                ctx = "%s:%s" % (name, tc)
                try:
                    case = convert_statement(stmt, ctx, stats)
                except Skip as why:
                    op = TOKEN.findall(stmt)[0]
                    stats.skipped[(op, str(why))] += 1
                    continue
                if case is None:
                    continue
                lines.append("%s @ %s" % (case, ctx))
                stats.kept[(name, case.split()[0])] += 1
        if len(lines) > n_before:
            used.append((name, lic, copyright_lines(text)))

    out = []
    out.append("# ITF1788 test vectors for bouncer's interval types (read by tests/test_itf1788.cpp).")
    out.append("# Generated by tools/itf1788_convert.py; do not edit by hand, regenerate (see the script).")
    out.append("# Source: %s" % origin)
    out.append("#   (Interval Test Framework for IEEE Std 1788-2015; the framework is Apache-2.0, its NOTICE:")
    out.append("#   Copyright 2014 Marco Nehmeier, Maximilian Kiesner, Chair of Software Engineering,")
    out.append("#   Department of Computer Science, University of Wuerzburg, Germany; each .itl file carries")
    out.append("#   its own copyright and licence notice).")
    out.append("#")
    out.append("# Cases taken from these files, under these licences (each line below names its file):")
    for name, lic, copy in used:
        out.append("#   %-28s %s" % (name, LICENCES[lic]))
        for c in copy:
            out.append("#       %s" % c)
    terms = {
        "apache": "the Apache License, Version 2.0",
        "lgpl": "the GNU Lesser General Public License, version 2.1 or (at your option) any later version",
        "permissive": "the FSF all-permissive notice (copying and distribution with the notice preserved)",
    }
    used_terms = [terms[k] for k in ("apache", "lgpl", "permissive") if any(lic == k for _, lic, _ in used)]
    notice = "# The notices license these files under " + "; or ".join(used_terms) + \
        "; all are offered WITHOUT ANY WARRANTY."
    out.extend(textwrap.wrap(notice, width=96, subsequent_indent="# "))
    out.append("# Licence texts: LICENSE.Apache-2.0 and LICENSE.LGPL-2.1 next to this file (the repository's")
    out.append("# LICENSE and COPYING.LESSER). Each line below stays under the licence of the file it names")
    out.append("# (a work based on it; changed from the original: literals rewritten as exact hexadecimal")
    out.append("# doubles, one case per line, only the cases of the operations listed below).")
    out.append("#")
    out.append("# Format: <op> <operand>... = <expected> @ <file>:<testcase>; intervals [lo,hi] with exact")
    out.append("# hexadecimal ends (inf, -inf), [empty]; [entire] is written [-inf,inf]. Every literal of")
    out.append("# ITF1788 denotes the double nearest to it; expected intervals are the tightest ones.")
    out.append("#")
    out.append("# Kept cases: %d" % len(lines))
    by_op = collections.Counter()
    for (name, op), n in stats.kept.items():
        by_op[op] += n
    out.append("#   by operation: " + ", ".join("%s %d" % (op, by_op[op]) for op in OPERATIONS if by_op[op]))
    by_file = collections.Counter()
    for (name, op), n in stats.kept.items():
        by_file[name] += n
    out.append("#   by file: " + ", ".join("%s %d" % kv for kv in sorted(by_file.items())))
    out.append("# Skipped cases of these operations, by reason:")
    reasons = collections.Counter()
    for (op, why), n in stats.skipped.items():
        reasons[why] += n
    for why, n in sorted(reasons.items(), key=lambda kv: -kv[1]):
        out.append("#   %5d  %s" % (n, why))
    out.append("# Literals that are not doubles (read round-to-nearest, as ITF1788 does): %d" % len(stats.inexact))
    seen = sorted(set(lit for _, lit in stats.inexact))
    if seen:
        out.append("#   " + " ".join(seen))
    out.append("")
    out.extend(lines)
    out.append("")

    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    with open(args.output, "w", encoding="utf-8") as fh:
        fh.write("\n".join(out))
    print("%s: %d cases from %d files; skipped %d (%s)" % (
        args.output, len(lines), len(used), sum(reasons.values()),
        "; ".join("%s: %d" % (w, n) for w, n in sorted(reasons.items(), key=lambda kv: -kv[1]))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
