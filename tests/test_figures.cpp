// What a referee checks in a figure, as properties of the drawing logic (io/plot.hpp's
// FigureLayout: what the renderer actually drew), not pixels copied from the program:
// the curve palette's colour distances (CIE76, against published CIELAB values), the label
// placement (no overlaps, as near as possible), legends that list only what is drawn, colour
// bars where a density is drawn, direct labels that overlap nothing, and axis titles that
// name their quantity; and the contact sheet (thumbnails in reading order, read back with
// Cairo's PNG reader).
#include <cairo/cairo.h>  // (the library links Cairo; its headers are not on the suites' path)
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "bouncer/base/error.hpp"
#include "bouncer/io/attractors.hpp"
#include "bouncer/io/contact_sheet.hpp"
#include "bouncer/io/grid_figures.hpp"
#include "bouncer/io/plot.hpp"

using namespace bouncer;

namespace {

Decimal dec(const char* s) { return *Decimal::parse(s); }

bool contains(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }
bool any_starts_with(const std::vector<std::string>& v, const std::string& prefix) {
  return std::any_of(v.begin(), v.end(), [&](const std::string& s) { return s.rfind(prefix, 0) == 0; });
}
bool overlap(const TextBox& a, const TextBox& b) { return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1; }

// No two boxes overlap, none overlaps the tick labels, and all lie in the canvas.
void expect_clear(const FigureLayout& lay, double w, double h) {
  for (size_t i = 0; i < lay.direct_labels.size(); ++i) {
    const TextBox& a = lay.direct_labels[i];
    EXPECT_GE(a.x0, 0) << a.text;
    EXPECT_LE(a.x1, w) << a.text;
    EXPECT_GE(a.y0, 0) << a.text;
    EXPECT_LE(a.y1, h) << a.text;
    for (size_t j = i + 1; j < lay.direct_labels.size(); ++j)
      EXPECT_FALSE(overlap(a, lay.direct_labels[j])) << a.text << " / " << lay.direct_labels[j].text;
    for (const TextBox& t : lay.tick_labels) EXPECT_FALSE(overlap(a, t)) << a.text << " / tick " << t.text;
  }
}

}  // namespace

// ---- colours ----------------------------------------------------------------------------------

TEST(Palette, LabConversionMatchesPublishedValues) {
  // sRGB (D65) to CIELAB reference values (e.g. Lindbloom's calculator, brucelindbloom.com).
  const Lab white = to_lab(Rgb{255, 255, 255}), black = to_lab(Rgb{0, 0, 0}), red = to_lab(Rgb{255, 0, 0});
  EXPECT_NEAR(white.l, 100, 0.01);
  EXPECT_NEAR(white.a, 0, 0.01);
  EXPECT_NEAR(white.b, 0, 0.01);
  EXPECT_NEAR(black.l, 0, 1e-9);
  EXPECT_NEAR(red.l, 53.24, 0.05);
  EXPECT_NEAR(red.a, 80.09, 0.05);
  EXPECT_NEAR(red.b, 67.20, 0.05);
  const Lab blue = to_lab(Rgb{0, 0, 255});
  EXPECT_NEAR(blue.l, 32.30, 0.05);
  EXPECT_NEAR(blue.a, 79.19, 0.05);
  EXPECT_NEAR(blue.b, -107.86, 0.05);
  // CIE76 is the Euclidean distance: white to black is 100.
  EXPECT_NEAR(delta_e76(Rgb{255, 255, 255}, Rgb{0, 0, 0}), 100, 0.01);
}

TEST(Palette, TenAndTwentyCurvesAreToldApartAndNoneIsFaintOnWhite) {
  for (int n : {10, 20}) {
    double worst = 1e9;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) worst = std::min(worst, delta_e76(series_color(i), series_color(j)));
    // 25 is several times the just-noticeable difference (about 2.3) and well above the
    // 10 or so at which thin lines of two colours are confused.
    EXPECT_GE(worst, 25) << n << " series";
  }
  for (int i = 0; i < 20; ++i) {
    EXPECT_LE(to_lab(series_color(i)).l, 72) << "series " << i << " is faint on white";
    EXPECT_GE(delta_e76(series_color(i), Rgb{255, 255, 255}), 30) << i;
  }
  // The case: the old category colours gave p = 2 and p = 8 (indices 1 and 7) nearly
  // the same blue.
  EXPECT_GE(delta_e76(series_color(1), series_color(7)), 25);
}

