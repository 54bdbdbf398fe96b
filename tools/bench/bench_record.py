"""bench_record: what the Python benchmarks share with the C++ ones (tools/bench/bench_record.hpp).

A benchmark's tables are data: named columns and rows of formatted cells, printed as aligned
text on stdout and, with `--json FILE`, written with the run's provenance (command, bouncer
version and commit, date, machine) as one JSON document of the same shape as the C++ tools'
that tools/bench/record_tables.py turns into the Markdown blocks of docs/guide/benchmarks.md.
`--columns` prints the tables' names and columns (JSON) without running anything.
Standard library only.
"""

import json
import re
import subprocess
import os
import sys
import time


class Table:
    def __init__(self, name, title, columns, notes=None):
        self.name, self.title, self.columns = name, title, list(columns)
        self.rows, self.notes = [], list(notes or [])

    def add(self, *cells):
        cells = [str(c) for c in cells]
        if len(cells) != len(self.columns):
            raise ValueError(f"bench table {self.name}: a row of {len(cells)} cells for {len(self.columns)} columns")
        self.rows.append(cells)

    def print_text(self, out=None):
        out = out or sys.stdout
        widths = [max(len(r[i]) for r in [self.columns] + self.rows) for i in range(len(self.columns))]
        for r in [self.columns] + self.rows:
            print("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip(), file=out)
        for n in self.notes:
            print(n, file=out)

    def as_json(self, with_rows):
        j = {"name": self.name, "title": self.title, "columns": self.columns}
        if with_rows:
            j["rows"], j["notes"] = self.rows, self.notes
        return j


def _first_line(path):
    try:
        with open(path) as f:
            return f.readline().strip()
    except OSError:
        return "unknown"


def _cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


class Run:
    """Provenance taken at start: the command (the tool's name and its arguments without
    --json FILE and --columns), the date, the machine and its load average."""

    def __init__(self, tool, argv):
        self.tool = tool
        words, skip = [], False
        for i, a in enumerate(argv):
            if skip:
                skip = False
                continue
            if a == "--json":
                skip = True
                continue
            if a.startswith("--json=") or a == "--columns":
                continue
            words.append(a)
        self.command = " ".join([tool] + words)
        self.date = time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime())
        self.machine = {"cpus": os.cpu_count(), "cpu": _cpu_model(), "load_at_start": _first_line("/proc/loadavg")}

    def print_columns(self, tables):
        print(json.dumps({"tool": self.tool, "tables": [t.as_json(False) for t in tables]}, indent=1, sort_keys=True))
        return 0

    def finish_cli(self, path, tables, cli):
        """finish() with the version and commit that the bouncer executable `cli` reports."""
        out = subprocess.run([cli, "--version"], stdout=subprocess.PIPE, text=True).stdout
        m = re.match(r"bouncer (\S+) \(commit ([^)]*)\)", out)
        self.finish(path, tables, m.group(1) if m else "unknown", m.group(2) if m else "unknown")

    def finish(self, path, tables, version, commit, build=""):
        """Writes the record to path (nothing when path is None)."""
        if not path:
            return
        doc = {"tool": self.tool, "command": self.command, "version": version, "commit": commit, "build": build,
               "date": self.date, "machine": self.machine, "tables": [t.as_json(True) for t in tables]}
        with open(path, "w") as f:
            json.dump(doc, f, indent=1, sort_keys=True)
            f.write("\n")
