// PNG figures decoded back with libpng (size, colours where they belong, tEXt provenance,
// atomic writes), PDF and SVG renderings (page size, font, metadata, no dates), the legend's
// placement, overlay curves clipped to the frame, the properties of the tick generators
// (linear, log10, log2), the colour ramps, and zoomed axes (offsets and their
// labels against hand-derived cases and exact rational arithmetic).
#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include "bouncer/io/plot.hpp"
#include "bouncer/scalar/decimal.hpp"

using namespace bouncer;
namespace fs = std::filesystem;

namespace {

struct Decoded {
  int width = 0, height = 0;
  long pixels_per_metre = 0;  // pHYs, when given in metres and square
  std::vector<std::uint8_t> rgb;
  std::map<std::string, std::string> text;
  Rgb at(int x, int y) const {
    const size_t i = (static_cast<size_t>(y) * width + x) * 3;
    return Rgb{rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

// An independent reader: libpng's classic API, any colour type converted to RGB8.
bool decode(const std::string& path, Decoded& out) {
  FILE* fp = std::fopen(path.c_str(), "rb");
  if (!fp) return false;
  unsigned char sig[8];
  if (std::fread(sig, 1, 8, fp) != 8 || png_sig_cmp(sig, 0, 8) != 0) {
    std::fclose(fp);
    return false;
  }
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(fp);
    return false;
  }
  png_init_io(png, fp);
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  out.width = static_cast<int>(png_get_image_width(png, info));
  out.height = static_cast<int>(png_get_image_height(png, info));
  png_uint_32 res_x = 0, res_y = 0;
  int unit = 0;
  if (png_get_pHYs(png, info, &res_x, &res_y, &unit) && unit == PNG_RESOLUTION_METER && res_x == res_y)
    out.pixels_per_metre = static_cast<long>(res_x);
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_strip_alpha(png);
  png_set_gray_to_rgb(png);
  png_read_update_info(png, info);
  EXPECT_EQ(png_get_rowbytes(png, info), static_cast<size_t>(out.width) * 3);
  out.rgb.assign(static_cast<size_t>(out.width) * out.height * 3, 0);
  std::vector<png_bytep> rows(static_cast<size_t>(out.height));
  for (int y = 0; y < out.height; ++y) rows[static_cast<size_t>(y)] = out.rgb.data() + static_cast<size_t>(y) * out.width * 3;
  png_read_image(png, rows.data());
  png_read_end(png, info);
  png_textp text = nullptr;
  int n = 0;
  png_get_text(png, info, &text, &n);
  for (int i = 0; i < n; ++i) out.text[text[i].key] = std::string(text[i].text, text[i].text_length);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(fp);
  return true;
}

struct TempDir {
  fs::path path;
  TempDir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("bouncer-test-plot-" + std::to_string(rd()) + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

bool same(Rgb a, Rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

mpq_class q(const std::string& decimal) {
  const auto d = Decimal::parse(decimal);
  EXPECT_TRUE(d.has_value()) << decimal;
  return d ? d->value() : mpq_class(0);
}

mpq_class pow10q(int e) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(std::abs(e)));
  return e < 0 ? mpq_class(mpz_class(1), p) : mpq_class(p);
}

// The ticks of an axis window [lo, hi] as the picture labels them.
Ticks zoomed_ticks(const AxisZoom& z, const mpq_class& lo, const mpq_class& hi, int target = 6) {
  return nice_ticks(z(lo), z(hi), target);
}

}  // namespace

TEST(Plot, FigureDecodesToItsSizeWithMetadataAndNoPartialFile) {
  TempDir tmp;
  Figure f;
  f.title = "Test θ ε";
  f.xlabel = "x";
  f.ylabel = "y";
  f.width = 640;
  f.height = 480;
  Series s;
  s.label = "line";
  s.lines = true;
  s.color = Rgb{200, 0, 0};
  for (int i = 0; i <= 100; ++i) {
    s.x.push_back(i);
    s.y.push_back(i * i);
  }
  f.series.push_back(s);
  f.metadata = {{"Title", "Test"}, {"bouncer:provenance", "{\"command\": \"test\"}"}};
  const std::string path = (tmp.path / "fig.png").string();
  write_png(path, f);
  EXPECT_FALSE(fs::exists(path + ".partial"));
  Decoded d;
  ASSERT_TRUE(decode(path, d));
  EXPECT_EQ(d.width, 640);
  EXPECT_EQ(d.height, 480);
  EXPECT_EQ(d.text["Title"], "Test");
  EXPECT_EQ(d.text["bouncer:provenance"], "{\"command\": \"test\"}");
  EXPECT_NE(d.text["Software"].find("bouncer"), std::string::npos);
  // Background white at the corner; the series colour is drawn somewhere.
  EXPECT_TRUE(same(d.at(0, 0), Rgb{255, 255, 255}));
  long red = 0;
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x) red += same(d.at(x, y), Rgb{200, 0, 0});
  EXPECT_GT(red, 200);
}

TEST(Plot, RasterCellsLandInTheirQuadrants) {
  TempDir tmp;
  ImageFigure f;
  f.title = "quadrants";
  f.width = 500;
  f.height = 400;
  Raster& r = f.raster;
  r.nx = 2;
  r.ny = 2;
  const Rgb tl{250, 0, 0}, tr{0, 250, 0}, bl{0, 0, 250}, br{250, 250, 0};
  r.pixels = {tl, tr, bl, br};  // row 0 is the top
  r.legend = {{"a", Rgb{1, 2, 3}}};
  const std::string path = (tmp.path / "img.png").string();
  write_png(path, f);
  Decoded d;
  ASSERT_TRUE(decode(path, d));
  EXPECT_EQ(d.width, 500);
  EXPECT_EQ(d.height, 400);
  auto centroid = [&](Rgb c, double& cx, double& cy) {
    long n = 0;
    cx = cy = 0;
    for (int y = 0; y < d.height; ++y)
      for (int x = 0; x < d.width; ++x)
        if (same(d.at(x, y), c)) { cx += x; cy += y; ++n; }
    if (n) { cx /= n; cy /= n; }
    return n;
  };
  double x1, y1, x2, y2, x3, y3, x4, y4;
  ASSERT_GT(centroid(tl, x1, y1), 1000);
  ASSERT_GT(centroid(tr, x2, y2), 1000);
  ASSERT_GT(centroid(bl, x3, y3), 1000);
  ASSERT_GT(centroid(br, x4, y4), 1000);
  EXPECT_LT(x1, x2);
  EXPECT_LT(y1, y3);
  EXPECT_LT(x3, x4);
  EXPECT_LT(y2, y4);
  EXPECT_NEAR(x1, x3, 2);
  EXPECT_NEAR(y1, y2, 2);
}

TEST(Plot, FailedWriteThrowsAndLeavesNothing) {
  TempDir tmp;
  Figure f;
  const std::string path = (tmp.path / "missing-dir" / "fig.png").string();
  EXPECT_THROW(write_png(path, f), std::runtime_error);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".partial"));
  ImageFigure bad;
  bad.raster.nx = 3;
  bad.raster.ny = 3;  // no pixels
  EXPECT_THROW(write_png((tmp.path / "bad.png").string(), bad), std::runtime_error);
  EXPECT_FALSE(fs::exists(tmp.path / "bad.png"));
}

