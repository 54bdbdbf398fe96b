// The pictures of the grid results (io/grid_figures.hpp).
#include "bouncer/io/grid_figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <tuple>

#include "bouncer/analysis/periodic.hpp"

namespace bouncer {

namespace {

// The share of n among the starts in the phase space, as the legends print it: " (12.3%)".
std::string share_text(long n, double inside) {
  char pct[32];
  std::snprintf(pct, sizeof pct, " (%.1f%%)", inside > 0 ? 100.0 * n / inside : 0.0);
  return pct;
}

}  // namespace

size_t pixel_of(size_t i, long nx, long ny) {
  const long col = static_cast<long>(i) % nx, row = ny - 1 - static_cast<long>(i) / nx;
  return static_cast<size_t>(row * nx + col);
}

std::string parameters_text(const ModelSpec& m) {
  std::string par = "a = " + m.a.text();
  if (m.law == Law::constant) par += ", ε = " + m.eps.text();
  if (m.law == Law::veldep) par += ", c = " + m.c.text();
  return par;
}

std::string parameter_label(Parameter p) {
  switch (p) {
    case Parameter::a: return "a (dimensionless gravity)";
    case Parameter::eps: return "ε (restitution)";
    case Parameter::c: return "c (restitution velocity scale)";
  }
  return name(p);
}

std::string model_name(const ModelSpec& m) {
  std::string s = model_title(m.law) + " model";
  if (m.wall.shape == WallShape::sine) s += ", sine wall";
  else if (m.wall.text != "triangle") s += ", " + m.wall.text + " wall";
  return s;
}

std::string model_title(Law law) {
  switch (law) {
    case Law::constant: return "constant restitution";
    case Law::veldep: return "velocity-dependent restitution";
    case Law::elastic: return "elastic";
  }
  return name(law);
}

Rgb attractor_color(OrbitClass cls, int rank, int sub_rank, Palette palette) {
  const bool paper = palette == Palette::paper;
  if (cls == OrbitClass::fixed || (paper && cls == OrbitClass::periodic)) return Rgb{0, 0, 0};
  switch (cls) {
    case OrbitClass::sticking: {
      if (paper) return Rgb{215, 25, 28};
      static const Rgb reds[] = {{213, 94, 0}, {150, 50, 0}, {240, 150, 100}, {110, 30, 10}, {235, 110, 60}, {180, 80, 40}};
      return reds[sub_rank % 6];
    }
    case OrbitClass::unbounded: return paper ? Rgb{30, 70, 210} : Rgb{0, 114, 178};
    case OrbitClass::chaotic: return paper ? Rgb{0, 150, 40} : Rgb{0, 158, 115};
    case OrbitClass::transient_chaos: {  // pale greens: chaos that settled later
      static const Rgb greens[] = {{150, 215, 110}, {200, 240, 160}, {105, 170, 75}, {175, 200, 60}};
      return greens[sub_rank % 4];
    }
    case OrbitClass::quasiperiodic: return Rgb{150, 60, 200};
    case OrbitClass::effective_sticking: return Rgb{255, 170, 160};
    case OrbitClass::undecided: return Rgb{150, 150, 150};
    case OrbitClass::outside: return Rgb{238, 238, 238};
    default: return category_color(rank);  // periodic
  }
}

std::string attractor_label(OrbitClass cls, long period) {
  switch (cls) {
    case OrbitClass::fixed: return "fixed point";
    case OrbitClass::periodic: return "period " + std::to_string(period);
    case OrbitClass::sticking: return "sticking, k = " + std::to_string(period);
    case OrbitClass::effective_sticking: return "effective sticking";
    case OrbitClass::transient_chaos:
      return period ? "transient chaos, settles with period " + std::to_string(period)
                    : std::string("transient chaos, settles (no period)");
    case OrbitClass::outside: return "outside the phase space (v < wall velocity)";
    default: return name(cls);
  }
}

std::vector<ClassCount> attractor_census(const std::vector<AttractorCell>& cells) {
  std::map<std::pair<std::string, long>, long> count;
  for (const AttractorCell& c : cells) ++count[{name(c.cls), c.period}];
  std::vector<ClassCount> out;
  for (const auto& [k, n] : count) out.push_back({*orbit_class_named(k.first), k.second, n});
  std::stable_sort(out.begin(), out.end(), [](const ClassCount& x, const ClassCount& y) { return x.points > y.points; });
  return out;
}

std::vector<CertifiedCount> certified_census(const std::vector<CertifiedCell>& cells) {
  std::map<std::pair<std::string, long>, long> count;
  for (const CertifiedCell& c : cells) ++count[{name(c.cls), c.period}];
  std::vector<CertifiedCount> out;
  for (const auto& [k, n] : count) out.push_back({*certified_class_named(k.first), k.second, n});
  std::stable_sort(out.begin(), out.end(), [](const CertifiedCount& x, const CertifiedCount& y) { return x.points > y.points; });
  return out;
}

ImageFigure basin_figure(const BasinResult& b, Palette palette) {
  const BasinRequest& r = b.request;
  const std::vector<ClassCount> order = attractor_census(b.cells);
  std::map<std::pair<OrbitClass, long>, Rgb> color;
  int periodic_rank = 0, sticking_rank = 0, transient_rank = 0;
  for (const ClassCount& k : order) {
    const bool transient = k.cls == OrbitClass::transient_chaos;
    color[{k.cls, k.period}] = attractor_color(k.cls, periodic_rank, transient ? transient_rank : sticking_rank, palette);
    if (k.cls == OrbitClass::periodic) ++periodic_rank;
    if (k.cls == OrbitClass::sticking) ++sticking_rank;
    if (transient) ++transient_rank;
  }
  ImageFigure fig;
  Raster& ras = fig.raster;
  ras.nx = static_cast<int>(r.nx);
  ras.ny = static_cast<int>(r.ny);
  // The window in the coordinates of its axes: relative to an offset when a double cannot
  // resolve it (a zoom at mpfr:256), the values themselves otherwise.
  set_exact_window(ras, r.theta_lo.value(), r.theta_hi.value(), r.v_range->first.value(), r.v_range->second.value());
  ras.pixels.resize(b.cells.size());
  for (size_t i = 0; i < b.cells.size(); ++i) ras.pixels[pixel_of(i, r.nx, r.ny)] = color[{b.cells[i].cls, b.cells[i].period}];
  // Shares in the legend are of the points in the phase space: the starts below the wall
  // velocity ("outside") are no orbits and do not count in the denominator.
  long outside = 0;
  for (const ClassCount& k : order)
    if (k.cls == OrbitClass::outside) outside += k.points;
  const double inside = static_cast<double>(b.cells.size()) - static_cast<double>(outside);
  // Legend entries: one per colour. The paper palette gives every periodic type one black and
  // every sticking period one red, so those are summed into one entry each.
  struct Entry {
    std::string label;
    Rgb color;
    long points;
    bool outside;
  };
  std::vector<Entry> entries;
  for (const ClassCount& k : order) {
    std::string label = attractor_label(k.cls, k.period);
    if (palette == Palette::paper && (k.cls == OrbitClass::fixed || k.cls == OrbitClass::periodic)) label = "fixed point or periodic";
    if (palette == Palette::paper && k.cls == OrbitClass::sticking) label = "sticking";
    auto it = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) { return e.label == label; });
    if (it == entries.end()) entries.push_back({label, color[{k.cls, k.period}], k.points, k.cls == OrbitClass::outside});
    else it->points += k.points;
  }
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) { return x.points > y.points; });
  const size_t shown = entries.size() > 14 ? 13 : entries.size();
  for (size_t k = 0; k < shown; ++k)
    ras.legend.emplace_back(entries[k].label + (entries[k].outside ? "" : share_text(entries[k].points, inside)),
                            entries[k].color);
  if (shown < entries.size()) ras.legend.emplace_back("+" + std::to_string(entries.size() - shown) + " more types", Rgb{255, 255, 255});

  fig.title = "Basins of attraction, " + model_name(r.model);
  fig.subtitle = parameters_text(r.model) + "; " + std::to_string(r.nx) + " x " + std::to_string(r.ny) + " points, " +
                 std::to_string(r.classify.transient) + " + " + std::to_string(r.classify.steps) + " steps, " +
                 r.precision.text();
  fig.xlabel = "θ₀ (initial phase)";
  fig.ylabel = "v₀ (initial velocity)";
  fig.width = 1000;
  fig.height = 700;
  return fig;
}

