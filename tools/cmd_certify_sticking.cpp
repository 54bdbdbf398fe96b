// bouncer certify-sticking: the certified sticking period of the orbit from the release
// state (or a given start), with precision escalation; over a parameter interval with
// --a-range, a computer-assisted theorem by adaptive bisection.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>
#include <set>
#include <sstream>

#include "bouncer/io/requests/certify_sticking.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

using json = nlohmann::ordered_json;

const char* kDecimalNote =
    "Decimal inputs are enclosed exactly: each decimal is enclosed by an interval (DoubleInterval or MPFI) with outward rounding, so "
    "every certified statement holds for the exact decimal values (not for their binary roundings).";

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

json null_or(const std::optional<long long>& x) { return x ? json(*x) : json(nullptr); }

// Is the plain-precision answer consistent with what was certified?
bool agrees(const StickingCertificate& c, const PlainSticking& d) {
  switch (c.outcome) {
    case StickingOutcome::sticks: return d.period && *d.period == *c.period;
    case StickingOutcome::never_sticks:
    case StickingOutcome::no_sticking_within_max_steps: return !d.period && !d.failed;
    case StickingOutcome::undecided: return !d.period || *d.period > c.steps_checked;
  }
  return false;
}

json attempts_json(const std::vector<Attempt>& attempts) {
  json a = json::array();
  for (const Attempt& t : attempts)
    a.push_back({{"scalar", t.scalar}, {"bits", t.bits}, {"decided", t.decided}, {"steps", t.steps}, {"reason", t.reason}, {"seconds", t.seconds}});
  return a;
}

json certificate_json(const StickingCertificate& c, const PlainSticking& d, long long max_steps) {
  json j;
  j["certified"] = c.certified;
  j["outcome"] = name(c.outcome);
  j["period"] = null_or(c.period);
  j["scalar"] = c.scalar.empty() ? json(nullptr) : json(c.scalar);
  j["bits"] = c.bits;
  j["steps_checked"] = c.steps_checked;
  j["statement"] = describe(c, max_steps);
  j["double_period"] = null_or(d.period);
  j["agrees"] = agrees(c, d);
  if (c.attractor)
    j["attractor"] = {{"period", c.attractor->period}, {"iterate", c.attractor->iterate},
                      {"entered_at", c.attractor->entered_at}, {"box", c.attractor->box}};
  else
    j["attractor"] = nullptr;
  j["lohner_fallbacks"] = c.fallbacks;
  j["attempts"] = attempts_json(c.attempts);
  j["seconds"] = c.seconds;
  return j;
}

json inputs_json(const Request& r) {
  json in;
  if (r.q.a_range) in["a_range"] = {exact_decimal(r.q.a_range->first), exact_decimal(r.q.a_range->second)};
  else in["a"] = r.q.model.a.text();
  in["eps"] = r.q.model.eps.text();
  in["theta"] = r.q.start.theta.text();
  in["v"] = r.q.start.v.text();
  in["wall"] = r.q.model.wall.text;
  in["downward_sticking"] = name(r.q.model.downward);
  in["max_steps"] = r.q.max_steps;
  in["max_bits"] = r.q.schedule.max_bits;
  in["start_bits"] = r.q.schedule.double_first ? json("double") : json(r.q.schedule.start_bits);
  in["method"] = name(r.q.method);
  return in;
}

// The model with a replaced by the exact decimal x (for plain runs inside a range).
ModelSpec with_a(ModelSpec m, const mpq_class& x) {
  m.a = *Decimal::parse(exact_decimal(x));
  return m;
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

    json body;
    body["note"] = kDecimalNote;
    body["inputs"] = inputs_json(r);
    body["method"] = std::string(name(r.q.method)) +
                     (r.q.method == EnclosureMethod::lohner ? " (mean-value form with a QR frame; interval Jacobian by Dual<S> over the run's interval type)"
                                                            : " (interval boxes)");
    body["schedule"] = r.q.schedule.text();
    if (!r.q.a_range) {
      const StickingCertificate c = certify_sticking(r.q);
      const PlainSticking d = plain_sticking_period<double>(r.q.model, r.q.start, 53, r.q.max_steps);
      p.bits = c.bits;
      const json cj = certificate_json(c, d, r.q.max_steps);
      for (const auto& [k, v] : cj.items()) body[k] = v;
    } else {
      const RangeReport rep = certify_sticking_range(r.q, r.range);
      bool all_agree = true;
      json pieces = json::array();
      long max_bits_used = 0;
      for (const RangePiece& piece : rep.pieces) {
        const mpq_class mid = (piece.lo + piece.hi) / 2;
        const PlainSticking d = plain_sticking_period<double>(with_a(r.q.model, mid), r.q.start, 53, r.q.max_steps);
        json pj;
        pj["a_lo"] = exact_decimal(piece.lo);
        pj["a_hi"] = exact_decimal(piece.hi);
        const json cj = certificate_json(piece.cert, d, r.q.max_steps);
        for (const auto& [k, v] : cj.items())
          if (k != "attempts") pj[k] = v;
        pj["double_period_at"] = exact_decimal(mid);
        all_agree = all_agree && pj["agrees"].get<bool>();
        max_bits_used = std::max(max_bits_used, piece.cert.bits);
        pieces.push_back(pj);
      }
      p.bits = max_bits_used;
      body["certified"] = rep.uncertified_length == 0;
      body["uncertified_length"] = exact_decimal(rep.uncertified_length);
      body["theorem"] = "Theorem (computer-assisted). " + rep.theorem;
      body["agrees"] = all_agree;
      body["pieces"] = pieces;
      body["seconds"] = rep.seconds;
    }
    write_result(r.out, r.json, p, body, &outputs);
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
