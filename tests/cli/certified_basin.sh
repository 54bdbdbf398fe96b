#!/usr/bin/env bash
# End-to-end: `bouncer basin --certify` and `bouncer bifurcation --certify` (certified
# pictures, constant restitution; velocity-dependent restitution without collapse).
#   - every in-phase-space point has a certified class or is undecided; the CSV columns are
#     as documented, and the JSON counts are those of the CSV;
#   - the certified classes agree with `bouncer certify-sticking` run by hand at sample
#     points (the same exact start: the printed double grid point);
#   - the artefact map finds the known artefact of the release orbit at eps = 0.5, a = 15:
#     double sticks with period 3773 there, the certified orbit does not stick through
#     its certified steps, so every point whose double orbit sticks is marked "differs";
#   - double's class is recomputed by `bouncer basin` without --certify (same column);
#   - PREFIX-artefacts.png is written; bad options exit 2 with one line and no file;
#   - scan --certify: the certificate at sample points equals certify-sticking's at the exact
#     double (a, eps); JSON counts = CSV;
#   - threads and shards: --threads 1, --threads 2 and two shards merged give the same rows;
#   - velocity-dependent: at a = 25, c = 1000 every start is certified trapped (period 3, the
#     orbit certify-periodic proves, or 31) and double agrees; a chaotic case is not_trapped;
#     scan and bifurcation --certify take (a, c) and --vary c; veldep collapse is refused
#     (exit 2) with the reason;
#   - elastic (area-preserving: no attractor to certify): every point is not_trapped (its exact
#     orbit certified through every step) or undecided, and its certified_steps is the horizon
#     that `bouncer orbit --method lohner` reaches from the same exact start, the longer of its
#     interval:double and interval:64 runs (the schedule of --max-bits 64);
#   - bifurcation --certify: each column's certificate equals certify-sticking's at the exact
#     double value of a (printed exactly), and at eps = 0.5, a ~ 15.2 double's sticking at step
#     283 is refuted (the exact orbit does not stick in 700 steps); with --vary eps each column
#     is certified at the exact double eps, as certify-sticking there.
# Usage: bash certified_basin.sh <bouncer-binary> <source-dir>
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
cd "$TMP"

common=(--model constant --transient 300 --steps 100 --quiet)
"$BOUNCER" basin "${common[@]}" --eps 0.5 --a 24 --grid 12x8 --certify --out c24 || fail c24 "exit $?"
"$BOUNCER" basin "${common[@]}" --eps 0.5 --a 24 --grid 12x8 --out d24 || fail d24 "exit $?"
"$BOUNCER" basin "${common[@]}" --eps 0.5 --a 15 --grid 10x6 --certify --max-bits 128 --out c15 || fail c15 "exit $?"
for p in c24 c15; do outputs "$p" "$p" csv png json; outputs "$p" "$p-artefacts" png; done

# bifurcation --certify: two columns, a = 15.2 and 15.3 as doubles, from the release state.
"$BOUNCER" bifurcation --model constant --eps 0.5 --range 15.2:15.3 --samples 2 --transient 600 --record 100 \
  --theta 0.5 --v 4 --certify --max-bits 256 --quiet --out bc || fail bc "exit $?"
outputs bc bc
# Elastic, a = 18 (the nine-branch accelerator's parameter), 6 x 4 starts, 2000 steps.
"$BOUNCER" basin --model elastic --a 18 --grid 6x4 --v-range 8:20 --transient 1500 --steps 500 --max-bits 64 \
  --certify --quiet --out el || fail el "exit $?"
"$BOUNCER" bifurcation --model elastic --range 18:18.5 --samples 2 --transient 300 --record 100 --theta 0.75 --v 12.5 \
  --certify --max-bits 64 --quiet --out elb || fail elb "exit $?"
python3 - "$BOUNCER" <<'PY' || fail properties "see above"
import csv, decimal, json, re, subprocess, sys
bouncer = sys.argv[1]
from clichecks import check, done
def rows(name):
    return list(csv.DictReader(l for l in open(name + ".csv") if not l.startswith("#")))

c24, d24 = rows("c24"), rows("d24")
check(list(c24[0].keys()) == ["theta", "v", "class", "period", "certified_steps", "scalar", "double_class",
                              "double_period", "agreement"], "columns: %s" % list(c24[0].keys()))
