// Pictures a person would put in a paper: line/scatter plots and density images with axes,
// tick labels, title and a legend. One drawing code (Cairo) for three formats: PNG (an
// antialiased image surface written with libpng, provenance in tEXt chunks), PDF and SVG
// (vector; provenance in the PDF document information and an SVG <metadata> element).
// Text uses one fixed font file, DejaVu Sans (Debian package fonts-dejavu-core), loaded with
// FreeType: no fontconfig lookup, so the output does not depend on the machine's fonts.
// Identical inputs give identical bytes in every format (no dates are written).
// (Implemented in lib/src/io/plot.cpp.)
#pragma once

#include <gmpxx.h>

#include <cmath>
#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace bouncer {

// ---- Zooms: axes narrower than a double resolves -------------------------------------------
// A window such as theta in [0.3, 0.3 + 1e-20] (a basin at mpfr:256) has ends that are the
// same double. Such an axis is drawn in coordinates t relative to the window:
//   value = origin + t * 10^exponent,
// the origin an exact decimal near the window and 10^exponent <= window width < 10^(exponent+1),
// so only t, of order 1, is a double and a window 1e-20 wide draws like any other. The
// ticks are nice values of t, labelled with t, and the axis title says what t is, as a
// physics journal labels a shifted and scaled axis (quantity over unit, ISO 80000-1):
// "θ0 - 0.3, in units of 1e-20" under ticks 0.0, 0.2, ..., 1.0.
struct AxisOffset {
  std::string origin;  // exact decimal text; empty: no offset (coordinates are the values)
  int exponent = 0;    // the unit is 10^exponent
  bool active() const { return !origin.empty(); }
};

// The coordinates of one axis whose window is [lo, hi], computed exactly from the values
// (a value of any precision converts exactly to a rational). An offset when plain tick
// labels would need more than about 8 significant digits (the window is narrower than 1e-7
// of its largest magnitude); otherwise the identity, so ordinary windows draw as always.
class AxisZoom {
 public:
  AxisZoom() = default;  // the identity
  AxisZoom(const mpq_class& lo, const mpq_class& hi);
  const AxisOffset& offset() const { return offset_; }
  bool active() const { return offset_.active(); }
  // t = (x - origin) / 10^exponent, or x itself without an offset; rounded to a double.
  double operator()(const mpq_class& x) const;
  // The same for a double value, without rationals (for many data points).
  double operator()(double x) const;
  // Units of t per unit of value: 10^-exponent, or 1 (for lengths such as error bars).
  double scale() const { return scale_d_; }

 private:
  AxisOffset offset_;
  mpq_class origin_, scale_;            // t = (x - origin) * scale
  double origin_d_ = 0, origin_err_ = 0, scale_d_ = 1;  // origin ~ origin_d_ + origin_err_
};

// The title of an axis: LABEL, or for an offset axis "LABEL - ORIGIN, in units of UNIT"
// ("+ 3" for the origin -3; UNIT as 1e-20, or 0.01 ... 1000 for exponents -3 ... 3; no
// "in units" when the unit is 1).
std::string axis_title(const std::string& label, const AxisOffset& offset);
// x rounded to a multiple of 10^exponent (halves up), as decimal text: a value on a zoomed
// axis printed with the digits the zoom resolves ("26.00000000000000000000512").
std::string decimal_rounded(const mpq_class& x, int exponent);
// The value a tick label t of an offset axis stands for, origin + t * 10^exponent, as an
// exact decimal text (the identity's labels stand for themselves).
std::string tick_value(const std::string& label, const AxisOffset& offset);

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
  bool dashed = false;         // the connecting line is dashed (also in the legend)
  // The label is written at the curve's end (where it leaves the frame: in a column right of
  // the frame, or a row above it), in the curve's colour, instead of in the legend; labels
  // that would overlap are moved apart (spread_labels) with a leader line to their curve.
  bool end_label = false;
};