TEST(Plot, LogAxisDrawsPositiveData) {
  TempDir tmp;
  Figure f;
  f.log_y = true;
  Series s;
  s.color = Rgb{0, 0, 200};
  for (int i = 0; i < 50; ++i) {
    s.x.push_back(i);
    s.y.push_back(std::pow(10.0, -i / 10.0));
  }
  s.x.push_back(51);
  s.y.push_back(-1);  // not drawable on a log axis: skipped, not an error
  f.series.push_back(s);
  const std::string path = (tmp.path / "log.png").string();
  write_png(path, f);
  Decoded d;
  ASSERT_TRUE(decode(path, d));
  EXPECT_EQ(d.width, 900);
  EXPECT_EQ(d.height, 600);
}

TEST(Ticks, NiceValuesInsideTheRangeEvenlySpacedWithDistinctLabels) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> mag(-6, 8), u(-1, 1);
  for (int trial = 0; trial < 2000; ++trial) {
    const double scale = std::pow(10.0, mag(rng));
    double lo = u(rng) * scale, hi = lo + std::fabs(u(rng)) * scale + scale * 1e-3;
    const int target = 3 + trial % 8;
    const Ticks t = nice_ticks(lo, hi, target);
    ASSERT_GE(t.values.size(), 2u) << lo << " " << hi;
    EXPECT_LE(t.values.size(), static_cast<size_t>(2 * target + 2)) << lo << " " << hi << " " << target;
    ASSERT_EQ(t.labels.size(), t.values.size());
    // Step = 1, 2 or 5 times a power of ten.
    const double m = t.step / std::pow(10.0, std::floor(std::log10(t.step) + 1e-12));
    EXPECT_TRUE(std::fabs(m - 1) < 1e-9 || std::fabs(m - 2) < 1e-9 || std::fabs(m - 5) < 1e-9) << t.step;
    std::set<std::string> labels(t.labels.begin(), t.labels.end());
    EXPECT_EQ(labels.size(), t.labels.size()) << lo << " " << hi;
    for (size_t i = 0; i < t.values.size(); ++i) {
      EXPECT_GE(t.values[i], lo - 1e-9 * std::fabs(t.step));
      EXPECT_LE(t.values[i], hi + 1e-9 * std::fabs(t.step));
      // A tick is an integer multiple of the step, and its label reads back as its value.
      EXPECT_NEAR(t.values[i] / t.step, std::round(t.values[i] / t.step), 1e-6);
      EXPECT_NEAR(std::strtod(t.labels[i].c_str(), nullptr), t.values[i], std::fabs(t.step) * 1e-3) << t.labels[i];
      if (i) {
        EXPECT_NEAR(t.values[i] - t.values[i - 1], t.step, t.step * 1e-9);
      }
    }
  }
}

