// The outputs of `bouncer attractors` (io/attractors.hpp).
#include "bouncer/io/attractors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#pragma GCC diagnostic push
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nlohmann/json.hpp>
#pragma GCC diagnostic pop

#include "bouncer/io/grid_figures.hpp"

namespace bouncer {

namespace {

using json = nlohmann::ordered_json;

std::string g(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

// A share and its error as percentages with the digits the error allows.
std::string share_pm(double p, double e) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.1f ± %.1f%%", 100 * p, 100 * e);
  return buf;
}

json enclosure(const Enclosure& e) { return json::array({e.lo, e.hi}); }

json certificate_json(const PeriodicCertificate& c) {
  json j;
  j["certified"] = c.certified;
  j["outcome"] = name(c.outcome);
  j["bits"] = c.bits;
  j["minimal_period"] = c.minimal_period_certified ? json(c.minimal_period) : json(nullptr);
  if (!c.certified) {
    j["reason"] = c.reason;
    return j;
  }
  j["stability"] = c.stability;
  json mu;
  mu["kind"] = c.multipliers.kind;
  if (c.multipliers.kind == "real") {
    mu["mu1"] = enclosure(c.multipliers.mu[0]);
    mu["mu2"] = enclosure(c.multipliers.mu[1]);
  } else if (c.multipliers.kind == "complex") {
    mu["re"] = enclosure(c.multipliers.mu[0]);
    mu["im"] = enclosure(c.multipliers.mu[1]);
    mu["modulus"] = enclosure(c.multipliers.modulus);
  }
  j["multipliers"] = mu;
  json pts = json::array();
  for (const EnclosedOrbitPoint& p : c.points) pts.push_back({{"theta", enclosure(p.theta)}, {"v", enclosure(p.v)}});
  j["points"] = pts;
  j["events"] = c.events;
  j["statement"] = c.statement;
  return j;
}

std::string label_of(int l) {
  if (l == AttractorsResult::kOutside) return "outside";
  if (l == AttractorsResult::kUndecidedStart) return "undecided";
  return std::to_string(l);
}

OrbitClass orbit_class(const FoundAttractor& a) {
  switch (a.kind) {
    case AttractorKind::periodic: return a.period == 1 ? OrbitClass::fixed : OrbitClass::periodic;
    case AttractorKind::family: return a.period == 1 ? OrbitClass::fixed : OrbitClass::periodic;
    case AttractorKind::sticking: return OrbitClass::sticking;
    case AttractorKind::chaotic: return OrbitClass::chaotic;
    case AttractorKind::quasiperiodic: return OrbitClass::quasiperiodic;
    case AttractorKind::effective_sticking: return OrbitClass::effective_sticking;
    case AttractorKind::accelerator:
    case AttractorKind::escape: return OrbitClass::unbounded;
    case AttractorKind::undecided: return OrbitClass::undecided;
  }
  return OrbitClass::undecided;
}

std::string certificate_text(const FoundAttractor& a) {
  if (!a.certificate) return "";
  const PeriodicCertificate& c = *a.certificate;
  if (!c.certified) return "not certified (" + c.reason + ")";
  std::string s = "certified (Krawczyk, " + std::to_string(c.bits) + " bits): " + name(c.outcome) + ", " + c.stability;
  if (c.multipliers.kind == "real")
    s += ", multipliers in [" + c.multipliers.mu[0].lo + ", " + c.multipliers.mu[0].hi + "] and [" + c.multipliers.mu[1].lo +
         ", " + c.multipliers.mu[1].hi + "]";
  else if (c.multipliers.kind == "complex")
    s += ", complex multipliers of modulus in [" + c.multipliers.modulus.lo + ", " + c.multipliers.modulus.hi + "]";
  return s;
}

}  // namespace

std::string attractor_title(const FoundAttractor& a) {
  const std::string q = std::to_string(a.period);
  switch (a.kind) {
    case AttractorKind::periodic: return a.period == 1 ? "fixed point" : "period " + q;
    case AttractorKind::family: return a.period == 1 ? "family of fixed points" : "family of period-" + q + " points";
    case AttractorKind::sticking: return "sticking cycle, k = " + q;
    case AttractorKind::chaotic: return "chaotic set";
    case AttractorKind::quasiperiodic: return "quasiperiodic set";
    case AttractorKind::effective_sticking: return "effective sticking";
    case AttractorKind::accelerator: return "accelerator mode, Q = " + q;
    case AttractorKind::escape: return "escape";
    case AttractorKind::undecided: return "undecided recurrence";
  }
  return "?";
}

std::string attractors_csv(const AttractorsResult& r) {
  std::string csv = "theta,v,attractor,kind,period\n";
  for (size_t i = 0; i < r.label.size(); ++i) {
    const int l = r.label[i];
    csv += r.theta[i].digits + ',' + r.v[i].digits + ',' + label_of(l) + ',';
    if (l >= 0) {
      const FoundAttractor& a = r.attractors[static_cast<size_t>(l)];
      csv += std::string(name(a.kind)) + ',' + std::to_string(a.period);
    } else {
      csv += label_of(l) + ",0";
    }
    csv += '\n';
  }
  return csv;
}

std::string attractors_json(const AttractorsResult& r) {
  const AttractorsRequest& q = r.request;
  json s;
  s["command"] = "attractors";
  s["starts"] = {q.nx, q.ny};
  s["sampling"] = name(q.sampling);
  s["theta_range"] = {q.theta_lo.text(), q.theta_hi.text()};
  s["v_range"] = {q.v_range->first.text(), q.v_range->second.text()};
  s["points"] = r.label.size();
  s["points_in_phase_space"] = r.inside;
  s["outside"] = r.outside;
  json m;
  m["cells"] = {q.cells_theta, q.cells_v};
  m["cell_size"] = {r.cell_theta, r.cell_v};
  m["v_range"] = {r.grid_v_lo, r.grid_v_hi};
  m["consecutive_recurrences"] = q.consecutive_recurrences;
  m["attractor_steps"] = q.attractor_steps;
  m["consecutive_hits"] = q.consecutive_hits;
  m["lost_steps"] = q.lost_steps;
  m["max_steps"] = q.max_steps;
  m["max_period"] = q.max_period;
  m["lyapunov_steps"] = q.lyapunov_steps;
  s["recurrence_grid"] = m;
  s["precision"] = q.precision.text();
  json list = json::array();
  for (const FoundAttractor& a : r.attractors) {
    json j;
    j["id"] = a.id;
    j["kind"] = name(a.kind);
    j["period"] = a.period;
    j["name"] = attractor_title(a);
    j["starts"] = a.starts;
    j["fraction"] = a.fraction;
    j["fraction_stderr"] = a.fraction_stderr;
    j["stable"] = a.stable;
    json pts = json::array();
    for (const AttractorPoint& p : a.points) pts.push_back({p.theta.digits, p.v.digits});
    j["points"] = pts;
    if (!a.multipliers.empty()) {
      json mu = json::array();
      for (size_t i = 0; i < a.multipliers.size(); ++i)
        mu.push_back({{"re", a.multipliers[i].first.digits}, {"im", a.multipliers[i].second.digits}, {"modulus", a.multiplier_moduli[i]}});
      j["multipliers"] = mu;
    }
    j["certificate"] = a.certificate ? certificate_json(*a.certificate) : json(nullptr);
    if (a.kind == AttractorKind::family)
      j["family"] = {{"members_found", a.family_members}, {"theta_min", a.family_theta_min}, {"theta_max", a.family_theta_max}};
    if (a.kind == AttractorKind::chaotic || a.kind == AttractorKind::quasiperiodic)
      j["lyapunov"] = {{"lambda", a.lambda}, {"stderr", a.lambda_stderr}, {"steps", a.lyapunov_steps}};
    if (a.kind == AttractorKind::accelerator) j["gain_per_period"] = a.accel_gain;
    j["followed_steps"] = a.followed_steps;
    j["cells"] = a.cells;
    j["first_start"] = a.first_start;
    j["evidence"] = a.evidence;
    list.push_back(j);
  }
  s["attractors"] = list;
  s["undecided"] = {{"starts", r.undecided}, {"fraction", r.undecided_fraction}, {"fraction_stderr", r.undecided_stderr}};
  s["recurrences_characterized"] = r.candidates;
  s["steps"] = r.steps;
  s["seconds"] = r.seconds;  // (timings: keys named "seconds", which audit ignores)
  s["certificates"] = {{"seconds", r.certify_seconds}};
  return s.dump();
}

ImageFigure attractors_figure(const AttractorsResult& r, Palette palette) {
  const AttractorsRequest& q = r.request;
  std::vector<Rgb> color;
  int periodic_rank = 0, sticking_rank = 0;
  for (const FoundAttractor& a : r.attractors) {
    const OrbitClass c = orbit_class(a);
    color.push_back(attractor_color(c, periodic_rank, sticking_rank, palette));
    if (c == OrbitClass::periodic || (c == OrbitClass::fixed && a.id > 0)) ++periodic_rank;
    if (c == OrbitClass::sticking) ++sticking_rank;
  }
  const Rgb undecided = attractor_color(OrbitClass::undecided, 0, 0, palette);
  const Rgb outside = attractor_color(OrbitClass::outside, 0, 0, palette);
  auto rgb = [&](int l) {
    return l >= 0 ? color[static_cast<size_t>(l)] : l == AttractorsResult::kOutside ? outside : undecided;
  };
  ImageFigure fig;
  Raster& ras = fig.raster;
  ras.nx = static_cast<int>(q.nx);
  ras.ny = static_cast<int>(q.ny);
  set_exact_window(ras, q.theta_lo.value(), q.theta_hi.value(), q.v_range->first.value(), q.v_range->second.value());
  if (q.sampling == StartSampling::grid) {
    ras.pixels.resize(r.label.size());
    for (size_t i = 0; i < r.label.size(); ++i) ras.pixels[pixel_of(i, q.nx, q.ny)] = rgb(r.label[i]);
  } else {
    // Halton points painted on the raster at their nearest pixel (the rest white).
    ras.pixels.assign(r.label.size(), Rgb{255, 255, 255});
    const double t0 = q.theta_lo.approx(), t1 = q.theta_hi.approx(), v0 = q.v_range->first.approx(), v1 = q.v_range->second.approx();
    for (size_t i = 0; i < r.label.size(); ++i) {
      const long col = std::clamp(static_cast<long>((r.theta[i].value - t0) / (t1 - t0) * static_cast<double>(q.nx)), 0L, q.nx - 1);
      const long row = std::clamp(static_cast<long>((r.v[i].value - v0) / (v1 - v0) * static_cast<double>(q.ny)), 0L, q.ny - 1);
      ras.pixels[pixel_of(static_cast<size_t>(row * q.nx + col), q.nx, q.ny)] = rgb(r.label[i]);
    }
  }
  const size_t shown = r.attractors.size() > 13 ? 12 : r.attractors.size();
  for (size_t k = 0; k < shown; ++k) {
    const FoundAttractor& a = r.attractors[k];
    std::string mark = a.certificate && a.certificate->certified ? " ✓" : "";
    ras.legend.emplace_back("#" + std::to_string(a.id) + " " + attractor_title(a) + mark + ": " +
                                share_pm(a.fraction, a.fraction_stderr),
                            color[k]);
  }
  if (shown < r.attractors.size())
    ras.legend.emplace_back("+" + std::to_string(r.attractors.size() - shown) + " more attractors", Rgb{255, 255, 255});
  if (r.undecided > 0) ras.legend.emplace_back("undecided: " + share_pm(r.undecided_fraction, r.undecided_stderr), undecided);
  if (r.outside > 0) ras.legend.emplace_back("below the wall velocity (no state)", outside);
  bool any_cert = false;
  for (const FoundAttractor& a : r.attractors) any_cert = any_cert || (a.certificate && a.certificate->certified);
  if (any_cert) ras.legend.emplace_back("✓ proved by Krawczyk", Rgb{255, 255, 255});
  fig.title = "Attractors and their basins, " + model_title(q.model.law) + " model";
  fig.subtitle = parameters_text(q.model) + "; " + std::to_string(q.nx) + " x " + std::to_string(q.ny) + " " +
                 (q.sampling == StartSampling::grid ? "grid" : "Halton") + " starts, shares ± 1 standard error; " +
                 q.precision.text();
  fig.xlabel = "θ₀ (initial phase)";
  fig.ylabel = "v₀ (initial velocity)";
  fig.width = 1200;
  fig.height = 700;
  return fig;
}

std::string attractors_text(const AttractorsResult& r) {
  const AttractorsRequest& q = r.request;
  std::ostringstream o;
  o << r.attractors.size() << " attractor" << (r.attractors.size() == 1 ? "" : "s") << " at " << name(q.model.law) << " "
    << parameters_text(q.model) << " from " << r.inside << " starts (" << q.nx << " x " << q.ny << " "
    << name(q.sampling) << " over theta " << q.theta_lo.text() << ".." << q.theta_hi.text() << ", v "
    << q.v_range->first.text() << ".." << q.v_range->second.text() << "), " << q.precision.text() << ":\n";
  for (const FoundAttractor& a : r.attractors) {
    o << "  #" << a.id << " " << attractor_title(a) << ": basin share " << g(a.fraction, 4) << " ± " << g(a.fraction_stderr, 2)
      << " (" << a.starts << " starts)";
    if (!a.multiplier_moduli.empty())
      o << ", " << (a.stable ? "stable" : "not stable") << ", |multipliers| " << g(a.multiplier_moduli[0], 6) << ", "
        << g(a.multiplier_moduli[1], 6);
    o << "\n";
    if (a.kind == AttractorKind::family)
      o << "      members reached: " << a.family_members << ", theta in [" << g(a.family_theta_min, 6) << ", "
        << g(a.family_theta_max, 6) << "], v = " << a.points[0].v.digits << "\n";
    else if (a.kind == AttractorKind::periodic || a.kind == AttractorKind::sticking) {
      o << "      points:";
      for (size_t i = 0; i < a.points.size() && i < 8; ++i) o << " (" << a.points[i].theta.digits << ", " << a.points[i].v.digits << ")";
      if (a.points.size() > 8) o << " ...";
      o << "\n";
    }
    if (a.kind == AttractorKind::chaotic || a.kind == AttractorKind::quasiperiodic)
      o << "      Lyapunov exponent " << g(a.lambda, 4) << " ± " << g(a.lambda_stderr, 2) << " per collision over "
        << a.lyapunov_steps << " steps (followed " << a.followed_steps << " steps)\n";
    if (a.kind == AttractorKind::accelerator)
      o << "      velocity gain " << g(a.accel_gain, 4) << " every " << a.period << " steps\n";
    if (a.kind != AttractorKind::periodic && a.kind != AttractorKind::family && !a.evidence.empty())
      o << "      evidence: " << a.evidence << "\n";
    if (a.certificate) o << "      " << certificate_text(a) << "\n";
  }
  o << "  undecided (no decision in " << q.max_steps << " steps): " << r.undecided << " starts\n";
  o << "  " << r.steps << " map steps, " << r.candidates << " recurrences characterized, " << g(r.seconds, 3) << " s (+ "
    << g(r.certify_seconds, 3) << " s certificates)\n";
  return o.str();
}

}  // namespace bouncer
