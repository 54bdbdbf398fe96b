// The grid commands' requests from their options (io/requests/grids.hpp).
#include "bouncer/io/requests/grids.hpp"

#include <algorithm>

#include "bouncer/io/options.hpp"

namespace bouncer {

namespace {

// --confirm[=BITS] (no value: 256) and --confirm-sample N|all (default 1000 starts) of basin
// and scan (run/cells.hpp GridConfirm).
GridConfirm grid_confirm_from(const Options& o, bool certify) {
  GridConfirm c;
  if (!o.has("confirm")) {
    if (o.has("confirm-sample")) throw InputError("confirm-sample", "is only used with --confirm");
    return c;
  }
  if (certify) throw InputError("confirm", "is not used with --certify (which compares double's class with the certified one)");
  c.on = true;
  const std::string bits = o.get("confirm");
  if (!bits.empty() && bits != "true") {
    const auto d = Decimal::parse(bits);
    if (!d || d->value().get_den() != 1 || d->value() < 64 || d->value() > kMaxBits)
      throw InputError("confirm", "must be a number of bits in [64, " + std::to_string(kMaxBits) + "], or no value for 256 (got '" +
                                      bits + "')");
    c.bits = d->value().get_num().get_si();
  }
  if (o.get_or("confirm-sample", "") != "all") {
    const std::string n = o.get_or("confirm-sample", "1000");
    const auto d = Decimal::parse(n);
    if (!d || d->value().get_den() != 1 || d->value() < 1 || d->value() > 1000000000000.0)
      throw InputError("confirm-sample", "must be a number of starts in [1, 1e12] or all (got '" + n + "')");
    c.sample = std::stol(d->value().get_num().get_str());
  }
  return c;
}

}  // namespace

BasinOptions basin_options(const Options& o) {
  BasinOptions b;
  BasinRequest& r = b.request;
  r.model = model_from(o);
  std::tie(r.nx, r.ny) = parse_grid("grid", o.get_or("grid", "100x100"), 8192);
  std::tie(r.theta_lo, r.theta_hi) = parse_range("theta-range", o.get_or("theta-range", "0:1"));
  if (o.has("v-range")) r.v_range = parse_range("v-range", o.get("v-range"));
  r.classify = classify_options_from(o);
  r.precision = point_precision(o);
  b.certify = flag_from(o, "certify");
  if (o.has("max-bits") && !b.certify) throw InputError("max-bits", "is only used with --certify");
  r.cert.max_steps = r.classify.transient + r.classify.steps;
  r.cert.max_bits = integer_from(o, "max-bits", 64, 4096, 256);
  r.cert.max_attractor_period = r.classify.max_period;
  r.confirm = grid_confirm_from(o, b.certify);
  return b;
}

ScanOptions scan_options(const Options& o) {
  ScanOptions so;
  ScanRequest& r = so.request;
  std::tie(r.a_lo, r.a_hi) = parse_range("a-range", o.get("a-range"));
  const Law law = parse_law("model", o.get("model"));
  if (law == Law::elastic) throw InputError("model", "scan needs an inelastic model (constant: a x eps; veldep: a x c)");
  const std::string y = law == Law::constant ? "eps" : "c", yr = y + "-range";
  std::tie(r.y_lo, r.y_hi) = parse_range(yr, o.get(yr));
  if (o.has("a")) throw InputError("a", "is scanned: give --a-range instead");
  if (o.has(y)) throw InputError(y, "is scanned: give --" + yr + " instead");
  // The model at the ranges' start (the request checks both ends of both ranges).
  Options m = o;
  m.set("a", r.a_lo.text());
  m.set(y, r.y_lo.text());
  try {
    r.model = model_from(m);
  } catch (const InputError& e) {
    throw InputError(e.field == "a" ? "a-range" : e.field == y ? yr : e.field, e.what());
  }
  std::tie(r.p, r.q) = parse_grid("grid", o.get_or("grid", "20x20"), 4096);
  r.k = integer_from(o, "ics", 1, 1000, 10);
  std::tie(r.theta_lo, r.theta_hi) = parse_range("theta-range", o.get_or("theta-range", "0:1"));
  if (o.has("v-range")) r.v_range = parse_range("v-range", o.get("v-range"));
  r.classify = classify_options_from(o);
  const std::string rule = o.get_or("recheck", "recurrence");
  if (const std::optional<RecheckRule> rr = recheck_rule_named(rule))
    r.classify.recheck = *rr;
  else
    throw InputError("recheck", "must be recurrence or full (got '" + rule + "')");
  r.precision = point_precision(o);
  const std::string show = o.get_or("show", "regular");
  if (show != "regular") {
    so.show = orbit_class_named(show);
    if (!so.show || std::find(scan_classes().begin(), scan_classes().end(), *so.show) == scan_classes().end()) {
      std::string allowed = "regular";
      for (OrbitClass c : scan_classes()) allowed += std::string(", ") + name(c);
      throw InputError("show", "must be one of " + allowed);
    }
  }
  // The analytic fixed-point curves (paper eq. 5) belong to the (a, eps) plane of the
  // constant model: drawn there by default, never elsewhere.
  const std::string curves = o.get_or("curves", y == "eps" && r.model.wall.shape == WallShape::piecewise ? "fixed-points" : "none");
  if (curves != "fixed-points" && curves != "none")
    throw InputError("curves", "must be fixed-points or none (got '" + curves + "')");
  if (curves == "fixed-points" && y != "eps")
    throw InputError("curves", "fixed-points needs --model constant (the curves are in the (a, eps) plane)");
  so.fixed_point_curves = curves == "fixed-points";
  if (so.fixed_point_curves) require_piecewise_wall(r.model, "--curves fixed-points (the triangle's eq. 5)");
  so.certify = flag_from(o, "certify");
  for (const char* k : {"max-bits", "theta", "v"})
    if (o.has(k) && !so.certify)
      throw InputError(k, "is only used with --certify (the certified start; the classified starts are --ics, --theta-range, --v-range)");
  // --certify: the release state by default, which every sticking orbit passes through: the
  // triangle's (1/2, 4), or a smooth wall's (theta_r, u(theta_r)).
  r.start = {parse_decimal("theta", o.get_or("theta", "0.5")), parse_decimal("v", o.get_or("v", "4"))};
  r.start_at_release = so.certify && r.model.wall.shape == WallShape::sine && !o.has("theta") && !o.has("v");
  r.cert.max_steps = r.classify.transient + r.classify.steps;
  r.cert.max_bits = integer_from(o, "max-bits", 64, 4096, 256);
  r.cert.max_attractor_period = r.classify.max_period;
  r.confirm = grid_confirm_from(o, so.certify);
  return so;
}

BifurcationOptions bifurcation_options(const Options& given) {
  BifurcationOptions b;
  BifurcationRequest& r = b.request;
  const std::string vary = given.get_or("vary", "a");
  Options o = given;
  default_to_range_start(o, vary);
  r.model = model_from(o);
  if (vary != "a" && vary != "eps" && vary != "c") throw InputError("vary", "must be a, eps or c (got '" + vary + "')");
  r.vary = parse_parameter("vary", vary);
  std::tie(r.lo, r.hi) = parse_range("range", o.get("range"));
  r.samples = integer_from(o, "samples", 1, 100000, 200);
  r.transient = integer_from(o, "transient", 0, 100000000, 5000);
  r.record = integer_from(o, "record", 1, 1000000, 500);
  const auto ics = initial_conditions_from(o, r.model);
  if (ics.size() != 1) throw InputError("theta", "takes one initial condition here");
  r.start = ics[0];
  r.carry = flag_from(o, "carry");
  r.precision = point_precision(o);
  const std::string show = o.get_or("show", "theta");
  if (show != "theta" && show != "v") throw InputError("show", "must be theta or v (got '" + show + "')");
  b.show_theta = show == "theta";
  b.bins = integer_from(o, "bins", 10, 4000, 400);
  r.certify = flag_from(o, "certify");
  if (o.has("max-bits") && !r.certify) throw InputError("max-bits", "is only used with --certify");
  r.cert.max_steps = r.transient + r.record;
  r.cert.max_bits = integer_from(o, "max-bits", 64, 4096, 256);
  return b;
}

}  // namespace bouncer
