#!/usr/bin/env python3
"""Rerun the examples the documentation quotes and compare their output with the quote.

A quoted example is an HTML comment `<!-- run -->` on its own line, then a fenced ```sh
block holding one `bouncer ...` command (continuation lines ending in `\\` allowed, `#`
comments ignored), then a fenced ```text block: what the command prints. GitHub and MkDocs
hide the comment, so the reader sees the command and its output. The comment may carry
options: `<!-- run: stderr exit=2 -->` compares standard error instead of standard output
and expects exit status 2 (an error message); the default is stdout and exit status 0.

Each marked command is run without a shell: the word `bouncer` is the executable given by
--bouncer, in an empty temporary directory where `data` is a link to the repository's
data/ (so `--scene data/scenes/NAME.toml` works and `--out` files land there), with
LC_ALL=C. The quoted block must equal the output after this normalisation, and only this:
  * trailing blanks are cut on every line (`--format table` pads its columns);
  * `(commit HEX)` and `(commit HEX+dirty-HEX)` become `(commit COMMIT)`: the build's commit;
  * in `# time:` lines every number becomes `T` (timings differ from run to run);
  * the temporary directory's path becomes `DIR`;
  * a quoted line holding only `...` (indented or not) stands for any number of printed
    lines (zero or more), so a quote
    may leave out provenance lines or long stretches; every other quoted line must match a
    printed line exactly, digits included, in order.
Examples must be fast: one command may use at most --max-cpu seconds of CPU (default 5: the
guideline is under 2.5 s on an idle machine; the CI machine ran the slowest example,
continue --certify, in 3.2 s where this one takes 2.1 s) and
all of them together at most --max-total (default 20), so the check stays in the suite.

    tools/check_docs_examples.py --bouncer build/tools/bouncer [--root DIR] [FILE.md ...]

Without files: README.md and every docs/**/*.md except the generated docs/reference/.
Exit 0: every quote matches; 1: one block per mismatch (a unified diff), or a marker
without its blocks, or a command that is not `bouncer` or too slow; 2: bad arguments.
Plain python3 (standard library).
"""
import argparse
import difflib
import os
import re
import resource
import shlex
import subprocess
import sys
import tempfile
import time

MARKER = re.compile(r"^<!-- run(?::\s*(.*?))?\s*-->\s*$")


class Example:
    def __init__(self, path, line, options, command, expected):
        self.path, self.line, self.options, self.command, self.expected = path, line, options, command, expected


def fenced_block(lines, i, lang):
    """The fenced block starting at line i (after blank lines) if its info string is lang:
    (content lines, index after the closing fence) or None."""
    while i < len(lines) and not lines[i].strip():
        i += 1
    if i >= len(lines) or lines[i].strip() != "```" + lang:
        return None
    j = i + 1
    while j < len(lines) and lines[j].strip() != "```":
        j += 1
    if j >= len(lines):
        return None
    return lines[i + 1:j], j + 1


def examples_of(path, errors):
    lines = open(path, encoding="utf-8").read().split("\n")
    out = []
    for i, line in enumerate(lines):
        m = MARKER.match(line)
        if not m:
            continue
        where = f"{path}:{i + 1}"
        sh = fenced_block(lines, i + 1, "sh")
        if sh is None:
            errors.append(f"{where}: <!-- run --> is not followed by a ```sh block")
            continue
        text = fenced_block(lines, sh[1], "text")
        if text is None:
            errors.append(f"{where}: the ```sh block after <!-- run --> is not followed by a ```text block")
            continue
        command = " ".join(l[:-1] if l.rstrip().endswith("\\") else l for l in
                           (l.rstrip() for l in sh[0]))
        try:
            words = shlex.split(command, comments=True)
        except ValueError as e:
            errors.append(f"{where}: cannot parse the command: {e}")
            continue
        if not words or words[0] != "bouncer":
            errors.append(f"{where}: a marked command must be one `bouncer ...` command, not {command!r}")
            continue
        options = {"stream": "stdout", "exit": 0}
        for opt in (m.group(1) or "").split():
            if opt in ("stdout", "stderr"):
                options["stream"] = opt
            elif re.fullmatch(r"exit=\d+", opt):
                options["exit"] = int(opt[5:])
            else:
                errors.append(f"{where}: unknown option {opt!r} in the run marker")
        out.append(Example(path, i + 1, options, words, text[0]))
    return out