classes = {"sticking", "fixed", "periodic", "no_sticking", "undecided", "outside"}
for r in c24:
    check(r["class"] in classes, "class %s" % r["class"])
    check(r["agreement"] in {"agrees", "differs", "undecided", "outside"}, "agreement %s" % r["agreement"])
    if r["class"] not in ("outside", "undecided"):
        check(r["scalar"] == "interval:double" or r["scalar"].startswith("interval:"), "scalar %s" % r["scalar"])
# The double twin is plain basin's answer at the same points.
check(len(c24) == len(d24), "same grid")
for r, d in zip(c24, d24):
    check((r["theta"], r["v"]) == (d["theta"], d["v"]), "same points")
    check((r["double_class"], r["double_period"]) == (d["class"], d["period"]), "twin %s vs %s" % (r, d))
# JSON counts are those of the CSV.
j = json.load(open("c24.json"))["summary"]
check(j["certified"] is True, "certified flag")
agree = {k: sum(1 for r in c24 if r["agreement"] == k) for k in ("agrees", "differs", "undecided")}
check(j["double_vs_certified"] == agree, "json %s vs csv %s" % (j["double_vs_certified"], agree))
check(sum(t["points"] for t in j["classes"]) == len(c24), "class counts")
# At eps = 0.5, a = 24 sticking has period 4 (certify-sticking from the release state).
stick = [r for r in c24 if r["class"] == "sticking"]
check(len(stick) > 0 and all(r["period"] == "4" for r in stick), "sticking period 4: %s" % {r["period"] for r in stick})
# Sample points against certify-sticking run by hand from the same exact start.
for r in [x for x in c24 if x["class"] in ("sticking", "fixed", "periodic")][:4]:
    out = subprocess.run([bouncer, "certify-sticking", "--eps", "0.5", "--a", "24", "--theta", r["theta"], "--v", r["v"],
                          "--max-steps", "400", "--max-bits", "256", "--json"], capture_output=True, text=True)
    c = json.loads(out.stdout)
    if r["class"] == "sticking":
        check(c["outcome"] == "sticks", "point %s,%s: certify-sticking says %s" % (r["theta"], r["v"], c["outcome"]))
    else:
        check(c["outcome"] == "never_sticks" and c["attractor"]["period"] == int(r["period"]),
              "point %s,%s: %s" % (r["theta"], r["v"], c["statement"]))
# eps = 0.5, a = 15: double's release orbit sticks (period 3773, an artefact); the certified
# one does not stick in its certified steps: no certified point may say "sticking, k = 3773",
# and every point whose double orbit sticks is marked "differs" or "undecided".
c15 = rows("c15")
check(not any(r["class"] == "sticking" for r in c15), "a = 15: a certified sticking class?")
double_sticks = [r for r in c15 if r["double_class"] == "sticking"]
check(len(double_sticks) > 0, "a = 15: double should stick somewhere (the known artefact)")
check(all(r["agreement"] in ("differs", "undecided") for r in double_sticks), "a = 15: artefacts not flagged")
j15 = json.load(open("c15.json"))["summary"]
check(j15["double_vs_certified"]["differs"] > 0, "a = 15: the artefact map finds no artefact")
# bifurcation --certify: two columns, a = 15.2 and 15.3 as doubles, from the release state.
jb = json.load(open("bc.json"))["summary"]
cols = jb["columns"]
check(len(cols) == 2 and jb["certified"] is True, "two certified columns")
check(cols[0]["a"].startswith("15.19999999999999928945"), "column a is the exact double: %s" % cols[0]["a"])
for c in cols:
    out = subprocess.run([bouncer, "certify-sticking", "--eps", "0.5", "--a", c["a"], "--max-steps", "700",
                          "--max-bits", "256", "--json"], capture_output=True, text=True)
    h = json.loads(out.stdout)
    if c["class"] == "no_sticking":
        check(h["outcome"] == "no_sticking_within_max_steps" and h["steps_checked"] == 700, "a=%s: %s" % (c["a"], h["statement"]))
    if c["class"] == "sticking":
        check(h["outcome"] == "sticks" and h["period"] == c["period"], "a=%s: %s vs %s" % (c["a"], c, h["statement"]))
        # double's own answer at the same double a, as certify-sticking reports it
        check(h["double_period"] == c["double_period"], "double period %s vs %s" % (h["double_period"], c["double_period"]))
        check((c["agreement"] == "agrees") == (c["double_period"] == c["period"]), "agreement %s" % c)
