#!/usr/bin/env python3
"""bouncer bad-input fuzzer: random mutations of valid command lines and of the valid TOML
scenes in data/scenes, run through the real `bouncer` binary, each run checked for:

  exit      status 0, 1 or 2 only: never a signal, an abort, a timeout or a sanitizer report
            (AddressSanitizer, LeakSanitizer, "runtime error:"), never 1 with "internal error"
  one line  on exit 2, stderr is exactly one newline-terminated line starting with "bouncer"
            and stdout is empty
  no output on exit 2, the case's output directory is empty; after any exit, no *.partial
  time      every run finishes within --timeout seconds

Mutations of command lines: drop, duplicate or misspell an option, drop or swap tokens,
unknown options and commands, and values replaced by NaN, inf, huge and tiny numbers, empty
or blank values, values with newlines or control characters, 100k-character values, wrong
separators. Mutations of scenes (shrunk first so that a valid one runs in well under a
second): truncation, flipped bytes, invalid UTF-8, values of the wrong type, out-of-range
values, duplicated, removed and unknown keys.

Deterministic: case I of seed S is the same on every run (--seed S --case I re-runs it
alone and prints the command, the scene and the output). Exit status 0 if every case holds,
1 otherwise (every failing case is listed with its reproduction), 2 on bad options.

Usage: tools/fuzz_input.py --bouncer build/tools/bouncer [--cases 300] [--seed 1] [--jobs 2]
"""
import argparse
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

SRC = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Valid, quick command lines. {OUT} is the case's output directory, {IN} its input
# directory (a recorded result for audit, shard tiles for merge).
COMMAND_LINES = [
    "orbit --model constant --a 24 --eps 0.5 --theta 0.25 --v 12 --steps 5 --out {OUT}/o.csv",
    "orbit --model veldep --a 28 --c 1000 --theta 0.1 --v 9 --steps 4 --precision mpfr:100 --format json --out {OUT}/o.json",
    "orbit --model elastic --a 19 --theta 0.2125 --v 28 --steps 50 --every 10 --wall asymmetric:0.3 --out {OUT}/o.csv",
    "orbit --model constant --a 28.82 --eps 0.96 --theta 0.5 --v 4 --steps 30 --precision interval:128 --out {OUT}/o.csv",
    "orbit --model constant --a 24 --eps 0.5 --theta 0.1,0.3 --v 9,10 --steps 3 --wall knots:0:-1,0.3:1,0.6:0 --downward-sticking impact --format table",
    "periodic --model constant --eps 0.9 --a 19 --period 2 --guess 0.1678819228862684,14.143149884133248 --out {OUT}/p.txt",
    "certify-sticking --eps 0.5 --a 24 --out {OUT}/s.txt",
    "certify-periodic --model constant --eps 0.9 --a 19 --period 2 --guess 0.1678819228862684,14.143149884133248 --json --out {OUT}/c.json",
    "sweep --model constant --eps 0.5 --a 24 --theta 0.05 --v 10.5 --steps 5 --out {OUT}/w.txt",
    "lyapunov --model constant --a 30 --eps 0.3 --theta 0.3 --v 9 --transient 10 --steps 100 --json --out {OUT}/l.json",
    "classify --model constant --a 24 --eps 0.5 --theta 0.05 --v 10.5 --transient 100 --steps 50",
    "bifurcation --model constant --eps 0.96 --vary a --range 28:29 --samples 6 --transient 50 --record 10 --theta 0.1 --v 5 --out {OUT}/bif",
    "portrait --model elastic --a 19 --theta 0.1,0.3 --v 10,12 --steps 50 --polar --out {OUT}/por",
    "basin --model constant --a 24 --eps 0.5 --theta-range 0:1 --v-range 4:20 --grid 6x4 --transient 50 --steps 20 --out {OUT}/bas",
    "scan --model constant --a-range 18:26 --eps-range 0.4:0.9 --grid 3x2 --ics 2 --transient 50 --steps 32 --out {OUT}/scan",
    "trajectory --model constant --a 24 --eps 0.5 --theta 0.5 --v 4 --periods 2 --samples 20 --out {OUT}/tra",
    "tongues --p-max 4 --a-range 1:30 --eps-range 0:0.9 --samples 20 --out {OUT}/ton",
    "continue --model constant --eps 0.25 --a 26 --period 1 --guess 0.5,4 --range 24:28 --json --out {OUT}/k.json",
    "audit {IN}/rec.csv",
    "merge {IN}/sh --quiet",
]

SCENE_SHRINK = {  # key -> small value, so that a valid scene runs quickly
    "steps": "20", "transient": "30", "samples": "5", "record": "10", "ics": "1",
    "grid": '"4x3"', "every": "1", "max-period": "8",
}