def normalise(text, tmpdir):
    out = []
    for line in text.replace(tmpdir, "DIR").split("\n"):
        line = re.sub(r"\(commit [0-9a-f]{7,40}(\+dirty-[0-9a-f]+)?\)", "(commit COMMIT)", line.rstrip())
        if line.startswith("# time:"):
            line = re.sub(r"\d+(\.\d+)?(e[-+]?\d+)?", "T", line)
        out.append(line)
    while out and out[-1] == "":
        out.pop()
    return out


def matches(expected, actual):
    """expected (with `...` wildcard lines) against actual, in order: True when it fits."""
    # positions in actual reachable after consuming expected[:k]
    reach = {0}
    for e in expected:
        if e.strip() == "...":
            lo = min(reach)
            reach = set(range(lo, len(actual) + 1))
        else:
            reach = {p + 1 for p in reach if p < len(actual) and actual[p] == e}
        if not reach:
            return False
    return len(actual) in reach


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bouncer", required=True, help="the built bouncer executable")
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."),
                    help="the repository (default: this script's)")
    ap.add_argument("--max-cpu", type=float, default=5.0, help="CPU seconds one example may use")
    ap.add_argument("--max-total", type=float, default=20.0, help="CPU seconds all examples may use")
    ap.add_argument("files", nargs="*")
    args = ap.parse_args()
    root = os.path.abspath(args.root)
    bouncer = os.path.abspath(args.bouncer)
    files = args.files
    if not files:
        files = [os.path.join(root, "README.md")]
        for d, dirs, fs in os.walk(os.path.join(root, "docs")):
            dirs[:] = sorted(x for x in dirs if os.path.join(d, x) != os.path.join(root, "docs", "reference"))
            files += [os.path.join(d, f) for f in sorted(fs) if f.endswith(".md")]
    errors, examples = [], []
    for f in files:
        examples += examples_of(f, errors)
    total = 0.0
    env = dict(os.environ, LC_ALL="C")
    for ex in examples:
        where = f"{os.path.relpath(ex.path, root)}:{ex.line}"
        with tempfile.TemporaryDirectory(prefix="bouncer-docs-") as tmp:
            tmp = os.path.realpath(tmp)
            os.symlink(os.path.join(root, "data"), os.path.join(tmp, "data"))
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            t0 = time.monotonic()
            p = subprocess.run([bouncer] + ex.command[1:], cwd=tmp, env=env, capture_output=True,
                               text=True, timeout=120)
            wall = time.monotonic() - t0
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
            total += cpu
            shown = " ".join(ex.command)
            if p.returncode != ex.options["exit"]:
                errors.append(f"{where}: `{shown}` exited {p.returncode}, not {ex.options['exit']}: "
                              f"{p.stderr.strip()[:300]}")
                continue
            actual = normalise(p.stdout if ex.options["stream"] == "stdout" else p.stderr, tmp)
            expected = normalise("\n".join(ex.expected), tmp)
            if not matches(expected, actual):
                diff = "".join(difflib.unified_diff([l + "\n" for l in expected], [l + "\n" for l in actual],
                                                    "quoted", "printed now"))
                errors.append(f"{where}: `{shown}` prints something else than the quote "
                              f"(`...` lines match any lines):\n{diff}")
            if cpu > args.max_cpu:
                errors.append(f"{where}: `{shown}` took {cpu:.2f} s of CPU, more than {args.max_cpu} s: "
                              "quote a faster example or leave it unmarked")
            print(f"  {cpu:5.2f} s CPU {wall:5.2f} s  {where}  {shown}")
    if total > args.max_total:
        errors.append(f"the examples took {total:.1f} s of CPU together, more than {args.max_total} s")
    if errors:
        print("\n".join(errors))
        print(f"check_docs_examples: {len(errors)} problem(s) in {len(examples)} examples")
        return 1
    print(f"check_docs_examples: {len(examples)} examples in {len(files)} files print what they quote "
          f"({total:.1f} s of CPU)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
