// `bouncer certify-chaos`'s output, from the typed answer of certify_chaos (verify/chaos.hpp)
// and the Arb replay of its certificate (verify/chaos_certificate.hpp): a JSON document
// (provenance first) or the same fields as "key: value" lines after the provenance lines,
// as the other certified commands write them.
#pragma once

#include <optional>
#include <ostream>

#include "bouncer/io/provenance.hpp"
#include "bouncer/verify/chaos.hpp"

namespace bouncer {

// The report: the statement (what is proved and what is not), the saddle and homoclinic
// orbit, the h-sets and every covering checked, the entropy bound, the replay's verdict
// (`replay`: none when nothing was proved to replay) and the seconds of each stage.
void write_certify_chaos(std::ostream& out, bool as_json, const Provenance& p, const ChaosSearchResult& r,
                         const std::optional<ReplayResult>& replay, double replay_seconds);

// The sentence of the proved statement, or of what failed.
std::string chaos_statement(const ChaosSearchResult& r, const std::optional<ReplayResult>& replay);

}  // namespace bouncer
