// `bouncer portrait`'s request from its options (io/requests/portrait.hpp).
#include "bouncer/io/requests/portrait.hpp"

#include "bouncer/io/options.hpp"

namespace bouncer {

PortraitOptions portrait_options(const Options& o) {
  PortraitOptions p;
  PortraitRequest& r = p.request;
  r.model = model_from(o);
  r.starts = initial_conditions_from(o, r.model);
  if (r.starts.size() > 1000) throw InputError("theta", "at most 1000 initial conditions");
  r.steps = integer_from(o, "steps", 1, 10000000, 1000);
  r.transient = integer_from(o, "transient", 0, 100000000, 0);
  if (static_cast<double>(r.steps) * static_cast<double>(r.starts.size()) > 2e7)
    throw InputError("steps", "orbits x steps must be at most 2e7 points");
  const std::string polar = o.get_or("polar", "false");
  if (polar != "true" && polar != "false") throw InputError("polar", "must be true or false");
  p.view.polar = polar == "true";
  for (const char* k : {"theta-range", "v-range"})
    if (p.view.polar && o.has(k)) throw InputError(k, "chooses the window of the (theta, v) picture, not of --polar");
  if (o.has("theta-range")) {
    p.view.theta_window = parse_range("theta-range", o.get("theta-range"));
    if (p.view.theta_window->first < Decimal::from_int(0) || p.view.theta_window->second > Decimal::from_int(1))
      throw InputError("theta-range", "must lie in [0, 1] (got '" + o.get("theta-range") + "')");
  }
  if (o.has("v-range")) {
    p.view.v_window = parse_range("v-range", o.get("v-range"));
    if (p.view.v_window->second.approx() > 1e15 || p.view.v_window->first.approx() < -1e15)
      throw InputError("v-range", "must lie within +-1e15");
  }
  r.precision = point_precision(o);
  return p;
}

}  // namespace bouncer