struct Figure {
  std::string title, xlabel, ylabel;
  std::vector<Series> series;
  bool log_y = false;          // base-10 logarithmic y axis (positive values only)
  bool log_x = false;          // logarithmic x axis in base log_x_base (2: ticks at powers of two)
  double log_x_base = 10;
  int width = 900, height = 600;
  // Written as PNG tEXt chunks (key, value): provenance, inputs, ...
  std::vector<std::pair<std::string, std::string>> metadata;
  // Axis ranges; NaN = from the data (with a small margin).
  double x_min = NAN, x_max = NAN, y_min = NAN, y_max = NAN;
  bool equal_aspect = false;   // one data unit is as long on both axes (polar plots)
  std::string subtitle;        // a second, smaller line under the title (parameters)
  bool legend_below = false;   // legend in rows under the plot instead of in the frame's best corner
  // Zoomed axes (AxisZoom): the series and x_min/x_max (y_min/y_max) are t coordinates of
  // these offsets. Inactive: plain values, and a window too narrow for plain tick labels
  // (from the data or the limits) is given an offset here (not with equal_aspect or log_y).
  AxisOffset x_offset, y_offset;
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
  // The colour bar's ticks at these values in [colorbar_lo, colorbar_hi] with these labels
  // (e.g. counts on a log scale); empty: nice ticks of [colorbar_lo, colorbar_hi].
  std::vector<std::pair<double, std::string>> colorbar_ticks;
  // Lines of text under the legend, without a swatch ("+3 more types").
  std::vector<std::string> notes;
  bool legend_below = false;  // legend in rows under the image instead of at the right
  // Zoomed axes (AxisZoom): x_min/x_max (y_min/y_max) are t coordinates of these offsets.
  // Inactive: plain values, and a window too narrow for plain tick labels gets an offset.
  AxisOffset x_offset, y_offset;
};

// Set the raster's window [x0, x1] x [y0, y1], given as exact values, in the coordinates of
// its axes: relative to an offset where a double cannot resolve the window (AxisZoom), the
// values themselves otherwise. Returns the two axes' maps, for drawing over the raster.
std::pair<AxisZoom, AxisZoom> set_exact_window(Raster& r, const mpq_class& x0, const mpq_class& x1, const mpq_class& y0, const mpq_class& y1);

// Text written over the picture at (x, y) in axis coordinates, centred there, in `color`
// with a white halo so that it reads on any background (direct labels of regions). One that
// would overlap an earlier one is left out: put the most important first.
struct Annotation {
  double x = 0, y = 0;
  std::string text;
  Rgb color{0, 0, 0};
};

struct ImageFigure {
  std::string title, xlabel, ylabel;
  Raster raster;
  std::vector<Annotation> annotations;
  // Curves drawn over the raster, clipped to its frame, in the raster's axis coordinates
  // (t coordinates of its offsets); labelled ones join the legend.
  std::vector<Series> overlay;
  int width = 900, height = 700;
  std::vector<std::pair<std::string, std::string>> metadata;
  std::string subtitle;
};

enum class ImageFormat { png, pdf, svg };
// Colours of categories and densities: safe (Okabe-Ito categories, viridis densities,
// colour-blind safe) or paper (the paper's: black periodic, red sticking, green chaos).
enum class Palette { safe, paper };
// "png", "pdf", "svg" (also the file extension without its dot).
const char* format_name(ImageFormat f);

// How a figure is rendered (presentation only: it changes no computed value).
// width, height: pixels of the PNG; the PDF/SVG page is width*72/dpi x height*72/dpi points.
// 0: the figure's own width/height (set for kDefaultDpi) scaled by dpi/kDefaultDpi, so that a
// 900 x 600 figure is 6 x 4 inches at any dpi (1800 x 1200 pixels at 300). Text sizes are set
// in points at `dpi` (9.5 pt body text, shrunk on small canvases). The PNG records dpi (pHYs).
constexpr double kDefaultDpi = 150;
struct RenderOptions {
  int width = 0, height = 0;
  double dpi = kDefaultDpi;
};
// Limits of RenderOptions (the command line checks them: exit 2 naming the option).
constexpr int kMinFigureWidth = 200, kMinFigureHeight = 150, kMaxFigureSide = 20000;
constexpr double kMinDpi = 36, kMaxDpi = 2400;

