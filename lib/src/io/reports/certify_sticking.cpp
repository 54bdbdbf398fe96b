#include "bouncer/io/reports/certify_sticking.hpp"

#include <algorithm>

#include "bouncer/scalar/decimal.hpp"
#include "json.hpp"

namespace bouncer {

namespace {

using reports::json;
using reports::null_or;

const char* kDecimalNote =
    "Decimal inputs are enclosed exactly: each decimal is enclosed by an interval (DoubleInterval or MPFI) with outward rounding, so "
    "every certified statement holds for the exact decimal values (not for their binary roundings).";

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
  j["agrees"] = plain_agrees(c, d);
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

json inputs_json(const StickingQuestion& q) {
  json in;
  if (q.a_range) in["a_range"] = {exact_decimal(q.a_range->first), exact_decimal(q.a_range->second)};
  else in["a"] = q.model.a.text();
  in["eps"] = q.model.eps.text();
  if (q.from_release) {
    in["start"] = "release";
  } else {
    in["theta"] = q.start.theta.text();
    in["v"] = q.start.v.text();
  }
  in["wall"] = q.model.wall.text;
  in["downward_sticking"] = name(q.model.downward);
  in["max_steps"] = q.max_steps;
  in["max_bits"] = q.schedule.max_bits;
  in["start_bits"] = q.schedule.double_first ? json("double") : json(q.schedule.start_bits);
  in["method"] = name(q.method);
  return in;
}

// The fields both forms start with: note, inputs, method, schedule.
json head(const StickingQuestion& q) {
  json body;
  body["note"] = kDecimalNote;
  body["inputs"] = inputs_json(q);
  body["method"] = std::string(name(q.method)) +
                   (q.method == EnclosureMethod::lohner ? " (mean-value form with a QR frame; interval Jacobian by Dual<S> over the run's interval type)"
                                                        : " (interval boxes)");
  body["schedule"] = q.schedule.text();
  return body;
}

}  // namespace

void write_certify_sticking(std::ostream& out, bool as_json, const Provenance& p, const StickingQuestion& q,
                            const StickingCertificate& c, const PlainSticking& double_run) {
  json body = head(q);
  const json cj = certificate_json(c, double_run, q.max_steps);  // named: items() must not outlive it
  for (const auto& [k, v] : cj.items()) body[k] = v;
  reports::write_certified(out, as_json, p, body);
}

void write_certify_sticking(std::ostream& out, bool as_json, const Provenance& p, const StickingQuestion& q,
                            const RangeReport& rep, const std::vector<PlainSticking>& double_at_midpoints) {
  json body = head(q);
  bool all_agree = true;
  json pieces = json::array();
  for (size_t i = 0; i < rep.pieces.size(); ++i) {
    const RangePiece& piece = rep.pieces[i];
    const PlainSticking& d = double_at_midpoints.at(i);
    json pj;
    pj["a_lo"] = exact_decimal(piece.lo);
    pj["a_hi"] = exact_decimal(piece.hi);
    const json cj = certificate_json(piece.cert, d, q.max_steps);
    for (const auto& [k, v] : cj.items())
      if (k != "attempts") pj[k] = v;
    pj["double_period_at"] = exact_decimal((piece.lo + piece.hi) / 2);
    all_agree = all_agree && plain_agrees(piece.cert, d);
    pieces.push_back(pj);
  }
  body["certified"] = rep.uncertified_length == 0;
  body["uncertified_length"] = exact_decimal(rep.uncertified_length);
  body["theorem"] = "Theorem (computer-assisted). " + rep.theorem;
  body["agrees"] = all_agree;
  body["pieces"] = pieces;
  body["seconds"] = rep.seconds;
  reports::write_certified(out, as_json, p, body);
}

long bits_used(const RangeReport& rep) {
  long bits = 0;
  for (const RangePiece& piece : rep.pieces) bits = std::max(bits, piece.cert.bits);
  return bits;
}

}  // namespace bouncer
