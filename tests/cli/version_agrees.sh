#!/usr/bin/env bash
# One version number in one place (issue 24): the CMake project's (CMakeLists.txt:
# project(bouncer VERSION x.y.z)) is the source, and every other place that states a version
# must state the same one:
#   - `bouncer --version` (its second word, after "bouncer"; the library's build_info, compiled from
#     PROJECT_VERSION);
#   - setup.py's project_version(), the Python package's metadata version, run as setup.py
#     defines it (its own function, executed here, not a copy of its regex), and setup()
#     must take its version from that function;
#   - pyproject.toml declares the version dynamic and states none of its own (and its
#     licence is MIT, as LICENSE);
#   - the Python module's bouncer.__version__, when this build has the module
#     (build/python/bouncer/_core*.so; without it that one line is reported as not checked);
#   - CITATION.cff's `version` (and the file is CFF 1.2.0 with the keys the format
#     requires: cff-version, message, title, authors; licence MIT, as LICENSE);
#   - CHANGELOG.md's newest release heading `## [x.y.z]`.
# The checker must also be able to fail: it is run again on a copy of those files whose
# CITATION.cff and CHANGELOG.md state another version, and must name both.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3
bouncer=$(cd "$(dirname "$BOUNCER")" && pwd)/$(basename "$BOUNCER")
build=$(cd "$(dirname "$bouncer")/.." && pwd)
cli_version=$("$bouncer" --version | awk '{print $2; exit}')

module_version=""
if compgen -G "$build/python/bouncer/_core*.so" >/dev/null; then
  python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
  [[ -x ${python:-} ]] || python=python3
  module_version=$(cd "$TMP" && PYTHONPATH=$build/python PYTHONDONTWRITEBYTECODE=1 "$python" -c \
    'import bouncer; print(bouncer.__version__)') || fail module "import bouncer from $build/python failed"
fi

# check_tree DIR: the checks above on the files of DIR; prints one line per disagreement
# and exits 1 if there is any.
check_tree() {
  python3 - "$1" "$cli_version" "$module_version" <<'PY'
import ast
import pathlib
import re
import sys

root, cli_version, module_version = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3]
problems = []

m = re.search(r"project\(\s*bouncer\s+VERSION\s+([0-9]+\.[0-9]+\.[0-9]+)\b", (root / "CMakeLists.txt").read_text())
if not m:
    sys.exit("CMakeLists.txt: no project(bouncer VERSION x.y.z)")
version = m.group(1)
found = {"bouncer --version": cli_version}

# setup.py: run its own project_version() (the function alone, not setup()).
tree = ast.parse((root / "setup.py").read_text())
funcs = [n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "project_version"]
if not funcs:
    problems.append("setup.py: no function project_version()")
else:
    env = {"re": re, "ROOT": root}
    exec(compile(ast.Module(body=funcs, type_ignores=[]), "setup.py", "exec"), env)
    found["setup.py project_version()"] = env["project_version"]()
calls = [n for n in ast.walk(tree) if isinstance(n, ast.Call) and getattr(n.func, "id", "") == "setup"]
kw = {k.arg: k.value for c in calls for k in c.keywords}
v = kw.get("version")
if not (isinstance(v, ast.Call) and getattr(v.func, "id", "") == "project_version"):
    problems.append("setup.py: setup(version=...) is not project_version()")

try:
    import tomllib
    project = tomllib.loads((root / "pyproject.toml").read_text()).get("project", {})
    if "version" in project:
        problems.append(f"pyproject.toml: states its own version {project['version']!r} (it must be dynamic)")
    if "version" not in project.get("dynamic", []):
        problems.append("pyproject.toml: version is not in [project] dynamic")
    if project.get("license") != {"text": "MIT"}:
        problems.append(f"pyproject.toml: license is {project.get('license')!r}, not MIT as LICENSE")
except ModuleNotFoundError:
    print("pyproject.toml: not checked (no tomllib in this Python)")

if module_version:
    found["bouncer.__version__"] = module_version
else:
    print("bouncer.__version__: not checked (this build has no Python module)")

cff = (root / "CITATION.cff").read_text()
top = dict(re.findall(r"^([a-z-]+):[ \t]*(.*?)[ \t]*$", cff, re.M))
def plain(s):
    return s.strip().strip('"').strip("'")
found["CITATION.cff version"] = plain(top.get("version", "(none)"))
if plain(top.get("cff-version", "")) != "1.2.0":
    problems.append(f"CITATION.cff: cff-version is {top.get('cff-version')!r}, not 1.2.0")
for key in ("message", "title", "authors", "license"):
    if key not in top:
        problems.append(f"CITATION.cff: no top-level {key}")
if plain(top.get("license", "")) != "MIT" or "MIT License" not in (root / "LICENSE").read_text():
    problems.append("CITATION.cff's license and LICENSE do not both say MIT")
try:
    import yaml  # the whole file, where PyYAML is installed
    data = yaml.safe_load(cff)
    if str(data.get("version")) != found["CITATION.cff version"]:
        problems.append(f"CITATION.cff: YAML reads version {data.get('version')!r}")
    if not data.get("authors") or not all(isinstance(a, dict) for a in data["authors"]):
        problems.append("CITATION.cff: authors is not a list of persons or entities")
except ModuleNotFoundError:
    pass

releases = re.findall(r"^## \[([0-9]+\.[0-9]+\.[0-9]+)\]", (root / "CHANGELOG.md").read_text(), re.M)
found["CHANGELOG.md newest release"] = releases[0] if releases else "(none)"

for where, v in found.items():
    if v != version:
        problems.append(f"{where} says {v}, CMakeLists.txt project(VERSION) says {version}")
for p in problems:
    print("DISAGREES: " + p)
print(f"version {version}: " + ", ".join(found))
sys.exit(1 if problems else 0)
PY
}

out=$(check_tree "$SRC" 2>&1) || fail agree "$out"
echo "$out"

# The checker can fail: a copy whose CITATION.cff and CHANGELOG.md say 9.9.9.
mkdir -p "$TMP/tree"
cp "$SRC/CMakeLists.txt" "$SRC/setup.py" "$SRC/pyproject.toml" "$SRC/LICENSE" "$TMP/tree/"
sed 's/^version: .*/version: 9.9.9/' "$SRC/CITATION.cff" >"$TMP/tree/CITATION.cff"
sed '0,/^## \[[0-9]/s/^## \[[0-9][0-9.]*\]/## [9.9.9]/' "$SRC/CHANGELOG.md" >"$TMP/tree/CHANGELOG.md"
rc=0
bad=$(check_tree "$TMP/tree" 2>&1) || rc=$?
[[ $rc -eq 1 ]] || fail negative "a CITATION.cff and CHANGELOG.md at 9.9.9 were not caught (exit $rc): $bad"
grep -q "CITATION.cff version says 9.9.9" <<<"$bad" || fail negative "CITATION.cff not named: $bad"
grep -q "CHANGELOG.md newest release says 9.9.9" <<<"$bad" || fail negative "CHANGELOG.md not named: $bad"

finish "version_agrees: CMakeLists.txt, bouncer --version, setup.py, pyproject.toml, CITATION.cff, CHANGELOG.md${module_version:+, bouncer.__version__} agree"
