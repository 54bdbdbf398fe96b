#!/usr/bin/env bash
# End-to-end: zooms at any precision. Every picture command (basin, bifurcation, scan,
# portrait, lyapunov --vary, continue) over a window 1e-20 wide at mpfr:256 -- where both
# ends of the window are the same double -- including the three commands of issue 9:
#   - exits 0 and writes PREFIX.csv, PREFIX.png (a PNG of the command's size) and PREFIX.json;
#   - the CSV coordinates are the grid of the window, checked against exact rational
#     arithmetic (python fractions): within 2 ulps at 256 bits of the exact decimal grid
#     point (the ends are rounded once, the grid arithmetic once more; see docs/guide/pictures.md), and
#     distinct (a double would make them one value);
#   - the pictures place what they show by the exact values: a basin across the wall's
#     knot theta = 1/2 is split at the middle of its frame, and portrait points at
#     theta = 0.3 + 5e-21 land half way across a window [0.3, 0.3 + 1e-20];
#   - bad windows exit 2.
# The tick labels themselves are checked in tests/test_plot.cpp (Zoom.*).
# Usage: bash picture_zoom.sh <bouncer-binary> <source-dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
require python3

# A PNG reader (zlib + the five PNG row filters) and the exact-arithmetic helpers.
cat >"$TMP/zoomcheck.py" <<'PY'
import json, math, struct, sys, zlib
from fractions import Fraction as F

def add_bytes(a, b):
    """Bytewise (a + b) mod 256 of two equal-length byte strings (no carries between bytes)."""
    n = len(a)
    x, y = int.from_bytes(a, "big"), int.from_bytes(b, "big")
    low, high = int.from_bytes(b"\x7f" * n, "big"), int.from_bytes(b"\x80" * n, "big")
    return (((x & low) + (y & low)) ^ ((x ^ y) & high)).to_bytes(n, "big")

