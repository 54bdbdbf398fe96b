#!/usr/bin/env python3
"""Links and FIFOs planted at every output and staging path of every command that writes
files (issue 21; base/output.hpp). For each command, a clean run first lists the files it
writes (its output set). Then, in a fresh folder each time, for every file F of the set:

  link at F           a symbolic link to a victim file outside the set: refused (exit 2) or
                      replaced, never written through: the victim keeps its bytes;
  link at F.partial   the staging name: the run succeeds, the victim keeps its bytes, F is a
                      regular file with the clean run's content (pictures: same kind);
  FIFO at F.partial   the run succeeds and does not hang;
  FIFO at F           written through: a reader gets the file, the FIFO stays a FIFO.

Grid commands also get PREFIX.tiles as a link to a victim directory holding a job.key
(refused, the directory untouched), and links at PREFIX.tiles/lock, job.toml, job.key and
tile-000000.partial (never followed). A reproduce directory gets links at its panels/ and
claims/ subdirectories and at a claim's output (refused, never followed).

Every run has a time limit: a hang is a failure. Exit 0 if every check holds, 1 otherwise.
Usage: planted_paths.py BOUNCER
"""
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import threading

BOUNCER = sys.argv[1]
MODEL = ["--model", "constant", "--eps", "0.5", "--a", "24"]
SMALL_GRID = ["--transient", "10", "--steps", "16", "--quiet", "--format", "png,pdf,svg"]
# (name, argv with {P} for the output prefix or path, grid?)
COMMANDS = [
    ("orbit", ["orbit", *MODEL, "--theta", "0.3", "--v", "12", "--steps", "5", "--out", "{P}.csv"], False),
    ("orbit-json", ["orbit", *MODEL, "--theta", "0.3", "--v", "12", "--steps", "5", "--format", "json", "--out", "{P}.json"], False),
    ("certify-sticking", ["certify-sticking", "--eps", "0.5", "--a", "24", "--json", "--out", "{P}.json"], False),
    ("certify-periodic", ["certify-periodic", *MODEL, "--period", "1", "--guess", "0.25,12", "--out", "{P}.txt"], False),
    ("sweep", ["sweep", *MODEL, "--theta", "0.5", "--v", "4", "--steps", "20", "--out", "{P}"], False),
    ("continue", ["continue", "--model", "constant", "--eps", "0.25", "--a", "26", "--period", "1", "--guess", "0.5,4",
                  "--range", "24:28", "--out", "{P}"], False),
    ("trajectory", ["trajectory", *MODEL, "--theta", "0.3", "--v", "12", "--periods", "2", "--out", "{P}"], False),
    ("tongues", ["tongues", "--p-max", "3", "--a-range", "0:30", "--eps-range", "0:1", "--out", "{P}"], False),
    ("basin", ["basin", *MODEL, "--grid", "4x3", *SMALL_GRID, "--out", "{P}"], True),
    ("basin-certify", ["basin", *MODEL, "--grid", "3x2", "--certify", "--transient", "10", "--steps", "16", "--quiet", "--out", "{P}"], True),
    ("scan", ["scan", "--model", "constant", "--a-range", "18:26", "--eps-range", "0.4:0.9", "--grid", "2x2", "--ics", "1",
              *SMALL_GRID, "--out", "{P}"], True),
    ("bifurcation", ["bifurcation", "--model", "constant", "--eps", "0.5", "--vary", "a", "--range", "20:24", "--samples", "4",
                     "--theta", "0.3", "--v", "12", "--transient", "10", "--record", "8", "--quiet", "--out", "{P}"], True),
    ("portrait", ["portrait", "--model", "elastic", "--a", "19", "--theta", "0.1", "--v", "9", "--steps", "50", "--quiet",
                  "--out", "{P}"], True),
    ("lyapunov-curve", ["lyapunov", "--model", "veldep", "--c", "1000", "--vary", "a", "--range", "24:26", "--samples", "3",
                        "--ics", "1", "--transient", "10", "--steps", "50", "--quiet", "--out", "{P}"], True),
]
TIMEOUT = 120
failures = []


def fail(case, what):
    failures.append(f"{case}: {what}")
    print(f"FAIL [{case}]: {what}", file=sys.stderr)


def run(argv, cwd):
    try:
        p = subprocess.run([BOUNCER, *argv], cwd=cwd, capture_output=True, text=True, timeout=TIMEOUT)
        return p.returncode, p.stderr
    except subprocess.TimeoutExpired:
        return "timeout", ""


def args(argv, prefix):
    return [a.replace("{P}", prefix) for a in argv]


def victim(root):
    v = root / "victims" / "victim"
    v.parent.mkdir(exist_ok=True)
    v.write_text("precious\n")
    return v


def check_victim(case, v):
    if v.read_text() != "precious\n":
        fail(case, f"the victim {v} was overwritten")


def output_set(name, argv, root):
    d = root / f"{name}-clean"
    d.mkdir()
    rc, err = run(args(argv, "p"), d)
    if rc != 0:
        fail(name, f"the clean run failed ({rc}): {err.strip()[:300]}")
        return {}
    return {f.name: f.read_bytes() for f in d.iterdir() if f.is_file()}


