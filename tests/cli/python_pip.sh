#!/usr/bin/env bash
# `pip install --no-build-isolation .` in a fresh virtual environment (with the system's site
# packages: Debian's numpy, setuptools and wheel), then the installed package away from the
# source and build trees: its metadata (importlib.metadata.version equals `bouncer
# --version`), an import, Model.step against the paper's eq. 5 fixed point, and the typed
# layer's quick tests (tests/python/test_model.py) run against it.
#
# Cost: the package reuses this build tree (BOUNCER_BUILD_DIR: setup.py brings its
# bouncer_python target up to date, a no-op here) instead of building the library a second
# time, which a plain `pip install .` does (minutes on 2 cores). The source is copied (the
# files pip needs) so that setuptools' scratch files never land in the source tree.
# Exit 77 (skipped) when this build has no Python module, or Debian's python3-venv,
# python3-pip, python3-setuptools or python3-wheel is missing.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
bouncer=$(cd "$(dirname "$BOUNCER")" && pwd)/$(basename "$BOUNCER")
src=$(cd "$SRC" && pwd)
build=$(cd "$(dirname "$bouncer")/.." && pwd)
tmp=$TMP
compgen -G "$build/python/bouncer/_core*.so" >/dev/null || skip "this build has no Python module"
python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
[[ -x $python ]] || skip "no Python3_EXECUTABLE in $build/CMakeCache.txt"
"$python" -c "import setuptools, wheel" 2>/dev/null || skip "python3-setuptools or python3-wheel is missing"
"$python" -m venv --system-site-packages "$tmp/venv" >/dev/null 2>&1 || skip "python3-venv is missing"
[[ -x $tmp/venv/bin/pip ]] || skip "the virtual environment has no pip (python3-pip)"

mkdir -p "$tmp/src/python"
cp "$src/pyproject.toml" "$src/setup.py" "$src/CMakeLists.txt" "$tmp/src/"
cp -r "$src/python/bouncer" "$src/python/README.md" "$tmp/src/python/"
BOUNCER_BUILD_DIR=$build "$tmp/venv/bin/pip" install --no-build-isolation --no-index --no-cache-dir --disable-pip-version-check \
  --quiet "$tmp/src" >"$tmp/pip.log" 2>&1 || { cat "$tmp/pip.log" >&2; echo "FAIL: pip install" >&2; exit 1; }

cli_version=$("$bouncer" --version | awk '{print $2}')
cd "$tmp"  # away from the source and build trees; no PYTHONPATH
env -u PYTHONPATH "$tmp/venv/bin/python" - "$cli_version" "$tmp/venv" <<'PY'
import importlib.metadata
import pathlib
import sys

import bouncer

cli_version, venv = sys.argv[1], pathlib.Path(sys.argv[2])
where = pathlib.Path(bouncer.__file__).resolve()
assert venv.resolve() in where.parents, f"imported from {where}, not the virtual environment"
meta = importlib.metadata.metadata("bouncer")
assert importlib.metadata.version("bouncer") == cli_version == bouncer.__version__, \
    (importlib.metadata.version("bouncer"), cli_version, bouncer.__version__)
assert "numpy" in (importlib.metadata.requires("bouncer") or []), importlib.metadata.requires("bouncer")
files = {str(f) for f in importlib.metadata.files("bouncer")}
assert {"bouncer/py.typed", "bouncer/_core.pyi", "bouncer/__init__.py"} <= files, sorted(files)
# eq. 5: a = 8 (1 + eps) / (1 - eps) = 24 at eps = 1/2: (1/4, 12) is a fixed point
s = bouncer.Model(model="constant", a="24", eps="0.5").step(0.25, 12.0)
assert abs(s.theta - 0.25) < 1e-15 and abs(s.v - 12) < 1e-13 and (s.event, s.periods) == ("impact", 1), s
print(f"python_pip: {meta['Name']} {meta['Version']} installed in a virtual environment; Model.step works")
PY
# The typed layer's quick tests against the installed package (the rest run in python.pytest).
BOUNCER_CLI=$bouncer PYTHONDONTWRITEBYTECODE=1 env -u PYTHONPATH "$tmp/venv/bin/python" -m pytest -q -p no:cacheprovider \
  "$src/tests/python/test_model.py" -k "bit_for_bit or namespace or typed or version or fast_double or eq5" \
  | tail -n 3
