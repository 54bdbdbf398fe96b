// The pictures of the orbit grids (run/): phase portraits (run/portrait.hpp) and exponent
// curves (run/exponent_curve.hpp), built from the typed results, with the counts their
// summaries print. The commands add the provenance (PNG metadata) and write them.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "bouncer/io/plot.hpp"
#include "bouncer/run/exponent_curve.hpp"
#include "bouncer/run/portrait.hpp"

namespace bouncer {

// What a portrait shows: (theta, v), in a window when given (any width: points are placed
// from their exact values when a double cannot resolve it; default theta in [0, 1], v from
// the data), or polar (angle 2 pi theta, radius v, equal scales; no window).
struct PortraitView {
  bool polar = false;
  std::optional<std::pair<Decimal, Decimal>> theta_window, v_window;
};

// Over every orbit: how many points, how many orbits stopped at an undecided step, the
// largest v (0 when there is no point).
struct PortraitCounts {
  long points = 0, undecided_orbits = 0;
  double max_v = 0;
};
PortraitCounts portrait_counts(const PortraitResult& p);

// One series per orbit (one colour each; the first 12 starts in the legend).
Figure portrait_figure(const PortraitResult& p, const PortraitView& view);

// How many rows (value x start) have each class, largest first (ties: by the class's name).
struct CurveClassCount {
  OrbitClass cls = OrbitClass::undecided;
  long rows = 0;
};
std::vector<CurveClassCount> exponent_census(const ExponentCurveResult& c);

// Lambda against the parameter with +- stderr bars, the zero line, one colour per class
// (the colours of the basins, io/grid_figures.hpp) with its count in the legend; rows with
// lambda -inf or NaN are counted in the subtitle, not drawn.
Figure exponent_curve_figure(const ExponentCurveResult& c, Palette palette);

}  // namespace bouncer