// ---- label placement ---------------------------------------------------------------------

TEST(Labels, SpreadLabelsKeepsFarLabelsAndSeparatesCloseOnes) {
  // Far apart: unchanged.
  const std::vector<double> far = spread_labels({10, 50, 90}, 5, 0, 100);
  EXPECT_DOUBLE_EQ(far[0], 10);
  EXPECT_DOUBLE_EQ(far[1], 50);
  EXPECT_DOUBLE_EQ(far[2], 90);
  // Two wanted at the same place: one size apart, centred on it.
  const std::vector<double> two = spread_labels({40, 40}, 6, 0, 100);
  EXPECT_DOUBLE_EQ(std::min(two[0], two[1]), 37);
  EXPECT_DOUBLE_EQ(std::max(two[0], two[1]), 43);
  // Against the upper end: pushed inside [lo, hi].
  const std::vector<double> top = spread_labels({99, 99.5, 100}, 4, 0, 100);
  for (double y : top) EXPECT_LE(y, 100 - 2 + 1e-9);
  EXPECT_NEAR(std::max({top[0], top[1], top[2]}) - std::min({top[0], top[1], top[2]}), 8, 1e-9);
}

TEST(Labels, RandomWishesNeverOverlapAndKeepTheirOrder) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + static_cast<int>(rng() % 25);
    const double size = 1 + (rng() % 100) / 10.0, lo = 0, hi = 300;
    std::uniform_real_distribution<double> u(-20, 320);
    std::vector<double> wanted(static_cast<size_t>(n));
    for (double& w : wanted) w = u(rng);
    const std::vector<double> at = spread_labels(wanted, size, lo, hi);
    ASSERT_EQ(at.size(), wanted.size());
    std::vector<size_t> order(wanted.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return wanted[a] < wanted[b]; });
    for (size_t k = 1; k < order.size(); ++k)  // same order as wished, at least one size apart
      EXPECT_GE(at[order[k]] - at[order[k - 1]], size - 1e-9);
    if (n * size <= hi - lo)
      for (double y : at) {
        EXPECT_GE(y, lo + size / 2 - 1e-9);
        EXPECT_LE(y, hi - size / 2 + 1e-9);
      }
  }
}

// ---- legends list only what is drawn ---------------------------------------------------------

TEST(Legend, RasterClassesWithoutACellAndCurvesOutsideTheWindowAreLeftOut) {
  ImageFigure f;
  Raster& r = f.raster;
  r.nx = 2;
  r.ny = 1;
  const Rgb a{10, 20, 30}, b{200, 100, 0}, c{0, 200, 0};
  r.pixels = {a, b};
  r.legend = {{"class a", a}, {"class b", b}, {"class c (no cell)", c}};
  r.notes = {"+3 more types"};
  Series inside, outside, key;
  inside.label = "inside";
  inside.x = {0.2, 0.8};
  inside.y = {0.5, 0.5};
  outside.label = "outside";
  outside.x = {3, 4};
  outside.y = {3, 4};
  key.label = "a line style (no points: a key)";
  f.overlay = {inside, outside, key};
  const FigureLayout lay = figure_layout(f);
  EXPECT_EQ(lay.legend, (std::vector<std::string>{"class a", "class b", "inside", "a line style (no points: a key)"}));
  EXPECT_EQ(lay.notes, (std::vector<std::string>{"+3 more types"}));
  EXPECT_FALSE(lay.colorbar);
}

