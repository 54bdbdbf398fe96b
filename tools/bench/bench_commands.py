"""bench_commands: certified runs of the bouncer command line, timed whole, with what they certified.

    python3 tools/bench/bench_commands.py --cli build/tools/bouncer [--quick] [--newcomer] [--threads N] [--json FILE]
    python3 tools/bench/bench_commands.py --columns    (the table's columns as JSON; nothing run)
    cmake --build build --target bench_commands      (the same, with the build's executable)

Each row is one run of one `bouncer` command, as a user types it (outputs written to a
temporary directory, then removed):
  * `basin --certify` at eps = 0.5, a = 24, 200 x 200 starts, 5000 + 500 steps, MPFI up to
    256 bits (the certified basin of docs/guide/pictures.md; issue 3's target: under 10
    minutes on 2 cores);
  * `bifurcation --certify` at eps = 0.96, a in [28, 30], 400 columns from (1/2, 4),
    5000 + 500 steps (the certified bifurcation columns);
  * with --newcomer, the newcomer's one command of docs/guide/attractors.md, `attractors
    --model veldep --c 1000 --vary a --range 15:31 --values 161 --starts 32x32` (5 to 6
    minutes on 2 cores by itself: left out unless asked for).
Each is timed by the wall clock, and by the CPU time (user + sys) and peak resident memory
of its process, both from wait4() (the resource usage of that one child, all its threads).
Beside the timings, the facts the run certified, read from its JSON summary: how many starts
or columns are certified and undecided, where double's answer is refuted, which tier of the
schedule decided them. Those counts are checked against each other before anything is
written (the classes sum to the grid, the agreement counts to the starts, the CSV has one row
per start, the columns listed are the samples asked for): a run whose summary does not add up
exits 1. Timings are printed, never checked. --quick: the same commands on 10 x 10 starts and
10 columns, and --newcomer on 5 values (seconds; the ctest smoke run bench.commands_quick).
--json FILE also writes the table with the run's provenance (tools/bench/bench_record.py, for
tools/bench/record_tables.py).
"""

import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ beside the scripts
import bench_record  # noqa: E402 (tools/bench/bench_record.py, beside this script)


class Failed(Exception):
    """A command failed, or its summary does not add up."""


def timed(argv, log_path):
    """(wall s, CPU s, peak RSS in MB, exit status) of one child process: its resource usage
    from wait4(), so the CPU time and the memory are its own (every thread), not those of the
    other children of this script. Its stdout and stderr go to log_path."""
    with open(log_path, "w") as log:
        t0 = time.perf_counter()
        p = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT)
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait again
    return wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024.0, p.returncode


def summary_of(prefix):
    with open(prefix + ".json") as f:
        return json.load(f)["summary"]


def count(s, n):
    return f"{s} of {n}"


def basin_facts(prefix, grid):
    s = summary_of(prefix)
    n = grid[0] * grid[1]
    classes = s["classes"]
    by_class = {}
    for c in classes:
        name = c["class"] + (f" {c['period']}" if c.get("period") else "")
        by_class[name] = by_class.get(name, 0) + c["points"]
    undecided = sum(c["points"] for c in classes if c["class"] == "undecided")
    agree = s["double_vs_certified"]
    decided_by = s["decided_by"]
    with open(prefix + ".csv") as f:
        rows = sum(1 for r in csv.reader(f) if r and not r[0].startswith("#")) - 1  # less the header
    problems = []
    if s["points"] != n or sum(by_class.values()) != n:
        problems.append(f"the classes count {sum(by_class.values())} starts, the summary {s['points']}, the grid {n}")
    if agree["agrees"] + agree["differs"] + agree["undecided"] != n:
        problems.append(f"double_vs_certified counts {agree['agrees'] + agree['differs'] + agree['undecided']} starts of {n}")
    if agree["undecided"] != undecided:
        problems.append(f"{undecided} starts are undecided, double_vs_certified says {agree['undecided']}")
    if sum(decided_by.values()) != n - undecided:
        problems.append(f"decided_by counts {sum(decided_by.values())} starts, {n - undecided} are decided")
    if rows != n:
        problems.append(f"the CSV has {rows} rows for {n} starts")
    if problems:
        raise Failed("basin --certify: " + "; ".join(problems))
    details = ("classes: " + ", ".join(f"{k} {v}" for k, v in sorted(by_class.items(), key=lambda kv: -kv[1]))
               + f"; double agrees at {agree['agrees']}; decided by "
               + ", ".join(f"{k} {v}" for k, v in sorted(decided_by.items(), key=lambda kv: -kv[1])))
    return [count(n - undecided, f"{n} starts"), str(undecided), str(agree["differs"]), details], []


def bifurcation_facts(prefix, samples):
    s = summary_of(prefix)
    cols = s["columns"]
    undecided = [c for c in cols if c["class"] == "undecided"]
    refuted = [c for c in cols if c["agreement"] == "differs"]
    agree = s["double_vs_certified"]
    tiers = {}
    for c in cols:
        if c["class"] != "undecided":
            tiers[c["scalar"]] = tiers.get(c["scalar"], 0) + 1
    problems = []
    if len(cols) != samples or s["samples"] != samples:
        problems.append(f"{len(cols)} columns listed, the summary says {s['samples']}, {samples} asked for")
    for k in ("agrees", "differs", "undecided"):
        listed = sum(1 for c in cols if c["agreement"] == k)
        if listed != agree[k]:
            problems.append(f"double_vs_certified says {agree[k]} {k}, the columns {listed}")
    if agree["undecided"] != len(undecided):
        problems.append(f"{len(undecided)} columns are undecided, double_vs_certified says {agree['undecided']}")
    if problems:
        raise Failed("bifurcation --certify: " + "; ".join(problems))
    certified = samples - len(undecided)

    def label(cls, period):
        return cls + (f" {period}" if period else "")

    details = (f"double agrees with {agree['agrees']} of the {certified} certified; decided by "
               + ", ".join(f"{k} {v}" for k, v in sorted(tiers.items(), key=lambda kv: -kv[1])))
    notes = [f"bifurcation --certify: double refuted at a = {float(c['a'])!r}: certified {label(c['class'], c['period'])} "
             f"(by {c['scalar']}), double says {label(c['double_class'], c['double_period'])}." for c in refuted]
    return [count(certified, f"{samples} columns"), str(len(undecided)), str(len(refuted)), details], notes


