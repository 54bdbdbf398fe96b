// `bouncer reproduce` as a library call: the whole paper (or the README's pictures) from a
// manifest (workflow/manifest.hpp). Every figure panel and every claim runs as a child
// process of the bouncer binary, or of a proof program found from it (proof_directory below),
// N at a time (workflow/scheduler.hpp), into the directory DIR:
//   DIR/report.md, DIR/report.html  every panel beside the paper's caption, the claims table,
//                                   provenance per item; times only in the "Times" section
//   DIR/claims.json                 per claim: expected verdict, this run's verdict, checks;
//                                   per panel: status and files; times only in "seconds" keys
//   DIR/panels/NAME.{png,pdf,svg,csv,json}  the panels' outputs; DIR/claims/ID.json claims'
//   DIR/pictures/...                (mode pictures) the README's pictures
//   DIR/logs/ID.stdout|stderr       what each child printed;  DIR/keys/ID.key  resume keys
// (workflow/report.hpp writes the reports). An item whose key (mode, argv, build version and
// commit) matches DIR/keys/ID.key and whose outputs exist is not rerun.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bouncer/workflow/checks.hpp"
#include "bouncer/workflow/manifest.hpp"
#include "bouncer/workflow/scheduler.hpp"

namespace bouncer {

enum class ReproduceMode {
  quick,     // small grids and few steps
  full,      // the paper's resolution
  pictures,  // the README's pictures (the manifest's [[picture]]), the same in every mode
};
const char* mode_name(ReproduceMode m);  // "quick", "full", "pictures"

// The manifest at `path` (read with the bounds of base/input.hpp), or the built-in paper
// manifest for "" (workflow/paper.hpp). Throws InputError("manifest", ...).
Manifest load_manifest(const std::string& path);
// How reports name that manifest: `path`, or kPaperManifestSource.
std::string manifest_source(const std::string& path);

// Where the proof programs (proof_NAME) of the bouncer binary `executable` ("": this
// process's, /proc/self/exe) are, found from the binary itself and never through PATH or a
// file the user chooses: in a build tree build/proofs/ beside build/tools/bouncer, in an
// install BIN/../libexec/bouncer/ (GNUInstallDirs' libexec, relative to bin, so that a
// relocated install or an unpacked .deb finds its own). std::nullopt: neither exists.
std::optional<std::string> proof_directory(const std::string& executable = "");
// How commands shown to a reader name a proof program's directory: kBuildProofPrefix
// (build/proofs/, checkout-relative) from a build tree, the install's absolute
// libexec/bouncer/ from an install.
std::string proof_prefix(const std::string& executable = "");

// Refuses (InputError "reproduce") to run inside a reproduce: its children have
// BOUNCER_IN_REPRODUCE set, and a manifest runs computing commands only.
void refuse_nested_reproduce();

struct ReproduceRequest {
  ReproduceMode mode = ReproduceMode::quick;
  std::optional<Manifest> manifest;  // std::nullopt: load_manifest(manifest_path)
  std::string manifest_path;         // "": the built-in paper manifest; names it in the reports
  std::string out = "reproduction";  // the directory DIR (made if missing; its parent must exist)
  // Items to run: claim ids, panel labels (also without "fig:"), picture ids (also without
  // "picture:"); std::nullopt: every item of the mode. An empty list or an unknown id is
  // InputError("only", ...), the latter naming close ids.
  std::optional<std::vector<std::string>> only;
  unsigned jobs = 0;                 // items run at once; 0: one per core
  std::string executable;            // the bouncer binary the items run; "": this process's
  JobProgress progress;              // told of each item as it is settled (may be empty)
};

enum class ClaimStatus { reproduced, not_reproduced, failed, deferred };
const char* status_name(ClaimStatus s);  // "reproduced", "not reproduced", "failed", "deferred"

enum class ItemKind { panel, claim, picture };

struct ItemResult {
  std::string id;                    // claim id, panel label or picture:NAME
  ItemKind kind = ItemKind::panel;
  std::size_t index = 0;             // into the manifest's panels, claims or pictures
  std::vector<std::string> argv;     // its command as in the manifest (empty: a pending panel)
  std::vector<std::string> outputs;  // its files, relative to DIR
  ItemState state = ItemState::pending;
  std::string problem;
  int exit_status = 0;
  double seconds = 0;
  // Claims only: whether the claim reproduced its expected verdict, and its checks.
  ClaimStatus status = ClaimStatus::failed;
  std::string verdict;                     // the expected verdict when reproduced, else why not
  std::vector<CheckResult> checks;
  std::vector<std::string> failed_checks;  // "CHECK (got VALUE)"
};

struct ReproduceResult {
  Manifest manifest;
  ReproduceMode mode = ReproduceMode::quick;
  std::string dir, build, manifest_source;
  std::string proof_prefix = kBuildProofPrefix;  // proof_prefix(): how the reports name proof programs
  std::vector<std::string> only;     // the ids selected with `only`, sorted
  unsigned jobs = 1;
  std::vector<ItemResult> items;     // panels, then claims, then pictures, in manifest order
  std::size_t claims = 0, reproduced = 0, not_reproduced = 0, deferred = 0, failed_items = 0;
  double seconds = 0;
  bool ok = false;                   // every item ran and every claim reproduced its verdict
  std::string summary;               // "N of M claims reproduced ...; K items failed"
  int stopped_by = 0;                // a signal stopped the run: no report was written
  int exit_status() const { return ok ? 0 : 1; }
};

// Runs the request and writes the reports (unless a signal stopped it: stopped_by, and the
// caller should end by that signal, scheduler.hpp). Throws InputError for bad requests (the
// field named as the command-line option: only, out, jobs, manifest) and OutputError.
ReproduceResult reproduce(const ReproduceRequest& request);

// --check: every command of a manifest, quick and full, validated without being run. Each
// bouncer command goes to `validate` with its scenes resolved (and a panel's --out in a
// temporary directory), under a set cancellation flag (base/cancel.hpp), so that it checks
// its options and inputs as it always does and stops at its first step; a proof binary
// must exist in proof_directory(executable).
struct CommandValidation {
  enum class Kind { stopped, ran, refused } kind = Kind::refused;
  int status = 0;       // exit status when refused
  std::string message;  // the one-line reason when refused
};
using CommandValidator = std::function<CommandValidation(const std::vector<std::string>& argv)>;
struct CommandCheck {
  std::string id, which;  // the item, and which of its commands (quick, full, run, ...)
  std::string verdict;    // "ok (...)" or "refused...: why"
  bool ok = false;
};
struct ManifestCheck {
  std::vector<CommandCheck> commands;
  std::size_t refused = 0;
};
ManifestCheck check_manifest(const Manifest& manifest, const CommandValidator& validate, const std::string& executable = "");

}  // namespace bouncer
