// The pictures of portraits and exponent curves (io/curve_figures.hpp).
#include "bouncer/io/curve_figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "bouncer/io/grid_figures.hpp"

namespace bouncer {

namespace {

// The exact value of a number as printed (a decimal with the digits of its precision).
mpq_class exact_of(const Number& x) {
  const auto d = Decimal::parse(x.digits);
  if (!d) throw std::runtime_error("not a finite decimal: '" + x.digits + "'");
  return d->value();
}

// One axis of the (theta, v) picture: its window when given, and how values are placed.
struct PortraitAxis {
  AxisZoom zoom;
  double lo = -INFINITY, hi = INFINITY;  // a little beyond the window, in double
  explicit PortraitAxis(const std::optional<std::pair<Decimal, Decimal>>& w) {
    if (!w) return;
    zoom = AxisZoom(w->first.value(), w->second.value());
    lo = std::nextafter(std::nextafter(w->first.approx(), -INFINITY), -INFINITY);
    hi = std::nextafter(std::nextafter(w->second.approx(), INFINITY), INFINITY);
  }
  // The coordinate of a value; NaN when it lies outside a zoomed window (a zoom places each
  // point from its exact value, so points far outside are not converted).
  double operator()(const Number& x) const {
    if (!zoom.active()) return x.value;
    if (!(x.value >= lo && x.value <= hi)) return NAN;
    return zoom(exact_of(x));
  }
};

}  // namespace

PortraitCounts portrait_counts(const PortraitResult& p) {
  PortraitCounts c;
  for (const PortraitOrbit& o : p.orbits) {
    c.points += static_cast<long>(o.points.size());
    c.undecided_orbits += o.undecided_step.has_value();
    for (const PortraitPoint& q : o.points) c.max_v = std::max(c.max_v, q.v.value);
  }
  return c;
}

Figure portrait_figure(const PortraitResult& p, const PortraitView& view) {
  const PortraitRequest& r = p.request;
  const size_t orbits = p.orbits.size();
  Figure fig;
  const double two_pi = 2 * std::acos(-1.0);
  const PortraitAxis ax(view.theta_window), ay(view.v_window);
  for (size_t k = 0; k < orbits; ++k) {
    Series s;
    s.color = orbits == 1 ? Rgb{20, 20, 20} : series_color(static_cast<int>(k) + 1);  // (index 0 is black)
    s.marker_size = static_cast<size_t>(r.steps) * orbits > 20000 ? 0 : 1;
    if (k < 12) s.label = "θ₀ = " + r.starts[k].theta.text() + ", v₀ = " + r.starts[k].v.text();
    for (const PortraitPoint& q : p.orbits[k].points) {
      const double th = q.theta.value, v = q.v.value;
      if (view.polar) {
        s.x.push_back(v * std::cos(two_pi * th));
        s.y.push_back(v * std::sin(two_pi * th));
      } else {
        const double x = ax(q.theta), y = ay(q.v);
        if (!std::isnan(x) && !std::isnan(y)) {
          s.x.push_back(x);
          s.y.push_back(y);
        }
      }
    }
    fig.series.push_back(std::move(s));
  }
  // Labels of starts with many digits (a zoom) need the width of the picture: legend below.
  for (const Series& s : fig.series) fig.legend_below = fig.legend_below || s.label.size() > 40;
  if (orbits > 12) {
    Series more;
    more.label = "... " + std::to_string(orbits - 12) + " more orbits";
    more.color = Rgb{160, 160, 160};
    fig.series.push_back(more);
  }
  fig.title = std::string(view.polar ? "Polar phase portrait, " : "Phase portrait, ") + model_name(r.model);
  std::string par = "a = " + r.model.a.text();
  if (r.model.law == Law::constant) par += ", ε = " + r.model.eps.text();
  if (r.model.law == Law::veldep) par += ", c = " + r.model.c.text();
  fig.subtitle = par + "; " + std::to_string(orbits) + (orbits == 1 ? " orbit, " : " orbits, ") + std::to_string(r.steps) +
                 " steps" + (r.transient ? " after " + std::to_string(r.transient) : "") + ", " + r.precision.text();
  if (view.polar) {
    fig.xlabel = "v cos(2πθ)";
    fig.ylabel = "v sin(2πθ)";
    fig.equal_aspect = true;
    fig.height = 800;
    fig.width = 1000;
  } else {
    fig.xlabel = "θ (phase of impact)";
    fig.ylabel = "v (velocity after impact)";
    fig.x_min = 0;
    fig.x_max = 1;
    if (view.theta_window) {
      fig.x_min = ax.zoom(view.theta_window->first.value());
      fig.x_max = ax.zoom(view.theta_window->second.value());
      fig.x_offset = ax.zoom.offset();
    }
    if (view.v_window) {
      fig.y_min = ay.zoom(view.v_window->first.value());
      fig.y_max = ay.zoom(view.v_window->second.value());
      fig.y_offset = ay.zoom.offset();
    }
  }
  return fig;
}

std::vector<CurveClassCount> exponent_census(const ExponentCurveResult& c) {
  long counts[kOrbitClassCount] = {};
  for (const ExponentColumn& col : c.columns)
    for (const ExponentRow& row : col.rows) ++counts[static_cast<int>(row.cls)];
  std::vector<CurveClassCount> out;
  for (int k = 0; k < kOrbitClassCount; ++k)
    if (counts[k]) out.push_back({static_cast<OrbitClass>(k), counts[k]});
  std::sort(out.begin(), out.end(), [](const CurveClassCount& x, const CurveClassCount& y) {
    return x.rows != y.rows ? x.rows > y.rows : std::string_view(name(x.cls)) < std::string_view(name(y.cls));
  });
  return out;
}

Figure exponent_curve_figure(const ExponentCurveResult& c, Palette palette) {
  const ExponentCurveRequest& r = c.request;
  // The x window: the range and 2% beyond each end, exactly; relative to an offset when a
  // double cannot resolve it (a zoom), and then each value is placed from its exact digits.
  const mpq_class lo = r.lo.value(), hi = r.hi.value();
  const mpq_class margin = r.samples == 1 ? mpq_class(1, 2) : mpq_class((hi - lo) / 50);
  const mpq_class x_lo = lo - margin, x_hi = (r.samples == 1 ? lo : hi) + margin;
  const AxisZoom zx(x_lo, x_hi);
  long not_drawn = 0;
  std::vector<double> xs;  // per column
  for (const ExponentColumn& col : c.columns) {
    xs.push_back(zx.active() ? zx(exact_of(col.value)) : col.value.value);
    for (const ExponentRow& row : col.rows) not_drawn += !std::isfinite(row.lambda);
  }

  // One series per class (legend order: by count, then name), error bars +- stderr, and the
  // zero line that separates contraction from chaos.
  Figure fig;
  {
    Series zero;
    zero.x = {zx(lo), zx(hi)};
    zero.y = {0, 0};
    zero.lines = true;
    zero.markers = false;
    zero.color = Rgb{120, 120, 120};
    fig.series.push_back(zero);
  }
  const int marker = r.samples * r.ics > 2000 ? 1 : r.samples * r.ics > 300 ? 2 : 3;
  int sticking_rank = 0;
  for (const CurveClassCount& k : exponent_census(c)) {
    Series s;
    s.color = attractor_color(k.cls, 0, sticking_rank, palette);
    if (k.cls == OrbitClass::sticking) ++sticking_rank;
    std::string label = name(k.cls);
    std::replace(label.begin(), label.end(), '_', ' ');
    s.label = label + " (" + std::to_string(k.rows) + ")";
    s.marker_size = marker;
    for (size_t i = 0; i < c.columns.size(); ++i)
      for (const ExponentRow& row : c.columns[i].rows)
        if (row.cls == k.cls) {
          s.x.push_back(xs[i]);
          s.y.push_back(row.lambda);
          s.yerr.push_back(row.stderr_);
        }
    fig.series.push_back(std::move(s));
  }
  const std::string vary = name(r.vary);
  fig.title = "Leading Lyapunov exponent, " + model_name(r.model);
  std::string fixed;
  if (r.vary != Parameter::a) fixed += "a = " + r.model.a.text() + ", ";
  if (r.model.law == Law::constant && r.vary != Parameter::eps) fixed += "ε = " + r.model.eps.text() + ", ";
  if (r.model.law == Law::veldep && r.vary != Parameter::c) fixed += "c = " + r.model.c.text() + ", ";
  fig.subtitle = fixed + std::to_string(r.samples) + " values x " + std::to_string(r.ics) + " start" + (r.ics == 1 ? "" : "s") +
                 ", " + std::to_string(r.lyapunov.transient) + " + " + std::to_string(r.lyapunov.steps) + " steps, " +
                 r.precision.text() + (not_drawn ? "; " + std::to_string(not_drawn) + " with λ = −∞ or NaN not drawn" : "");
  fig.xlabel = parameter_label(r.vary);
  fig.ylabel = "λ per collision (± standard error)";
  fig.legend_below = true;
  fig.x_min = zx(x_lo);
  fig.x_max = zx(x_hi);
  fig.x_offset = zx.offset();
  return fig;
}

}  // namespace bouncer