CertifiedMap certified_map(const CertifiedBasinResult& b) {
  const BasinRequest& r = b.request;
  CertifiedMap m;
  m.x_name = "theta";
  m.y_name = "v";
  m.nx = r.nx;
  m.ny = r.ny;
  m.x0 = r.theta_lo.value();
  m.x1 = r.theta_hi.value();
  m.y0 = r.v_range->first.value();
  m.y1 = r.v_range->second.value();
  m.title = "Certified basins, " + model_name(r.model) + ": each coloured pixel is proved";
  m.subtitle = "a = " + r.model.a.text() +
               (r.model.law == Law::veldep ? ", c = " + r.model.c.text()
                : r.model.law == Law::constant ? ", ε = " + r.model.eps.text()
                                               : "") +
               "; " + std::to_string(r.nx) + " x " + std::to_string(r.ny) + " exact starts, " +
               std::to_string(r.cert.max_steps) + " steps, interval:double then MPFI up to " +
               std::to_string(r.cert.max_bits) + " bits";
  m.xlabel = "θ₀ (initial phase)";
  m.ylabel = "v₀ (initial velocity)";
  m.max_steps = r.cert.max_steps;
  m.max_bits = r.cert.max_bits;
  m.collapses = r.model.law == Law::constant;
  m.area_preserving = r.model.law == Law::elastic;
  return m;
}

