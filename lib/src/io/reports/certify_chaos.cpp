#include "bouncer/io/reports/certify_chaos.hpp"

#include <string>

#include "json.hpp"

namespace bouncer {

using reports::json;
using reports::json_number;

std::string chaos_statement(const ChaosSearchResult& r, const std::optional<ReplayResult>& replay) {
  if (!r.proved) return "not proved: " + r.message;
  const ChaosCertificate& c = r.certificate;
  std::string s = "proved (MPFI at " + std::to_string(c.bits) + " bits";
  s += replay && replay->valid ? ", replayed in Arb at " + std::to_string(replay->bits) + " bits"
                               : std::string(", NOT confirmed by the Arb replay");
  s += "): h_top(F) >= " + r.entropy.bound + " per impact. F has a compact invariant set inside " +
       std::to_string(c.sets.size()) + " disjoint h-sets on which F^" + std::to_string(c.k) +
       " is semiconjugate onto the subshift of the coverings' graph (a horseshoe: every itinerary of the graph is "
       "followed by a true orbit, each periodic itinerary by a periodic orbit). Not proved: that the attractor is "
       "this set, or that typical orbits are chaotic.";
  return s;
}

void write_certify_chaos(std::ostream& out, bool as_json, const Provenance& p, const ChaosSearchResult& r,
                         const std::optional<ReplayResult>& replay, double replay_seconds) {
  const bool valid = r.proved && replay && replay->valid;
  json body;
  body["certified"] = valid;
  body["statement"] = chaos_statement(r, replay);
  body["entropy"] = {{"bound", r.proved ? json(r.entropy.bound) : json(nullptr)},
                     {"bound_double", r.proved ? json_number(r.entropy.bound_double) : json(nullptr)},
                     {"quotient", r.proved ? json(r.entropy.quotient.get_str()) : json(nullptr)},
                     {"per", "impact"}};
  const ChaosSearchOrbit& o = r.orbit;
  body["saddle"] = o.period ? json{{"period", o.period}, {"theta", json_number(o.theta)}, {"v", json_number(o.v)},
                                   {"lambda_u", json_number(o.lambda_u)}, {"lambda_s", json_number(o.lambda_s)}}
                            : json(nullptr);
  body["homoclinic"] = o.m ? json{{"t", json_number(o.t)}, {"m", o.m}, {"return_distance", json_number(o.return_distance)}}
                           : json(nullptr);
  body["k"] = r.certificate.k;
  body["hsets"] = r.certificate.sets.size();
  body["disjoint"] = r.disjoint;
  json covs = json::array();
  for (const ChaosCovering& v : r.coverings)
    covs.push_back({{"from", v.from}, {"to", v.to}, {"proved", v.result.proved}, {"sign", v.result.sign},
                    {"pieces", v.result.pieces}, {"failure", name(v.result.failure)}});
  body["coverings"] = covs;
  if (replay) {
    json problems = json::array();
    for (const std::string& s : replay->problems) problems.push_back(s);
    body["replay"] = {{"library", "Arb"}, {"valid", replay->valid}, {"bits", replay->bits},
                      {"recomputed_bound", replay->recomputed_bound}, {"problems", problems}};
  } else {
    body["replay"] = nullptr;
  }
  body["seconds"] = {{"search", r.search_seconds}, {"coverings", r.check_seconds}, {"replay", replay_seconds}};
  reports::write_certified(out, as_json, p, body);
}

}  // namespace bouncer