TEST(Legend, ArtefactMapNamesTheUncomparedCellsOnlyWhenThereAreAny) {
  ImageFigure frame;
  frame.raster.nx = 2;
  frame.raster.ny = 2;
  frame.raster.pixels.assign(4, Rgb{255, 255, 255});
  const AgreementWords words{"artefacts", "agrees", "differs", "undecided", "not confirmed"};
  const std::vector<Agreement> all{Agreement::agrees, Agreement::agrees, Agreement::differs, Agreement::agrees};
  const FigureLayout full = figure_layout(agreement_figure(frame, all, 2, 2, words, Palette::safe));
  EXPECT_FALSE(any_starts_with(full.legend, "not confirmed"));
  EXPECT_FALSE(any_starts_with(full.legend, "undecided"));  // no such cell either
  EXPECT_TRUE(any_starts_with(full.legend, "agrees"));
  EXPECT_TRUE(any_starts_with(full.legend, "differs"));
  const std::vector<Agreement> sample{Agreement::agrees, Agreement::outside, Agreement::outside, Agreement::undecided};
  const FigureLayout part = figure_layout(agreement_figure(frame, sample, 2, 2, words, Palette::safe));
  EXPECT_TRUE(contains(part.legend, "not confirmed"));
  EXPECT_TRUE(any_starts_with(part.legend, "undecided"));
  EXPECT_FALSE(any_starts_with(part.legend, "differs"));
}

// The artefact map drawn over another figure's frame (a scan's, which has a colour bar and
// notes) shows only its own key: the four agreement classes, no colour bar, no notes.
TEST(Legend, ArtefactMapDropsTheFramesOwnKey) {
  ImageFigure frame;
  frame.raster.nx = 2;
  frame.raster.ny = 1;
  frame.raster.pixels.assign(2, Rgb{255, 255, 255});
  frame.raster.colorbar = {Rgb{0, 0, 0}, Rgb{255, 255, 0}};
  frame.raster.colorbar_label = "share of starts";
  frame.raster.notes = {"a cell mixes these"};
  const AgreementWords words{"artefacts", "agrees", "differs", "undecided", "not confirmed"};
  const FigureLayout with_frame = figure_layout(frame);
  ASSERT_TRUE(with_frame.colorbar) << "the frame itself must show its colour bar, or this test proves nothing";
  const FigureLayout lay = figure_layout(agreement_figure(frame, {Agreement::agrees, Agreement::differs}, 2, 1, words, Palette::safe));
  EXPECT_FALSE(lay.colorbar);
  EXPECT_TRUE(lay.notes.empty());
  EXPECT_TRUE(any_starts_with(lay.legend, "agrees"));
  EXPECT_TRUE(any_starts_with(lay.legend, "differs"));
}

// A bifurcation result by hand: `columns` columns over a in [20, 21], each with the given
// points (theta; sticking).
BifurcationResult bifurcation(int columns, bool with_sticking) {
  BifurcationResult b;
  b.request.lo = dec("20");
  b.request.hi = dec("21");
  b.request.samples = columns;
  b.request.record = 50;
  for (int k = 0; k < columns; ++k) {
    BifurcationColumn col;
    col.value.value = 20 + k / (columns - 1.0);
    for (int i = 0; i < 50; ++i) {
      BifurcationPoint p;
      p.theta.value = (k % 3 == 0) ? 0.25 : std::fmod(0.618 * i, 1.0);  // a dense line and a spread
      p.v.value = 5 + i % 7;
      col.points.push_back(p);
    }
    if (with_sticking && k == columns / 2) {
      BifurcationPoint s;
      s.theta.value = 0.5;
      s.v.value = 4;
      s.sticking = true;
      col.points.push_back(s);
    }
    b.columns.push_back(col);
  }
  return b;
}

TEST(Legend, BifurcationDensityHasAColourBarAndNamesStickingOnlyWhereDrawn) {
  for (Palette palette : {Palette::safe, Palette::paper}) {
    const FigureLayout plain = figure_layout(bifurcation_figure(bifurcation(30, false), true, 100, palette));
    EXPECT_TRUE(plain.colorbar);
    // Counts on the bar: the densest cell has 50 points (the line at theta = 1/4).
    EXPECT_EQ(plain.colorbar_ticks, (std::vector<std::string>{"1", "2", "5", "10", "20", "50"}));
    EXPECT_FALSE(any_starts_with(plain.legend, "sticking release"));
    const FigureLayout sticky = figure_layout(bifurcation_figure(bifurcation(30, true), true, 100, palette));
    EXPECT_TRUE(sticky.colorbar);
    EXPECT_TRUE(any_starts_with(sticky.legend, "sticking release"));
  }
}