CertifiedMap certified_map(const CertifiedScanResult& s) {
  const ScanRequest& r = s.request;
  CertifiedMap m;
  m.x_name = "a";
  m.y_name = name(s.y);
  m.nx = r.p;
  m.ny = r.q;
  m.x0 = r.a_lo.value();
  m.x1 = r.a_hi.value();
  m.y0 = r.y_lo.value();
  m.y1 = r.y_hi.value();
  m.title = "Certified parameter scan, " + model_name(r.model) + ": each coloured pixel is proved";
  m.subtitle = (r.start_at_release ? std::string("the orbit of the release state (θ_r, 2π cos 2πθ_r)")
                                   : "the orbit of (θ₀, v₀) = (" + r.start.theta.text() + ", " + r.start.v.text() + ")") +
               "; " + std::to_string(r.p) +
               " x " + std::to_string(r.q) + " exact parameter points, " + std::to_string(r.cert.max_steps) +
               " steps, interval:double then MPFI up to " + std::to_string(r.cert.max_bits) + " bits";
  m.xlabel = parameter_label(Parameter::a);
  m.ylabel = parameter_label(s.y);
  m.max_steps = r.cert.max_steps;
  m.max_bits = r.cert.max_bits;
  m.collapses = r.model.law == Law::constant;
  return m;
}

std::string certified_label(CertifiedClass cls, long period, long long max_steps, long max_bits, bool collapses,
                            bool area_preserving) {
  const std::string never = collapses ? "never sticks: " : "";
  switch (cls) {
    case CertifiedClass::sticking: return "sticking, k = " + std::to_string(period);
    case CertifiedClass::fixed: return never + "trapped at a fixed point";
    case CertifiedClass::periodic: return never + "trapped, period " + std::to_string(period);
    case CertifiedClass::no_sticking: return "no (further) sticking in ≥ " + std::to_string(max_steps) + " steps";
    case CertifiedClass::not_trapped:
      return area_preserving ? "exact orbit certified through " + std::to_string(max_steps) + " steps"
                             : "certified " + std::to_string(max_steps) + " steps, no trapping set";
    case CertifiedClass::undecided: return "undecided at " + std::to_string(max_bits) + " bits";
    case CertifiedClass::outside: break;
  }
  return "outside the phase space (v < wall velocity)";
}