TEST(Ticks, ExamplesAPersonWouldExpect) {
  const Ticks t = nice_ticks(0, 1, 5);
  EXPECT_EQ(t.labels, (std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
  const Ticks a = nice_ticks(28, 30, 4);
  EXPECT_EQ(a.labels, (std::vector<std::string>{"28.0", "28.5", "29.0", "29.5", "30.0"}));
  const Ticks z = nice_ticks(-1e-17, 2, 2);  // no "-0" or "1e-17" at the origin
  EXPECT_EQ(z.labels.front(), "0");
}

TEST(Ticks, LogTicksArePowersOfTenInRange) {
  const Ticks t = log_ticks(3e-5, 2e3);
  ASSERT_GE(t.values.size(), 3u);
  for (size_t i = 0; i < t.values.size(); ++i) {
    EXPECT_GE(t.values[i], 3e-5);
    EXPECT_LE(t.values[i], 2e3);
    const double e = std::log10(t.values[i]);
    EXPECT_NEAR(e, std::round(e), 1e-12);
    EXPECT_NEAR(std::strtod(t.labels[i].c_str(), nullptr), t.values[i], t.values[i] * 1e-12);
  }
  const Ticks fine = log_ticks(1.5, 40);  // short range: 2 and 5 multiples too
  EXPECT_NE(std::find(fine.values.begin(), fine.values.end(), 2.0), fine.values.end());
  EXPECT_NE(std::find(fine.values.begin(), fine.values.end(), 10.0), fine.values.end());
}

TEST(Colors, CategoriesAreDistinctAndAvoidTheReservedRedAndBlue) {
  std::set<std::tuple<int, int, int>> seen;
  for (int i = 0; i < 40; ++i) {
    const Rgb c = category_color(i);
    EXPECT_TRUE(seen.insert({c.r, c.g, c.b}).second) << i;
    // Reserved: saturated red (sticking) and saturated blue (unbounded).
    EXPECT_FALSE(c.r > 180 && c.g < 60 && c.b < 60) << i;
    EXPECT_FALSE(c.b > 180 && c.r < 60 && c.g < 100) << i;
  }
  // The density ramp darkens monotonically.
  for (int i = 1; i <= 100; ++i) {
    const Rgb a = ramp_color((i - 1) / 100.0), b = ramp_color(i / 100.0);
    EXPECT_LE(b.r + b.g + b.b, a.r + a.g + a.b);
  }
}

// ---- Cairo renderings: formats, size, legend, overlays -------------------------------------

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

Figure small_figure() {
  Figure f;
  f.title = "A figure with θ, ε and a long title that has to fit into the width of a small canvas somehow";
  f.xlabel = "θ";
  f.ylabel = "v";
  Series s;
  s.label = "points";
  s.color = Rgb{0, 114, 178};
  for (int i = 0; i <= 40; ++i) {
    s.x.push_back(i / 40.0);
    s.y.push_back(std::sin(i / 6.0));
  }
  f.series.push_back(s);
  f.metadata = {{"Title", "small"}, {"bouncer:provenance", "{\"command\": \"test\"}"}};
  return f;
}

TEST(Render, PdfAndSvgPagesAreSizeTimes72OverDpiWithFontAndProvenanceAndNoDate) {
  TempDir tmp;
  const Figure f = small_figure();
  RenderOptions ro;
  ro.width = 800;
  ro.height = 500;
  ro.dpi = 200;  // 800 x 500 px = 288 x 180 pt
  const std::string pdf = (tmp.path / "f.pdf").string(), svg = (tmp.path / "f.svg").string();
  write_figure(pdf, f, ImageFormat::pdf, ro);
  write_figure(svg, f, ImageFormat::svg, ro);
  EXPECT_FALSE(fs::exists(pdf + ".partial"));
  const std::string p = slurp(pdf), v = slurp(svg);
  EXPECT_EQ(p.rfind("%PDF-", 0), 0u);
  EXPECT_NE(p.find("/MediaBox [ 0 0 288 180 ]"), std::string::npos) << p.substr(0, 2000);
  EXPECT_NE(p.find("DejaVuSans"), std::string::npos);
  EXPECT_EQ(p.find("CreationDate"), std::string::npos);
  EXPECT_NE(p.find("/Title (small)"), std::string::npos);
  EXPECT_NE(v.find("width=\"288pt\" height=\"180pt\""), std::string::npos) << v.substr(0, 400);
  EXPECT_NE(v.find("<metadata>"), std::string::npos);
  EXPECT_NE(v.find("bouncer:provenance: {&quot;command&quot;: &quot;test&quot;}"), std::string::npos);
  EXPECT_NE(v.find("<symbol"), std::string::npos);  // glyphs: text was drawn
}

// A scatter of many dots (a long orbit's portrait): in PDF and SVG more than 50000 of them
// become one image of the frame (the rest of the page stays vector), so the file stays small
// and cairo's SVG writer does not run out of memory; a few stay vector paths. In a PNG a dot
// repeated at the same place changes no pixel (each is drawn once).
TEST(Render, ManyMarkersBecomeOneImageInVectorFormatsAndRepeatsChangeNoPixel) {
  TempDir tmp;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Figure big = small_figure();
  big.series[0].x.clear();
  big.series[0].y.clear();
  for (int i = 0; i < 60000; ++i) {
    big.series[0].x.push_back(u(rng));
    big.series[0].y.push_back(u(rng));
  }
  RenderOptions ro;
  for (ImageFormat fmt : {ImageFormat::svg, ImageFormat::pdf}) {
    const std::string path = (tmp.path / (fmt == ImageFormat::svg ? "big.svg" : "big.pdf")).string();
    write_figure(path, big, fmt, ro);
    const std::string v = slurp(path);
    EXPECT_LT(v.size(), 4u << 20) << path;
    if (fmt == ImageFormat::svg) {
      EXPECT_NE(v.find("<image"), std::string::npos);
      EXPECT_NE(v.find("<symbol"), std::string::npos);  // the text is still vector glyphs
    }
  }
  const std::string few = (tmp.path / "few.svg").string();
  write_figure(few, small_figure(), ImageFormat::svg, ro);
  EXPECT_EQ(slurp(few).find("<image"), std::string::npos);

  Figure once = small_figure(), thrice = small_figure();
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i <= 40; ++i) {
      thrice.series[0].x.push_back(once.series[0].x[static_cast<size_t>(i)]);
      thrice.series[0].y.push_back(once.series[0].y[static_cast<size_t>(i)]);
    }
  const std::string a = (tmp.path / "once.png").string(), b = (tmp.path / "thrice.png").string();
  write_figure(a, once, ImageFormat::png, ro);
  write_figure(b, thrice, ImageFormat::png, ro);
  Decoded da, db;
  ASSERT_TRUE(decode(a, da));
  ASSERT_TRUE(decode(b, db));
  EXPECT_TRUE(da.rgb == db.rgb);
}

TEST(Render, SizeOptionSetsThePngPixelsAndBadOptionsThrow) {
  TempDir tmp;
  const Figure f = small_figure();
  RenderOptions ro;
  ro.width = 321;
  ro.height = 234;
  const std::string path = (tmp.path / "s.png").string();
  write_figure(path, f, ImageFormat::png, ro);
  Decoded d;
  ASSERT_TRUE(decode(path, d));
  EXPECT_EQ(d.width, 321);
  EXPECT_EQ(d.height, 234);
  std::set<std::tuple<int, int, int>> colours;
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x) colours.insert({d.at(x, y).r, d.at(x, y).g, d.at(x, y).b});
  EXPECT_GT(colours.size(), 20u);  // antialiased text and curves
  ro.width = 50;
  EXPECT_THROW(write_figure(path, f, ImageFormat::png, ro), std::runtime_error);
  ro.width = 400;
  ro.dpi = 1;
  EXPECT_THROW(write_figure(path, f, ImageFormat::pdf, ro), std::runtime_error);
}