def png(path, pixels=True):
    """(width, height, rows as RGB bytes or None, text keys) of an 8-bit RGB PNG."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, keys = 8, b"", set()
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype == 2, (depth, ctype)
        elif kind == b"IDAT":
            idat += body
        elif kind in (b"tEXt", b"zTXt"):
            keys.add(body.split(b"\0", 1)[0].decode())
        pos += 12 + n
    if not pixels:
        return w, h, None, keys
    raw, stride, rows, prev = zlib.decompress(idat), w * 3, [], bytes(w * 3)
    for y in range(h):
        f, line = raw[y * (stride + 1)], raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)]
        if f == 2:  # up: the commonest filter, without a loop over bytes
            line = add_bytes(line, prev)
        elif f != 0:
            line = bytearray(line)
            for i in range(stride):
                a = line[i - 3] if i >= 3 else 0
                b, c = prev[i], prev[i - 3] if i >= 3 else 0
                if f == 1: line[i] = (line[i] + a) & 255
                elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
                elif f == 4:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
            line = bytes(line)
        rows.append(line)
        prev = line
    return w, h, rows, keys

def at(rows, x, y):
    """The (r, g, b) of pixel (x, y)."""
    return tuple(rows[y][3 * x:3 * x + 3])

def frame(rows):
    """Pixel edges (left, top, right, bottom) of the plot frame: the long dark lines."""
    dark = b"\x28\x28\x28"
    h, w = len(rows), len(rows[0]) // 3
    lines = [y for y in range(h) if sum(rows[y][3 * x:3 * x + 3] == dark for x in range(0, w, 2)) > w // 6]
    sample = range(lines[0], lines[-1], 4)
    cols = [x for x in range(w) if sum(rows[y][3 * x:3 * x + 3] == dark for y in sample) > len(sample) * 9 // 10]
    return cols[0], lines[0], cols[-1], lines[-1]

def csv_rows(path):
    return [l.rstrip("\n").split(",") for l in open(path) if not l.startswith("#")][1:]

def ulp256(x):
    """The spacing of 256-bit binary numbers at x (x != 0)."""
    x = abs(F(x))
    e = math.floor(math.log2(x.numerator) - math.log2(x.denominator))
    while F(2) ** e > x: e -= 1
    while F(2) ** (e + 1) <= x: e += 1
    return F(2) ** (e - 255)

def near(got, exact, ulps=2):
    """got (decimal text) is within `ulps` 256-bit ulps of the exact rational."""
    return abs(F(got) - exact) <= ulps * ulp256(exact)
PY
# check NAME ARGS...: a python check (on stdin, importing zoomcheck, ARGS in sys.argv[1:]),
# queued: all checks run in one python process at the end (python starts slowly).
checks=0
check() {
  local name=$1
  shift
  checks=$((checks + 1))
  cat >"$TMP/check-$checks.py"
  printf '%s %s %s\n' "$checks" "$name" "$*" >>"$TMP/checks.txt"
}
run_checks() {
  [[ -s $TMP/checks.txt ]] || return 0
  local rc=0
  PYTHONPATH=$TMP python3 - "$TMP" <<'PY' || rc=$?
import sys, traceback
tmp, failed = sys.argv[1], 0
for line in open(tmp + "/checks.txt"):
    number, name, *args = line.split()
    sys.argv = ["check"] + args
    try:
        exec(compile(open(f"{tmp}/check-{number}.py").read(), name, "exec"), {"__name__": "__main__"})
    except Exception:
        failed += 1
        print(f"FAIL [{name}]: " + traceback.format_exc(limit=-1).strip().replace("\n", " | "), file=sys.stderr)
sys.exit(min(failed, 100))
PY
  failures=$((failures + rc))
}

# zoom_outputs NAME PREFIX WIDTH HEIGHT: `outputs` (the three files, no tiles or partial
# files left), a PNG of that size with provenance, a JSON at mpfr:256.
zoom_outputs() {
  local name=$1 p=$2
  outputs "$name" "$p"
  check "$name" "$p" "$3" "$4" <<'PY'
import json, sys
from zoomcheck import png
p, w, h = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
d = json.load(open(p + ".json"))
assert d["provenance"]["precision"] == "mpfr:256", d["provenance"]
width, height, _, keys = png(p + ".png", pixels=False)
assert (width, height) == (w, h), (width, height)
assert "bouncer:provenance" in keys, keys
PY
}

M="--precision mpfr:256 --quiet"

# --- issue 9's three commands --------------------------------------------------------------
run basin9 basin --model constant --a 24 --eps 0.5 --grid 5x3 --transient 20 --steps 20 \
  --theta-range 0.3:0.30000000000000000001 --v-range 6:8 $M --out "$TMP/basin9" && zoom_outputs basin9 "$TMP/basin9" 1000 700
check basin9.grid "$TMP/basin9.csv" <<'PY'
import sys
from fractions import Fraction as F
from zoomcheck import csv_rows, near
rows = csv_rows(sys.argv[1])
assert len(rows) == 15, len(rows)
lo, hi, n = F("0.3"), F("0.30000000000000000001"), 5
for k, r in enumerate(rows):
    i, j = k % n, k // n
    assert near(r[0], lo + (hi - lo) * (2 * i + 1) / (2 * n)), (k, r[0])  # cell centres
    assert near(r[1], F(6) + F(2) * (2 * j + 1) / 6), (k, r[1])
assert len({r[0] for r in rows}) == 5  # five phases, not one double
PY
run bif9 bifurcation --model constant --eps 0.96 --range 28:28.000000000000001 --samples 5 --transient 10 \
  --record 4 --theta 0.1 --v 5 $M --out "$TMP/bif9" && zoom_outputs bif9 "$TMP/bif9" 900 700
run scan9 scan --model constant --a-range 10:10.0000000000000000001 --eps-range 0.5:0.6 --grid 3x2 --ics 2 \
  --transient 10 --steps 32 --max-period 8 $M --out "$TMP/scan9" && zoom_outputs scan9 "$TMP/scan9" 900 700
check scan9.grid "$TMP/scan9.csv" <<'PY'
import sys
from fractions import Fraction as F
from zoomcheck import csv_rows, near
rows = csv_rows(sys.argv[1])
lo, hi = F("10"), F("10.0000000000000000001")
for k, r in enumerate(rows):
    assert near(r[0], lo + (hi - lo) * (2 * (k % 3) + 1) / 6), (k, r[0])
    assert near(r[1], F("0.5") + F("0.1") * (2 * (k // 3) + 1) / 4), (k, r[1])
PY

# --- every picture command, window 1e-20 wide ----------------------------------------------
run bif bifurcation --model constant --eps 0.96 --range 28:28.00000000000000000001 --samples 7 --transient 10 \
  --record 3 --theta 0.1 --v 5 $M --out "$TMP/bif" && zoom_outputs bif "$TMP/bif" 900 700
check bif.grid "$TMP/bif.csv" <<'PY'
import sys
from fractions import Fraction as F
from zoomcheck import csv_rows, near
rows = csv_rows(sys.argv[1])
assert len(rows) == 21, len(rows)
lo, hi = F(28), F("28.00000000000000000001")
values = sorted({r[0] for r in rows}, key=F)
assert len(values) == 7, values
for k, v in enumerate(values):
    assert near(v, lo + (hi - lo) * k / 6), (k, v)  # p_k = lo + (hi - lo) k/(K - 1)
assert values[0] == "28", values[0]  # the ends are exact
PY

run lyap lyapunov --model veldep --c 1000 --vary a --range 26:26.00000000000000000001 --samples 5 --transient 100 \
  --steps 500 $M --out "$TMP/lyap" && zoom_outputs lyap "$TMP/lyap" 900 600
check lyap.grid "$TMP/lyap.csv" <<'PY'
import sys
from fractions import Fraction as F
from zoomcheck import csv_rows, near
rows = csv_rows(sys.argv[1])
assert len(rows) == 5, len(rows)
lo, hi = F(26), F("26.00000000000000000001")
for k, r in enumerate(rows):
    assert near(r[0], lo + (hi - lo) * k / 4), (k, r[0])
PY

# The picture places the five values across the window [lo - 2%, hi + 2%] of the range.
check lyap.places "$TMP/lyap" <<'PY'
import sys
from zoomcheck import csv_rows, frame, png
assert all(r[6] == "periodic" for r in csv_rows(sys.argv[1] + ".csv")), "expected periodic rows (colour below)"
_, _, px, _ = png(sys.argv[1] + ".png")
left, top, right, bottom = frame(px)
colour = bytes((230, 159, 0))  # the first periodic type
xs = sorted({x for y in range(top + 1, bottom) for x in range(left + 1, right) if px[y][3 * x:3 * x + 3] == colour})
clusters = [[xs[0]]]
for x in xs[1:]:
    if x - clusters[-1][-1] > 3: clusters.append([])
    clusters[-1].append(x)
centres = [(sum(c) / len(c) - left) / (right - left) for c in clusters]
assert len(centres) == 5, centres
for k, c in enumerate(centres):
    assert abs(c - (0.02 + k / 4) / 1.04) < 0.01, (k, c)
PY

run cont continue --model veldep --c 1000 --a 28 --period 7 --guess 0.19204436106841707,26.916257785320354 \
  --range 28:28.00000000000000000001 --precision mpfr:256 --out "$TMP/cont" && zoom_outputs cont "$TMP/cont" 900 600
check cont.grid "$TMP/cont.csv" <<'PY'
import sys
from fractions import Fraction as F
from zoomcheck import csv_rows, ulp256
rows = csv_rows(sys.argv[1])
lo, hi = F(28), F("28.00000000000000000001")
a = [F(r[0]) for r in rows]
assert len(a) > 10 and a == sorted(a) and len(set(a)) == len(a), "branch points not increasing"
assert all(lo - ulp256(lo) <= x <= hi + ulp256(hi) for x in a), "a branch point outside the range"
assert a[-1] - a[0] > (hi - lo) / 2, "the branch does not cross the range"
PY

# The branch's points run across the whole picture.
check cont.places "$TMP/cont" <<'PY'
import sys
from zoomcheck import frame, png
_, _, px, _ = png(sys.argv[1] + ".png")
left, top, right, bottom = frame(px)
stable = bytes((33, 102, 172))
xs = [x for y in range(top + 1, bottom) for x in range(left + 1, right) if px[y][3 * x:3 * x + 3] == stable]
assert xs, "no branch points drawn"
assert (min(xs) - left) / (right - left) < 0.02 and (max(xs) - left) / (right - left) > 0.98, (min(xs), max(xs), left, right)
PY

# A basin across the wall's knot theta = 1/2: below it the wall moves up at 4, so v0 near 0
# is outside the phase space; above it the wall moves down at 4 and every point is inside.
# At 256 bits the left half of the grid is outside and the right half is not; the picture
# splits at the middle of its frame. (In double the window is one value, 0.5.)
run knot basin --model constant --a 24 --eps 0.5 --grid 4x3 --transient 20 --steps 20 \
  --theta-range 0.49999999999999999999:0.50000000000000000001 --v-range 0:0.00000000000000000003 $M \
  --out "$TMP/knot" && zoom_outputs knot "$TMP/knot" 1000 700
check knot.split "$TMP/knot" <<'PY'
import sys
from fractions import Fraction as F
from zoomcheck import at, csv_rows, frame, png
rows = csv_rows(sys.argv[1] + ".csv")
for th, v, cls, q in rows:
    assert (cls == "outside") == (F(th) < F(1, 2)), (th, cls)
_, _, px, _ = png(sys.argv[1] + ".png")
left, top, right, bottom = frame(px)
outside = (238, 238, 238)
mid_row = [at(px, x, (top + bottom) // 2) for x in range(left + 1, right)]
edge = next(i for i, p in enumerate(mid_row) if p != outside)  # first pixel that is not outside
frac = edge / (right - left - 1)
assert abs(frac - 0.5) < 0.01, frac
assert all(p == outside for p in mid_row[:edge]) and all(p != outside for p in mid_row[edge:])
PY

# A portrait zoomed on [0.3, 0.3 + 1e-20] x [7, 7 + 3e-20]: starts at fractions (0.5, 1/3) and
# (0.9, 2/3) of the window are drawn there (their later points lie far outside).
run por portrait --model constant --a 24 --eps 0.5 --theta 0.300000000000000000005,0.300000000000000000009 \
  --v 7.00000000000000000001,7.00000000000000000002 --steps 2 --theta-range 0.3:0.30000000000000000001 \
  --v-range 7:7.00000000000000000003 $M --out "$TMP/por" && zoom_outputs por "$TMP/por" 900 600
check por.places "$TMP/por" <<'PY'
import sys
from fractions import Fraction as F
from zoomcheck import at, csv_rows, frame, png, near
rows = csv_rows(sys.argv[1] + ".csv")
starts = [r for r in rows if r[1] == "0"]
assert near(starts[0][2], F("0.300000000000000000005"), 1) and near(starts[1][3], F("7.00000000000000000002"), 1), starts
_, _, px, _ = png(sys.argv[1] + ".png")
left, top, right, bottom = frame(px)
for colour, fx, fy in [((230, 159, 0), 0.5, 1 / 3), ((86, 180, 233), 0.9, 2 / 3)]:  # category colours 0, 1
    c = bytes(colour)
    pts = [(x, y) for y in range(top + 1, bottom) for x in range(left + 1, right) if px[y][3 * x:3 * x + 3] == c]
    assert pts, colour
    cx, cy = sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts)
    assert abs((cx - left) / (right - left) - fx) < 0.01, (colour, cx)
    assert abs((bottom - cy) / (bottom - top) - fy) < 0.01, (colour, cy)
PY

# --- bad windows: exit 2, one line, no files ------------------------------------------------
bad() {  # bad NAME ARGS...
  local name=$1
  shift
  rm -rf "$TMP/bad" && mkdir "$TMP/bad"
  refused "bad:$name" "" "$@" --out "$TMP/bad/o"
  empty_dir "bad:$name" "$TMP/bad"
}
P="portrait --model constant --a 24 --eps 0.5 --theta 0.3 --v 7"
bad empty-window $P --theta-range 0.3:0.3
bad theta-window-outside $P --theta-range 0.5:1.5
bad polar-window $P --polar --theta-range 0.3:0.4
bad v-window-order $P --v-range 8:7

run_checks
finish
