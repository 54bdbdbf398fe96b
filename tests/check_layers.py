#!/usr/bin/env python3
"""The library's layers (docs/guide/development.md): base -> scalar -> model ->
analysis -> verify -> run -> io -> workflow. A file of one layer includes headers of its own and lower
layers only, and the numerics target (every layer but io and workflow) needs none of the I/O libraries.
Also: tools/ and python/ hold no science the issue named (no class-name comparison of
strings, no re-parsing of grid items with getline in the command files).
Usage: check_layers.py SOURCE-DIR; exits 1 naming each violation."""
import pathlib
import re
import sys

ORDER = ["base", "scalar", "model", "analysis", "verify", "run", "io", "workflow"]
RANK = {layer: i for i, layer in enumerate(ORDER)}
IO_LIBRARIES = re.compile(r'#include [<"](nlohmann/|toml\+\+/|png\.h|cairo)')
CLASS_NAMES = ("fixed|periodic|sticking|quasiperiodic|chaotic|unbounded|effective_sticking|undecided|"
               "transient_chaos|outside|no_sticking|not_trapped|agrees|differs")
CLASS_COMPARE = re.compile(r'(==|!=)\s*"(%s)"' % CLASS_NAMES)

root = pathlib.Path(sys.argv[1])
bad = []
for path in sorted((root / "lib").rglob("*.[ch]pp")):
    rel = path.relative_to(root / "lib")
    layer = rel.parts[2] if rel.parts[0] == "include" else rel.parts[1]
    if layer not in RANK:
        bad.append(f"{path}: in no layer ({', '.join(ORDER)})")
        continue
    text = path.read_text()
    for used in re.findall(r'#include "bouncer/(\w+)/', text):
        if used in RANK and RANK[used] > RANK[layer]:
            bad.append(f"{path}: layer {layer} includes the higher layer {used}")
    if layer not in ("io", "workflow") and IO_LIBRARIES.search(text):
        bad.append(f"{path}: layer {layer} (bouncer::numerics) includes an I/O library")
for folder in ("tools", "python"):
    for path in sorted((root / folder).rglob("*")):
        if path.suffix not in (".cpp", ".hpp", ".py") or "bench" in path.parts:
            continue
        for n, line in enumerate(path.read_text().splitlines(), 1):
            if CLASS_COMPARE.search(line) and "``" not in line:  # (not a docstring's example)
                bad.append(f"{path}:{n}: a class compared by its name: {line.strip()}")
for path in sorted((root / "tools").glob("cmd_*.cpp")):
    if path.name == "cmd_reproduce.cpp":
        continue  # it reads manifests, not grid items
    for n, line in enumerate(path.read_text().splitlines(), 1):
        if "getline" in line:
            bad.append(f"{path}:{n}: a command re-parses text: {line.strip()}")
for b in bad:
    print(b)
print(f"check_layers: {len(bad)} violations" if bad else "check_layers: the layers hold")
sys.exit(1 if bad else 0)
