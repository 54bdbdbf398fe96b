"""bench_python: the cost of the Python layer over the library, measured in one run.

    PYTHONPATH=build/python python3 tools/bench/bench_python.py [--quick] [--cli build/tools/bouncer] [--json FILE]
    python3 tools/bench/bench_python.py --columns    (the table's columns as JSON; nothing run)
    cmake --build build --target bench_python      (the same, with the build's paths)

Rows (double precision, constant restitution eps = 0.96, a = 28.82, from (0.3, 7.5): a
chaotic orbit without sticking):
  * Model.step per call from a Python loop (`s = step(theta, v); theta, v = s.theta, s.v`),
    next to the same steps inside the library's orbit loop without storing rows
    (Model.orbit(..., every=N): the C++ floor) and a bare Python loop of the same shape;
  * Model.orbit of N = 1e6 steps to numpy arrays, against the CLI's orbit of the same steps
    run in this process (bouncer.run("orbit", ...): `bouncer orbit`'s code, CSV text into a
    buffer), and against the floor;
  * with --cli: the executable itself (`bouncer orbit ... > /dev/null`), for reference.
Targets (issue 22): step <= 2 us per call; orbit to numpy <= 1.5 x the CLI's in-process orbit.
Each time is the best of several rounds (thread CPU time is not used: orbit runs on a worker
thread); the machine is shared, so absolute numbers vary from run to run. Timings are
printed, never checked; --quick is a smoke run (small N, one round). --json FILE also writes
the table with the run's provenance (tools/bench/bench_record.py, for tools/bench/record_tables.py).
"""

import argparse
import os
import platform
import subprocess
import sys
import time

sys.dont_write_bytecode = True  # no __pycache__ beside the scripts
import bench_record  # noqa: E402 (tools/bench/bench_record.py, beside this script)

PARAMS = dict(model="constant", a="28.82", eps="0.96")
START = (0.3, 7.5)


def best(f, rounds):
    times = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="smoke run: small N, one round")
    ap.add_argument("--cli", help="the bouncer executable, to time `bouncer orbit` as a process too")
    ap.add_argument("--json", metavar="FILE", help="also write the table and the run's provenance as JSON")
    ap.add_argument("--columns", action="store_true", help="print the table's columns as JSON and exit (nothing run)")
    args = ap.parse_args()
    run = bench_record.Run("bench_python.py", sys.argv[1:])
    table = bench_record.Table("python", "the Python layer over the library (double, eps = 0.96, a = 28.82, start (0.3, 7.5))",
                               ["measurement", "value", "target"])
    if args.columns:
        return run.print_columns([table])
    global bouncer
    import bouncer
    n_orbit = 20000 if args.quick else 10**6
    n_step = 20000 if args.quick else 300000
    rounds = 1 if args.quick else 5

    m = bouncer.Model(**PARAMS)
    step = m.step

    def step_loop():
        theta, v = START
        for _ in range(n_step):
            s = step(theta, v)
            theta, v = s.theta, s.v

    def empty_loop():
        theta, v = START
        for _ in range(n_step):
            s = (theta, v)
            theta, v = s[0], s[1]

    def floor_steps():
        m.orbit(*START, n_step, every=n_step)

    t_step = best(step_loop, rounds) / n_step
    t_empty = best(empty_loop, rounds) / n_step
    t_floor_step = best(floor_steps, rounds) / n_step

    arrays = {}

    def orbit_numpy():
        arrays["o"] = m.orbit(*START, n_orbit)

    def orbit_cli_inprocess():
        bouncer.run("orbit", **PARAMS, theta=str(START[0]), v=str(START[1]), steps=n_orbit)

    def orbit_floor():
        m.orbit(*START, n_orbit, every=n_orbit)

    t_orbit = best(orbit_numpy, rounds)
    t_cli = best(orbit_cli_inprocess, max(1, rounds // 2))
    t_floor = best(orbit_floor, rounds)
    t_exe = None
    if args.cli:
        words = bouncer._words("orbit", dict(PARAMS, theta=str(START[0]), v=str(START[1]), steps=n_orbit))[1:]

        def exe():
            subprocess.run([args.cli, *words], stdout=subprocess.DEVNULL, check=True)

        t_exe = best(exe, max(1, rounds // 2))

    o = arrays["o"]
    assert len(o) == n_orbit + 1 and o.status == "completed"
    print("# bench_python: the Python layer over the library (double, eps = 0.96, a = 28.82, start (0.3, 7.5))")
    print(f"# bouncer {bouncer.__version__} (commit {bouncer._core.commit}), Python {platform.python_version()}, "
          f"{os.cpu_count()} cpus, load average at start {os.getloadavg()[0]:.2f}")
    table.add("Model.step per call from Python", f"{t_step * 1e6:.3f} us", "<= 2 us")
    table.add("  the same step in the library loop (floor)", f"{t_floor_step * 1e6:.3f} us", "")
    table.add("  a Python loop of the same shape, no step", f"{t_empty * 1e6:.3f} us", "")
    table.add(f"Model.orbit, {n_orbit} steps to numpy", f"{t_orbit:.3f} s", "")
    table.add("  the CLI orbit in this process (bouncer.run)", f"{t_cli:.3f} s", "")
    table.add("  the library loop without rows (floor)", f"{t_floor:.3f} s", "")
    if t_exe is not None:
        table.add("  the bouncer executable, CSV to /dev/null", f"{t_exe:.3f} s", "")
    table.add("ratio Model.orbit / CLI in-process orbit", f"{t_orbit / t_cli:.3f}x", "<= 1.5x")
    table.add("ratio Model.orbit / floor", f"{t_orbit / t_floor:.3f}x", "")
    table.add("ratio Model.step per call / floor per step", f"{t_step / t_floor_step:.1f}x", "")
    table.notes.append(f"Best of {rounds} rounds{' (--quick)' if args.quick else ''}; wall-clock time; "
                       f"Python {platform.python_version()}.")
    table.print_text()
    run.finish(args.json, [table], bouncer.__version__, bouncer._core.commit)
    return 0


if __name__ == "__main__":
    sys.exit(main())
