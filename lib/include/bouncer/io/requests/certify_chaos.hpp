// `bouncer certify-chaos`'s request: what the command line (tools/cmd_certify_chaos.cpp)
// reads from its options before it calls certify_chaos (verify/chaos.hpp) and replays the
// certificate (verify/chaos_certificate.hpp). --json and --out are the command's own.
#pragma once

#include "bouncer/io/scene.hpp"
#include "bouncer/verify/chaos.hpp"

namespace bouncer {

// The question of certify-chaos.
struct CertifyChaosRequest {
  // The model (--model, --a, --c or --eps, --wall, ...; --model veldep by default).
  ModelSpec model;
  // --bits (MPFI precision of the coverings), --max-period (saddles of period 1..Q),
  // --max-pieces (finest subdivision); the rest of the search at its defaults.
  ChaosSearchOptions search;
  // --replay-bits: Arb's precision when the certificate is replayed.
  long replay_bits = 256;
};

// Validates every option above; throws InputError naming the option.
CertifyChaosRequest certify_chaos_request(const Options& given);

}  // namespace bouncer