# a = 15.2: the exact orbit does not stick in 700 steps (its first sticking is at step 1320,
# certify-sticking --max-steps 2000 --max-bits 512); double sticks at step 283: refuted.
check(cols[0]["class"] == "no_sticking" and cols[0]["double_class"] == "sticking" and cols[0]["double_period"] == 283
      and cols[0]["agreement"] == "differs", "a = 15.2: double's 283 refuted: %s" % cols[0])
check(jb["double_vs_certified"]["differs"] >= 1, "the refuted column is counted")
# Elastic: not_trapped or undecided, with the horizon of `orbit --method lohner` from the same
# exact start (the CSV prints the shortest text that reads back as the double).
el = rows("el")
check(len(el) == 24, "24 rows: %d" % len(el))
seen = set()
for r in el:
    seen.add(r["class"])
    steps = int(r["certified_steps"])
    check(r["class"] in ("not_trapped", "undecided"), "class %s" % r["class"])
    check(r["agreement"] == "undecided", "elastic agreement %s" % r["agreement"])
    if r["class"] == "not_trapped":
        check(steps == 2000 and r["scalar"] in ("interval:double", "interval:64"), "not_trapped row %s" % r)
    else:
        check(steps < 2000 and r["scalar"] == "", "undecided row %s" % r)
    exact = [str(decimal.Decimal(float(r[k]))) for k in ("theta", "v")]
    horizon = 0
    for precision in ("interval:double", "interval:64"):
        subprocess.run([bouncer, "orbit", "--model", "elastic", "--a", "18", "--theta", exact[0], "--v", exact[1],
                        "--steps", "2000", "--precision", precision, "--method", "lohner", "--out", "o.csv"],
                       check=False, capture_output=True)
        end = [l for l in open("o.csv") if l.startswith("# end: orbit 0")]
        m = re.search(r"undecided at step (\d+)", end[0]) if end else None
        horizon = max(horizon, int(m.group(1)) - 1 if m else 2000)
    check(horizon == steps, "(%s, %s): certified_steps %d, orbit's horizon %d" % (r["theta"], r["v"], steps, horizon))
check(seen == {"not_trapped", "undecided"}, "both classes at a = 18: %s" % seen)
summary = json.load(open("el.json"))["summary"]
check(summary["double_vs_certified"]["differs"] == 0, "elastic differs: %s" % summary["double_vs_certified"])
elb = json.load(open("elb.json"))["summary"]["columns"]
check(len(elb) == 2 and all(c["class"] in ("not_trapped", "undecided") for c in elb), "elastic columns %s" % elb)
done()
PY

# bifurcation --certify --vary eps: each column is the exact orbit at the exact double eps;
# its certificate equals certify-sticking's there (eps = 0.49 as a double: sticks, period 31).
"$BOUNCER" bifurcation --model constant --a 15 --vary eps --range 0.49:0.51 --samples 3 --transient 600 --record 100 \
  --theta 0.5 --v 4 --certify --max-bits 256 --quiet --out be || fail be "exit $?"
python3 - "$BOUNCER" <<'PY' || fail bif-eps "see above"
import json, subprocess, sys
bouncer = sys.argv[1]
cols = json.load(open("be.json"))["summary"]["columns"]
bad = 0
if [c["eps"][:6] for c in cols] != ["0.4899", "0.5", "0.5100"]:
    print("eps columns: %s" % [c["eps"] for c in cols]); bad += 1
for c in cols:
    h = json.loads(subprocess.run([bouncer, "certify-sticking", "--a", "15", "--eps", c["eps"], "--max-steps", "700",
                                   "--max-bits", "256", "--json"], capture_output=True, text=True).stdout)
    want = {"sticks": "sticking", "no_sticking_within_max_steps": "no_sticking"}.get(h["outcome"], h["outcome"])
    if want != c["class"] or (want == "sticking" and h["period"] != c["period"]):
        print("eps=%s: column %s, certify-sticking %s" % (c["eps"], c, h["statement"])); bad += 1
