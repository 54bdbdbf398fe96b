// bouncer certify-periodic: a period-Q orbit proved by the Krawczyk operator (existence and
// local uniqueness in a box), with enclosures of its points and multipliers, certified
// stability, minimal period and event sequence; at one exact parameter value or for every
// value of a parameter interval (adaptive bisection), with precision escalation.
#include <memory>
#include <set>

#include "bouncer/verify/accelerator.hpp"
#include "bouncer/io/requests/certify_periodic.hpp"
#include "bouncer/verify/sticking.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

using json = nlohmann::ordered_json;

const std::set<std::string>& certify_periodic_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"period", "guess", "family", "lift", "max-bits", "start-bits", "max-depth", "max-pieces", "max-iter", "grid", "json",
              "out", "a-range", "eps-range", "c-range", "vary"});
    return k;
  }();
  return keys;
}

// The science inputs are the library's request (io/requests/certify_periodic.hpp); --json
// and --out are the command's.
struct Request {
  PeriodicQuestion q;
  std::optional<Decimal> lift;  // accelerator ladder (verify/accelerator.hpp)
  bool json = false;
  std::optional<std::string> out;
};

Request request_from(const Options& o) {
  CertifyPeriodicRequest science = certify_periodic_request(o);
  Request r;
  r.q = std::move(science.question);
  r.lift = science.lift;
  r.json = o.get_or("json", "false") == "true";
  if (o.has("out")) r.out = o.get("out");
  return r;
}

json enclosure_json(const Enclosure& e) { return json::array({e.lo, e.hi}); }

json certificate_json(const PeriodicCertificate& c) {
  json j;
  j["certified"] = c.certified;
  j["outcome"] = name(c.outcome);
  j["statement"] = c.statement;
  j["bits"] = c.bits;
  j["period"] = c.period;
  j["minimal_period"] = c.minimal_period_certified ? json(c.minimal_period) : json(nullptr);
  if (!c.certified) {
    j["reason"] = c.reason;
  } else {
    j["stability"] = c.stability;
    json pts = json::array();
    for (const EnclosedOrbitPoint& p : c.points) pts.push_back({{"theta", enclosure_json(p.theta)}, {"v", enclosure_json(p.v)}});
    j["points"] = pts;
    j["events"] = c.events;
    j["wall_periods"] = c.wall_periods;
    json mu;
    mu["kind"] = c.multipliers.kind;
    mu["trace"] = enclosure_json(c.multipliers.trace);
    mu["det"] = enclosure_json(c.multipliers.det);
    if (c.multipliers.kind == "real") {
      mu["mu1"] = enclosure_json(c.multipliers.mu[0]);
      mu["mu2"] = enclosure_json(c.multipliers.mu[1]);
    } else if (c.multipliers.kind == "complex") {
      mu["re"] = enclosure_json(c.multipliers.mu[0]);
      mu["im"] = enclosure_json(c.multipliers.mu[1]);
      mu["modulus"] = enclosure_json(c.multipliers.modulus);
    }
    j["multipliers"] = mu;
    if (c.outcome != PeriodicOutcome::through_release) {
      json k;
      k["unknowns"] = c.unknowns;
      k["box"] = json::array({enclosure_json(c.box[0]), enclosure_json(c.box[1])});
      k["image"] = json::array({enclosure_json(c.image[0]), enclosure_json(c.image[1])});
      k["free"] = c.free_name;
      k["free_range"] = enclosure_json(c.free_range);
      k["inflations"] = c.inflations;
      j["krawczyk"] = k;
    }
    if (c.family_parameter) {
      json f;
      f["parameter_at_theta"] = enclosure_json(*c.family_parameter);
      f["given_parameter"] = c.given_parameter;
      if (c.strip_theta) {
        f["strip_theta"] = enclosure_json(*c.strip_theta);
        f["strip_v"] = enclosure_json(*c.strip_v);
        f["strip_parameter"] = enclosure_json(*c.strip_parameter);
      } else {
        f["strip_theta"] = nullptr;
      }
      j["family"] = f;
    }
  }
  if (!c.double_theta.empty()) {
    j["double_newton"] = {c.double_theta, c.double_v};
    j["double_distance"] = c.double_distance ? json(*c.double_distance) : json(nullptr);
  }
  json a = json::array();
  for (const Attempt& t : c.attempts)
    a.push_back({{"bits", t.bits}, {"decided", t.decided}, {"reason", t.reason}, {"seconds", t.seconds}});
  j["attempts"] = a;
  j["seconds"] = c.seconds;
  return j;
}

