#include "bouncer/io/reports/certify_periodic.hpp"

#include <algorithm>

#include "bouncer/scalar/decimal.hpp"
#include "json.hpp"

namespace bouncer {

namespace {

using reports::json;

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
      k["formulation"] = c.shooting ? "shooting" : "composed";
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

json inputs_json(const PeriodicQuestion& q) {
  json in;
  const std::string par = name(q.vary);
  for (const char* p : {"a", "eps", "c"}) {
    if (q.range && par == p) {
      in[par + "_range"] = {exact_decimal(q.range->first), exact_decimal(q.range->second)};
      continue;
    }
    const Parameter pp = parse_parameter("vary", p);
    if (pp == Parameter::a || (pp == Parameter::eps && q.model.law == Law::constant) ||
        (pp == Parameter::c && q.model.law == Law::veldep))
      in[p] = parameter_of(q.model, pp).text();
  }
  in["model"] = name(q.model.law);
  in["wall"] = q.model.wall.text;
  in["period"] = q.period;
  in["guess"] = q.guess ? json::array({q.guess->theta.text(), q.guess->v.text()}) : json(nullptr);
  in["schedule"] = q.schedule.text();
  return in;
}

// The fields every form starts with: note, inputs, method.
json head(const CertifyPeriodicRequest& r) {
  json body;
  body["note"] =
      "Decimal inputs are enclosed exactly (MPFI, outward rounding): every certified statement holds for the exact "
      "decimal values. Enclosure ends are printed rounded outward.";
  body["inputs"] = inputs_json(r.question);
  body["method"] =
      "Krawczyk operator on F(x) = P^Q(x) - x (composed) or on the Q equations P(x_i) - x_{i+1 mod Q} with every orbit "
      "point an unknown (multiple shooting: periods >= 12, or where P^Q fails) in mean-value form over the box and the "
      "parameter interval; interval Jacobian by Dual<Mpfi> through the same step; every branch decided for the whole box; "
      "shooting's multipliers from the product of the steps' Jacobians in Lohner's form";
  return body;
}

}  // namespace

void write_certify_periodic(std::ostream& out, bool as_json, const Provenance& p, const CertifyPeriodicRequest& r,
                            const PeriodicCertificate& c) {
  json body = head(r);
  const json cj = certificate_json(c);  // named: items() must not outlive it
  for (const auto& [k, v] : cj.items()) body[k] = v;
  reports::write_certified(out, as_json, p, body);
}

void write_certify_periodic(std::ostream& out, bool as_json, const Provenance& p, const CertifyPeriodicRequest& r,
                            const PeriodicRangeReport& rep) {
  json body = head(r);
  json pieces = json::array();
  for (const PeriodicPiece& piece : rep.pieces) {
    json pj;
    pj["lo"] = exact_decimal(piece.lo);
    pj["hi"] = exact_decimal(piece.hi);
    const json cj = certificate_json(piece.cert);
    for (const auto& [k, v] : cj.items())
      if (k != "attempts" && k != "statement") pj[k] = v;
    pieces.push_back(pj);
  }
  body["certified"] = rep.uncertified_length == 0;
  body["uncertified_length"] = exact_decimal(rep.uncertified_length);
  body["theorem"] = "Theorem (computer-assisted). " + rep.theorem;
  body["pieces"] = pieces;
  body["seconds"] = rep.seconds;
  reports::write_certified(out, as_json, p, body);
}

void write_certify_periodic(std::ostream& out, bool as_json, const Provenance& p, const CertifyPeriodicRequest& r,
                            const LadderCertificate& c) {
  json body = head(r);
  body["method"] = "exact rational arithmetic (GMP) on the ladder conditions of verify/accelerator.hpp";
  body["inputs"]["lift"] = r.lift ? json(r.lift->text()) : json(nullptr);
  body["certified"] = c.certified;
  body["outcome"] = c.certified ? "accelerator_mode" : "not_a_ladder";
  body["statement"] = c.statement;
  if (c.certified) {
    body["gain_per_impact"] = exact_decimal(c.D);
    body["first_flight_periods"] = exact_decimal(c.m0);
    body["periods_added_per_impact"] = exact_decimal(c.J);
    body["first_flight_least_gap"] = exact_decimal(c.min_gap);
  }
  reports::write_certified(out, as_json, p, body);
}

long bits_used(const PeriodicRangeReport& rep) {
  long bits = 0;
  for (const PeriodicPiece& piece : rep.pieces) bits = std::max(bits, piece.cert.bits);
  return bits;
}

}  // namespace bouncer