if not (cols[0]["class"] == "sticking" and cols[0]["period"] == 31):
    print("eps = 0.49: want sticking period 31, got %s" % cols[0]); bad += 1
sys.exit(bad > 0)
PY

# scan --certify: per parameter point the exact orbit of the release state (1/2, 4) at the
# exact double (a, eps); the certificate equals certify-sticking's there.
"$BOUNCER" scan --model constant --a-range 14:16 --eps-range 0.45:0.55 --grid 4x3 --transient 300 --steps 100 \
  --certify --quiet --out sc || fail sc "exit $?"
[[ -s sc-artefacts.png && -s sc.png ]] || fail sc "missing pictures"
python3 - "$BOUNCER" <<'PY' || fail scan-certify "see above"
import json, subprocess, sys
bouncer = sys.argv[1]
rows = [l.rstrip("\n").split(",") for l in open("sc.csv") if not l.startswith("#")]
bad = 0
if rows[0] != "a,eps,class,period,certified_steps,scalar,double_class,double_period,agreement".split(","):
    print("header %s" % rows[0]); bad += 1
rows = rows[1:]
if len(rows) != 12:
    print("%d rows, want 12" % len(rows)); bad += 1
s = json.load(open("sc.json"))["summary"]
counts = {k: sum(r[8] == k for r in rows) for k in ("agrees", "differs", "undecided")}
if s["double_vs_certified"] != counts:
    print("JSON counts %s, CSV %s" % (s["double_vs_certified"], counts)); bad += 1
for r in rows[::5]:  # three sample points
    h = json.loads(subprocess.run([bouncer, "certify-sticking", "--a", r[0], "--eps", r[1], "--max-steps", "400",
                                   "--max-bits", "256", "--json"], capture_output=True, text=True).stdout)
    want = {"sticks": "sticking", "no_sticking_within_max_steps": "no_sticking"}.get(h["outcome"], h["outcome"])
    if r[2] in ("fixed", "periodic"):
        ok = h["outcome"] == "never_sticks"
    else:
        ok = want == r[2] and (want != "sticking" or h["period"] == int(r[3]))
    if not ok:
        print("a=%s eps=%s: scan %s, certify-sticking %s" % (r[0], r[1], r[2:5], h["statement"])); bad += 1
sys.exit(bad > 0)
PY

# Bad input: exit 2, one line, no files.
expect_bad() {
  local name=$1
  shift
  rm -f bad.*
  refused "$name" "" "$@" --out bad
  absent "$name" "bad.*"
}
expect_bad veldep-collapse basin --model veldep --a 25 --c 1000 --veldep-collapse on --grid 4x4 --certify
expect_bad twin basin --model constant --eps 0.5 --a 24 --grid 4x4 --certify --precision mpfr:100
expect_bad bits basin --model constant --eps 0.5 --a 24 --grid 4x4 --certify --max-bits 9999
expect_bad bits-alone basin --model constant --eps 0.5 --a 24 --grid 4x4 --max-bits 128
expect_bad bif-carry bifurcation --model constant --eps 0.5 --range 15:16 --samples 2 --carry --certify
expect_bad start-bits-typo certify-sticking --eps 0.5 --a 24 --start-bits doubel
expect_bad scan-collapse scan --model veldep --veldep-collapse on --a-range 20:21 --c-range 100:200 --grid 2x2 --certify
refused collapse-reason "collapse has no certified test" basin --model veldep --a 25 --c 1000 --veldep-collapse on --grid 4x4 --certify


# Velocity-dependent restitution (no collapse): a = 25, c = 1000, the paper's "chaotic attractor
# with a riddled basin" (claim 18). Every start is certified trapped: in the period-3 attractor
# that Krawczyk proves (certify-periodic below), or in the period-31 one; double agrees. A
# chaotic case (c = 10, a = 20: lambda ~ 0.08) gives not_trapped, compared with nothing.
"$BOUNCER" basin --model veldep --a 25 --c 1000 --grid 8x6 --transient 2000 --steps 300 --certify --quiet --out vb
"$BOUNCER" certify-periodic --model veldep --c 1000 --a 25 --period 3 --guess 0.18703729141819947,30.210923880542616 \
  --json >vp.json
