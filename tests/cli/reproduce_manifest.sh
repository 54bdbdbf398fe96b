#!/usr/bin/env bash
# The paper manifest (data/paper/manifest.toml) is complete:
#   * every label of data/paper/figure-labels.txt is a panel's label or a figure's label, and
#     every figure label with panels is covered by at least one panel; no panel label is
#     missing from the list;
#   * (the stored list and captions against the paper's .tex: reproduce_manifest_tex.sh)
#   * every panel is ready (quick and full commands, starting with bouncer) or pending with a
#     reason;
#   * a certified twin (twin_of) is labelled PANEL-certified, in PANEL's figure, with its
#     caption, and its commands certify;
#   * every claim has an expected verdict from the five words, a run command and checks, and
#     together the claims cover all 11 claim groups of DESIGN.md section 4 and the claims table's
#     rows 1-15 (docs/claims.md);
#   * `reproduce --check` accepts every command of the manifest, quick and full, and the documentation
#     pictures' commands with their built-in scenes (each is
#     parsed and validated by the command itself, stopped before its first step): a full
#     command that only --full would run is checked here too; and it refuses the bad command
#     of the failing test manifest, naming it and its option, with exit 1;
#   * a panel's tiles_from names an earlier panel whose commands differ from its own only in
#     presentation options (--show).
# Usage: bash reproduce_manifest.sh <bouncer-binary> <source-dir>
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh" "$@"
if ! "$BOUNCER" reproduce --check > "$TMP/check" 2> "$TMP/check.err"; then
  { grep -v ': ok' "$TMP/check" || true; cat "$TMP/check.err"; } >&2
  die "reproduce --check refused commands of the manifest (above)"
fi
n=$(python3 -c 'import sys,tomllib; m=tomllib.load(open(sys.argv[1],"rb")); print(sum(2 for p in m["panel"] if p["status"]=="ready") + sum(1 + ("full_run" in c or c["run"][0].startswith("proof_")) for c in m["claim"]) + len(m.get("picture", [])))' "$SRC/data/paper/manifest.toml")
grep -q "^$n commands checked, 0 refused$" "$TMP/check" || die "expected $n commands checked: $(tail -1 "$TMP/check")"
grep -q '^fig:paramspace1 full: ok (validated' "$TMP/check" || die "the full scan was not validated"
set +e
"$BOUNCER" reproduce --check --manifest "$SRC/tests/data/reproduce-failing-manifest.toml" > "$TMP/checkf" 2>&1
s=$?
set -e
[ "$s" = 1 ] || die "--check of a bad command: exit $s, expected 1"
grep -q "^bad-command run: refused (exit 2): a: " "$TMP/checkf" || die "the bad command is not named: $(cat "$TMP/checkf")"
python3 - "$SRC/data/paper/manifest.toml" "$SRC/data/paper/figure-labels.txt" <<'PY'
import os, re, sys, tomllib
manifest, labels_file = sys.argv[1:3]
m = tomllib.load(open(manifest, "rb"))
errors = []
labels = [l.strip() for l in open(labels_file) if l.strip() and not l.startswith("#")]
all_panels = m.get("panel", [])
# Certified twins (twin_of) are bouncer's, not the paper's: label = the twin's label +
# "-certified", same figure, a `basin --certify` command; the rest of the checks are on the
# paper's panels.
panels = [p for p in all_panels if "twin_of" not in p and "beside" not in p]
twins = [p for p in all_panels if "twin_of" in p]
# Sine-wall panels (beside): label = the triangle panel's + "-sine", same figure and caption,
# and exactly its commands with --wall sine appended: the same parameters and resolution.
for t in [p for p in all_panels if "beside" in p]:
    of = next((p for p in panels if p["label"] == t["beside"]), None)
    if of is None:
        errors.append(f"{t['label']}: beside {t['beside']!r} is not a panel of the manifest")
        continue
    if t["label"] != of["label"] + "-sine" or t["figure"] != of["figure"] or t["caption"] != of["caption"]:
        errors.append(f"{t['label']}: a sine panel is labelled {of['label']}-sine, in figure {of['figure']}, with its caption")
    for v in ("quick", "full"):
        if t.get(v) != of.get(v, []) + ["--wall", "sine"]:
            errors.append(f"{t['label']}: its '{v}' command must be {of['label']}'s with --wall sine appended")
