"""The checks of the CLI scripts' inline Python (tests/cli/*.sh, `python3 - <<'PY'`):
check(cond, what) reports a failed property on stderr and counts it; done() exits 1 if any
failed, else 0. tests/cli/lib/common.sh puts this directory on PYTHONPATH."""
import sys

failures = 0


def check(cond, what):
    global failures
    if not cond:
        print("FAIL:", what, file=sys.stderr)
        failures += 1


def done():
    sys.exit(1 if failures else 0)