std::pair<ImageFigure, ImageFigure> certified_figures(const CertifiedMap& m, const std::vector<CertifiedCell>& cells,
                                                      Palette palette) {
  long outside = 0;
  for (const CertifiedCell& c : cells) outside += c.agreement == Agreement::outside;
  const double inside = static_cast<double>(cells.size()) - static_cast<double>(outside);
  const std::vector<CertifiedCount> order = certified_census(cells);
  std::map<std::pair<CertifiedClass, long>, Rgb> color;
  int periodic_rank = 0, sticking_rank = 0;
  for (const CertifiedCount& k : order) {
    Rgb c;
    // pale blue: a weaker statement, and no colour of the attractor palette (whose sky blue
    // marks a periodic class); pale lavender: the same weak kind
    switch (k.cls) {
      case CertifiedClass::no_sticking: c = Rgb{198, 219, 239}; break;
      case CertifiedClass::not_trapped: c = Rgb{218, 210, 235}; break;
      case CertifiedClass::sticking: c = attractor_color(OrbitClass::sticking, periodic_rank, sticking_rank, palette); break;
      case CertifiedClass::fixed: c = attractor_color(OrbitClass::fixed, periodic_rank, sticking_rank, palette); break;
      case CertifiedClass::periodic: c = attractor_color(OrbitClass::periodic, periodic_rank, sticking_rank, palette); break;
      case CertifiedClass::undecided: c = attractor_color(OrbitClass::undecided, periodic_rank, sticking_rank, palette); break;
      case CertifiedClass::outside: c = attractor_color(OrbitClass::outside, periodic_rank, sticking_rank, palette); break;
    }
    color[{k.cls, k.period}] = c;
    if (k.cls == CertifiedClass::periodic) ++periodic_rank;
    if (k.cls == CertifiedClass::sticking) ++sticking_rank;
  }
  auto make_figure = [&](const std::string& title) {
    ImageFigure fig;
    fig.raster.nx = static_cast<int>(m.nx);
    fig.raster.ny = static_cast<int>(m.ny);
    set_exact_window(fig.raster, m.x0, m.x1, m.y0, m.y1);
    fig.raster.pixels.resize(cells.size());
    fig.title = title;
    fig.subtitle = m.subtitle;
    fig.xlabel = m.xlabel;
    fig.ylabel = m.ylabel;
    fig.width = 1000;
    fig.height = 700;
    return fig;
  };
  ImageFigure cert = make_figure(m.title);
  for (size_t i = 0; i < cells.size(); ++i) cert.raster.pixels[pixel_of(i, m.nx, m.ny)] = color[{cells[i].cls, cells[i].period}];
  // The legend names the 12 largest classes; a scan can have a hundred sticking periods,
  // which the CSV and the JSON list in full.
  constexpr size_t kLegendClasses = 12;
  long rest = 0;
  for (size_t j = 0; j < order.size(); ++j) {
    const CertifiedCount& k = order[j];
    const bool out = k.cls == CertifiedClass::outside;
    if (j >= kLegendClasses && order.size() > kLegendClasses + 1) {
      rest += out ? 0 : k.points;
      continue;
    }
    cert.raster.legend.emplace_back(certified_label(k.cls, k.period, m.max_steps, m.max_bits, m.collapses, m.area_preserving) +
                                        (out ? "" : share_text(k.points, inside)),
                                    color[{k.cls, k.period}]);
  }
  if (order.size() > kLegendClasses + 1)
    cert.raster.legend.emplace_back(std::to_string(order.size() - kLegendClasses) + " more classes" + share_text(rest, inside) +
                                        ": in the CSV and JSON",
                                    Rgb{255, 255, 255});
  // The artefact map: where double's class differs from the certified one.
  std::vector<Agreement> agreement;
  agreement.reserve(cells.size());
  for (const CertifiedCell& c : cells) agreement.push_back(c.agreement);
  ImageFigure art = agreement_figure(make_figure(""), agreement, m.nx, m.ny,
                                     {"Where double is wrong: double's class against the certified one", "double agrees",
                                      "double differs: an artefact", "no certified answer", ""},
                                     palette);
  return {std::move(cert), std::move(art)};
}

