#!/usr/bin/env python3
"""The check of the generated benchmark tables catches hand edits (ctest bench.tables_catch_edits).

`tools/bench/record_tables.py --check` must accept docs/guide/benchmarks.md as committed and
reject copies of it edited by hand, each in one way a person editing a table would: a row with
a cell too many, a row with a cell too few, a renamed column, a command that is no benchmark's,
a provenance line removed, the provenance of one block of a run changed, an end marker lost,
a table line after the notes. Each edit is checked to change the page (so that no case passes
by editing nothing), and the check's message must name the problem. And the recorder's own
output passes the check and leaves the prose alone: every block rewritten from a made-up record
(the tools' columns from `--columns`, cells with characters Markdown would read: | * _ < >)
is accepted, and the lines outside the blocks are unchanged. Nothing is timed.

    python3 tests/check_bench_tables.py --build-dir build
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RECORDER = os.path.join(ROOT, "tools", "bench", "record_tables.py")
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(RECORDER))
import record_tables  # noqa: E402
PAGE = os.path.join(ROOT, "docs", "guide", "benchmarks.md")


def run_check(text, build):
    with tempfile.NamedTemporaryFile("w", suffix=".md", delete=False) as f:
        f.write(text)
        path = f.name
    try:
        p = subprocess.run([sys.executable, RECORDER, "--check", "--page", path, "--build-dir", build],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        return p.returncode, p.stdout + p.stderr
    finally:
        os.unlink(path)


def first_block(lines, prefix=""):
    """(begin, end) line indices of the first block whose name starts with prefix."""
    for i, line in enumerate(lines):
        m = re.match(r"^<!-- bench:(\S+) begin -->$", line)
        if m and m.group(1).startswith(prefix):
            for j in range(i + 1, len(lines)):
                if lines[j] == f"<!-- bench:{m.group(1)} end -->":
                    return i, j
    raise SystemExit(f"check_bench_tables: no bench:{prefix}... block in the page")


def data_row(lines, b, e):
    """The first data row of the block's table (after the header and separator rows)."""
    rows = [i for i in range(b, e) if lines[i].startswith("|")]
    if len(rows) < 3:
        raise SystemExit("check_bench_tables: the first block has no data row")
    return rows[2]


def edits(lines):
    b, e = first_block(lines)
    r = data_row(lines, b, e)
    header = next(i for i in range(b, e) if lines[i].startswith("|"))
    prov = next(i for i in range(b, e) if lines[i].startswith("Recorded by `"))
    cb, ce = first_block(lines, "certify/")
    cprov = next(i for i in range(cb, ce) if lines[i].startswith("Recorded by `"))

    def edit(f):
        new = list(lines)
        f(new)
        return new

    def set_line(i, text):
        return lambda new: new.__setitem__(i, text)

    return [
        ("a row with a cell too many", "cells for", edit(set_line(r, lines[r] + " 1.0 |"))),
        ("a row with a cell too few", "cells for", edit(set_line(r, lines[r][:lines[r].rstrip(" |").rfind("|") + 1]))),
        ("a renamed column", "header row", edit(set_line(header, lines[header].replace("| ", "| my ", 1)))),
        ("a command that is no benchmark's", "is not one of",
         edit(set_line(prov, re.sub(r"^Recorded by `[^\s`]+", "Recorded by `bench_nothing", lines[prov])))),
        ("the provenance line removed", "provenance line", edit(lambda new: new.__delitem__(prov))),
        ("one block of a run with another provenance", "differs",
         edit(set_line(cprov, re.sub(r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d UTC", "1999-01-01 00:00:00 UTC", lines[cprov])))),
        ("an end marker lost", "end marker|begins inside", edit(lambda new: new.__delitem__(e))),
        ("a table line after the notes", "after the notes", edit(lambda new: new.insert(e, "| x |"))),
    ]


def outside(lines):
    """The lines outside the bench blocks."""
    blocks, _ = record_tables.find_blocks(lines)
    spans = sorted(blocks.values())
    out, k = [], 0
    for b, e in spans:
        out += lines[k:b]
        k = e + 1
    return out + lines[k:]


def rewritten(lines, build):
    """The page with every block rewritten by the recorder from a made-up record of its tool."""
    blocks, problems = record_tables.find_blocks(lines)
    if problems:
        raise SystemExit(f"check_bench_tables: the page's markers: {problems}")
    new = {}
    for name in blocks:
        key, _, table = name.partition("/")
        columns = record_tables.columns_of(key, build)[table]
        rec = {"command": record_tables.BENCHMARKS[key]["tool"] + " --quick", "version": "9.9.9", "commit": "0" * 40,
               "date": "2000-01-01 00:00:00 UTC",
               "machine": {"cpus": 2, "cpu": "Test CPU(R) (2 cores)", "load_at_start": "0.50 1.00 1.50 1/99 123"}}
        t = {"name": table, "columns": columns,
             "rows": [[f"a|b*c_d <{i}>" for i in range(len(columns))], ["" for _ in columns]],
             "notes": ["a note | with * and _", "a second note"]}
        new[name] = record_tables.block(name, rec, t)
    return record_tables.replace_blocks(lines, blocks, new)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"))
    ap.add_argument("--page", default=PAGE, help="the page (default: docs/guide/benchmarks.md)")
    args = ap.parse_args()
    build = os.path.abspath(args.build_dir)
    with open(args.page) as f:
        text = f.read()
    lines = text.split("\n")
    failures = []
    code, out = run_check(text, build)
    if code != 0:
        failures.append(f"the committed page fails the check:\n{out}")
    regenerated = rewritten(lines, build)
    if regenerated == lines:
        failures.append("the recorder's rewrite changed nothing (the test would prove nothing)")
    elif outside(regenerated) != outside(lines):
        failures.append("the recorder's rewrite changed lines outside the blocks")
    else:
        code, out = run_check("\n".join(regenerated), build)
        if code != 0:
            failures.append(f"the recorder's own output fails the check:\n{out}")
        else:
            print("check_bench_tables: the recorder's own output passes, the prose unchanged")
    for what, expect, new in edits(lines):
        if new == lines:
            failures.append(f"{what}: the edit changed nothing (the test would prove nothing)")
            continue
        code, out = run_check("\n".join(new), build)
        if code == 0:
            failures.append(f"{what}: accepted by the check")
        elif not re.search(expect, out):
            failures.append(f"{what}: rejected, but without naming it ({expect!r} not in: {out.strip()[:300]})")
        else:
            print(f"check_bench_tables: {what}: rejected")
    for f in failures:
        print(f"check_bench_tables: FAILED: {f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
