#!/usr/bin/env bash
# End-to-end: the picture formats and presentation options (docs/guide/pictures.md).
#   * --format png,pdf,svg writes PREFIX.png/.pdf/.svg: PNG magic and an IHDR of --size
#     pixels with more than one colour and the provenance chunk; %PDF- with a MediaBox of
#     size*72/dpi points, the DejaVu Sans font embedded (text drawn), the provenance in its
#     document information and no creation date; SVG that parses as XML with width/height of
#     size*72/dpi pt, glyphs drawn and the provenance in <metadata>;
#   * two runs give byte-identical PNG, PDF and SVG (a second apart: no dates anywhere);
#   * --format pdf writes no PNG (and the JSON lists the files written);
#   * another --format/--size/--palette reuses the saved tiles (same job key, tiles untouched);
#   * --tiles-from: a scan drawn with another --show from a finished job's kept tiles computes
#     nothing (its tiles dir is filled by import: every tile there, none newer computed) and
#     gives the same CSV rows; another job's tiles, a prefix without tiles, or no --out: exit 2;
#   * bad --format/--size/--dpi/--palette/--curves/--recheck (scan): exit 2, one line naming the option, nothing
#     written; scene files take the same keys; sweep and continue take them too;
#   * without the font file (hidden by a bind mount, where allowed): exit 1, one line naming
#     fonts-dejavu-core, nothing written; without --out no font is needed.
# Usage: bash picture_formats.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
BASIN=(basin --model constant --a 24 --eps 0.5 --v-range 2:20 --grid 24x16 --transient 100 --steps 64 --quiet)

# --- three formats, twice, a second apart -------------------------------------------------
mkdir -p "$TMP/r1" "$TMP/r2"
(cd "$TMP/r1" && "$BOUNCER" "${BASIN[@]}" --format png,pdf,svg --size 640x420 --dpi 100 --out b) || fail formats "basin exit $?"
sleep 1
(cd "$TMP/r2" && "$BOUNCER" "${BASIN[@]}" --format png,pdf,svg --size 640x420 --dpi 100 --out b) || fail formats "second run exit $?"
for ext in png pdf svg; do
  [[ -s $TMP/r1/b.$ext ]] || fail "formats-$ext" "b.$ext missing or empty"
  cmp -s "$TMP/r1/b.$ext" "$TMP/r2/b.$ext" || fail "determinism-$ext" "two runs of the same inputs differ"
done
python3 - "$TMP/r1/b" 640 420 100 <<'PY' || fail formats "a file does not have the expected signature or content"
import re, struct, sys, zlib
import xml.etree.ElementTree as ET
prefix, w, h, dpi = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
ok = True
def bad(msg):
    global ok
    ok = False
    print("  " + msg, file=sys.stderr)

# PNG: magic, IHDR = --size, provenance chunk, decoded pixels with many colours.
data = open(prefix + ".png", "rb").read()
if data[:8] != b"\x89PNG\r\n\x1a\n": bad("PNG magic missing")
pos, chunks, idat = 8, {}, b""
while pos < len(data):
    n, = struct.unpack(">I", data[pos:pos + 4]); kind = data[pos + 4:pos + 8]; body = data[pos + 8:pos + 8 + n]
    chunks.setdefault(kind, []).append(body); pos += 12 + n
    if kind == b"IDAT": idat += body
pw, ph, depth, ctype = struct.unpack(">IIBB", chunks[b"IHDR"][0][:10])
if (pw, ph) != (w, h): bad(f"PNG IHDR {pw}x{ph}, expected {w}x{h}")
texts = b"".join(chunks.get(b"tEXt", []) + chunks.get(b"zTXt", []))
if b"bouncer:provenance" not in texts: bad("PNG has no bouncer:provenance chunk")
raw = zlib.decompress(idat); bpp = 3 if ctype == 2 else 4; stride = pw * bpp
rows, prev = [], bytearray(stride)
for y in range(ph):
    f = raw[y * (stride + 1)]; line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0; b = prev[i]; c = prev[i - bpp] if i >= bpp else 0
        if f == 1: line[i] = (line[i] + a) & 255
        elif f == 2: line[i] = (line[i] + b) & 255
        elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(bytes(line)); prev = line
colours = {r[i:i + 3] for r in rows for i in range(0, stride, bpp)}
if len(colours) < 20: bad(f"PNG has only {len(colours)} colours (antialiased text and a picture have many)")
if rows[0][:3] != b"\xff\xff\xff": bad("PNG corner is not the white background")