def attractors_facts(prefix, values):
    s = summary_of(prefix)
    if len(s["values"]) != values:
        raise Failed(f"attractors: {len(s['values'])} values in the summary, {values} asked for")
    kinds = {}
    for c in s["chains"]:
        kinds[c["kind"]] = kinds.get(c["kind"], 0) + 1
    events = [e for b in s["branches"] for e in b["events"] if e["kind"] != "range_end"]
    certified = sum(1 for e in events if e["certified"])
    periods = [b["period"] for b in s["branches"] if b.get("period")]
    details = (f"{len(s['chains'])} chains (" + ", ".join(f"{v} {k}" for k, v in sorted(kinds.items(), key=lambda kv: -kv[1]))
               + f"), {len(s['branches'])} branches" + (f" (periods {min(periods)} to {max(periods)})" if periods else ""))
    return [count(certified, f"{len(events)} branch events"), str(len(events) - certified), "-", details], []


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", default="build/tools/bouncer", help="the bouncer executable (default build/tools/bouncer)")
    ap.add_argument("--quick", action="store_true", help="smoke run: 10 x 10 starts, 10 columns (seconds)")
    ap.add_argument("--newcomer", action="store_true",
                    help="also the newcomer's attractors run over a in [15, 31] (5 to 6 minutes on 2 cores; 5 values with --quick)")
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 1,
                    help="--threads of every command (default: the machine's cores)")
    ap.add_argument("--json", metavar="FILE", help="also write the table and the run's provenance as JSON")
    ap.add_argument("--columns", action="store_true", help="print the table's columns as JSON and exit (nothing run)")
    args = ap.parse_args()
    run = bench_record.Run("bench_commands.py", sys.argv[1:])
    table = bench_record.Table("commands", "certified runs of the command line: time, memory and what they certified",
                               ["command", "threads", "wall s", "CPU s", "peak RSS MB", "certified", "undecided",
                                "double refuted", "details"])
    if args.columns:
        return run.print_columns([table])
    if args.threads < 1:
        print(f"bench_commands: --threads {args.threads}: must be an integer >= 1", file=sys.stderr)
        return 2
    cli = os.path.abspath(args.cli)
    grid = (10, 10) if args.quick else (200, 200)
    samples = 10 if args.quick else 400
    values = 5 if args.quick else 161
    # (shown command, arguments, facts): the shown command is the row's name, without --out
    # and --threads (the table's column), exactly what a user types.
    cases = [
        (["basin", "--model", "constant", "--eps", "0.5", "--a", "24", "--grid", f"{grid[0]}x{grid[1]}", "--certify"],
         lambda p: basin_facts(p, grid)),
        (["bifurcation", "--model", "constant", "--eps", "0.96", "--range", "28:30", "--samples", str(samples),
          "--theta", "0.5", "--v", "4", "--certify"],
         lambda p: bifurcation_facts(p, samples)),
    ]
    if args.newcomer:
        cases.append((["attractors", "--model", "veldep", "--c", "1000", "--vary", "a", "--range", "15:31", "--values",
                       str(values), "--starts", "32x32"], lambda p: attractors_facts(p, values)))
    with tempfile.TemporaryDirectory(prefix="bench-commands-") as tmp:
        for k, (words, facts) in enumerate(cases):
            prefix = os.path.join(tmp, f"c{k}")
            shown = "bouncer " + " ".join(words)
            print(f"bench_commands: {shown} --threads {args.threads} ...", flush=True)
            wall, cpu, rss, code = timed([cli] + words + ["--threads", str(args.threads), "--out", prefix], prefix + ".log")
            if code != 0:
                with open(prefix + ".log") as f:
                    tail = f.read().strip().splitlines()[-3:]
                print(f"bench_commands: {shown} failed (exit {code}): {' '.join(tail)}", file=sys.stderr)
                return 1
            try:
                cells, notes = facts(prefix)
            except (Failed, OSError, KeyError, ValueError) as x:
                print(f"bench_commands: {shown}: its summary does not add up: {x}", file=sys.stderr)
                return 1
            table.add(shown, str(args.threads), f"{wall:.1f}", f"{cpu:.1f}", f"{rss:.1f}", *cells)
            table.notes.extend(notes)
    table.notes.append("wall s: the wall clock; CPU s: user + sys of the command's process, every thread; peak RSS: its "
                       "largest resident set (both from wait4()). certified: starts, columns or branch events with a "
                       "certificate; undecided: no claim at the largest precision; double refuted: where the certificate "
                       f"contradicts plain double's class.{' --quick: small grids, a smoke run.' if args.quick else ''}")
    print()
    table.print_text()
    run.finish_cli(args.json, [table], cli)
    return 0


if __name__ == "__main__":
    sys.exit(main())
