// bouncer reproduce: the whole paper in one command. The work is the library's
// (workflow/reproduce.hpp: the manifest, its checks, the scheduler and the reports, README
// "Reproducing the paper"); this file reads the options, calls it, and prints: one progress
// line per item on stderr, the summary, and each claim that did not reproduce. Exit 0: every
// item ran and every claim's check reproduced its expected verdict; 1: an item failed or a
// check did not hold (the report says which); 2: bad options. A signal (SIGINT, SIGTERM,
// SIGHUP) stops the run and its children, writes no report, and ends reproduce by that
// signal after saying how to resume. `bouncer audit DIR` reruns a reproduce directory and
// compares it item by item (tools/cmd_audit.cpp).
#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "bouncer/workflow/report.hpp"
#include "bouncer/workflow/reproduce.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "run_command.hpp"

namespace bouncer::cli {

namespace {

struct Options_ {
  bool quick = false, full = false, claims_table = false, check = false, pictures = false;
  std::string out = "reproduction", only, jobs, manifest;
};

std::string seconds_text(double x, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

// --check: each bouncer command runs in this process (its cancellation flag set by the
// library), its output swallowed: it validates its options and inputs and stops.
int check(const Manifest& m) {
  const ManifestCheck c = check_manifest(m, [](const std::vector<std::string>& argv) {
    CommandCapture swallow;
    const CaptureScope capture(&swallow);
    const CommandOutcome r = run_command(argv, false);
    using K = CommandValidation::Kind;
    return CommandValidation{r.kind == CommandOutcome::Kind::cancelled ? K::stopped
                             : r.kind == CommandOutcome::Kind::ok      ? K::ran
                                                                       : K::refused,
                             r.status, r.message};
  });
  for (const CommandCheck& k : c.commands) command_out() << k.id << " " << k.which << ": " << k.verdict << "\n";
  command_out() << c.commands.size() << " commands checked, " << c.refused << " refused\n";
  return c.refused ? 1 : 0;
}

int run_reproduce(const Options_& o) {
  refuse_nested_reproduce();
  if (o.quick && o.full) throw InputError("quick", "give one of --quick or --full, not both");
  if (o.pictures && (o.quick || o.full))
    throw InputError("pictures", "draws the documentation's pictures, the same in every mode: give it without --quick or --full");
  ReproduceRequest request;
  request.mode = o.pictures ? ReproduceMode::pictures : o.full ? ReproduceMode::full : ReproduceMode::quick;
  request.manifest_path = o.manifest;
  request.manifest = load_manifest(o.manifest);
  if (o.claims_table) {
    command_out() << claims_table(*request.manifest);
    return 0;
  }
  if (o.check) return check(*request.manifest);
  if (!o.jobs.empty()) {
    const bool digits = std::all_of(o.jobs.begin(), o.jobs.end(), ::isdigit);
    if (!digits || o.jobs.size() > 4 || std::stoi(o.jobs) < 1 || std::stoi(o.jobs) > 1024)
      throw InputError("jobs", "must be an integer in [1, 1024], got '" + o.jobs + "'");
    request.jobs = static_cast<unsigned>(std::stoi(o.jobs));
  }
  if (!o.only.empty()) {
    request.only.emplace();
    std::stringstream ss(o.only);
    for (std::string w; std::getline(ss, w, ',');) request.only->push_back(w);
  }
  request.out = o.out;
  request.progress = [](const Job& job, size_t finished, size_t total) {
    std::cerr << "reproduce [" << finished << "/" << total << "] " << job.id << ": " << state_name(job.state);
    if (job.state == ItemState::done || job.state == ItemState::failed) std::cerr << " (" << seconds_text(job.seconds, 1) << " s)";
    if (!job.problem.empty()) std::cerr << ": " << job.problem;
    std::cerr << "\n";
  };
  const ReproduceResult r = reproduce(request);
  if (r.stopped_by) {
    std::cerr << "reproduce: stopped by signal " << r.stopped_by << " (" << ::strsignal(r.stopped_by)
              << "); finished items are kept in " << r.dir << ": run the same command again to resume\n";
    reraise_stop_signal(r.stopped_by);
  }
  std::cerr << "reproduce: " << r.summary << "; " << seconds_text(r.seconds, 1) << " s; report in "
            << (std::filesystem::path(r.dir) / "report.md").string() << "\n";
  if (!r.ok) {
    std::map<std::string, std::string> not_reproduced;  // (by id, as the report's reader looks them up)
    for (const ItemResult& it : r.items)
      if (it.kind == ItemKind::claim && it.status != ClaimStatus::reproduced && it.status != ClaimStatus::deferred)
        not_reproduced[it.id] = it.verdict;
    for (const auto& [id, verdict] : not_reproduced) std::cerr << "reproduce: " << id << ": " << verdict << "\n";
  }
  return r.exit_status();
}

}  // namespace

CommandRunner setup_reproduce(CLI::App* sub) {
  auto o = std::make_shared<Options_>();
  sub->add_flag("--quick", o->quick, "Small grids and few steps (default; under 3 minutes on 2 cores)");
  sub->add_flag("--full", o->full, "Paper resolution: 5000 transient + 500 recorded steps, 10 x 10 starts per scan point");
  sub->add_option("--out", o->out, "Output directory (default: reproduction)");
  sub->add_option("--only", o->only, "Comma list of panel labels (fig:basin1 or basin1) and claim ids");
  sub->add_option("--jobs", o->jobs, "Items run at once, integer in [1, 1024] (default: cores)");
  sub->add_flag("--claims-table", o->claims_table, "Print the Markdown claims table (docs/claims.md) from the manifest and exit");
  sub->add_flag("--pictures", o->pictures,
                "Draw the documentation's pictures (data/pictures/) instead of the paper, into DIR/pictures/; "
                "cp DIR/pictures/*.png data/pictures/ regenerates them");
  sub->add_flag("--check", o->check,
                "Validate every command of the manifest (quick and full) without running it: one line each; exit 1 if any is refused");
  sub->add_option("--manifest", o->manifest, "")->group("");  // hidden: another manifest (tests)
  auto run = [o](const std::string&) { return run_reproduce(*o); };
  return run;
}

}  // namespace bouncer::cli