// ---- direct labels -----------------------------------------------------------------------------

ScanResult scan(bool curves_window_top) {
  ScanResult s;
  ScanRequest& r = s.request;
  r.model.law = Law::constant;
  r.a_lo = dec("10");
  r.a_hi = dec("30");
  r.y_lo = dec("0.05");
  r.y_hi = dec(curves_window_top ? "0.95" : "0.6");
  r.p = 8;
  r.q = 6;
  r.k = 2;
  s.y = Parameter::eps;
  for (int i = 0; i < 48; ++i) {
    ScanCell c;
    c.count[static_cast<size_t>(i % 3 == 0 ? OrbitClass::periodic : OrbitClass::chaotic)] = 4;
    s.cells.push_back(c);
  }
  return s;
}

TEST(DirectLabels, TheTenEq5CurvesOfTheScanAreNamedAtTheirEndsWithoutOverlap) {
  for (bool paper_window : {true, false}) {
    const ImageFigure fig = scan_figure(scan(paper_window), std::nullopt, true, Palette::safe);
    const FigureLayout lay = figure_layout(fig);
    std::vector<std::string> named;
    for (const TextBox& b : lay.direct_labels) named.push_back(b.text);
    // In the paper's window (a in [10, 30], eps in [0.05, 0.95]) every curve shows. With
    // eps up to 0.6 curve p reaches a >= 10 only if a(0.6) = 8 * 1.6 / (0.4 p) = 32 / p >= 10:
    // p = 1, 2, 3 (p = 1 leaves through the right edge, a(0.6) = 32 > 30; 2 and 3 through
    // the top); the others are not drawn and not named.
    const int shown = paper_window ? 10 : 3;
    EXPECT_EQ(named.size(), static_cast<size_t>(shown));
    for (int p = 1; p <= shown; ++p) EXPECT_TRUE(contains(named, "p = " + std::to_string(p))) << p;
    for (const std::string& n : named) EXPECT_FALSE(contains(lay.legend, n)) << n << " in the legend too";
    EXPECT_TRUE(lay.colorbar);  // the share is a density: its key is the bar
    expect_clear(lay, fig.width, fig.height);
    // Each named curve is drawn: the legend's key explains them.
    EXPECT_TRUE(any_starts_with(lay.legend, "eq. 5"));
  }
}

TEST(DirectLabels, CrowdedCurveEndsOfALinePlotAreSpreadApart) {
  // Twelve curves ending within 5% of the height of each other at the right edge (the
  // Arnold tongues at a = 30): the labels must not overlap each other or the ticks.
  Figure f;
  f.width = 1000;
  f.height = 760;
  f.x_min = 0;
  f.x_max = 30;
  f.y_min = 0;
  f.y_max = 1;
  for (int p = 1; p <= 12; ++p) {
    Series s;
    s.label = "p = " + std::to_string(p);
    s.end_label = true;
    s.lines = true;
    s.markers = false;
    s.color = series_color(p - 1);
    for (int k = 0; k <= 100; ++k) {
      const double a = 0.3 * k, r = a * p / 8;  // eq. 5 solved for eps: (r - 1)/(r + 1)
      s.x.push_back(a);
      s.y.push_back(r > 1 ? (r - 1) / (r + 1) : NAN);
    }
    f.series.push_back(s);
  }
  const FigureLayout lay = figure_layout(f);
  EXPECT_EQ(lay.direct_labels.size(), 12u);
  EXPECT_TRUE(lay.legend.empty());
  expect_clear(lay, f.width, f.height);
  // All right of the frame: the curves leave through its right edge.
  for (const TextBox& b : lay.direct_labels) EXPECT_GT(b.x0, lay.frame.x1) << b.text;
}

