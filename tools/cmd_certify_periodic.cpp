// bouncer certify-periodic: a period-Q orbit proved by the Krawczyk operator (existence and
// local uniqueness in a box), with enclosures of its points and multipliers, certified
// stability, minimal period and event sequence; at one exact parameter value or for every
// value of a parameter interval (adaptive bisection), with precision escalation.
#include <memory>
#include <set>

#include "bouncer/io/reports/certify_periodic.hpp"
#include "bouncer/io/requests/certify_periodic.hpp"
#include "bouncer/verify/accelerator.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

const std::set<std::string>& certify_periodic_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"period", "guess", "family", "formulation", "lift", "max-bits", "start-bits", "max-depth", "max-pieces", "max-iter", "grid", "json",
              "out", "a-range", "eps-range", "c-range", "vary"});
    return k;
  }();
  return keys;
}

// The science inputs are the library's request (io/requests/certify_periodic.hpp); --json
// and --out are the command's.
struct Request {
  CertifyPeriodicRequest science;  // the question, and --lift (an accelerator ladder)
  bool json = false;
  std::optional<std::string> out;
};

Request request_from(const Options& o) {
  Request r;
  r.science = certify_periodic_request(o);
  r.json = o.get_or("json", "false") == "true";
  if (o.has("out")) r.out = o.get("out");
  return r;
}

}  // namespace

CommandRunner setup_certify_periodic(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("period", "Period Q, integer in [1, " + std::to_string(kMaxCertifiedPeriod) + "] (required)");
  opts->add_list("guess", "Starting point theta,v for Newton (default: a grid of guesses in the trapping region)");
  opts->add("a-range", "A0:A1: certify for every a in [A0, A1] (adaptive bisection), instead of --a");
  opts->add("eps-range", "E0:E1: the same for eps (--model constant)");
  opts->add("c-range", "C0:C1: the same for c (--model veldep)");
  opts->add("vary", "The parameter of a family (its unknown) or of a range: a (default) | eps | c");
  opts->add("family", "auto (default: when Newton finds a multiplier 1) | on | off: certify a neutral family on the "
                      "quotient by theta, with the parameter as an unknown");
  opts->add("formulation", "auto (default: the first point's P^Q below period 12, every point an unknown from 12 on, the "
                           "other where the first fails) | composed | shooting: the unknowns of an isolated orbit's proof");
  opts->add("lift", "D: prove an accelerator mode P(x) = x + (0, D) forever, in exact arithmetic (--model elastic, "
                    "--period 1, --guess)");
  opts->add("max-bits", "Largest interval precision of the escalation schedule (default 1024)");
  opts->add("start-bits", "First precision of the schedule 64, 128, ... doubling (default 64)");
  opts->add("max-depth", "With a range: bisection depth limit, integer in [0, 40] (default 8)");
  opts->add("max-pieces", "With a range: at most this many certification runs (default 256)");
  opts->add("max-iter", "Newton iterations, integer in [1, 10000] (default 60)");
  opts->add("grid", "Newton guesses per axis without --guess, integer in [1, 64] (default 8)");
  opts->add("out", "Write to FILE (atomically) instead of stdout");
  sub->add_flag("--json", *as_json, "JSON output");

  auto run = [opts, scene, as_json](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "certify-periodic", certify_periodic_keys()),
                      opts->collected());
    if (*as_json) o.set("json", "true");
    const Request r = request_from(o);
    OutputSet outputs;  // reserved before the work: a path that cannot be written is found at once
    if (r.out) outputs.reserve("out", *r.out);
    const PeriodicQuestion& q = r.science.question;
    Provenance p = provenance_for("certify-periodic", o, Precision{Precision::Kind::interval, q.schedule.max_bits}, argv_text);
    p.precision = "interval, escalated " + q.schedule.text();
    auto write = [&](const auto& result) {  // the certificate, a range's report or a ladder
      write_atomically(r.out, [&](std::ostream& s) { write_certify_periodic(s, r.json, p, r.science, result); }, &outputs);
    };
    if (r.science.lift) {
      const LadderCertificate c = certify_ladder(q.model, *q.guess, *r.science.lift);
      p.precision = "exact (rational arithmetic)";
      p.bits = 0;
      write(c);
    } else if (!q.range) {
      const PeriodicCertificate c = certify_periodic(q);
      p.bits = c.bits;
      write(c);
    } else {
      const PeriodicRangeReport rep = certify_periodic_range(q);
      p.bits = bits_used(rep);
      write(rep);
    }
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
