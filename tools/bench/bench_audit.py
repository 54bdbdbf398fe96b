"""bench_audit: `bouncer audit DIR` against the `bouncer reproduce` it reruns, measured in one run.

    python3 tools/bench/bench_audit.py --cli build/tools/bouncer [--rounds N] [--only IDS] [--quick] [--json FILE]
    python3 tools/bench/bench_audit.py --columns    (the table's columns as JSON; nothing run)
    cmake --build build --target bench_audit      (the same, with the build's executable)

Each round runs `bouncer reproduce --quick --out T/rK` and then `bouncer audit T/rK` (the
audit reruns that same reproduce in its private directory and compares item by item), and
times both by the wall clock. The audit's own stderr line ("bouncer audit: X s the rerun of
reproduce, Y s the comparison") splits its time into the rerun and the comparison.
Rows: the run, the audit, its rerun and its comparison (best and median over the rounds),
the CPU time of the run and of the audit (user + sys of every process, from
getrusage(RUSAGE_CHILDREN): the work done, much less sensitive to the load than the wall
clock), and audit / run per round. The target (issue 24, item 7): the audit takes the run's time
plus the comparison's. The machine is shared: the run and the audit of one round follow each
other, so that both see about the same load; absolute times vary from run to run. Timings
are printed, never checked; --quick is a smoke run (two items, one round) that checks only
that the audit says identical. --json FILE also writes the table with the run's provenance
(tools/bench/bench_record.py, for tools/bench/record_tables.py).
"""

import argparse
import os
import platform
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ beside the scripts
import bench_record  # noqa: E402 (tools/bench/bench_record.py, beside this script)

QUICK_ONLY = "elastic-period2,fig:arnold"


def cpu_of_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(argv):
    """Wall-clock seconds, CPU seconds (user + sys of the process and every descendant it
    waited for: reproduce waits for its items, audit for its reproduce) and the process."""
    c0, t0 = cpu_of_children(), time.perf_counter()
    p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return time.perf_counter() - t0, cpu_of_children() - c0, p


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", default="build/tools/bouncer", help="the bouncer executable (default build/tools/bouncer)")
    ap.add_argument("--rounds", type=int, default=1, help="run + audit pairs (default 1; each about 2 x 40-90 s)")
    ap.add_argument("--only", help="reproduce --only LIST (default: every item of --quick)")
    ap.add_argument("--quick", action="store_true", help=f"smoke run: --only {QUICK_ONLY}, one round")
    ap.add_argument("--json", metavar="FILE", help="also write the table and the run's provenance as JSON")
    ap.add_argument("--columns", action="store_true", help="print the table's columns as JSON and exit (nothing run)")
    args = ap.parse_args()
    run = bench_record.Run("bench_audit.py", sys.argv[1:])
    table = bench_record.Table("audit", "bouncer audit DIR against the bouncer reproduce --quick it reruns",
                               ["what", "best s", "median s"])
    if args.columns:
        return run.print_columns([table])
    only = QUICK_ONLY if args.quick else args.only
    rounds = 1 if args.quick else max(1, args.rounds)
    cli = os.path.abspath(args.cli)

    rows = {"run": [], "audit": [], "rerun": [], "comparison": [], "run_cpu": [], "audit_cpu": []}
    with tempfile.TemporaryDirectory(prefix="bench-audit-") as tmp:
        for k in range(rounds):
            d = os.path.join(tmp, f"r{k}")
            argv = [cli, "reproduce", "--quick", "--out", d] + (["--only", only] if only else [])
            t_run, cpu_run, p = timed(argv)
            if p.returncode != 0:
                sys.exit(f"bench_audit: reproduce failed (exit {p.returncode}): {p.stderr.strip().splitlines()[-1:]}")
            t_audit, cpu_audit, a = timed([cli, "audit", d])
            if a.returncode != 0 or "identical" not in a.stdout:
                sys.exit(f"bench_audit: audit did not say identical (exit {a.returncode}): {a.stdout.strip()} {a.stderr.strip()}")
            m = re.search(r"bouncer audit: ([0-9.]+) s the rerun of reproduce, ([0-9.]+) s the comparison", a.stderr)
            if not m:
                sys.exit(f"bench_audit: no timing line on audit's stderr: {a.stderr.strip()}")
            rows["run"].append(t_run)
            rows["audit"].append(t_audit)
            rows["rerun"].append(float(m.group(1)))
            rows["comparison"].append(float(m.group(2)))
            rows["run_cpu"].append(cpu_run)
            rows["audit_cpu"].append(cpu_audit)

    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"bench_audit: {platform.node()}, {os.cpu_count()} cores, load {load:.1f} at the end; "
          f"reproduce --quick{' --only ' + only if only else ''}, {rounds} round(s)")
    print()
    for name, label in (("run", "bouncer reproduce --quick (the run)"), ("audit", "bouncer audit DIR (the audit)"),
                        ("rerun", "  of which the rerun of reproduce"), ("comparison", "  of which the comparison"),
                        ("run_cpu", "CPU of the run (user + sys, every process)"),
                        ("audit_cpu", "CPU of the audit (user + sys, every process)")):
        v = rows[name]
        table.add(label, f"{min(v):.2f}", f"{statistics.median(v):.2f}")
    ratios = ", ".join(f"{a / r:.2f}" for a, r in zip(rows["audit"], rows["run"]))
    cpu_ratios = ", ".join(f"{a / r:.2f}" for a, r in zip(rows["audit_cpu"], rows["run_cpu"]))
    table.notes.append(f"audit / run per round: {ratios} wall clock, {cpu_ratios} CPU (target: about 1, the comparison's "
                       f"{statistics.median(rows['comparison']):.2f} s on top; the wall clock follows the machine's load, "
                       f"the CPU time the work done); {rounds} round(s), load average {load:.1f} at the end.")
    table.print_text()
    run.finish_cli(args.json, [table], cli)
    return 0


if __name__ == "__main__":
    sys.exit(main())