BAD_VALUES = [
    "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e999999999", "-1e999999999", "1e400",
    "1e-400", "1e30", "-1e30", "99999999999999999999999999999", "-99999999999999999999999",
    "9223372036854775808", "-9223372036854775809", "4294967296", "0", "-0", "-1", "0.0",
    "", " ", "  24", "24 ", "\t", "1\n2", "0.5\nx", "\r", "0.1\x01", "\x7f", "\x1b[31m",
    "1,2,3", ",", ":", "0:1:2", "1:", ":1", "x", "0x10", "1_000", "1e", "e5", ".", "-", "+",
    "--", "1/2", "½", "\u00e9", "0.25.1", "3x", "x3", "0x0", "1x0", "-3x4", "mpfr:", "mpfr:0",
    "mpfr:99999999999", "interval:8", "knots:", "knots:0:1", "asymmetric:", "asymmetric:1",
    "true", "on", "off",
]


def long_values(rng):
    n = 100000
    return rng.choice(["9" * n, "0." + "1" * n, "a" * n, "1e" + "9" * n, ",".join(["1"] * (n // 2)),
                       "-" * n, "\n" * n, ("0.1:" * (n // 4))[:n]])


def bad_value(rng):
    if rng.random() < 0.08:
        return long_values(rng)
    return rng.choice(BAD_VALUES)


def typo(rng, word):
    if not word:
        return "x"
    i = rng.randrange(len(word))
    op = rng.randrange(4)
    if op == 0:
        return word[:i] + word[i + 1:]
    if op == 1:
        return word[:i] + rng.choice("abcdefgxyz-_=") + word[i:]
    if op == 2 and len(word) > 1:
        j = min(i + 1, len(word) - 1)
        w = list(word)
        w[i], w[j] = w[j], w[i]
        return "".join(w)
    return word.upper()


def option_spans(args):
    """(start, end) of each option with its values: --x v1 v2 ... up to the next --option."""
    spans = []
    i = 1
    while i < len(args):
        if args[i].startswith("--"):
            j = i + 1
            while j < len(args) and not args[j].startswith("--"):
                j += 1
            spans.append((i, j))
            i = j
        else:
            i += 1
    return spans


def mutate_args(rng, args):
    args = list(args)
    for _ in range(1 + rng.randrange(3)):
        spans = option_spans(args)
        op = rng.randrange(12)
        if op == 0 and spans:  # drop an option
            s, e = rng.choice(spans)
            del args[s:e]
        elif op == 1 and spans:  # duplicate an option (maybe with a bad value)
            s, e = rng.choice(spans)
            extra = args[s:e]
            if len(extra) > 1 and rng.random() < 0.5:
                extra[1] = bad_value(rng)
            pos = rng.randrange(1, len(args) + 1)
            args[pos:pos] = extra
        elif op == 2 and spans:  # misspelled option
            s, _ = rng.choice(spans)
            args[s] = "--" + typo(rng, args[s][2:])
        elif op in (3, 4, 5, 6) and spans:  # bad value
            s, e = rng.choice(spans)
            if e > s + 1:
                k = rng.randrange(s + 1, e)
                if rng.random() < 0.3 and "," in args[k]:
                    parts = args[k].split(",")
                    parts[rng.randrange(len(parts))] = bad_value(rng)
                    args[k] = ",".join(parts)
                elif rng.random() < 0.3 and ":" in args[k]:
                    parts = args[k].split(":")
                    parts[rng.randrange(len(parts))] = bad_value(rng)
                    args[k] = ":".join(parts)
                else:
                    args[k] = bad_value(rng)
            else:
                args.insert(e, bad_value(rng))
        elif op == 7 and spans:  # --opt=value form with a bad value
            s, e = rng.choice(spans)
            args[s:e] = [args[s] + "=" + bad_value(rng)]
        elif op == 8:  # unknown command
            args[0] = rng.choice([typo(rng, args[0]), "frobnicate", "", "-", "--orbit", "ORBIT", bad_value(rng)])
        elif op == 9:  # unknown option
            pos = rng.randrange(1, len(args) + 1)
            args[pos:pos] = rng.choice([["--bogus"], ["--bogus", "1"], ["-x"], ["--"], ["-"], ["--a="], [bad_value(rng)]])
        elif op == 10 and len(args) > 2:  # swap two tokens
            i, j = rng.randrange(len(args)), rng.randrange(len(args))
            args[i], args[j] = args[j], args[i]
        elif op == 11 and len(args) > 1:  # drop one token
            del args[rng.randrange(len(args))]
    return [a[:120000] for a in args]  # the kernel's limit for one argument is 128 KiB


# ---- scenes -------------------------------------------------------------------------------
def shrink(text):
    out = []
    for line in text.splitlines():
        m = re.match(r"^([A-Za-z-]+)\s*=", line)
        if m and m.group(1) in SCENE_SHRINK:
            line = f"{m.group(1)} = {SCENE_SHRINK[m.group(1)]}"
        out.append(line)
    return "\n".join(out) + "\n"


def mutate_scene(rng, text):
    data = text.encode()
    for _ in range(1 + rng.randrange(3)):
        lines = data.split(b"\n")
        keyed = [i for i, l in enumerate(lines) if re.match(rb"^[A-Za-z-]+\s*=", l)]
        op = rng.randrange(10)
        if op == 0 and data:  # truncate
            data = data[:rng.randrange(len(data))]
            continue
        if op == 1 and data:  # flip bytes
            b = bytearray(data)
            for _ in range(1 + rng.randrange(4)):
                b[rng.randrange(len(b))] ^= 1 << rng.randrange(8)
            data = bytes(b)
            continue
        if op == 2 and data:  # invalid UTF-8 / control characters
            pos = rng.randrange(len(data) + 1)
            data = data[:pos] + rng.choice([b"\xff", b"\xc3", b"\x00", b"\x01", b"\x1b", b"\r", b"\xed\xa0\x80"]) + data[pos:]
            continue
        if not keyed:
            continue
        i = rng.choice(keyed)
        key = lines[i].split(b"=", 1)[0].strip()
        if op in (3, 4, 5):  # wrong type or out-of-range value
            v = rng.choice([b"1", b"-1", b"0", b"1e30", b"-1e30", b"nan", b"inf", b"-inf", b"true", b"1.5",
                            b"[]", b"[1, 2]", b'["a", 3]', b"{ x = 1 }", b'""', b'"nan"', b'"inf"', b'"-1"',
                            b'"1e999999"', b'"0"', b'"x"', b'"1e30"', b'"24\\n1"', b'"\\u0001"', b"1979-05-27",
                            b"9223372036854775807", b"-9223372036854775808", b"99999999999999999999",
                            b'"' + b"9" * 100000 + b'"', b"0x10", b"1_000", b"+inf"])
            lines[i] = key + b" = " + v
        elif op == 6:  # duplicate a key
            lines.insert(i + 1, lines[i])
        elif op == 7:  # remove a key
            del lines[i]
        elif op == 8:  # unknown key, or a table header
            lines.insert(i, rng.choice([b"bogus = 1", b'colour = "red"', b"[table]", b"[[array]]", b"a.b = 1"]))
        else:  # value without quotes (a TOML float/int where a string is expected) or unparsable
            val = lines[i].split(b"=", 1)[1].strip()
            lines[i] = key + b" = " + (val.strip(b'"') if rng.random() < 0.5 else val + b" trailing")
        data = b"\n".join(lines)
    return data


# ---- running a case -----------------------------------------------------------------------
SANITIZER_MARKS = ("AddressSanitizer", "LeakSanitizer", "UndefinedBehaviorSanitizer", "runtime error:",
                   "terminate called", "Assertion `", "Segmentation fault", "stack smashing")


class Case:
    def __init__(self, index, kind, args, scene=None):
        self.index, self.kind, self.args, self.scene = index, kind, args, scene


def make_case(seed, index, scenes):
    rng = random.Random(f"bouncer-fuzz-input:{seed}:{index}")
    if rng.random() < 0.65:
        base = rng.choice(COMMAND_LINES).split()
        return Case(index, "command line", mutate_args(rng, base))
    name = rng.choice(sorted(scenes))
    text = shrink(scenes[name])
    command = re.search(r'^command\s*=\s*"([a-z-]+)"', text, re.M).group(1)
    args = [command, "--scene", "{IN}/scene.toml", "--out", "{OUT}/res"]
    if rng.random() < 0.2:
        args = mutate_args(rng, args)
    return Case(index, f"scene {name}", args, mutate_scene(rng, text))


def prepare_inputs(bouncer, root):
    """A recorded result (for audit) and shard tiles (for merge), made once."""
    inp = os.path.join(root, "inputs")
    os.makedirs(inp)
    subprocess.run([bouncer, "orbit", "--model", "constant", "--a", "24", "--eps", "0.5", "--theta", "0.25",
                    "--v", "12", "--steps", "3", "--out", os.path.join(inp, "rec.csv")], check=True,
                   stdout=subprocess.DEVNULL, timeout=120)
    for i in range(2):
        subprocess.run([bouncer, "basin", "--model", "constant", "--a", "24", "--eps", "0.5", "--grid", "4x3",
                        "--transient", "20", "--steps", "16", "--shard", f"{i}/2", "--quiet",
                        "--out", os.path.join(inp, "sh")], check=True, stdout=subprocess.DEVNULL, timeout=120)
    return inp


def run_case(bouncer, root, inputs, case, timeout):
    d = os.path.join(root, f"case{case.index}")
    out, inp = os.path.join(d, "out"), os.path.join(d, "in")
    os.makedirs(out)
    shutil.copytree(inputs, inp)
    if case.scene is not None:
        with open(os.path.join(inp, "scene.toml"), "wb") as f:
            f.write(case.scene)
    args = [a.replace("{OUT}", out).replace("{IN}", inp) for a in case.args]
    problems = []
    try:
        p = subprocess.run([bouncer] + args, cwd=out, stdin=subprocess.DEVNULL, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        shutil.rmtree(d, ignore_errors=True)
        return [f"did not finish within {timeout} s"], None
    rc, stdout, stderr = p.returncode, p.stdout, p.stderr.decode("utf-8", "replace")
    if rc < 0:
        problems.append(f"killed by signal {-rc}")
    elif rc not in (0, 1, 2):
        problems.append(f"exit status {rc}")
    for mark in SANITIZER_MARKS:
        if mark in stderr:
            problems.append(f"stderr has '{mark}'")
    if rc == 1 and "internal error" in stderr:
        problems.append("exit 1 with an internal error")
    if rc == 2:
        if not (stderr.endswith("\n") and stderr.count("\n") == 1 and stderr.startswith("bouncer")):
            problems.append("exit 2 without exactly one stderr line starting with 'bouncer'")
        if stdout:
            problems.append("exit 2 with output on stdout")
        left = sorted(os.listdir(out))
        if left:
            problems.append(f"exit 2 left output behind: {left[:5]}")
    partial = [f for r, _, fs in os.walk(d) for f in fs if f.endswith(".partial")]
    if partial:
        problems.append(f"*.partial left behind: {partial[:5]}")
    shutil.rmtree(d, ignore_errors=True)
    return problems, (rc, stderr)


def show(s, limit=300):
    r = repr(s)
    return r if len(r) <= limit else r[:limit] + f"...<{len(s)} chars>"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bouncer", required=True, help="the bouncer binary")
    ap.add_argument("--cases", type=int, default=300, help="number of cases (default 300)")
    ap.add_argument("--seed", type=int, default=1, help="seed (default 1)")
    ap.add_argument("--case", type=int, help="run only case I of the seed, and print it in full")
    ap.add_argument("--jobs", type=int, default=2, help="cases run at the same time (default 2)")
    ap.add_argument("--timeout", type=float, default=30, help="time limit per run in seconds (default 30)")
    try:
        o = ap.parse_args()
    except SystemExit as e:
        sys.exit(0 if e.code == 0 else 2)
    if o.cases < 1 or o.jobs < 1 or o.timeout <= 0:
        print("fuzz_input: --cases and --jobs must be >= 1, --timeout > 0", file=sys.stderr)
        sys.exit(2)
    bouncer = os.path.abspath(o.bouncer)
    scenes = {}
    for name in sorted(os.listdir(os.path.join(SRC, "data", "scenes"))):
        if name.endswith(".toml"):
            with open(os.path.join(SRC, "data", "scenes", name)) as f:
                scenes[name] = f.read()
    indices = [o.case] if o.case is not None else list(range(o.cases))
    root = tempfile.mkdtemp(prefix="bouncer-fuzz-input.")
    try:
        inputs = prepare_inputs(bouncer, root)
        cases = [make_case(o.seed, i, scenes) for i in indices]
        with ThreadPoolExecutor(max_workers=o.jobs) as pool:
            results = list(pool.map(lambda c: run_case(bouncer, root, inputs, c, o.timeout), cases))
    finally:
        shutil.rmtree(root, ignore_errors=True)
    statuses = {}
    failures = 0
    for case, (problems, res) in zip(cases, results):
        key = "timeout" if res is None else str(res[0])
        statuses[key] = statuses.get(key, 0) + 1
        if problems or o.case is not None:
            if problems:
                failures += 1
            print(f"case {case.index} ({case.kind}): {'; '.join(problems) if problems else 'ok'}")
            print(f"  bouncer {' '.join(show(a, 120) for a in case.args)}")
            if case.scene is not None:
                print(f"  scene: {show(case.scene, 600 if o.case is None else 100000)}")
            if res is not None:
                print(f"  exit {res[0]}, stderr: {show(res[1], 400)}")
            print(f"  reproduce: tools/fuzz_input.py --bouncer {o.bouncer} --seed {o.seed} --case {case.index}")
    summary = ", ".join(f"exit {k}: {v}" for k, v in sorted(statuses.items()))
    print(f"fuzz_input: seed {o.seed}, {len(cases)} cases ({summary}); {failures} failing")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