// --dpi without --size: the pixels scale with the resolution (the figure's own size is set
// for 150 dpi), so the figure keeps its physical size, and the PNG says how many pixels per
// inch it has (pHYs, per metre: 300 / 0.0254 = 11811.02 -> 11811).
TEST(Render, DpiScalesTheOwnSizeAndIsRecordedInThePng) {
  TempDir tmp;
  Figure f = small_figure();
  f.width = 450;
  f.height = 300;
  const std::string path = (tmp.path / "d.png").string();
  RenderOptions ro;  // 150 dpi: the figure's own size
  write_figure(path, f, ImageFormat::png, ro);
  Decoded d;
  ASSERT_TRUE(decode(path, d));
  EXPECT_EQ(d.width, 450);
  EXPECT_EQ(d.height, 300);
  EXPECT_EQ(d.pixels_per_metre, 5906);  // 150 / 0.0254 = 5905.5 -> 5906
  ro.dpi = 300;
  write_figure(path, f, ImageFormat::png, ro);
  ASSERT_TRUE(decode(path, d));
  EXPECT_EQ(d.width, 900);
  EXPECT_EQ(d.height, 600);
  EXPECT_EQ(d.pixels_per_metre, 11811);
  ro.width = 500;  // --size wins over the scaling
  ro.height = 400;
  write_figure(path, f, ImageFormat::png, ro);
  ASSERT_TRUE(decode(path, d));
  EXPECT_EQ(d.width, 500);
  EXPECT_EQ(d.height, 400);
  EXPECT_EQ(d.pixels_per_metre, 11811);
}

