// The outputs of `bouncer attractors` (io/attractors.hpp).
#include "bouncer/io/attractors.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#pragma GCC diagnostic push
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nlohmann/json.hpp>
#pragma GCC diagnostic pop

#include "bouncer/io/grid_figures.hpp"
#include "bouncer/scalar/decimal.hpp"

namespace bouncer {

namespace {

using json = nlohmann::ordered_json;

std::string g(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

// The shortest decimal that reads back to x (as the JSON writer prints doubles).
std::string shortest(double x) {
  for (int digits = 1; digits < 17; ++digits) {
    const std::string t = g(x, digits);
    if (std::strtod(t.c_str(), nullptr) == x) return t;
  }
  return g(x, 17);
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
  fig.title = "Attractors and their basins, " + model_name(q.model);
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

namespace {

std::string chain_title(const AttractorChain& c) {
  FoundAttractor a;
  a.kind = c.kind;
  a.period = c.period;
  return attractor_title(a);
}

// The short name written inside a band of the stacked figure: "P3" (period 3), "F2" (family
// of period-2 points), "k4" (sticking cycle), "Q5" (accelerator mode), "chaos", "qp", ...
std::string chain_tag(const AttractorChain& c) {
  const std::string q = std::to_string(c.period);
  switch (c.kind) {
    case AttractorKind::periodic: return "P" + q;
    case AttractorKind::family: return "F" + q;
    case AttractorKind::sticking: return "k" + q;
    case AttractorKind::chaotic: return "chaos";
    case AttractorKind::quasiperiodic: return "qp";
    case AttractorKind::effective_sticking: return "eff. st.";
    case AttractorKind::accelerator: return "Q" + q;
    case AttractorKind::escape: return "esc.";
    case AttractorKind::undecided: return "?";
  }
  return "?";
}

// Where a chain exists: "23.05..23.15" (first..last value present), or several pieces.
std::string presence(const AttractorsSweepResult& r, const AttractorChain& c) {
  std::string out;
  for (size_t k = 0; k < c.index.size(); ++k) {
    if (c.index[k] < 0 || (k > 0 && c.index[k - 1] >= 0)) continue;
    size_t e = k;
    while (e + 1 < c.index.size() && c.index[e + 1] >= 0) ++e;
    out += (out.empty() ? "" : ", ") + r.values[k].text() + (e > k ? ".." + r.values[e].text() : "");
  }
  return out;
}

// An enclosure [lo, hi] rounded outward to about 16 significant digits (still an enclosure).
std::string short_enclosure(const Enclosure& e) {
  const mpq_class lo = parse_decimal("lo", e.lo).value(), hi = parse_decimal("hi", e.hi).value();
  const double mag = std::max(std::fabs(lo.get_d()), 1e-300);
  const long k = std::max<long>(0, 15 - static_cast<long>(std::floor(std::log10(mag))));
  mpz_class scale;
  mpz_ui_pow_ui(scale.get_mpz_t(), 10, static_cast<unsigned long>(k));
  const mpq_class a = lo * scale, b = hi * scale;
  mpz_class fa, cb;
  mpz_fdiv_q(fa.get_mpz_t(), a.get_num_mpz_t(), a.get_den_mpz_t());
  mpz_cdiv_q(cb.get_mpz_t(), b.get_num_mpz_t(), b.get_den_mpz_t());
  return "[" + exact_decimal(mpq_class(fa, scale)) + ", " + exact_decimal(mpq_class(cb, scale)) + "]";
}

std::string event_words(const BranchEventInfo& e) {
  if (e.kind == "border") return "border collision";
  if (e.kind == "period_doubling") return "period doubling";
  if (e.kind == "doubling") return "birth at a period doubling";  // a doubling end (continuation.hpp)
  if (e.kind == "neimark_sacker") return "Neimark-Sacker bifurcation";
  if (e.kind == "event_change") return "change of the event sequence";
  if (e.kind == "period_collapse") return "collapse onto a smaller period";
  if (e.kind == "lost") return "loss of the corrector";
  return e.kind;  // fold
}

// "border collision at a* = 23.23 (impact 2 reaches ...; certified [lo, hi])"
std::string event_sentence(const BranchEventInfo& e, const std::string& vary) {
  std::string s = event_words(e) + " at " + vary + "* = " + e.param_text;
  std::string note = e.detail;
  if (e.certified) note += std::string(note.empty() ? "" : "; ") + "certified " + short_enclosure(e.enclosure);
  else if (e.tried) note += std::string(note.empty() ? "" : "; ") + "not certified: " + e.reason;
  else note += std::string(note.empty() ? "" : "; ") + "not certified";
  return s + " (" + note + ")";
}

// The chain of the same branch present on the other side of an unexplained transition (the
// matching split one branch into two chains: its orbit moved more than the match distance
// between the values), or -1.
int same_branch_chain(const AttractorsSweepResult& r, size_t chain, const ChainTransition& t) {
  const int b = r.branches->chain_branch[chain];
  if (t.event >= 0 || b < 0) return -1;
  const size_t other_side = t.appears ? t.before : t.after;
  for (int c : r.branches->branches[static_cast<size_t>(b)].chains)
    if (static_cast<size_t>(c) != chain && r.chains[static_cast<size_t>(c)].index[other_side] >= 0) return c;
  return -1;
}

std::string transition_sentence(const AttractorsSweepResult& r, size_t chain, const ChainTransition& t) {
  const std::string vary = name(r.request.vary);
  std::string s = std::string(t.appears ? "appears" : "disappears") + " at " + vary + " in (" + r.values[t.before].text() +
                  ", " + r.values[t.after].text() + "): ";
  if (t.event >= 0) return s + event_sentence(r.branches->branches[static_cast<size_t>(t.branch)].events[static_cast<size_t>(t.event)], vary);
  s += "not explained by a known branch end";
  const int b = r.branches->chain_branch[chain];
  if (b < 0) {
    const AttractorKind k = r.chains[chain].kind;
    return s + (k == AttractorKind::family ? " (a family: no isolated branch)" : k == AttractorKind::periodic || k == AttractorKind::sticking ? " (not continued)" : " (no branch to continue: " + std::string(name(k)) + ")");
  }
  const ContinuedBranch& cb = r.branches->branches[static_cast<size_t>(b)];
  if (const int c = same_branch_chain(r, chain, t); c >= 0)
    return s + " (the same branch is chain " + std::to_string(c) + " there: its orbit moved more than the match distance)";
  if (!cb.started) return s + " (the branch did not start: " + cb.note + ")";
  return s + " (its branch spans " + vary + " in [" + cb.low_param + ", " + cb.high_param +
         "]: the basin fell below the sampling resolution, or the orbit is unstable there)";
}

nlohmann::ordered_json event_json(const BranchEventInfo& e) {
  nlohmann::ordered_json j;
  j["kind"] = e.kind;
  j["end"] = e.end ? json(e.high ? "high" : "low") : json(nullptr);
  j["param"] = e.param_text;
  j["bracket"] = {e.bracket_lo, e.bracket_hi};
  j["detail"] = e.detail;
  j["certified"] = e.certified;
  j["enclosure"] = e.certified ? json{e.enclosure.lo, e.enclosure.hi} : json(nullptr);
  if (e.tried && !e.certified) j["reason"] = e.reason;
  return j;
}

}  // namespace

std::string attractors_sweep_csv(const AttractorsSweepResult& r) {
  const std::string vary = name(r.request.vary);
  std::string csv = vary + ",chain,kind,period,starts,fraction,fraction_stderr\n";
  for (size_t k = 0; k < r.values.size(); ++k) {
    const AttractorsResult& at = r.at[k];
    for (const AttractorChain& c : r.chains) {
      if (c.index[k] < 0) continue;
      const FoundAttractor& a = at.attractors[static_cast<size_t>(c.index[k])];
      csv += r.values[k].text() + ',' + std::to_string(c.id) + ',' + name(a.kind) + ',' + std::to_string(a.period) + ',' +
             std::to_string(a.starts) + ',' + shortest(a.fraction) + ',' + shortest(a.fraction_stderr) + '\n';
    }
    csv += r.values[k].text() + ",undecided,undecided,0," + std::to_string(at.undecided) + ',' + shortest(at.undecided_fraction) +
           ',' + shortest(at.undecided_stderr) + '\n';
  }
  return csv;
}

std::string attractors_sweep_json(const AttractorsSweepResult& r) {
  const AttractorsRequest& q = r.request.point;
  json s;
  s["command"] = "attractors";
  s["vary"] = name(r.request.vary);
  s["range"] = {r.request.lo.text(), r.request.hi.text()};
  json values = json::array();
  for (const Decimal& v : r.values) values.push_back(v.text());
  s["values"] = values;
  s["starts"] = {q.nx, q.ny};
  s["sampling"] = name(q.sampling);
  s["precision"] = q.precision.text();
  s["match_distance"] = r.request.match_distance;
  json chains = json::array();
  for (const AttractorChain& c : r.chains) {
    json j;
    j["chain"] = c.id;
    j["kind"] = name(c.kind);
    j["period"] = c.period;
    j["name"] = chain_title(c);
    j["present"] = presence(r, c);
    // Where the chain was joined by its continued branch, not by the match distance.
    json joined = json::array();
    for (const size_t k : c.joined) joined.push_back({r.values[k].text(), r.values[k + 1].text()});
    j["joined_by_branch"] = joined;
    json f = json::array(), e = json::array(), id = json::array(), cert = json::array();
    for (size_t k = 0; k < c.index.size(); ++k) {
      if (c.index[k] < 0) {
        f.push_back(nullptr), e.push_back(nullptr), id.push_back(nullptr), cert.push_back(nullptr);
        continue;
      }
      const FoundAttractor& a = r.at[k].attractors[static_cast<size_t>(c.index[k])];
      f.push_back(a.fraction);
      e.push_back(a.fraction_stderr);
      id.push_back(a.id);
      cert.push_back(a.certificate ? json(a.certificate->certified) : json(nullptr));
    }
    j["fraction"] = f;
    j["fraction_stderr"] = e;
    j["attractor_id"] = id;  // its id at each value (the per-value runs' numbering)
    j["certified"] = cert;
    if (r.branches) {
      const size_t ci = static_cast<size_t>(&c - r.chains.data());
      const int b = r.branches->chain_branch[ci];
      j["branch"] = b >= 0 ? json(b) : json(nullptr);
      json ends = json::array();
      for (const ChainTransition& t : r.branches->transitions[ci]) {
        json tj;
        tj["appears"] = t.appears;
        tj["between"] = {r.values[t.before].text(), r.values[t.after].text()};
        tj["explained"] = t.event >= 0;
        tj["event"] = t.event >= 0 ? event_json(r.branches->branches[static_cast<size_t>(t.branch)].events[static_cast<size_t>(t.event)])
                                   : json(nullptr);
        const int same = same_branch_chain(r, ci, t);
        tj["same_branch_chain"] = same >= 0 ? json(same) : json(nullptr);
        tj["sentence"] = transition_sentence(r, ci, t);
        ends.push_back(tj);
      }
      j["ends"] = ends;
    }
    chains.push_back(j);
  }
  s["chains"] = chains;
  if (r.branches) {
    json bs = json::array();
    for (const ContinuedBranch& b : r.branches->branches) {
      json bj;
      bj["kind"] = name(b.kind);
      bj["period"] = b.period;
      bj["chains"] = b.chains;
      bj["started_at"] = r.values[b.from_value].text();
      bj["started"] = b.started;
      if (!b.started) bj["note"] = b.note;
      bj["span"] = b.started ? json{b.low_param, b.high_param} : json(nullptr);
      bj["orbit_events"] = b.events_text;
      json ev = json::array();
      for (const BranchEventInfo& e : b.events) ev.push_back(event_json(e));
      bj["events"] = ev;
      bj["corrector_runs"] = b.corrector_runs;
      bs.push_back(bj);
    }
    s["branches"] = bs;
    s["branch_work"] = {{"seconds", r.branches->seconds}};  // (a timing: audit ignores "seconds")
  } else {
    s["branches"] = nullptr;
  }
  json und = json::array();
  long long steps = 0;
  double seconds = 0;
  for (const AttractorsResult& at : r.at) {
    und.push_back(at.undecided_fraction);
    steps += at.steps;
    seconds += at.seconds + at.certify_seconds;
  }
  s["undecided_fraction"] = und;
  s["steps"] = steps;
  s["seconds"] = seconds;
  return s.dump();
}

ImageFigure attractors_sweep_figure(const AttractorsSweepResult& r, Palette palette) {
  const AttractorsRequest& q = r.request.point;
  const size_t n = r.values.size();
  // Colours by family, not by chain: a sweep can have a hundred chains, and a hundred
  // colours cannot be told apart. A family is the chains of one kind and period (one title:
  // "period 3"); the families are ranked by their summed share over the sweep and the 12
  // largest get the attractor colours (distinct, colour-blind safe first), the rest two
  // alternating greys, light and dark, so that neighbouring bands still separate. The large
  // bands carry their family's tag written in them (chain_tag), so a reader needs no colour
  // to name them; the legend lists the 12 families.
  constexpr size_t kColouredFamilies = 12;
  std::vector<std::string> family_of(r.chains.size());
  std::vector<std::string> families;
  std::vector<double> family_share;
  for (size_t c = 0; c < r.chains.size(); ++c) {
    family_of[c] = chain_title(r.chains[c]);
    double share = 0;
    for (size_t k = 0; k < n; ++k)
      if (r.chains[c].index[k] >= 0) share += r.at[k].attractors[static_cast<size_t>(r.chains[c].index[k])].fraction;
    auto it = std::find(families.begin(), families.end(), family_of[c]);
    if (it == families.end()) {
      families.push_back(family_of[c]);
      family_share.push_back(share);
    } else {
      family_share[static_cast<size_t>(it - families.begin())] += share;
    }
  }
  std::vector<size_t> family_order(families.size());
  for (size_t i = 0; i < families.size(); ++i) family_order[i] = i;
  std::stable_sort(family_order.begin(), family_order.end(), [&](size_t x, size_t y) { return family_share[x] > family_share[y]; });
  std::vector<Rgb> family_color(families.size());
  std::vector<size_t> family_rank(families.size());
  {
    int periodic_rank = 0, sticking_rank = 0;
    for (size_t rank = 0; rank < family_order.size(); ++rank) {
      const size_t fam = family_order[rank];
      family_rank[fam] = rank;
      const size_t c = static_cast<size_t>(std::find(family_of.begin(), family_of.end(), families[fam]) - family_of.begin());
      FoundAttractor a;
      a.kind = r.chains[c].kind;
      a.period = r.chains[c].period;
      a.id = 1;
      const OrbitClass cls = orbit_class(a);
      family_color[fam] = rank < kColouredFamilies
                              ? attractor_color(cls == OrbitClass::fixed ? OrbitClass::periodic : cls, periodic_rank, sticking_rank, palette)
                              : Rgb{0, 0, 0};
      if (cls == OrbitClass::periodic || cls == OrbitClass::fixed) ++periodic_rank;
      if (cls == OrbitClass::sticking) ++sticking_rank;
    }
  }
  std::vector<Rgb> color(r.chains.size());
  const Rgb other_light{214, 206, 192}, other_dark{120, 108, 92};
  size_t others = 0;
  for (size_t c = 0; c < r.chains.size(); ++c) {
    const size_t fam = static_cast<size_t>(std::find(families.begin(), families.end(), family_of[c]) - families.begin());
    color[c] = family_rank[fam] < kColouredFamilies ? family_color[fam] : (others++ % 2 == 0 ? other_light : other_dark);
  }
  ImageFigure fig;
  Raster& ras = fig.raster;
  ras.nx = static_cast<int>(n);
  ras.ny = 400;
  const mpq_class half = (r.request.hi.value() - r.request.lo.value()) / (2 * static_cast<long>(n - 1));
  const std::pair<AxisZoom, AxisZoom> zoom = set_exact_window(ras, r.request.lo.value() - half, r.request.hi.value() + half, 0, 1);
  ras.pixels.assign(n * 400, Rgb{255, 255, 255});
  const Rgb undecided = attractor_color(OrbitClass::undecided, 0, 0, palette);
  // Each chain's tallest band (at value tallest_at): where its tag is written.
  std::vector<std::array<double, 2>> tallest(r.chains.size(), {0.0, 0.0});  // bottom, top
  std::vector<size_t> tallest_at(r.chains.size(), 0);
  for (size_t k = 0; k < n; ++k) {
    std::vector<std::pair<double, Rgb>> bands;  // cumulative top of each band, from the bottom
    double top = 0;
    for (size_t c = 0; c < r.chains.size(); ++c) {
      const int i = r.chains[c].index[k];
      if (i < 0) continue;
      const double share = r.at[k].attractors[static_cast<size_t>(i)].fraction;
      if (share > tallest[c][1] - tallest[c][0]) {
        tallest[c] = {top, top + share};
        tallest_at[c] = k;
      }
      top += share;
      bands.emplace_back(top, color[c]);
    }
    bands.emplace_back(top + r.at[k].undecided_fraction, undecided);
    for (int row = 0; row < 400; ++row) {
      const double y = (row + 0.5) / 400;
      for (const auto& [t, rgb] : bands)
        if (y < t) {
          ras.pixels[static_cast<size_t>((399 - row)) * n + k] = rgb;
          break;
        }
    }
  }
  // The legend: one entry per coloured family, largest first, with where its chains are
  // and, for the chains continued as branches, the explained appearances and
  // disappearances (a*): dots on the frame's top and bottom in the family's colour at each,
  // joined by a dashed vertical line when there are at most 12 chains ("certified": every
  // one enclosed by Krawczyk).
  const size_t shown = std::min(family_order.size(), kColouredFamilies);
  for (size_t rank = 0; rank < shown; ++rank) {
    const size_t fam = family_order[rank];
    std::vector<size_t> members;
    for (size_t c = 0; c < r.chains.size(); ++c)
      if (family_of[c] == families[fam]) members.push_back(c);
    std::vector<std::string> at;
    bool all_certified = true;
    if (r.branches) {
      Series line;
      line.color = family_color[fam];
      line.lines = true;
      line.markers = false;
      line.dashed = true;
      Series dots;
      dots.color = family_color[fam];
      dots.marker_size = 4;
      for (size_t c : members)
        for (const ChainTransition& t : r.branches->transitions[c]) {
          if (t.event < 0) continue;
          const BranchEventInfo& e = r.branches->branches[static_cast<size_t>(t.branch)].events[static_cast<size_t>(t.event)];
          const double x = ras.x_offset.active() ? NAN : e.param;
          if (!std::isfinite(x)) continue;
          line.x.insert(line.x.end(), {x, x, NAN});
          line.y.insert(line.y.end(), {0.0, 1.0, NAN});
          dots.x.insert(dots.x.end(), {x, x});
          dots.y.insert(dots.y.end(), {0.99, 0.01});
          at.push_back(g(e.param, 5) + (e.kind == "border" ? "" : e.kind == "period_doubling" || e.kind == "doubling" ? " PD" : " " + e.kind));
          all_certified = all_certified && e.certified;
        }
      if (!at.empty()) {
        // Many chains: the dots on the frame's edges mark the a* (full-height lines of a
        // hundred events would hide the bands).
        if (r.chains.size() <= 12) fig.overlay.push_back(line);
        fig.overlay.push_back(dots);
      }
    }
    std::string where = members.size() == 1 ? presence(r, r.chains[members[0]]) : std::to_string(members.size()) + " chains";
    if (!at.empty()) {
      std::string m;
      for (size_t j = 0; j < at.size() && j < 3; ++j) m += (j ? ", " : "") + at[j];
      if (at.size() > 3) m += ", ...";
      where += std::string("; ") + name(r.request.vary) + "* " + m + (all_certified ? " certified" : "");
    }
    ras.legend.emplace_back(families[fam] + " [" + chain_tag(r.chains[members[0]]) + "] (" + where + ")", family_color[fam]);
  }
  if (shown < family_order.size()) {
    ras.legend.emplace_back(std::to_string(family_order.size() - shown) + " smaller families (greys, light and dark in turn)",
                            other_light);
  }
  // Tags in the bands tall enough for a line of text (a tenth of the starts or more), the
  // tallest first (where two would overlap, the renderer keeps the first).
  std::vector<size_t> by_height(r.chains.size());
  for (size_t c = 0; c < by_height.size(); ++c) by_height[c] = c;
  std::stable_sort(by_height.begin(), by_height.end(), [&](size_t x, size_t y) {
    return tallest[x][1] - tallest[x][0] > tallest[y][1] - tallest[y][0];
  });
  for (size_t c : by_height)
    if (tallest[c][1] - tallest[c][0] >= 0.1)
      fig.annotations.push_back({zoom.first(r.values[tallest_at[c]].value()), (tallest[c][0] + tallest[c][1]) / 2,
                                 chain_tag(r.chains[c]), Rgb{0, 0, 0}});
  ras.notes.push_back("tags in the bands, e.g. P3: period 3, F2: family of period-2 points, k4: sticking cycle k = 4");  // a key, not a list of what is drawn
  ras.legend_below = families.size() > 6;
  ras.legend.emplace_back("undecided", undecided);
  const std::string vary = name(r.request.vary);
  fig.title = "Basin shares of the attractors against " + vary + ", " + model_name(q.model);
  // "a = 22.5..23.7, c = 1000": the model's parameters with the varied one's range.
  const ModelSpec& m = q.model;
  auto par = [&](Parameter p, const char* label, const Decimal& d) {
    return std::string(label) + " = " + (p == r.request.vary ? r.request.lo.text() + ".." + r.request.hi.text() : d.text());
  };
  std::string params = par(Parameter::a, "a", m.a);
  if (m.law == Law::constant) params += ", " + par(Parameter::eps, "ε", m.eps);
  if (m.law == Law::veldep) params += ", " + par(Parameter::c, "c", m.c);
  fig.subtitle = params + "; " + std::to_string(n) + " values, " + std::to_string(q.nx) + " x " + std::to_string(q.ny) +
                 " starts each; " + q.precision.text();
  fig.xlabel = parameter_label(r.request.vary);
  fig.ylabel = "share of the starts (stacked)";
  fig.width = 1300;
  fig.height = 720;
  return fig;
}

std::string attractors_sweep_text(const AttractorsSweepResult& r) {
  std::ostringstream o;
  o << r.chains.size() << " attractor chain" << (r.chains.size() == 1 ? "" : "s") << " over " << name(r.request.vary) << " in "
    << r.request.lo.text() << ".." << r.request.hi.text() << " (" << r.values.size() << " values):\n";
  for (const AttractorChain& c : r.chains) {
    double lo = 1, hi = 0;
    for (size_t k = 0; k < c.index.size(); ++k)
      if (c.index[k] >= 0) {
        const double f = r.at[k].attractors[static_cast<size_t>(c.index[k])].fraction;
        lo = std::min(lo, f);
        hi = std::max(hi, f);
      }
    o << "  chain " << c.id << ": " << chain_title(c) << " at " << name(r.request.vary) << " = " << presence(r, c) << ", share "
      << g(lo, 3) << ".." << g(hi, 3);
    if (r.branches && r.branches->chain_branch[static_cast<size_t>(c.id)] >= 0)
      o << ", branch " << r.branches->chain_branch[static_cast<size_t>(c.id)];
    o << "\n";
    if (r.branches)
      for (const ChainTransition& t : r.branches->transitions[static_cast<size_t>(c.id)])
        o << "      " << transition_sentence(r, static_cast<size_t>(c.id), t) << "\n";
  }
  if (r.branches) {
    const std::string vary = name(r.request.vary);
    long explained = 0, certified = 0, transitions = 0, split = 0;
    for (size_t c = 0; c < r.chains.size(); ++c)
      for (const ChainTransition& t : r.branches->transitions[c]) {
        ++transitions;
        split += same_branch_chain(r, c, t) >= 0;
        if (t.event < 0) continue;
        ++explained;
        certified += r.branches->branches[static_cast<size_t>(t.branch)].events[static_cast<size_t>(t.event)].certified;
      }
    o << r.branches->branches.size() << " branch" << (r.branches->branches.size() == 1 ? "" : "es")
      << " continued from the periodic chains (" << g(r.branches->seconds, 3) << " s); " << explained << " of " << transitions
      << " appearances and disappearances explained by a branch event, " << certified << " of them certified; " << split
      << " where the branch goes on as another chain; " << transitions - explained - split << " not explained:\n";
    for (size_t b = 0; b < r.branches->branches.size(); ++b) {
      const ContinuedBranch& cb = r.branches->branches[b];
      o << "  branch " << b << ": " << (cb.kind == AttractorKind::sticking ? "sticking cycle, k = " : "period ") << cb.period
        << " from " << vary << " = " << r.values[cb.from_value].text() << " (chain";
      for (size_t i = 0; i < cb.chains.size(); ++i) o << (i ? ", " : " ") << cb.chains[i];
      o << ")";
      if (!cb.started) {
        o << ": not started (" << cb.note << ")\n";
        continue;
      }
      o << ", " << vary << " in [" << cb.low_param << ", " << cb.high_param << "], events " << cb.events_text << "\n";
      for (const BranchEventInfo& e : cb.events)
        if (!(e.end && (e.kind == "range_end" || e.kind == "max_points")))
          o << "      " << (e.end ? (e.high ? "high end: " : "low end: ") : "on the way: ") << event_sentence(e, vary) << "\n";
    }
  }
  return o.str();
}

}  // namespace bouncer
