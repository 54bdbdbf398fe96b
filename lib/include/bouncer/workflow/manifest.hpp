// A reproduce manifest (data/paper/manifest.toml, or another given to `reproduce --manifest`):
// the paper's figure panels, its claims with their checks, and the README's pictures, each
// with the bouncer command (or proof program) that makes it.
//
// A manifest is data, and may come from someone else (`reproduce --manifest FILE`, or the
// manifest a reproduce directory names, which `audit DIR` reruns). What it may ask for is
// bounded by parse_manifest, for the built-in manifest too:
//   * its ids, labels and file names become file names in the reproduce directory: letters,
//     digits and . _ : + - only, no "..", at most 100 characters (no '/', so nothing is
//     written outside the directory);
//   * every command is one of bouncer's computing commands, or a proof program beside it
//     with --full, --json, --bits only: never reproduce, audit or merge (a manifest that ran
//     itself spawned hundreds of processes), and never an option that chooses where a
//     command reads tiles or writes (--out, --tiles-from, --keep-tiles, --shard): reproduce
//     gives each command its place in the directory. --scene names a scene built into
//     bouncer (data/scenes/, workflow/paper.hpp), not a file.
//   * its text is at most kMaxManifestBytes and nested at most kMaxTomlDepth (base/input.hpp).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bouncer/workflow/checks.hpp"

namespace bouncer {

struct Panel {
  // twin_of: not a panel of the paper but bouncer's certified twin of one (label
  // fig:NAME-certified): the same picture from `basin --certify`, with its artefact map.
  std::string label, figure, panel, caption, note, scene, status, reason, twin_of;
  // beside: not a panel of the paper but the same picture for the sine wall (label
  // fig:NAME-sine, the commands of panel `beside` with --wall sine), drawn beside it in its
  // figure: the paper's headline comparison of the two walls, panel by panel.
  std::string beside;
  // tiles_from: the label of an earlier panel whose grid is this one's too (only the
  // picture differs, e.g. --show): computed once, drawn twice.
  std::string tiles_from;
  std::vector<std::pair<std::string, std::string>> params;
  std::vector<std::string> quick, full;  // status "ready": both; "pending": a reason instead
  // The label without "fig:": the panel's file names (panels/NAME.png).
  std::string name() const { return label.rfind("fig:", 0) == 0 ? label.substr(4) : label; }
};

struct Claim {
  std::string id, row, text, paper, expected, verdict, evidence, rerun;
  std::vector<long> groups;
  std::vector<std::string> run, full_run;  // full_run defaults to run (+ --full for a proof)
  bool quick = true;                       // settled in --quick too (else deferred to --full)
  std::vector<Check> checks;
};

// [[picture]]: a picture of bouncer's README (data/pictures/NAME.png), not of the paper.
struct Picture {
  std::string name, readme, about;
  std::vector<std::string> command;
  std::vector<std::string> files;  // the pictures it writes (default NAME.png)
  std::string id() const { return "picture:" + name; }
};

struct Manifest {
  std::vector<Panel> panels;
  std::vector<Claim> claims;
  std::vector<Picture> pictures;
};

// The words a claim's `expected` may be.
const std::vector<std::string>& verdict_words();

// Why a manifest may not run `argv` (one of the bounds above), or "" when it may (an empty
// argv too: a command the manifest does not give).
std::string command_problem(const std::vector<std::string>& argv);

// Parses and bounds a manifest; `source` names it in messages. Throws InputError("manifest",
// "SOURCE panel LABEL: ...") naming the item and the field at fault.
Manifest parse_manifest(const std::string& text, const std::string& source);

// The directory a proof program is named from in commands shown to a reader: the build
// tree's, relative to the checkout (build/proofs/proof_NAME), as the README and the
// manifest's `rerun` texts write it.
inline constexpr const char* kBuildProofPrefix = "build/proofs/";

// A manifest command as a shell line: words quoted where needed, a proof program as
// PROOF_PREFIX + proof_NAME (by default where the build puts it; an installed bouncer passes
// its own proof directory, reproduce.hpp's proof_prefix).
std::string command_text(const std::vector<std::string>& argv, const std::string& proof_prefix = kBuildProofPrefix);
// A claim's `rerun` text as a reader runs it: build/proofs/ replaced by `proof_prefix`, a
// built-in scene's path (--scene data/scenes/picture-NAME.toml) by its name (--scene NAME,
// found from any directory and from an install), `ctest -R X` run in build/ (and, for an
// install, said to need a build tree of the sources).
std::string rerun_text(const std::string& rerun, const std::string& proof_prefix);

}  // namespace bouncer