TEST(Render, SmallLegendGoesInsideTheFrameAwayFromTheData) {
  // Data only in the lower left: the legend belongs in the upper right of the frame.
  TempDir tmp;
  Figure f;
  f.width = 600;
  f.height = 400;
  const Rgb data{0, 0, 200}, key{200, 0, 200};
  Series s{"data", {}, {}, data, false, true, 3};
  for (int i = 0; i < 30; ++i) {
    s.x.push_back(i * 0.01);
    s.y.push_back(i * 0.01);
  }
  s.x.push_back(1);
  s.y.push_back(1e-9);  // stretches the window to [0, 1] in x
  s.x.push_back(1e-9);
  s.y.push_back(1);     // and in y
  f.series.push_back(s);
  f.series.push_back(Series{"a second entry", {}, {}, key, false, true, 0});
  f.series.back().x = {0.0};
  f.series.back().y = {0.0};
  const std::string path = (tmp.path / "leg.png").string();
  write_png(path, f);
  Decoded d;
  ASSERT_TRUE(decode(path, d));
  long upper_right = 0, elsewhere = 0;
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x)
      if (same(d.at(x, y), key)) (x > d.width / 2 && y < d.height / 2 ? upper_right : elsewhere) += 1;
  EXPECT_GT(upper_right, 30);  // the legend's swatch, a filled square
  EXPECT_LT(elsewhere, upper_right);
}

TEST(Render, OverlayCurvesAreDrawnOverTheRasterAndClippedToTheFrame) {
  TempDir tmp;
  ImageFigure f;
  f.width = 500;
  f.height = 400;
  Raster& r = f.raster;
  r.nx = r.ny = 1;
  r.pixels = {Rgb{255, 255, 255}};
  const Rgb curve{0, 200, 0};
  Series s;
  s.color = curve;
  s.lines = true;
  s.markers = false;
  for (int k = 0; k <= 100; ++k) {  // a diagonal that runs far outside the window
    s.x.push_back(-1 + 3 * k / 100.0);
    s.y.push_back(-1 + 3 * k / 100.0);
  }
  f.overlay.push_back(s);
  const std::string path = (tmp.path / "ov.png").string();
  write_png(path, f);
  Decoded d;
  ASSERT_TRUE(decode(path, d));
  int x0 = d.width, x1 = 0, y0 = d.height, y1 = 0;
  long n = 0;
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x)
      if (same(d.at(x, y), curve)) {
        ++n;
        x0 = std::min(x0, x); x1 = std::max(x1, x);
        y0 = std::min(y0, y); y1 = std::max(y1, y);
      }
  ASSERT_GT(n, 100);
  // Clipped: the curve stays inside the figure's margins (the frame), and rises to the right.
  EXPECT_GT(x0, 20);
  EXPECT_LT(x1, d.width - 5);
  EXPECT_GT(y0, 20);
  EXPECT_LT(y1, d.height - 20);
  EXPECT_TRUE(same(d.at(x0 + 2, y1 - 2), curve) || same(d.at(x0 + 3, y1 - 3), curve) || x1 - x0 > 100);
}