# PDF: signature, MediaBox = size*72/dpi points, embedded font, metadata, no dates.
pdf = open(prefix + ".pdf", "rb").read()
if not pdf.startswith(b"%PDF-"): bad("PDF signature missing")
m = re.search(rb"/MediaBox \[\s*0 0 ([0-9.]+) ([0-9.]+)\s*\]", pdf)
if not m: bad("PDF has no MediaBox")
elif abs(float(m.group(1)) - w * 72 / dpi) > 0.01 or abs(float(m.group(2)) - h * 72 / dpi) > 0.01:
    bad(f"PDF MediaBox {m.group(1)} x {m.group(2)}, expected {w * 72 / dpi} x {h * 72 / dpi}")
if b"DejaVuSans" not in pdf: bad("PDF does not embed DejaVu Sans (no text drawn?)")
if b"CreationDate" in pdf or b"ModDate" in pdf: bad("PDF carries a date")
if b"/Title (Basins of attraction" not in pdf: bad("PDF has no title in its document information")
if b"/Subject" not in pdf: bad("PDF has no provenance (Subject)")

# SVG: XML, width/height in points, glyphs, metadata.
root = ET.parse(prefix + ".svg").getroot()
def pt(v): return float(v[:-2]) if v.endswith("pt") else float(v)
if abs(pt(root.get("width")) - w * 72 / dpi) > 0.01 or abs(pt(root.get("height")) - h * 72 / dpi) > 0.01:
    bad(f"SVG size {root.get('width')} x {root.get('height')}, expected {w * 72 / dpi}pt x {h * 72 / dpi}pt")
ns = "{http://www.w3.org/2000/svg}"
if not root.findall(f".//{ns}symbol"): bad("SVG has no glyphs (no text drawn)")
meta = root.find(f"{ns}metadata")
if meta is None or "bouncer:provenance" not in (meta.text or ""): bad("SVG has no provenance <metadata>")
sys.exit(0 if ok else 1)
PY

# --- --format pdf alone: no PNG; the JSON names the files written ----------------------------
"$BOUNCER" "${BASIN[@]}" --format pdf --out "$TMP/p" || fail pdf-only "exit $?"
[[ -e $TMP/p.png || -e $TMP/p.svg ]] && fail pdf-only "a PNG or SVG was written for --format pdf"
[[ -s $TMP/p.pdf && -s $TMP/p.csv && -s $TMP/p.json ]] || fail pdf-only "PDF, CSV or JSON missing"
python3 -c 'import json,sys; f=json.load(open(sys.argv[1]))["files"]; sys.exit(0 if sorted(f)==["csv","json","pdf"] else 1)' "$TMP/p.json" ||
  fail pdf-only "JSON files are not csv, pdf, json"

# --- presentation does not invalidate tiles -----------------------------------------------------
"$BOUNCER" "${BASIN[@]}" --out "$TMP/t" --keep-tiles || fail tiles "first run exit $?"
key1=$(cat "$TMP/t.tiles/job.key")
sum1=$(cd "$TMP/t.tiles" && ls | grep -v -e lock -e job | sort | xargs md5sum | md5sum)
stamp1=$(cd "$TMP/t.tiles" && ls --full-time | grep -v -e lock -e job | md5sum)
sleep 1
"$BOUNCER" "${BASIN[@]}" --out "$TMP/t" --keep-tiles --format svg,png --size 500x400 --dpi 96 --palette paper 2>"$TMP/t.err" ||
  fail tiles "second run exit $?"
[[ $(cat "$TMP/t.tiles/job.key") == "$key1" ]] || fail tiles "the job key changed with --format/--size/--dpi/--palette"
[[ $(cd "$TMP/t.tiles" && ls | grep -v -e lock -e job | sort | xargs md5sum | md5sum) == "$sum1" ]] || fail tiles "tiles changed"
[[ $(cd "$TMP/t.tiles" && ls --full-time | grep -v -e lock -e job | md5sum) == "$stamp1" ]] || fail tiles "tiles were rewritten"
[[ -s $TMP/t.err ]] && fail tiles "stderr: $(head -c 300 "$TMP/t.err")"
cmp -s <(grep -v '^#' "$TMP/t.csv") <(grep -v '^#' "$TMP/p.csv") || fail tiles "CSV rows differ from a fresh run"