// The font file every figure's text is drawn with, and a check that it can be loaded
// (OutputError naming the Debian package fonts-dejavu-core if not).
const char* figure_font_path();
void check_figure_font();

// Throw std::runtime_error (OutputError for I/O and a missing font) on failure. The stream
// forms write the picture's bytes to `out` (an OutputSet's file: base/output.hpp); the path
// forms write one file through write_output (staged, then renamed into place).
void write_figure(std::ostream& out, const Figure& f, ImageFormat format, const RenderOptions& r = {});
void write_figure(std::ostream& out, const ImageFigure& f, ImageFormat format, const RenderOptions& r = {});
void write_figure(const std::string& path, const Figure& f, ImageFormat format, const RenderOptions& r = {});
void write_figure(const std::string& path, const ImageFigure& f, ImageFormat format, const RenderOptions& r = {});
inline void write_png(const std::string& path, const Figure& f) { write_figure(path, f, ImageFormat::png); }
inline void write_png(const std::string& path, const ImageFigure& f) { write_figure(path, f, ImageFormat::png); }

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
// Powers of `base` (> 1; 10 gives log_ticks) inside [lo, hi], at most about 10 of them
// (every k-th power on a long range); labels are the values (64, 128, ...) or base^k.
Ticks log_ticks(double lo, double hi, double base);

// A grey density ramp, white (t = 0) to near-black (t = 1): the paper's look.
Rgb ramp_color(double t);
// A perceptually uniform, colour-blind-safe ramp (viridis: dark purple at 0, yellow at 1).
Rgb viridis_color(double t);
// A qualitative palette for curves and point series on white: index 0, 1, ... are
// told apart by colour (CIE76 delta E >= 25 between any two of the first 20) and none is
// faint on white (CIE L* <= 72); the first seven are the Okabe-Ito colours without its
// yellow (colour-blind safe), the rest chosen greedily for the largest smallest delta E at
// moderate chroma. Beyond 20 the colours repeat darker. Ten or more
// curves should also carry their labels (Series::end_label): no palette tells ten curves
// apart for every reader.
Rgb series_color(int index);
// CIE L*a*b* of an sRGB colour (D65) and the CIE76 colour difference of two colours.
struct Lab {
  double l = 0, a = 0, b = 0;
};
Lab to_lab(Rgb c);
double delta_e76(Rgb x, Rgb y);

// Label placement on one axis: labels of extent `size` wanted at centres `wanted` (any
// order) inside [lo, hi]; returns centres in the same order, at least `size` apart, each as
// near its wanted place as that allows (clusters of touching labels are centred on their
// wanted mean, then pushed inside [lo, hi]; if they do not fit, they are packed from lo).
std::vector<double> spread_labels(const std::vector<double>& wanted, double size, double lo, double hi);

// What a drawn figure shows, for checks: the legend entries and notes drawn (in order), the
// colour bar's tick labels (empty: no colour bar) and the boxes (figure pixels) of the
// direct labels (end labels, annotations), of the tick labels and of the frame.
struct TextBox {
  std::string text;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
struct FigureLayout {
  std::vector<std::string> legend, notes;
  bool colorbar = false;
  std::vector<std::string> colorbar_ticks;
  std::vector<TextBox> direct_labels, tick_labels;
  TextBox frame;
};
FigureLayout figure_layout(const Figure& f, const RenderOptions& r = {});
FigureLayout figure_layout(const ImageFigure& f, const RenderOptions& r = {});

// Distinct colours for categories (attractors): index 0, 1, ... never red or blue, which
// are reserved for sticking and unbounded orbits. The first ones are Okabe-Ito colours
// (distinguishable with the common colour-vision deficiencies).
Rgb category_color(int index);

}  // namespace bouncer
