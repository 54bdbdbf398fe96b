// `bouncer certify-sticking`'s output, from the typed certificates (verify/sticking.hpp) and
// the double runs they are compared with: a JSON document (provenance, note, inputs, method,
// schedule, then the certificate's fields; one-space indent) or the same fields as
// "key: value" lines after the provenance lines ("# time:" lines for the seconds).
#pragma once

#include <ostream>
#include <vector>

#include "bouncer/io/provenance.hpp"
#include "bouncer/verify/sticking.hpp"

namespace bouncer {

// One start at one parameter value; `double_run`: the double run of the same question.
void write_certify_sticking(std::ostream& out, bool as_json, const Provenance& p, const StickingQuestion& q,
                            const StickingCertificate& c, const PlainSticking& double_run);
// Over --a-range: the theorem and one entry per piece, each with its double run at the
// piece's midpoint (double_at_midpoints[i] for rep.pieces[i]: double_sticking_at_midpoints).
void write_certify_sticking(std::ostream& out, bool as_json, const Provenance& p, const StickingQuestion& q,
                            const RangeReport& rep, const std::vector<PlainSticking>& double_at_midpoints);

// The most bits any piece of a range used (the provenance's bits).
long bits_used(const RangeReport& rep);

}  // namespace bouncer
