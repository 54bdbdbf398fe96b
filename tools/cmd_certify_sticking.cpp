// bouncer certify-sticking: the certified sticking period of the orbit from the release
// state (or a given start), with precision escalation; over a parameter interval with
// --a-range, a computer-assisted theorem by adaptive bisection.
#include <memory>
#include <set>

#include "bouncer/io/reports/certify_sticking.hpp"
#include "bouncer/io/requests/certify_sticking.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

const std::set<std::string>& certify_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "max-steps", "max-bits", "start-bits", "method", "a-range", "max-depth", "max-pieces",
              "prove-attractor", "json", "out"});
    return k;
  }();
  return keys;
}

// The science inputs are the library's request (io/requests/certify_sticking.hpp); --json
// and --out are the command's.
struct Request {
  StickingQuestion q;
  RangeOptions range;
  bool json = false;
  std::optional<std::string> out;
};

Request request_from(const Options& o) {
  CertifyStickingRequest science = certify_sticking_request(o);
  Request r;
  r.q = std::move(science.question);
  r.range = science.range;
  r.json = o.get_or("json", "false") == "true";
  if (o.has("out")) r.out = o.get("out");
  return r;
}

}  // namespace

CommandRunner setup_certify_sticking(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("theta", "Start phase in [0, 1) (default 0.5: the release state)");
  opts->add("v", "Start velocity (default 4: the release state)");
  opts->add("max-steps", "Follow the orbit at most this many steps, integer in [1, 1e9] (default 100000)");
  opts->add("max-bits", "Largest interval precision of the escalation schedule (default 4096)");
  opts->add("start-bits", "First precision of the schedule: double (default: interval:double, then MPFI at 64, 128, 256, ... doubling) or BITS (MPFI at BITS, 2 BITS, ...)");
  opts->add("method", "Enclosure method: lohner (default: mean-value form, QR frame) | naive (interval boxes)");
  opts->add("a-range", "A0:A1: certify for every a in [A0, A1] by adaptive bisection (instead of --a)");
  opts->add("max-depth", "With --a-range: bisection depth limit, integer in [0, 40] (default 10)");
  opts->add("max-pieces", "With --a-range: at most this many certification runs (default 400)");
  opts->add("prove-attractor", "on (default) | off: when no sticking is found, try to prove that it never sticks");
  opts->add("out", "Write to FILE (atomically) instead of stdout");
  sub->add_flag("--json", *as_json, "JSON output");

  auto run = [opts, scene, as_json](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "certify-sticking", certify_keys()), opts->collected());
    if (*as_json) o.set("json", "true");
    certify_sticking_defaults(o);  // the provenance records them
    const Request r = request_from(o);
    OutputSet outputs;  // reserved before the work: a path that cannot be written is found at once
    if (r.out) outputs.reserve("out", *r.out);
    Precision prec{Precision::Kind::interval, r.q.schedule.max_bits};
    Provenance p = provenance_for("certify-sticking", o, prec, argv_text);
    p.precision = "interval, escalated " + r.q.schedule.text();  // p.bits: the bits that certified

    auto write = [&](const auto&... result) {  // a certificate, or a range's report, with their double runs
      write_atomically(r.out, [&](std::ostream& s) { write_certify_sticking(s, r.json, p, r.q, result...); }, &outputs);
    };
    if (!r.q.a_range) {
      const StickingCertificate c = certify_sticking(r.q);
      const PlainSticking d = plain_sticking_period<double>(r.q.model, r.q.start, 53, r.q.max_steps, r.q.from_release);
      p.bits = c.bits;
      write(c, d);
    } else {
      const RangeReport rep = certify_sticking_range(r.q, r.range);
      const std::vector<PlainSticking> d = double_sticking_at_midpoints(r.q, rep);
      p.bits = bits_used(rep);
      write(rep, d);
    }
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
