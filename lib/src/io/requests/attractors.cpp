// `bouncer attractors`: the request from the options (io/requests/attractors.hpp).
#include "bouncer/io/requests/attractors.hpp"

#include <tuple>

#include "bouncer/io/options.hpp"

namespace bouncer {

AttractorsRequest attractors_request(const Options& o) {
  AttractorsRequest r;
  r.model = model_from(o);
  std::tie(r.nx, r.ny) = parse_grid("starts", o.get_or("starts", "100x100"), 8192);
  if (r.nx * r.ny > 4000000)
    throw InputError("starts", "must be NxM with N*M <= 4000000 (got " + o.get("starts") + ")");
  const std::string sampling = o.get_or("sampling", "grid");
  if (sampling == "grid") r.sampling = StartSampling::grid;
  else if (sampling == "halton") r.sampling = StartSampling::halton;
  else throw InputError("sampling", "must be grid or halton (got '" + sampling + "')");
  std::tie(r.theta_lo, r.theta_hi) = parse_range("theta-range", o.get_or("theta-range", "0:1"));
  if (o.has("v-range")) r.v_range = parse_range("v-range", o.get("v-range"));
  std::tie(r.cells_theta, r.cells_v) = parse_grid("cells", o.get_or("cells", "512x512"), 4096);
  if (r.cells_theta < 16 || r.cells_v < 16)
    throw InputError("cells", "must be NxM with 16 <= N, M <= 4096 (got '" + o.get("cells") + "')");
  r.consecutive_recurrences = integer_from(o, "recurrences", 1, 1000000, 100);
  r.attractor_steps = integer_from(o, "attractor-steps", 10, 10000000, 1000);
  r.consecutive_hits = integer_from(o, "hits", 1, 1000000, 8);
  r.lost_steps = integer_from(o, "lost-steps", 1, 1000000, 20);
  r.max_steps = integer_from(o, "max-steps", 100, 1000000000, 200000);
  r.lyapunov_steps = integer_from(o, "lyapunov-steps", 100, 1000000000, 100000);
  r.classify = classify_options_from(o);
  r.max_period = r.classify.max_period;
  r.certify = !flag_from(o, "no-certify");
  if (o.has("max-bits") && !r.certify) throw InputError("max-bits", "is not used with --no-certify");
  r.max_bits = integer_from(o, "max-bits", 64, 4096, 1024);
  r.precision = point_precision(o);
  return r;
}

std::optional<AttractorsSweepRequest> attractors_sweep_request(const Options& o) {
  if (!o.has("vary")) {
    for (const char* k : {"range", "values", "no-branches"})
      if (o.has(k)) throw InputError(k, "is only used with --vary a|eps|c");
    return std::nullopt;
  }
  AttractorsSweepRequest s;
  s.vary = parse_parameter("vary", o.get("vary"));
  if (!o.has("range")) throw InputError("range", "is needed with --vary: LO:HI (decimals, LO < HI)");
  Options m = o;
  default_to_range_start(m, name(s.vary));
  s.point = attractors_request(m);
  std::tie(s.lo, s.hi) = parse_range("range", o.get("range"));
  s.values = integer_from(o, "values", 2, 1000, 11);
  s.continue_branches = !flag_from(o, "no-branches");
  s.certify_ends = s.point.certify;  // --no-certify: the branches' ends are not proved either
  return s;
}

}  // namespace bouncer
