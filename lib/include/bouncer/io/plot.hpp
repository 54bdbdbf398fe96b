// Pictures a person would put in a paper: line/scatter plots and density images with axes,
// tick labels, title and a legend, written as PNG (libpng) with provenance in tEXt chunks.
// Text is drawn with a built-in bitmap font, so no font package is needed.
// (Implemented in lib/src/io/plot.cpp; the font is lib/src/io/plot_font.inc.)
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace bouncer {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb& x, const Rgb& y) { return x.r == y.r && x.g == y.g && x.b == y.b; }
};

struct Series {
  std::string label;           // legend entry (empty: no entry)
  std::vector<double> x, y;
  Rgb color{0, 0, 0};
  bool lines = false;          // connect the points
  bool markers = true;         // draw the points
  int marker_size = 2;         // marker radius in pixels (0: one pixel)
  // Vertical error bars: y[i] +- yerr[i] (empty: none; non-finite entries: no bar).
  std::vector<double> yerr = {};
};

struct Figure {
  std::string title, xlabel, ylabel;
  std::vector<Series> series;
  bool log_y = false;
  int width = 900, height = 600;
  // Written as PNG tEXt chunks (key, value): provenance, inputs, ...
  std::vector<std::pair<std::string, std::string>> metadata;
  // Axis ranges; NaN = from the data (with a small margin).
  double x_min = NAN, x_max = NAN, y_min = NAN, y_max = NAN;
  bool equal_aspect = false;   // one data unit is as long on both axes (polar plots)
  std::string subtitle;        // a second, smaller line under the title (parameters)
  bool legend_below = false;   // legend in rows under the plot instead of at the right
};

// A raster over a rectangle of data space (row 0 = top = y_max), e.g. a density image of a
// bifurcation diagram or a basin of attraction, drawn inside axes with a legend.
struct Raster {
  int nx = 0, ny = 0;
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  std::vector<Rgb> pixels;  // nx * ny, row-major from the top
  std::vector<std::pair<std::string, Rgb>> legend;
  // Optional colour bar beside the image: ramp[0] at colorbar_lo ... ramp.back() at _hi.
  std::vector<Rgb> colorbar;
  double colorbar_lo = 0, colorbar_hi = 1;
  std::string colorbar_label;
  bool legend_below = false;  // legend in rows under the image instead of at the right
};

struct ImageFigure {
  std::string title, xlabel, ylabel;
  Raster raster;
  int width = 900, height = 700;
  std::vector<std::pair<std::string, std::string>> metadata;
  std::string subtitle;
};

// Throw std::runtime_error on I/O failure. Write atomically (PATH.partial, then rename).
void write_png(const std::string& path, const Figure& f);
void write_png(const std::string& path, const ImageFigure& f);

// Axis ticks: "nice" values (1, 2 or 5 times a power of ten apart) inside [lo, hi], about
// `target` of them (at least 2 when lo < hi), with labels that tell them apart.
struct Ticks {
  std::vector<double> values;
  std::vector<std::string> labels;
  double step = 0;
};
Ticks nice_ticks(double lo, double hi, int target = 6);
// Decades (and 2, 5 multiples when the range is short) for a logarithmic axis, lo > 0.
Ticks log_ticks(double lo, double hi);

// A perceptually ordered colour ramp (dark to light), t in [0, 1].
Rgb ramp_color(double t);
// Distinct colours for categories (attractors): index 0, 1, ... never red or blue, which
// are reserved for sticking and unbounded orbits.
Rgb category_color(int index);

}  // namespace bouncer