def planted(name, argv, grid, root):
    files = output_set(name, argv, root)
    if not files:
        return
    for f in sorted(files):
        # A link at the output path itself: refused or replaced, never followed.
        d = root / f"{name}-link-{f}"
        d.mkdir()
        v = victim(root)
        (d / f).symlink_to(v)
        rc, err = run(args(argv, "p"), d)
        if rc not in (0, 2):
            fail(f"{name} link at {f}", f"exit {rc}: {err.strip()[:300]}")
        check_victim(f"{name} link at {f}", v)
        # A link at its staging name: the run succeeds, the victim untouched.
        d = root / f"{name}-partial-link-{f}"
        d.mkdir()
        v = victim(root)
        (d / (f + ".partial")).symlink_to(v)
        rc, err = run(args(argv, "p"), d)
        if rc != 0:
            fail(f"{name} link at {f}.partial", f"exit {rc}: {err.strip()[:300]}")
        else:
            out = d / f
            if out.is_symlink() or not out.is_file() or out.stat().st_size == 0:
                fail(f"{name} link at {f}.partial", "the output is not a regular file with content")
            if os.path.lexists(d / (f + ".partial")):
                fail(f"{name} link at {f}.partial", "the staging name is still there")
        check_victim(f"{name} link at {f}.partial", v)
        # A FIFO at the staging name: no hang.
        d = root / f"{name}-partial-fifo-{f}"
        d.mkdir()
        os.mkfifo(d / (f + ".partial"))
        rc, err = run(args(argv, "p"), d)
        if rc != 0:
            fail(f"{name} FIFO at {f}.partial", f"exit {rc}: {err.strip()[:300]}")
        # A FIFO at the output path: written through to its reader.
        d = root / f"{name}-fifo-{f}"
        d.mkdir()
        os.mkfifo(d / f)
        got = {}

        def reader(path=d / f):
            with open(path, "rb") as r:
                got["bytes"] = r.read()

        t = threading.Thread(target=reader, daemon=True)
        t.start()
        rc, err = run(args(argv, "p"), d)
        t.join(timeout=30)
        if rc != 0:
            fail(f"{name} FIFO at {f}", f"exit {rc}: {err.strip()[:300]}")
        elif t.is_alive():
            fail(f"{name} FIFO at {f}", "the reader got no end of file")
            with open(d / f, "wb"):
                pass
        elif not got.get("bytes"):
            fail(f"{name} FIFO at {f}", "the reader got nothing")
        elif files[f][:4] != got["bytes"][:4]:
            fail(f"{name} FIFO at {f}", "the reader got another kind of file")
        if not (d / f).is_fifo():
            fail(f"{name} FIFO at {f}", "the FIFO was replaced")
    if not grid:
        return
    # The tile directory and the files in it.
    d = root / f"{name}-tiles-link"
    d.mkdir()
    vd = root / "victims" / f"{name}-dir"
    vd.mkdir(parents=True)
    (vd / "job.key").write_text("0123456789abcdef\n")
    (vd / "keep.txt").write_text("precious\n")
    (d / "p.tiles").symlink_to(vd)
    rc, err = run(args(argv, "p"), d)
    if rc != 2:
        fail(f"{name} p.tiles a link", f"exit {rc}, expected 2: {err.strip()[:300]}")
    if sorted(x.name for x in vd.iterdir()) != ["job.key", "keep.txt"]:
        fail(f"{name} p.tiles a link", f"the linked directory changed: {sorted(x.name for x in vd.iterdir())}")
    for inside in ("lock", "job.toml", "job.key", "tile-000000.partial"):
        d = root / f"{name}-tiles-{inside}"
        (d / "p.tiles").mkdir(parents=True)
        v = victim(root)
        (d / "p.tiles" / inside).symlink_to(v)
        rc, err = run(args(argv, "p") + ["--keep-tiles"], d)
        if rc not in (0, 2):
            fail(f"{name} link at p.tiles/{inside}", f"exit {rc}: {err.strip()[:300]}")
        check_victim(f"{name} link at p.tiles/{inside}", v)


def reproduce(root):
    argv = ["reproduce", "--only", "elastic-period2", "--out", "r"]
    for sub in ("claims", "logs", "keys"):
        d = root / f"reproduce-{sub}"
        (d / "r").mkdir(parents=True)
        vd = root / "victims" / f"reproduce-{sub}"
        vd.mkdir(parents=True)
        (vd / "keep.txt").write_text("precious\n")
        (d / "r" / sub).symlink_to(vd)
        rc, err = run(argv, d)
        if rc != 2:
            fail(f"reproduce r/{sub} a link", f"exit {rc}, expected 2: {err.strip()[:300]}")
        if [x.name for x in vd.iterdir()] != ["keep.txt"]:
            fail(f"reproduce r/{sub} a link", "files were written through the link")
    for rel in ("claims/elastic-period2.json", "logs/elastic-period2.stderr", "report.md", "claims.json",
                "claims/elastic-period2.json.partial", "keys/elastic-period2.key.partial"):
        d = root / ("reproduce-" + rel.replace("/", "-"))
        (d / "r" / "claims").mkdir(parents=True)
        (d / "r" / "logs").mkdir()
        (d / "r" / "keys").mkdir()
        v = victim(root)
        (d / "r" / rel).symlink_to(v)
        rc, err = run(argv, d)
        if rc not in (0, 2):
            fail(f"reproduce link at r/{rel}", f"exit {rc}: {err.strip()[:300]}")
        check_victim(f"reproduce link at r/{rel}", v)


def main():
    root = pathlib.Path(tempfile.mkdtemp(prefix="bouncer-planted-"))
    try:
        (root / "victims").mkdir()
        for name, argv, grid in COMMANDS:
            planted(name, argv, grid, root)
        reproduce(root)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    if failures:
        print(f"{len(failures)} planted-path check(s) failed", file=sys.stderr)
        return 1
    print(f"planted paths: all checks passed ({len(COMMANDS)} commands and reproduce)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
