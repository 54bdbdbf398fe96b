// bouncer audit FILE: rerun a recorded result from its provenance and report whether the
// new result is bit-identical. The audit is the library's (workflow/audit.hpp: what a
// result is, the trust boundary, the rerun in a private directory, a reproduce directory
// item by item; workflow/compare_results.hpp: what is compared and what is volatile); this
// command reruns with this same binary, checks the rebuilt command as its own command line
// would, and reports.
//
// Exit status: 0 identical, 1 different (the first difference is printed) or the rerun
// failed, 2 the file is not a result (or cannot be read).
#include <atomic>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bouncer/base/cancel.hpp"
#include "bouncer/base/error.hpp"
#include "bouncer/workflow/audit.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "run_command.hpp"

namespace bouncer::cli {

namespace {

std::string self_path() {
  std::error_code ec;
  const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : p.string();
}

// The rebuilt command validated as the command line validates it, in this process: its
// options parsed and checked, stopped at its first step. The message of bad input, if any.
std::optional<std::string> check_command(const std::vector<std::string>& words) {
  const std::atomic<bool> stop{true};
  const CancelScope cancel(&stop);
  CommandCapture swallow;
  const CaptureScope capture(&swallow);
  const CommandOutcome r = run_command(words, false);
  if (r.kind == CommandOutcome::Kind::input) return r.message;
  return std::nullopt;
}

int report(const AuditRequest& request, const AuditResult& r) {
  std::ostream& out = command_out();
  // A reproduce directory's audit takes as long as the reproduce it reruns: where its time
  // went, on stderr beside reproduce's own progress (times are never part of the verdict).
  if (r.reproduce_directory && r.verdict != AuditVerdict::not_a_result) {
    std::ostringstream t;
    t << std::fixed << std::setprecision(1) << "bouncer audit: " << r.rerun_seconds << " s the rerun of reproduce, "
      << std::setprecision(2) << r.compare_seconds << " s the comparison\n";
    std::cerr << t.str();
  }
  switch (r.verdict) {
    case AuditVerdict::not_a_result:
      throw InputError("file", r.message);
    case AuditVerdict::rerun_failed:
      if (r.reproduce_directory) std::cerr << "bouncer audit: " << r.message << "\n";
      else out << "audit: DIFFERENT: " << r.message << "\n";
      return 1;
    case AuditVerdict::identical:
      if (r.reproduce_directory)
        out << "bouncer audit: identical: " << r.claims_compared << " claims (verdicts and checks) and " << r.outputs_compared
            << " outputs of " << r.directory << " match the rerun (times, invocations and output paths ignored; "
            "pictures compared through their CSV and JSON)\n";
      else
        out << "audit: IDENTICAL: the rerun reproduces '" << request.file
            << (r.data_file.empty() ? std::string() : "' and its npy data '" + r.data_file)
            << "' bit for bit (volatile fields skipped: timings, invocation, output location)\n";
      return 0;
    case AuditVerdict::different:
      if (r.reproduce_directory) {
        out << "bouncer audit: DIFFERENT: " << r.differences.size() << " difference(s) in " << r.directory << "\n";
        for (const std::string& d : r.differences) out << "  " << d << "\n";
      } else if (r.is_json) {
        out << "audit: DIFFERENT: first difference at " << r.first.path << ": " << r.first.detail << " (file vs rerun)\n";
      } else {
        out << "audit: DIFFERENT: first difference at " << r.first.path << " (volatile lines skipped):\n  file:  "
            << r.first.file_line << "\n  rerun: " << r.first.rerun_line << "\n";
      }
      return 1;
  }
  return 1;
}

}  // namespace

CommandRunner setup_audit(CLI::App* sub) {
  auto file = std::make_shared<std::string>();
  auto trust = std::make_shared<bool>(false);
  sub->add_option("file", *file, "A JSON or CSV/text result written by bouncer, or a bouncer reproduce directory")->required();
  sub->add_flag("--trust-manifest", *trust,
                "Rerun a reproduce directory made from another manifest than bouncer's built-in one (its commands are "
                "still limited to bouncer's computing commands, writing into audit's temporary directory)");
  auto run = [file, trust](const std::string&) {
    AuditRequest request;
    request.file = *file;
    request.trust_manifest = *trust;
    request.executable = self_path();
    request.check_command = check_command;
    request.on_rerun = [](const std::string& shown) { command_out() << "audit: rerunning `" << shown << "`\n"; };
    return report(request, audit(request));
  };
  return run;
}

}  // namespace bouncer::cli