panel_labels = [p["label"] for p in panels]
figure_labels = {p["figure"] for p in panels}
if len(set(panel_labels)) != len(panel_labels):
    errors.append("duplicate panel labels")
for t in twins:
    of = next((p for p in panels if p["label"] == t["twin_of"]), None)
    if of is None:
        errors.append(f"{t['label']}: twin_of {t['twin_of']!r} is not a panel of the manifest")
        continue
    if t["label"] != of["label"] + "-certified" or t["figure"] != of["figure"]:
        errors.append(f"{t['label']}: a twin is labelled {of['label']}-certified, in figure {of['figure']}")
    if t["caption"] != of["caption"]:
        errors.append(f"{t['label']}: a twin shows its panel's caption")
    for v in ("quick", "full"):
        if "--certify" not in t.get(v, []):
            errors.append(f"{t['label']}: a twin's '{v}' command must certify (--certify)")
for l in labels:
    if l not in panel_labels and l not in figure_labels:
        errors.append(f"{l}: in the paper, not in the manifest")
for l in panel_labels + sorted(figure_labels):
    if l not in labels:
        errors.append(f"{l}: in the manifest, not a label of the paper")
for p in panels:
    if p["status"] == "ready":
        for v in ("quick", "full"):
            if not p.get(v) or p[v][0] != "bouncer":
                errors.append(f"{p['label']}: ready panel needs a '{v}' bouncer command")
    elif p["status"] == "pending":
        if not p.get("reason"):
            errors.append(f"{p['label']}: pending without a reason")
    else:
        errors.append(f"{p['label']}: status {p['status']!r}")
words = {"confirmed", "refuted", "corrected", "not reproduced", "consistent"}
groups, rows = set(), set()
for c in m.get("claim", []):
    if c["expected"] not in words:
        errors.append(f"{c['id']}: expected {c['expected']!r}")
    if not c.get("run") or not c.get("checks"):
        errors.append(f"{c['id']}: needs run and checks")
    groups.update(c.get("groups", []))
    rows.add(re.match(r"\d+", c["row"]).group(0))
if groups != set(range(1, 12)):
    errors.append(f"claim groups covered {sorted(groups)}, DESIGN.md section 4 has 1..11")
if not {str(i) for i in range(1, 16)} <= rows:
    errors.append(f"claims table rows covered {sorted(rows, key=int)}, need at least 1..15 (the paper claims of the first claims tables)")
# tiles_from: an earlier panel, the same command apart from --show (a presentation option).
def without_show(argv):
    out, skip = [], False
    for w in argv:
        if skip: skip = False; continue
        if w == "--show": skip = True; continue
        out.append(w)
    return out
seen = {}
for p in all_panels:
    src = p.get("tiles_from")
    if src:
        if src not in seen:
            errors.append(f"{p['label']}: tiles_from {src} is not an earlier panel")
        else:
            for k in ("quick", "full"):
                if without_show(seen[src][k]) != without_show(p[k]):
                    errors.append(f"{p['label']}: its {k} command is not {src}'s apart from --show")
    seen[p["label"]] = p
if errors:
    print("FAIL:\n  " + "\n  ".join(errors)); sys.exit(1)
print(f"ok: {len(panels)} panels ({sum(p['status'] == 'pending' for p in panels)} pending), {len(m['claim'])} claims, "
      f"{len(labels)} labels (against the paper's .tex: reproduce_manifest_tex.sh)")
PY