TEST(Render, ALongTitleOnASmallCanvasIsWrappedNotCut) {
  // A title far wider than the canvas: shrunk and wrapped onto two lines, so the columns at
  // the canvas edges stay white (nothing runs off) and text is drawn on two bands of rows.
  TempDir tmp;
  Figure f = small_figure();
  f.title = "Leading Lyapunov exponent against the restitution coefficient, velocity-dependent restitution model";
  f.width = 420;
  f.height = 320;
  const std::string path = (tmp.path / "t.png").string();
  write_png(path, f);
  Decoded d;
  ASSERT_TRUE(decode(path, d));
  auto ink = [&](int x, int y) { const Rgb c = d.at(x, y); return c.r + c.g + c.b < 600; };
  for (int y = 0; y < d.height / 4; ++y)
    for (int x : {0, 1, 2, d.width - 3, d.width - 2, d.width - 1}) EXPECT_FALSE(ink(x, y)) << x << "," << y;
  // Rows of the title band with ink, grouped into runs: two lines of text.
  int runs = 0;
  bool prev = false;
  for (int y = 0; y < d.height / 6; ++y) {
    bool any = false;
    for (int x = 0; x < d.width && !any; ++x) any = ink(x, y);
    runs += any && !prev;
    prev = any;
  }
  EXPECT_GE(runs, 2);
}

TEST(Ticks, Log2TicksArePowersOfTwoLabelledWithTheirValues) {
  const Ticks t = log_ticks(24, 4096, 2);
  ASSERT_FALSE(t.values.empty());
  EXPECT_EQ(t.values.front(), 32);
  EXPECT_EQ(t.values.back(), 4096);
  for (size_t i = 0; i < t.values.size(); ++i) {
    EXPECT_EQ(std::exp2(std::round(std::log2(t.values[i]))), t.values[i]);
    EXPECT_EQ(t.labels[i], std::to_string(static_cast<long>(t.values[i])));
  }
  EXPECT_LE(t.values.size(), 11u);
  const Ticks wide = log_ticks(1.0 / 1024, 1e12, 2);  // a long range: every k-th power
  EXPECT_LE(wide.values.size(), 11u);
  EXPECT_GE(wide.values.size(), 4u);
  const Ticks ten = log_ticks(1, 1000, 10);  // base 10 is log_ticks
  EXPECT_EQ(ten.values, log_ticks(1, 1000).values);
}