json inputs_json(const Request& r) {
  json in;
  const std::string par = name(r.q.vary);
  for (const char* p : {"a", "eps", "c"}) {
    if (r.q.range && par == p) {
      in[par + "_range"] = {exact_decimal(r.q.range->first), exact_decimal(r.q.range->second)};
      continue;
    }
    const Parameter pp = parse_parameter("vary", p);
    if (pp == Parameter::a || (pp == Parameter::eps && r.q.model.law == Law::constant) ||
        (pp == Parameter::c && r.q.model.law == Law::veldep))
      in[p] = parameter_of(r.q.model, pp).text();
  }
  in["model"] = name(r.q.model.law);
  in["wall"] = r.q.model.wall.text;
  in["period"] = r.q.period;
  in["guess"] = r.q.guess ? json::array({r.q.guess->theta.text(), r.q.guess->v.text()}) : json(nullptr);
  in["schedule"] = r.q.schedule.text();
  return in;
}

}  // namespace

CommandRunner setup_certify_periodic(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("period", "Period Q, integer in [1, 1000] (required)");
  opts->add_list("guess", "Starting point theta,v for Newton (default: a grid of guesses in the trapping region)");
  opts->add("a-range", "A0:A1: certify for every a in [A0, A1] (adaptive bisection), instead of --a");
  opts->add("eps-range", "E0:E1: the same for eps (--model constant)");
  opts->add("c-range", "C0:C1: the same for c (--model veldep)");
  opts->add("vary", "The parameter of a family (its unknown) or of a range: a (default) | eps | c");
  opts->add("family", "auto (default: when Newton finds a multiplier 1) | on | off: certify a neutral family on the "
                      "quotient by theta, with the parameter as an unknown");
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
    Provenance p = provenance_for("certify-periodic", o, Precision{Precision::Kind::interval, r.q.schedule.max_bits}, argv_text);
    p.precision = "interval, escalated " + r.q.schedule.text();
    json body;
    body["note"] =
        "Decimal inputs are enclosed exactly (MPFI, outward rounding): every certified statement holds for the exact "
        "decimal values. Enclosure ends are printed rounded outward.";
    body["inputs"] = inputs_json(r);
    body["method"] =
        "Krawczyk operator on F(x) = P^Q(x) - x in mean-value form over the box and the parameter interval; interval "
        "Jacobian by Dual<Mpfi> through the same step; every branch decided for the whole box";
    if (r.lift) {
      const LadderCertificate c = certify_ladder(r.q.model, *r.q.guess, *r.lift);
      body["method"] = "exact rational arithmetic (GMP) on the ladder conditions of verify/accelerator.hpp";
      body["inputs"]["lift"] = r.lift->text();
      body["certified"] = c.certified;
      body["outcome"] = c.certified ? "accelerator_mode" : "not_a_ladder";
      body["statement"] = c.statement;
      if (c.certified) {
        body["gain_per_impact"] = exact_decimal(c.D);
        body["first_flight_periods"] = exact_decimal(c.m0);
        body["periods_added_per_impact"] = exact_decimal(c.J);
        body["first_flight_least_gap"] = exact_decimal(c.min_gap);
      }
      p.precision = "exact (rational arithmetic)";
      p.bits = 0;
    } else if (!r.q.range) {
      const PeriodicCertificate c = certify_periodic(r.q);
      p.bits = c.bits;
      const json cj = certificate_json(c);  // named: items() must not outlive it
      for (const auto& [k, v] : cj.items()) body[k] = v;
    } else {
      const PeriodicRangeReport rep = certify_periodic_range(r.q);
      json pieces = json::array();
      long bits = 0;
      for (const PeriodicPiece& piece : rep.pieces) {
        json pj;
        pj["lo"] = exact_decimal(piece.lo);
        pj["hi"] = exact_decimal(piece.hi);
        const json cj = certificate_json(piece.cert);
        for (const auto& [k, v] : cj.items())
          if (k != "attempts" && k != "statement") pj[k] = v;
        bits = std::max(bits, piece.cert.bits);
        pieces.push_back(pj);
      }
      p.bits = bits;
      body["certified"] = rep.uncertified_length == 0;
      body["uncertified_length"] = exact_decimal(rep.uncertified_length);
      body["theorem"] = "Theorem (computer-assisted). " + rep.theorem;
      body["pieces"] = pieces;
      body["seconds"] = rep.seconds;
    }
    write_result(r.out, r.json, p, body, &outputs);
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