ImageFigure agreement_figure(ImageFigure frame, const std::vector<Agreement>& cells, long nx, long ny,
                             const AgreementWords& words, Palette palette) {
  long counts[4] = {0, 0, 0, 0};
  for (Agreement a : cells) ++counts[static_cast<int>(a)];
  const double compared = static_cast<double>(cells.size()) - static_cast<double>(counts[static_cast<int>(Agreement::outside)]);
  const Rgb agree_rgb{205, 205, 205}, differ_rgb = palette == Palette::paper ? Rgb{215, 25, 28} : Rgb{213, 94, 0},
            undecided_rgb{90, 90, 90}, outside_rgb{255, 255, 255};
  ImageFigure art = std::move(frame);
  art.title = words.title;
  art.raster.legend.clear();
  // The frame's own key (a scan's colour bar and notes) is not this map's.
  art.raster.colorbar.clear();
  art.raster.colorbar_ticks.clear();
  art.raster.colorbar_label.clear();
  art.raster.notes.clear();
  art.raster.pixels.assign(cells.size(), outside_rgb);
  for (size_t i = 0; i < cells.size(); ++i) {
    const Agreement a = cells[i];
    art.raster.pixels[pixel_of(i, nx, ny)] = a == Agreement::agrees      ? agree_rgb
                                             : a == Agreement::differs   ? differ_rgb
                                             : a == Agreement::undecided ? undecided_rgb
                                                                         : outside_rgb;
  }
  art.raster.legend.emplace_back(words.agrees + share_text(counts[static_cast<int>(Agreement::agrees)], compared), agree_rgb);
  art.raster.legend.emplace_back(words.differs + share_text(counts[static_cast<int>(Agreement::differs)], compared), differ_rgb);
  art.raster.legend.emplace_back(words.undecided + share_text(counts[static_cast<int>(Agreement::undecided)], compared),
                                 undecided_rgb);
  if (!words.outside.empty()) art.raster.legend.emplace_back(words.outside, outside_rgb);
  return art;
}

ImageFigure scan_figure(const ScanResult& s, std::optional<OrbitClass> show, bool fixed_point_curves, Palette palette) {
  const ScanRequest& r = s.request;
  ImageFigure fig;
  Raster& ras = fig.raster;
  ras.nx = static_cast<int>(r.p);
  ras.ny = static_cast<int>(r.q);
  // The window in the coordinates of its axes (relative to an offset for a zoom).
  const auto [zx, zy] = set_exact_window(ras, r.a_lo.value(), r.a_hi.value(), r.y_lo.value(), r.y_hi.value());
  ras.pixels.resize(s.cells.size());
  const bool paper = palette == Palette::paper;
  const Rgb paper_green{0, 150, 40};
  for (size_t i = 0; i < s.cells.size(); ++i) {
    const ScanCell& c = s.cells[i];
    const long inside = c.in_phase_space();
    const long regular_n = c[OrbitClass::fixed] + c[OrbitClass::periodic];
    const long hit = show ? c[*show] : regular_n;
    const double frac = inside > 0 ? static_cast<double>(hit) / inside : 0;
    const double regular = inside > 0 ? static_cast<double>(regular_n) / inside : 0;
    const double chaotic = inside > 0 ? static_cast<double>(c[OrbitClass::chaotic]) / inside : 0;
    Rgb px = viridis_color(frac);
    if (paper) {  // the paper's look: black where the starts are regular, green where chaotic
      auto ch = [&](double green) {
        return static_cast<std::uint8_t>(std::lround(255 * (1 - regular - chaotic) + green * chaotic));
      };
      px = Rgb{ch(paper_green.r), ch(paper_green.g), ch(paper_green.b)};
    }
    ras.pixels[pixel_of(i, r.p, r.q)] = px;
  }
  const std::string shown = show ? name(*show) : "fixed + periodic";
  if (paper) {
    ras.legend = {{"fixed + periodic (black: all starts)", Rgb{0, 0, 0}},
                  {"chaotic (green: all starts)", paper_green},
                  {"neither (sticking, ...)", Rgb{255, 255, 255}}};
    // The legend lists only colours some cell has; the blends need their rule stated.
    ras.notes = {"a cell mixes these by the shares of its starts"};
  } else {
    for (int i = 0; i < 64; ++i) ras.colorbar.push_back(viridis_color(i / 63.0));
    ras.colorbar_lo = 0;
    ras.colorbar_hi = 1;
    ras.colorbar_label = "share of starts " + shown;
  }
  if (fixed_point_curves) {
    // Paper eq. 5: the fixed points of the constant model exist at a = 8(1+eps)/(p(1-eps)),
    // p = 1..10 (fig. paramspace1's curves), drawn over the window in its axis coordinates.
    // Ten curves: each in its own colour of the qualitative palette (the paper palette: its
    // blue) and named "p = N" at its end, where it leaves the frame; the legend says what
    // they are.
    const double e0 = r.y_lo.value().get_d(), e1 = std::min(r.y_hi.value().get_d(), 1 - 1e-9);
    Series key;
    key.label = "eq. 5: a = 8(1+ε)/(p(1−ε))";
    key.color = paper ? Rgb{30, 70, 210} : Rgb{90, 90, 90};
    key.lines = true;
    key.markers = false;
    fig.overlay.push_back(key);
    for (int pp = 1; pp <= 10; ++pp) {
      Series curve;
      curve.label = "p = " + std::to_string(pp);
      curve.end_label = true;
      curve.color = paper ? Rgb{30, 70, 210} : series_color(pp - 1);
      curve.lines = true;
      curve.markers = false;
      for (int k = 0; k <= 400; ++k) {
        const double e = e0 + (e1 - e0) * k / 400.0;
        curve.x.push_back(zx(paper::fixed_point_a(e, pp)));
        curve.y.push_back(zy(e));
      }
      fig.overlay.push_back(curve);
    }
  }
  fig.title = "Parameter scan: " + shown + " solutions";
  fig.subtitle = model_name(r.model) + "; " + std::to_string(r.p) + " x " + std::to_string(r.q) +
                 " parameters, " + std::to_string(r.k) + " x " + std::to_string(r.k) + " initial conditions, " +
                 std::to_string(r.classify.transient) + " + " + std::to_string(r.classify.steps) + " steps, " +
                 r.precision.text();
  fig.xlabel = parameter_label(Parameter::a);
  fig.ylabel = parameter_label(s.y);
  return fig;
}