TEST(Colors, ViridisRunsFromDarkToLight) {
  auto luma = [](Rgb c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  for (int i = 1; i <= 100; ++i) EXPECT_LT(luma(viridis_color((i - 1) / 100.0)), luma(viridis_color(i / 100.0)) + 1e-9);
  EXPECT_TRUE(same(viridis_color(0), Rgb{68, 1, 84}));
  EXPECT_TRUE(same(viridis_color(1), Rgb{253, 231, 37}));
}

// ---- zoomed axes ---------------------------------------------------------------------------

TEST(Zoom, OrdinaryWindowsKeepPlainCoordinates) {
  // Plain labels need at most about 8 digits: no offset, t is the value itself.
  for (const auto& [lo, hi] : std::vector<std::pair<std::string, std::string>>{
           {"0", "1"}, {"28", "29"}, {"-1e-20", "1e-20"}, {"1e-20", "2e-20"}, {"28", "28.000003"}, {"4", "20"}}) {
    const AxisZoom z(q(lo), q(hi));
    EXPECT_FALSE(z.active()) << lo << ":" << hi;
    EXPECT_EQ(z(q(lo)), q(lo).get_d());
    EXPECT_EQ(z(2.5), 2.5);
    EXPECT_EQ(axis_title("a", z.offset()), "a");
    EXPECT_EQ(tick_value("0.25", z.offset()), "0.25");
  }
  // Just past the threshold (width < 1e-7 of the magnitude) an offset appears.
  EXPECT_TRUE(AxisZoom(q("28"), q("28.0000027")).active());
}

TEST(Zoom, HandDerivedOffsetsAndTitles) {
  // [0.3, 0.3 + 1e-20]: width 1e-20 -> unit 1e-20; the middle 0.3 + 5e-21 rounded to a
  // multiple of 1e-19 is 0.3; t runs over [0, 1].
  const AxisZoom a(q("0.3"), q("0.30000000000000000001"));
  ASSERT_TRUE(a.active());
  EXPECT_EQ(a.offset().origin, "0.3");
  EXPECT_EQ(a.offset().exponent, -20);
  EXPECT_EQ(a(q("0.3")), 0.0);
  EXPECT_EQ(a(q("0.30000000000000000001")), 1.0);
  EXPECT_EQ(a(q("0.300000000000000000005")), 0.5);
  EXPECT_EQ(axis_title("θ0 (initial phase)", a.offset()), "θ0 (initial phase) - 0.3, in units of 1e-20");
  const Ticks t = zoomed_ticks(a, q("0.3"), q("0.30000000000000000001"), 5);
  EXPECT_EQ(t.labels, (std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
  EXPECT_EQ(tick_value("0.2", a.offset()), "0.300000000000000000002");
  EXPECT_EQ(tick_value("1.0", a.offset()), "0.30000000000000000001");

  // The bifurcation range 28 : 28 + 1e-15.
  const AxisZoom b(q("28"), q("28.000000000000001"));
  EXPECT_EQ(b.offset().origin, "28");
  EXPECT_EQ(b.offset().exponent, -15);
  EXPECT_EQ(axis_title("a", b.offset()), "a - 28, in units of 1e-15");

  // Negative values: [-3 - 2e-20, -3 - 1e-20] -> origin -3, t in [-2, -1], "+ 3".
  const AxisZoom c(q("-3.00000000000000000002"), q("-3.00000000000000000001"));
  EXPECT_EQ(c.offset().origin, "-3");
  EXPECT_EQ(c(q("-3.00000000000000000002")), -2.0);
  EXPECT_EQ(c(q("-3.00000000000000000001")), -1.0);
  EXPECT_EQ(axis_title("v", c.offset()), "v + 3, in units of 1e-20");
  EXPECT_EQ(tick_value("-1.5", c.offset()), "-3.000000000000000000015");

  // A window across a multiple of 1e-19: the origin takes the digit it needs.
  const AxisZoom d(q("0.300000000000000000095"), q("0.300000000000000000105"));
  EXPECT_EQ(d.offset().origin, "0.3000000000000000001");
  EXPECT_EQ(d(q("0.300000000000000000095")), -0.5);
  EXPECT_EQ(tick_value("-0.5", d.offset()), "0.300000000000000000095");

  // Tiny and huge magnitudes: scientific origins; units 1000 and 1 read plainly.
  const AxisZoom e(q("1e-30"), q("1.000000000000001e-30"));
  EXPECT_EQ(axis_title("x", e.offset()), "x - 1e-30, in units of 1e-45");
  const AxisZoom f(q("1e20"), q("100000000000000001000"));
  EXPECT_EQ(axis_title("x", f.offset()), "x - 1e20, in units of 1000");
  const AxisZoom g(q("10000000000"), q("10000000005"));
  EXPECT_EQ(axis_title("x", g.offset()), "x - 10000000000");
  const AxisZoom h(q("12.5"), q("12.50000000005"));  // unit 1e-11, origin 12.5
  EXPECT_EQ(axis_title("x", h.offset()), "x - 12.5, in units of 1e-11");

  // Values printed with the digits a zoom resolves: rounded to a multiple of 10^e.
  EXPECT_EQ(decimal_rounded(q("26.0000000000000000000051234"), -23), "26.00000000000000000000512");
  EXPECT_EQ(decimal_rounded(q("26.0000000000000000000051256"), -23), "26.00000000000000000000513");
  EXPECT_EQ(decimal_rounded(q("26.0000000000000000000051234"), -20), "26.00000000000000000001");
  EXPECT_EQ(decimal_rounded(q("0.125"), -2), "0.13");
  EXPECT_EQ(decimal_rounded(q("-0.125"), -2), "-0.12");  // halves up
  EXPECT_EQ(decimal_rounded(q("1234.5"), 2), "1200");
  EXPECT_EQ(decimal_rounded(q("3.0000000000000000000000001e-30"), -56), "3.0000000000000000000000001e-30");
}

TEST(Zoom, TicksOfRandomWindowsAreExactDistinctAndInside) {
  // Windows of width 1e-8 .. 1e-61 of their magnitude, magnitudes 1e-30 .. 1e30, both signs.
  // Every tick label, read through the offset, is a value inside the window, exactly, and
  // adjacent ticks differ by exactly the step in value units.
  std::mt19937_64 rng(2026);
  std::uniform_int_distribution<int> digit(0, 9), mag(-30, 30), depth(9, 60), sign(0, 1);
  for (int trial = 0; trial < 400; ++trial) {
    std::string lo_text = sign(rng) ? "-0." : "0.";
    lo_text += std::to_string(1 + digit(rng) % 9);
    for (int i = 0; i < 70; ++i) lo_text += std::to_string(digit(rng));
    const int m = mag(rng), d = depth(rng);
    lo_text += "e" + std::to_string(m);
    const mpq_class lo = q(lo_text);
    const mpq_class width = mpq_class(1 + digit(rng) % 9) * pow10q(m - d);
    const mpq_class hi = lo + width;
    const AxisZoom z(lo, hi);
    ASSERT_TRUE(z.active()) << lo_text << " width 1e" << m - d;
    const mpq_class unit = pow10q(z.offset().exponent);
    EXPECT_TRUE(unit <= width && width < unit * 10) << lo_text;
    // Short tick labels: |t| stays small.
    EXPECT_LT(std::fabs(z(lo)), 11.0) << lo_text;
    EXPECT_LT(std::fabs(z(hi)), 21.0) << lo_text;
    const Ticks t = zoomed_ticks(z, lo, hi, 3 + trial % 6);
    ASSERT_GE(t.values.size(), 2u) << lo_text;
    std::set<std::string> distinct(t.labels.begin(), t.labels.end());
    EXPECT_EQ(distinct.size(), t.labels.size()) << lo_text;
    const mpq_class origin = q(z.offset().origin);
    std::vector<mpq_class> values;
    for (const std::string& label : t.labels) {
      const mpq_class v = q(tick_value(label, z.offset()));
      EXPECT_EQ(v, origin + q(label) * unit) << label;
      // Inside the window (t rounded to a double: 1e-9 of a step of slack, as nice_ticks).
      EXPECT_GE(v, lo - width * mpq_class(1, 1000000)) << label << " " << lo_text;
      EXPECT_LE(v, hi + width * mpq_class(1, 1000000)) << label << " " << lo_text;
      values.push_back(v);
    }
    const mpq_class step = q(tick_value(t.labels[1], z.offset())) - q(tick_value(t.labels[0], z.offset()));
    EXPECT_GT(step, 0);
    for (size_t i = 1; i < values.size(); ++i) EXPECT_EQ(values[i] - values[i - 1], step) << lo_text;
  }
}

TEST(Zoom, DoubleCoordinatesAgreeWithExactOnes) {
  // A window of a few hundred ulps of 12 (a degenerate plot range in double).
  const double lo = 12, hi = 12 + 300 * std::ldexp(1.0, -49);
  const AxisZoom z{mpq_class(lo), mpq_class(hi)};
  ASSERT_TRUE(z.active());
  for (int k = 0; k <= 300; k += 7) {
    const double x = 12 + k * std::ldexp(1.0, -49);
    EXPECT_NEAR(z(x), z(mpq_class(x)), 1e-12 * std::max(1.0, std::fabs(z(mpq_class(x))))) << k;
  }
}

TEST(Zoom, PicturesOfAWindow1e20WideDraw) {
  TempDir tmp;
  const mpq_class lo = q("0.3"), hi = q("0.30000000000000000001"), vlo = q("7"), vhi = q("7.00000000000000000003");
  const AxisZoom zx(lo, hi), zy(vlo, vhi);
  // A raster in t coordinates: the four quadrant colours land as in an ordinary window.
  ImageFigure f;
  f.width = 500;
  f.height = 400;
  f.xlabel = "θ0";
  f.ylabel = "v0";
  Raster& r = f.raster;
  r.nx = r.ny = 2;
  const Rgb tl{250, 0, 0}, tr{0, 250, 0};
  r.pixels = {tl, tr, Rgb{0, 0, 250}, Rgb{250, 250, 0}};
  r.x_min = zx(lo);
  r.x_max = zx(hi);
  r.y_min = zy(vlo);
  r.y_max = zy(vhi);
  r.x_offset = zx.offset();
  r.y_offset = zy.offset();
  const std::string path = (tmp.path / "zoom.png").string();
  ASSERT_NO_THROW(write_png(path, f));
  Decoded d;
  ASSERT_TRUE(decode(path, d));
  EXPECT_EQ(d.width, 500);
  EXPECT_EQ(d.height, 400);
  long left = 0, right = 0;
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x) {
      left += same(d.at(x, y), tl) && x < d.width / 2;
      right += same(d.at(x, y), tr) && x > d.width / 3;
    }
  EXPECT_GT(left, 1000);
  EXPECT_GT(right, 1000);
  // The same window in plain doubles is empty (both ends are the double 0.3): an error,
  // not a picture of the wrong window.
  r.x_offset = r.y_offset = AxisOffset{};
  r.x_min = lo.get_d();
  r.x_max = hi.get_d();
  EXPECT_THROW(write_png(path, f), std::runtime_error);

  // A line plot whose data span 2e-15 around 12 in double gets an offset by itself and draws
  // its points inside the frame.
  Figure g;
  Series s;
  s.color = Rgb{200, 0, 0};
  s.marker_size = 3;
  for (int k = 0; k <= 8; ++k) {
    s.x.push_back(k);
    s.y.push_back(12 + k * std::ldexp(1.0, -49));
  }
  g.series.push_back(s);
  const std::string gp = (tmp.path / "flat.png").string();
  ASSERT_NO_THROW(write_png(gp, g));
  ASSERT_TRUE(decode(gp, d));
  int ymin = d.height, ymax = 0;
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < d.width; ++x)
      if (same(d.at(x, y), Rgb{200, 0, 0})) { ymin = std::min(ymin, y); ymax = std::max(ymax, y); }
  EXPECT_GT(ymax - ymin, d.height / 2);  // the 2e-15 spread fills the frame's height
}