"$BOUNCER" basin --model veldep --a 20 --c 10 --grid 3x2 --transient 600 --steps 200 --certify --quiet --out vc
"$BOUNCER" scan --model veldep --a-range 24.5:25.5 --c-range 900:1100 --grid 2x2 --transient 2000 --steps 300 --certify \
  --quiet --out vs
"$BOUNCER" bifurcation --model veldep --a 25 --vary c --range 900:1100 --samples 2 --transient 2000 --record 300 \
  --theta 0.5 --v 4 --certify --quiet --out vf
python3 - <<'PY' || fail veldep "certified velocity-dependent grids"
import csv, json, sys
def rows(p):
    return list(csv.DictReader(l for l in open(p + ".csv") if not l.startswith("#")))
bad = 0
krawczyk = json.load(open("vp.json"))
if not (krawczyk.get("certified") and krawczyk.get("minimal_period", 3) == 3):
    print("certify-periodic does not prove the period-3 orbit:", krawczyk.get("statement")); bad += 1
b = rows("vb")
if len(b) != 48: print("vb.csv: expected 48 rows"); bad += 1
for r in b:
    if r["class"] != "periodic" or r["period"] not in ("3", "31") or r["agreement"] != "agrees":
        print("a = 25, c = 1000:", r); bad += 1
if sum(r["period"] == "3" for r in b) < 40: print("period 3 is not the main attractor"); bad += 1
for r in rows("vc"):
    if r["class"] not in ("not_trapped", "undecided") or r["agreement"] != "undecided":
        print("c = 10, a = 20 (chaotic):", r); bad += 1
    if r["class"] == "not_trapped" and r["certified_steps"] != "800":
        print("not_trapped must be certified through every step:", r); bad += 1
s = rows("vs")
if len(s) != 4 or list(s[0])[:3] != ["a", "c", "class"]: print("vs.csv columns or rows:", list(s[0])); bad += 1
if json.load(open("vs.json"))["summary"].get("c_range") != ["900", "1100"]: print("vs.json: no c_range"); bad += 1
for r in s:
    if r["class"] not in ("fixed", "periodic", "not_trapped", "undecided"): print("scan veldep:", r); bad += 1
cols = json.load(open("vf.json"))["summary"].get("columns", [])
if len(cols) != 2 or any("c" not in c for c in cols): print("vf.json certified columns:", cols); bad += 1
sys.exit(bad > 0)
PY
expect_bad scan-theta scan --model constant --a-range 20:21 --eps-range 0.4:0.5 --grid 2x2 --theta 0.3
expect_bad scan-start scan --model constant --a-range 20:21 --eps-range 0.4:0.5 --grid 2x2 --certify --theta 0.25 --v 1

# The grid runner's threads and shards: one thread, two threads, and two shards merged give the
# same certified rows and the same JSON (apart from the invocation and the file names).
cg=(--model constant --transient 300 --steps 100 --quiet --eps 0.5 --a 24 --grid 12x8 --certify)
"$BOUNCER" basin "${cg[@]}" --threads 1 --out g1 || fail g1 "exit $?"
"$BOUNCER" basin "${cg[@]}" --threads 2 --out g2 || fail g2 "exit $?"
"$BOUNCER" basin "${cg[@]}" --shard 0/2 --out gs || fail gs0 "exit $?"
[[ ! -e gs.csv ]] || fail gs0 "a shard wrote the outputs before the merge"
"$BOUNCER" basin "${cg[@]}" --shard 1/2 --out gs || fail gs1 "exit $?"
"$BOUNCER" merge gs || fail merge "exit $?"
python3 - <<'PY' || fail threads-shards "see above"
import json, sys
def rows(p):
    return [l for l in open(p + ".csv") if not l.startswith("#")]
def doc(p):
    j = json.load(open(p + ".json"))
    j["provenance"].pop("invocation", None)
    j.pop("files", None)
    return j
bad = 0
for p in ("g2", "gs"):
    if rows(p) != rows("g1"):
        print(f"{p}.csv rows differ from g1.csv"); bad += 1
    if doc(p) != doc("g1"):
        print(f"{p}.json differs from g1.json beyond invocation and files"); bad += 1
if len(rows("g1")) != 1 + 12 * 8:
    print("g1.csv: expected 96 rows"); bad += 1
sys.exit(bad > 0)
PY

finish