ImageFigure bifurcation_figure(const BifurcationResult& b, bool show_theta, long bins, Palette palette) {
  const BifurcationRequest& r = b.request;
  // Density raster: one column per parameter value, `bins` rows over the shown variable.
  double y0 = 0, y1 = 1;
  if (!show_theta) {
    y0 = std::numeric_limits<double>::infinity();
    y1 = -y0;
    for (const BifurcationColumn& col : b.columns)
      for (const BifurcationPoint& pt : col.points)
        if (std::isfinite(pt.v.value)) {
          y0 = std::min(y0, pt.v.value);
          y1 = std::max(y1, pt.v.value);
        }
    if (!std::isfinite(y0)) {
      y0 = 0;
      y1 = 1;
    }
    const double pad = std::max(1e-9, (y1 - y0) * 0.04);
    y0 -= pad;
    y1 += pad;
  }
  const int nx = static_cast<int>(std::min<long>(r.samples, 1600));
  const int ny = static_cast<int>(bins);
  auto column_of = [&](size_t k) { return r.samples == 1 ? 0 : static_cast<int>(static_cast<double>(k) * nx / r.samples); };
  std::vector<long> count(static_cast<size_t>(nx) * ny, 0);
  std::vector<char> stick(static_cast<size_t>(nx) * ny, 0);
  for (size_t k = 0; k < b.columns.size(); ++k) {
    const int col = column_of(k);
    for (const BifurcationPoint& pt : b.columns[k].points) {
      const double y = show_theta ? pt.theta.value : pt.v.value;
      if (!std::isfinite(y)) continue;
      const int row = std::clamp(static_cast<int>((y1 - y) / (y1 - y0) * ny), 0, ny - 1);
      const size_t at = static_cast<size_t>(row) * nx + col;
      if (pt.sticking) stick[at] = 1;
      else ++count[at];
    }
  }
  long max_count = 1;
  for (long c : count) max_count = std::max(max_count, c);
  ImageFigure fig;
  Raster& ras = fig.raster;
  ras.nx = nx;
  ras.ny = ny;
  // Each value's column is centred on it: the window reaches half a sample beyond the ends,
  // exactly, and is drawn relative to an offset when a double cannot resolve it (a zoom).
  const mpq_class half = r.samples == 1 ? mpq_class(1, 2) : mpq_class((r.hi.value() - r.lo.value()) / (2 * (r.samples - 1)));
  const mpq_class x_lo = r.lo.value() - half, x_hi = (r.samples == 1 ? r.lo.value() : r.hi.value()) + half;
  const AxisZoom zx(x_lo, x_hi);
  ras.x_min = zx(x_lo);
  ras.x_max = zx(x_hi);
  ras.x_offset = zx.offset();
  ras.y_min = y0;
  ras.y_max = y1;
  // Density of orbit points, log scale: grey to black (--palette paper, the paper's look) or
  // viridis from green (sparse) to dark purple (dense), both readable on the white background.
  const bool paper = palette == Palette::paper;
  const Rgb red = paper ? Rgb{215, 25, 28} : Rgb{213, 94, 0};
  auto density = [&](double t) { return paper ? ramp_color(0.45 + 0.55 * t) : viridis_color(0.75 * (1 - t)); };
  // --certify: the background of each column says what the certificate says of double there.
  // not_trapped (veldep, elastic): the exact orbit is certified through every step but its
  // class is not decided; pale lavender as in the certified basins, not the grey of "nothing
  // certified".
  const Rgb refuted_bg{250, 205, 185}, undecided_bg{222, 222, 222}, orbit_only_bg{218, 210, 235};
  long orbit_only = 0, differs = 0, undecided = 0;
  std::vector<Rgb> column_bg(static_cast<size_t>(nx), Rgb{255, 255, 255});
  for (size_t k = 0; k < b.columns.size(); ++k) {
    if (!b.columns[k].certified) continue;
    const CertifiedCell& c = *b.columns[k].certified;
    Rgb& bg = column_bg[static_cast<size_t>(column_of(k))];
    differs += c.agreement == Agreement::differs;
    undecided += c.agreement == Agreement::undecided;
    if (c.agreement == Agreement::differs) bg = refuted_bg;
    else if (c.agreement == Agreement::undecided && bg.r == 255)
      bg = c.cls == CertifiedClass::not_trapped ? orbit_only_bg : undecided_bg;
    orbit_only += c.cls == CertifiedClass::not_trapped;
  }
  for (size_t i = 0; i < count.size(); ++i) {
    if (stick[i]) ras.pixels.push_back(red);
    else if (count[i] == 0) ras.pixels.push_back(column_bg[i % static_cast<size_t>(nx)]);
    else ras.pixels.push_back(density(std::log1p(static_cast<double>(count[i])) / std::log1p(static_cast<double>(max_count))));
  }
  // The density's key is the colour bar (orbit points per cell, log scale, ticks at 1, 2, 5,
  // 10, ... up to the densest cell); the legend names the marks (a sticking release only
  // where one is drawn: the renderer leaves out classes no cell has).
  {
    const double full = std::log1p(static_cast<double>(max_count));
    const double lo = max_count > 1 ? std::log1p(1.0) / full : 0;  // one point per cell at most: one colour
    for (int i = 0; i < 64; ++i) ras.colorbar.push_back(density(lo + (1 - lo) * i / 63.0));
    ras.colorbar_lo = lo;
    ras.colorbar_hi = 1;
    ras.colorbar_label = "orbit points per cell (log scale)";
    for (long decade = 1; decade <= max_count; decade *= 10)
      for (long m : {1L, 2L, 5L})
        if (m * decade <= max_count) {
          // Every 1-2-5 step while there are few decades, only the powers of ten beyond.
          if (m != 1 && max_count > 1000) continue;
          ras.colorbar_ticks.emplace_back(max_count > 1 ? std::log1p(static_cast<double>(m * decade)) / full : 1,
                                          std::to_string(m * decade));
        }
  }
  const bool sine = r.model.wall.shape == WallShape::sine;
  ras.legend = {{show_theta ? (sine ? "sticking release (θ where the wall's acceleration is -a)" : "sticking release (θ = 1/2)")
                            : (sine ? "sticking release (v = the wall's velocity there)" : "sticking release (v = 4)"),
                 red}};
  if (r.certify) {
    ras.legend.emplace_back("double refuted by the certificate (" + std::to_string(differs) + " values)", refuted_bg);
    if (orbit_only > 0)
      ras.legend.emplace_back("orbit certified, class open (" + std::to_string(orbit_only) + " values)", orbit_only_bg);
    ras.legend.emplace_back("no certified answer (" + std::to_string(undecided - orbit_only) + " values)", undecided_bg);
  }
  ras.legend_below = true;
  fig.title = "Bifurcation diagram, " + model_name(r.model);
  std::string fixed;
  if (r.vary != Parameter::a) fixed += "a = " + r.model.a.text() + ", ";
  if (r.model.law == Law::constant && r.vary != Parameter::eps) fixed += "ε = " + r.model.eps.text() + ", ";
  if (r.model.law == Law::veldep && r.vary != Parameter::c) fixed += "c = " + r.model.c.text() + ", ";
  fig.subtitle = fixed + "θ₀ = " + r.start.theta.text() + ", v₀ = " + r.start.v.text() + "; " + std::to_string(r.transient) +
                 " + " + std::to_string(r.record) + " steps x " + std::to_string(r.samples) + (r.carry ? " (carried)" : "") +
                 ", " + r.precision.text() +
                 (r.certify ? "; columns certified (interval:double, then MPFI up to " + std::to_string(r.cert.max_bits) + " bits)"
                            : "");
  fig.xlabel = parameter_label(r.vary);
  fig.ylabel = show_theta ? "θ (phase of impact)" : "v (velocity after impact)";
  return fig;
}

