#include "bouncer/io/requests/certify_chaos.hpp"

namespace bouncer {

CertifyChaosRequest certify_chaos_request(const Options& given) {
  Options o = given;
  if (!o.has("model")) o.set("model", "veldep");
  CertifyChaosRequest r;
  r.model = model_from(o);
  require_piecewise_wall(r.model, "certify-chaos");
  r.search.bits = integer_from(o, "bits", 32, 4096, r.search.bits);
  r.search.max_period = static_cast<int>(integer_from(o, "max-period", 1, 8, r.search.max_period));
  r.search.max_pieces = static_cast<int>(integer_from(o, "max-pieces", 1, 1024, r.search.max_pieces));
  r.replay_bits = integer_from(o, "replay-bits", 32, 65536, r.replay_bits);
  return r;
}

}  // namespace bouncer