TEST(DirectLabels, CurvesLeavingThroughTheTopAreNamedAboveTheFrame) {
  Figure f;
  f.x_min = 0;
  f.x_max = 10;
  f.y_min = 0;
  f.y_max = 10;
  for (int k = 1; k <= 4; ++k) {
    Series s;
    s.label = "slope " + std::to_string(k);
    s.end_label = true;
    s.lines = true;
    s.markers = false;
    s.x = {0, 20};
    s.y = {0, 20.0 * k};  // leaves through the top at x = 10 / k
    f.series.push_back(s);
  }
  const FigureLayout lay = figure_layout(f);
  ASSERT_EQ(lay.direct_labels.size(), 4u);
  for (const TextBox& b : lay.direct_labels) {
    if (b.text == "slope 1") {
      EXPECT_GT(b.x0, lay.frame.x1);  // through the corner (10, 10): the right column
    } else {
      EXPECT_LT(b.y1, lay.frame.y0);  // above the frame
    }
  }
  expect_clear(lay, f.width, f.height);
}

// ---- axis titles -------------------------------------------------------------------------------

TEST(AxisTitles, ParameterAxesNameTheirSymbolAndQuantity) {
  for (Parameter p : {Parameter::a, Parameter::eps, Parameter::c}) {
    const std::string t = parameter_label(p);
    // A symbol, then its meaning in parentheses: never a lone glyph.
    EXPECT_NE(t.find(" ("), std::string::npos) << t;
    EXPECT_EQ(t.back(), ')') << t;
  }
  EXPECT_EQ(parameter_label(Parameter::eps).rfind("ε (", 0), 0u);
  const ImageFigure fig = scan_figure(scan(true), std::nullopt, false, Palette::safe);
  EXPECT_EQ(fig.xlabel, parameter_label(Parameter::a));
  EXPECT_EQ(fig.ylabel, parameter_label(Parameter::eps));
}

// ---- the stacked basin shares of attractors --vary -------------------------------------------

TEST(StackedShares, AHundredChainsAreColouredByFamilyAndTheLargeBandsTagged) {
  // 6 values, 20 attractors at each: the first with 43% of the starts, 19 with 3%; 120
  // chains of 40 periods (3 chains each).
  AttractorsSweepResult r;
  r.request.lo = dec("20");
  r.request.hi = dec("21");
  r.request.values = 6;
  r.request.point.model.law = Law::veldep;
  for (int k = 0; k < 6; ++k) {
    r.values.push_back(*Decimal::parse(std::to_string(20 + k * 0.2).substr(0, 4)));
    AttractorsResult at;
    for (int i = 0; i < 20; ++i) {
      FoundAttractor a;
      a.kind = AttractorKind::periodic;
      a.period = 2 + (k * 20 + i) % 40;
      a.fraction = i == 0 ? 0.43 : 0.03;
      at.attractors.push_back(a);
    }
    r.at.push_back(at);
  }
  for (int c = 0; c < 120; ++c) {
    AttractorChain ch;
    ch.id = c;
    ch.kind = AttractorKind::periodic;
    ch.period = 2 + c % 40;
    ch.index.assign(6, -1);
    ch.index[static_cast<size_t>(c / 20)] = c % 20;
    r.chains.push_back(ch);
  }
  const ImageFigure fig = attractors_sweep_figure(r, Palette::safe);
  const FigureLayout lay = figure_layout(fig);
  // 12 families in colour and one entry for the 28 others (undecided: no cell, left out).
  ASSERT_EQ(lay.legend.size(), 13u);
  EXPECT_EQ(lay.legend.back().rfind("28 smaller families", 0), 0u);
  EXPECT_FALSE(any_starts_with(lay.legend, "undecided"));
  for (size_t i = 0; i < 12; ++i)
    for (size_t j = i + 1; j < 12; ++j)
      EXPECT_GE(delta_e76(fig.raster.legend[i].second, fig.raster.legend[j].second), 10) << lay.legend[i] << " / " << lay.legend[j];
  // The six 43% bands carry their tags (the periods of chains 0, 20, ..., 100: 2, 22, 2, 22,
  // 2, 22); the 3% bands are too thin for text.
  ASSERT_EQ(lay.direct_labels.size(), 6u);
  for (size_t i = 0; i < 6; ++i) EXPECT_TRUE(lay.direct_labels[i].text == "P2" || lay.direct_labels[i].text == "P22");
  expect_clear(lay, fig.width, fig.height);
}