# --- bad values: exit 2, one line naming the option, nothing written ------------------------------
bad() {  # bad NAME OPTION ARGS...
  local name=$1 option=$2
  shift 2
  refused "bad-$name" "$option" "$@" --out "$TMP/bad_$name"
  absent "bad-$name" "$TMP/bad_$name*"
}
bad format-gif format "${BASIN[@]}" --format gif
bad format-empty-item format "${BASIN[@]}" --format png,,pdf
bad format-case format "${BASIN[@]}" --format PNG
bad size-small size "${BASIN[@]}" --size 100x100
bad size-large size "${BASIN[@]}" --size 30000x600
bad size-word size "${BASIN[@]}" --size big
bad size-one size "${BASIN[@]}" --size 900
bad size-negative size "${BASIN[@]}" --size -900x600
bad dpi-low dpi "${BASIN[@]}" --dpi 10
bad dpi-high dpi "${BASIN[@]}" --dpi 5000
bad dpi-word dpi "${BASIN[@]}" --dpi fine
bad palette palette "${BASIN[@]}" --palette rainbow
SCAN=(scan --model constant --a-range 20:24 --eps-range 0.4:0.6 --grid 3x2 --ics 2 --transient 50 --steps 32 --quiet)
bad curves curves "${SCAN[@]}" --curves parabola
bad recheck-typo recheck "${SCAN[@]}" --recheck ful
bad recheck-case recheck "${SCAN[@]}" --recheck Full
bad curves-veldep curves scan --model veldep --a-range 20:24 --c-range 0.4:0.6 --grid 2x2 --curves fixed-points
bad sweep-format format sweep --model constant --eps 0.5 --a 24 --theta 0.5 --v 4 --steps 10 --format jpeg
bad continue-size size continue --model constant --eps 0.25 --a 26 --period 1 --guess 0.5,4 --range 20:31 --size 9x9

# --- --tiles-from: one grid, drawn again with another --show -----------------------------------
"$BOUNCER" "${SCAN[@]}" --out "$TMP/tf1" --keep-tiles || fail tiles-from "first run exit $?"
"$BOUNCER" "${SCAN[@]}" --show chaotic --out "$TMP/tf2" --tiles-from "$TMP/tf1" --keep-tiles 2>"$TMP/tf2.err" ||
  fail tiles-from "reuse exit $?: $(cat "$TMP/tf2.err")"
cmp -s <(grep -v '^#' "$TMP/tf1.csv") <(grep -v '^#' "$TMP/tf2.csv") || fail tiles-from "CSV rows differ"
[[ $(cat "$TMP/tf1.tiles/job.key") == $(cat "$TMP/tf2.tiles/job.key") ]] || fail tiles-from "--show changed the job key"
[[ $(cd "$TMP/tf1.tiles" && ls | grep -v -e lock -e job | sort | xargs md5sum) == $(cd "$TMP/tf2.tiles" && ls | grep -v -e lock -e job | sort | xargs md5sum) ]] ||
  fail tiles-from "the reused tiles are not the first job's"
grep -q '"show": "chaotic"' "$TMP/tf2.json" || fail tiles-from "the second picture does not show chaotic"
bad tiles-from-other tiles-from "${SCAN[@]}" --max-period 16 --tiles-from "$TMP/tf1"
bad tiles-from-none tiles-from "${SCAN[@]}" --tiles-from "$TMP/nothing-here"
refused tiles-from-no-out 'tiles-from: needs --out' "${SCAN[@]}" --tiles-from "$TMP/tf1"

# --- scene keys, scan curves, sweep and continue ------------------------------------------------
cat >"$TMP/scene.toml" <<'TOML'
command = "scan"
model = "constant"
a-range = "20:24"
eps-range = "0.4:0.6"
grid = "3x2"
ics = 2
transient = 50
steps = 32
format = "svg"
size = "600x400"
dpi = 72
palette = "paper"
curves = "none"
TOML
"$BOUNCER" scan --scene "$TMP/scene.toml" --quiet --out "$TMP/sc" || fail scene "exit $?"
[[ -s $TMP/sc.svg && ! -e $TMP/sc.png ]] || fail scene "format = \"svg\" from the scene not honoured"
grep -q 'width="600pt" height="400pt"' "$TMP/sc.svg" || fail scene "size/dpi from the scene not honoured: $(grep -o '<svg[^>]*>' "$TMP/sc.svg")"
"$BOUNCER" sweep --model constant --eps 0.5 --a 24 --theta 0.5 --v 4 --steps 50 --format svg,pdf --out "$TMP/sw" >/dev/null ||
  fail sweep "exit $?"
[[ -s $TMP/sw.svg && -s $TMP/sw.pdf && ! -e $TMP/sw.png ]] || fail sweep "svg and pdf expected, no png"
"$BOUNCER" continue --model constant --eps 0.25 --a 26 --period 1 --guess 0.5,4 --range 24:28 --format pdf --out "$TMP/co" >/dev/null ||
  fail continue "exit $?"
[[ -s $TMP/co.pdf && ! -e $TMP/co.png ]] || fail continue "pdf expected, no png"

# The font file missing: tests/cli/missing_font.sh (it needs a mount namespace).

finish