std::string certified_map_csv(const CertifiedMap& m, const std::vector<Number>& xs, const std::vector<Number>& ys,
                              const std::vector<CertifiedCell>& cells) {
  std::string csv = m.x_name + "," + m.y_name + ",class,period,certified_steps,scalar,double_class,double_period,agreement\n";
  for (size_t i = 0; i < cells.size(); ++i)
    csv += xs[i % static_cast<size_t>(m.nx)].digits + ',' + ys[i / static_cast<size_t>(m.nx)].digits + ',' + encode(cells[i]) + '\n';
  return csv;
}

ImageFigure basin_confirm_figure(const BasinResult& b, Palette palette) {
  const BasinRequest& r = b.request;
  const auto [first, second] = check_precisions(r.precision, r.confirm.bits);
  const std::string hi = first.text();
  std::vector<Agreement> a;
  a.reserve(b.cells.size());
  for (const AttractorCell& c : b.cells)
    a.push_back(!c.confirm                                    ? Agreement::outside
                : *c.confirm == PrecisionVerdict::agrees      ? Agreement::agrees
                : *c.confirm == PrecisionVerdict::artefact    ? Agreement::differs
                                                              : Agreement::undecided);
  const std::string own = r.precision.text();
  return agreement_figure(basin_figure(b, palette), a, r.nx, r.ny,
                          {"Where " + own + " is wrong: its class against " + hi + " and " + second.text(),
                           hi + " agrees", own + "'s class is an artefact", "precision dependent",
                           "not confirmed (outside the sample or the phase space)"},
                          palette);
}

