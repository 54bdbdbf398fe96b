// `bouncer certify-periodic`'s output, from the typed certificates (verify/periodic_certify.hpp,
// verify/accelerator.hpp): a JSON document (provenance, note, inputs, method, then the
// certificate's fields; one-space indent) or the same fields as "key: value" lines after the
// provenance lines ("# time:" lines for the seconds).
#pragma once

#include <ostream>

#include "bouncer/io/provenance.hpp"
#include "bouncer/io/requests/certify_periodic.hpp"
#include "bouncer/verify/accelerator.hpp"
#include "bouncer/verify/periodic_certify.hpp"

namespace bouncer {

// At one parameter value (or over one interval: the question's range unset).
void write_certify_periodic(std::ostream& out, bool as_json, const Provenance& p, const CertifyPeriodicRequest& r,
                            const PeriodicCertificate& c);
// Over the question's range: the theorem and one entry per piece.
void write_certify_periodic(std::ostream& out, bool as_json, const Provenance& p, const CertifyPeriodicRequest& r,
                            const PeriodicRangeReport& rep);
// --lift: the accelerator ladder, proved in exact arithmetic.
void write_certify_periodic(std::ostream& out, bool as_json, const Provenance& p, const CertifyPeriodicRequest& r,
                            const LadderCertificate& c);

// The most bits any piece of a range used (the provenance's bits).
long bits_used(const PeriodicRangeReport& rep);

}  // namespace bouncer
