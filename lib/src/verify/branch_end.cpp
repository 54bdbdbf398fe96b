#include "bouncer/verify/branch_end.hpp"

#include <optional>
#include <utility>

#include "bouncer/verify/periodic_certify.hpp"

namespace bouncer {

BranchEndCertificate certify_branch_end(const BranchEndQuestion& e) {
  PeriodicQuestion q;
  q.model = with_parameter(e.model, e.vary, e.lo);  // as certify-periodic: the model at the range's start
  q.period = e.period;
  q.guess = e.last_point;
  q.vary = e.vary;
  q.range = std::make_pair(e.lo.value(), e.hi.value());
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
  BranchEndCertificate c;
  if (from && to) {
    c.certified = true;
    c.from = *from;
    c.to = *to;
    c.bound = e.high_end ? *to : *from;
    for (const std::string& s : rep.pieces[e.high_end ? 0 : rep.pieces.size() - 1].cert.events)
      c.events += (c.events.empty() ? "" : " ") + s;
  }
  c.theorem = rep.theorem;
  c.pieces = rep.pieces.size();
  return c;
}

}  // namespace bouncer
