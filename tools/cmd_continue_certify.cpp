// bouncer continue --certify (see continue_certify.hpp).
#include "continue_certify.hpp"

#include "bouncer/verify/periodic_certify.hpp"
#include "bouncer/verify/sticking.hpp"

namespace bouncer::cli {

nlohmann::ordered_json certify_end(const EndToCertify& e) {
  const Decimal lo = parse_decimal("certify", e.lo), hi = parse_decimal("certify", e.hi);
  PeriodicQuestion q;
  q.model = with_parameter(e.model, e.vary, lo);  // as certify-periodic: the model at the range's start
  q.period = e.period;
  q.guess = InitialCondition{parse_decimal("certify", e.theta), parse_decimal("certify", e.v)};
  q.vary = e.vary;
  q.range = std::make_pair(lo.value(), hi.value());
  q.family = FamilyMode::isolated;
  // Pieces next to a* cannot be certified (the orbit's box straddles the border): a short
  // schedule keeps their cost bounded. The bisection goes depth first from the range's
  // low end, so the piece budget must allow the full depth on both sides.
  q.schedule = EscalationSchedule{64, 256, true};
  q.max_depth = 10;
  q.max_pieces = 512;
  const PeriodicRangeReport rep = certify_periodic_range(q);
  // The certified run that starts at the branch side of the interval.
  std::optional<mpq_class> from, to;
  if (e.high_end) {
    for (const PeriodicPiece& p : rep.pieces) {
      if (!p.cert.certified) break;
      if (!from) from = p.lo;
      to = p.hi;
    }
  } else {
    for (auto it = rep.pieces.rbegin(); it != rep.pieces.rend(); ++it) {
      if (!it->cert.certified) break;
      if (!to) to = it->hi;
      from = it->lo;
    }
  }
  nlohmann::ordered_json j;
  j["range"] = {e.lo, e.hi};
  if (from && to) {
    j["certified_range"] = {exact_decimal(*from), exact_decimal(*to)};
    j["certified_to"] = exact_decimal(e.high_end ? *to : *from);
    std::string events;
    for (const std::string& s : rep.pieces[e.high_end ? 0 : rep.pieces.size() - 1].cert.events)
      events += (events.empty() ? "" : " ") + s;
    j["events"] = events;
  } else {
    j["certified_range"] = nullptr;
    j["certified_to"] = nullptr;
  }
  j["theorem"] = rep.theorem;
  j["pieces"] = rep.pieces.size();
  return j;
}

}  // namespace bouncer::cli