// A parameter point of the sample is "an artefact" where at least one of its confirmed starts
// is (double's class there is not what mpfr:B and mpfr:2B both give), else "precision
// dependent" where one is, else "agrees"; points outside the sample are not confirmed.
ImageFigure scan_confirm_figure(const ScanResult& s, Palette palette) {
  const ScanRequest& r = s.request;
  const auto [first, second] = check_precisions(r.precision, r.confirm.bits);
  const std::string hi = first.text();
  std::vector<Agreement> a;
  a.reserve(s.cells.size());
  for (const ScanCell& c : s.cells)
    a.push_back(!c.confirmed                                                        ? Agreement::outside
                : c.verdicts[static_cast<size_t>(PrecisionVerdict::artefact)] > 0            ? Agreement::differs
                : c.verdicts[static_cast<size_t>(PrecisionVerdict::precision_dependent)] > 0 ? Agreement::undecided
                                                                                             : Agreement::agrees);
  const std::string own = r.precision.text();
  return agreement_figure(scan_figure(s, std::nullopt, false, palette), a, r.p, r.q,
                          {"Where " + own + " is wrong: each point's starts against " + hi + " and " + second.text(),
                           "every start agrees", "an artefact at some start", "precision dependent at some start",
                           "not confirmed (outside the sample)"},
                          palette);
}

}  // namespace bouncer