// ---- contact sheet -----------------------------------------------------------------------------

TEST(ContactSheet, ThumbnailsAppearInReadingOrderAndAMissingFileWritesNothing) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("bouncer-sheet-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // Five figures, each one raster cell of its own colour (a large uniform area).
  const Rgb colours[] = {{200, 30, 30}, {30, 160, 30}, {30, 30, 200}, {200, 160, 30}, {120, 30, 160}};
  std::vector<std::string> files;
  for (int i = 0; i < 5; ++i) {
    ImageFigure f;
    f.title = "figure " + std::to_string(i);
    f.raster.nx = f.raster.ny = 1;
    f.raster.pixels = {colours[i]};
    files.push_back((dir / ("f" + std::to_string(i) + ".png")).string());
    write_png(files.back(), f);
  }
  ContactSheetOptions o;
  o.columns = 2;
  o.thumb_width = 300;
  const std::string sheet = (dir / "sheet.png").string();
  const std::pair<int, int> size = write_contact_sheet(files, sheet, o);
  // Read back with Cairo's own PNG reader (not the writer's libpng path).
  cairo_surface_t* img = cairo_image_surface_create_from_png(sheet.c_str());
  ASSERT_EQ(cairo_surface_status(img), CAIRO_STATUS_SUCCESS);
  const int w = cairo_image_surface_get_width(img), h = cairo_image_surface_get_height(img);
  EXPECT_EQ(w, size.first);
  EXPECT_EQ(h, size.second);
  EXPECT_GE(w, 2 * 300);   // two columns of 300-pixel thumbnails
  EXPECT_LT(w, 2 * 300 + 200);
  const unsigned char* data = cairo_image_surface_get_data(img);
  const int stride = cairo_image_surface_get_stride(img);
  std::vector<double> cx(5, 0), cy(5, 0);
  std::vector<long> n(5, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint32_t px;
      std::memcpy(&px, data + static_cast<size_t>(y) * stride + 4 * static_cast<size_t>(x), 4);
      const Rgb c{static_cast<std::uint8_t>(px >> 16), static_cast<std::uint8_t>(px >> 8), static_cast<std::uint8_t>(px)};
      for (int i = 0; i < 5; ++i)
        if (c == colours[i]) {
          cx[i] += x;
          cy[i] += y;
          ++n[i];
        }
    }
  cairo_surface_destroy(img);
  for (int i = 0; i < 5; ++i) {
    ASSERT_GT(n[i], 5000) << "thumbnail " << i;  // about 0.3^2 of the raster's area
    cx[i] /= n[i];
    cy[i] /= n[i];
  }
  // Reading order: 0 1 / 2 3 / 4.
  EXPECT_LT(cx[0], cx[1]);
  EXPECT_NEAR(cy[0], cy[1], 2);
  EXPECT_LT(cy[1], cy[2]);
  EXPECT_NEAR(cx[0], cx[2], 2);
  EXPECT_NEAR(cx[2], cx[4], 2);
  EXPECT_LT(cy[3], cy[4]);
  // A missing picture: an error naming it, and no sheet (not even a partial one).
  const std::string other = (dir / "other.png").string();
  std::vector<std::string> bad = files;
  bad.push_back((dir / "missing.png").string());
  EXPECT_THROW(write_contact_sheet(bad, other, o), OutputError);
  EXPECT_FALSE(fs::exists(other));
  EXPECT_FALSE(fs::exists(other + ".partial"));
  EXPECT_THROW(write_contact_sheet({}, other, o), std::invalid_argument);
  fs::remove_all(dir);
}
