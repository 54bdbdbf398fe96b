// Figures drawn with Cairo: one drawing code for PNG (an antialiased image surface written
// with libpng, provenance in tEXt chunks), PDF and SVG (vector surfaces, provenance in the
// document information / a <metadata> element). Text is DejaVu Sans from a fixed font file
// through FreeType (no fontconfig), so the bytes depend only on the inputs. Every file is
// written to PATH.partial and renamed into place.
#include "bouncer/io/plot.hpp"

#include <cairo-ft.h>
#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include <png.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_set>
#include <utility>
#include <vector>

#include "bouncer/base/output.hpp"
#include "bouncer/io/contact_sheet.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/scalar/decimal.hpp"

namespace bouncer {

namespace {

std::string format_number(double v, double step) {
  if (std::fabs(v) < step * 1e-9) v = 0;  // no "-0" or "1e-17" at the origin
  char buf[64];
  const double mag = std::max(std::fabs(v), step);
  if (step >= 1e-4 && mag < 1e7) {
    int decimals = 0;
    while (decimals < 12 && std::fabs(step * std::pow(10.0, decimals) - std::round(step * std::pow(10.0, decimals))) > 1e-6 * step * std::pow(10.0, decimals))
      ++decimals;
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  } else {
    // Enough significant digits to tell neighbouring ticks apart.
    const int sig = std::clamp(static_cast<int>(std::ceil(std::log10(mag / step) - 1e-9)) + 1, 1, 17);
    std::snprintf(buf, sizeof buf, "%.*g", sig, v);
  }
  return buf;
}


// libpng's default handlers print to stderr; ours stay silent (the caller reports one line).
void png_silent_error(png_structp png, png_const_charp) { png_longjmp(png, 1); }
void png_silent_warning(png_structp, png_const_charp) {}

// ---- exact decimals for zoomed axes ----
mpq_class pow10(long e) {
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(e < 0 ? -e : e));
  return e < 0 ? mpq_class(mpz_class(1), p) : mpq_class(p);
}

// The decimal m * 10^k with the fewest digits: plain from 1e-5 to below 1e15, else
// scientific ("3.000000000000000000001e-25").
std::string decimal_text(mpz_class m, long k) {
  if (m == 0) return "0";
  while (mpz_divisible_ui_p(m.get_mpz_t(), 10)) {
    m /= 10;
    ++k;
  }
  const bool negative = m < 0;
  const std::string digits = mpz_class(abs(m)).get_str();
  const long n = static_cast<long>(digits.size()), magnitude = n - 1 + k;
  std::string out = negative ? "-" : "";
  if (magnitude >= -5 && magnitude < 15) {
    if (k >= 0) {
      out += digits;
      out.append(static_cast<size_t>(k), '0');
    } else if (n + k > 0) {
      out.append(digits, 0, static_cast<size_t>(n + k));
      out += '.';
      out.append(digits, static_cast<size_t>(n + k));
    } else {
      out += "0.";
      out.append(static_cast<size_t>(-(n + k)), '0');
      out += digits;
    }
  } else {
    out += digits[0];
    if (n > 1) {
      out += '.';
      out.append(digits, 1);
    }
    out += 'e';
    out += std::to_string(magnitude);
  }
  return out;
}

// A rational with a terminating decimal expansion as decimal text.
std::string decimal_text(const mpq_class& q) {
  mpq_class x = q;
  long k = 0;
  while (x.get_den() != 1) {
    if (k < -100000) throw std::logic_error("decimal_text: not a terminating decimal");
    x *= 10;
    --k;
  }
  return decimal_text(x.get_num(), k);
}

// floor(log10(w)) for w > 0, exactly.
long floor_log10(const mpq_class& w) {
  long e = static_cast<long>(mpz_sizeinbase(w.get_num_mpz_t(), 10)) - static_cast<long>(mpz_sizeinbase(w.get_den_mpz_t(), 10));
  while (pow10(e) > w) --e;
  while (pow10(e + 1) <= w) ++e;
  return e;
}

std::string unit_text(int exponent) {
  if (exponent >= -3 && exponent <= 3) return decimal_text(mpz_class(1), exponent);
  return "1e" + std::to_string(exponent);
}

// Bits of a PNG writer that must not hold C++ objects across setjmp. Encodes into `out`
// (the bytes go to the output through the one writer, base/output.hpp).
void png_append(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), length);
}
void png_no_flush(png_structp) {}
bool encode_png(std::string* out, int w, int h, double dpi, const std::uint8_t* rgb, png_text* text, int ntext) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, png_silent_error, png_silent_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, out, png_append, png_no_flush);
  png_set_compression_level(png, 9);
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // The physical resolution (pHYs, pixels per metre), so that a viewer or a typesetter
  // shows the figure at the size its text was set for.
  const auto per_metre = static_cast<png_uint_32>(std::lround(dpi / 0.0254));
  png_set_pHYs(png, info, per_metre, per_metre, PNG_RESOLUTION_METER);
  if (ntext > 0) png_set_text(png, info, text, ntext);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) png_write_row(png, const_cast<png_bytep>(rgb + static_cast<size_t>(y) * w * 3));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

// tEXt is Latin-1 with keys of 1..79 printable characters: keep ASCII, replace the rest.
std::string latin(const std::string& s, size_t max) {
  std::string out;
  for (char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    out.push_back(c == '\n' || (c >= 32 && c < 127) ? ch : '?');
    if (out.size() >= max) break;
  }
  return out;
}

// ---- drawing with Cairo ----------------------------------------------------------------------

constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kGrid{232, 232, 232};
constexpr Rgb kFrame{40, 40, 40};
constexpr Rgb kMuted{80, 80, 80};
constexpr const char* kFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// The one font face, loaded once from the fixed file (kept for the life of the process).
cairo_font_face_t* font_face() {
  static FT_Library library = nullptr;
  static FT_Face face = nullptr;
  static cairo_font_face_t* cairo_face = nullptr;
  if (cairo_face) return cairo_face;
  if (!library && FT_Init_FreeType(&library) != 0) throw OutputError("cannot initialise FreeType to draw text");
  if (FT_New_Face(library, kFontFile, 0, &face) != 0) {
    face = nullptr;
    throw OutputError(std::string("cannot load the font file '") + kFontFile +
                      "' that pictures are drawn with: install the Debian package 'fonts-dejavu-core'");
  }
  // No hinting: glyph outlines (and so the pixels) do not depend on FreeType's hinter settings.
  cairo_face = cairo_ft_font_face_create_for_ft_face(face, FT_LOAD_NO_HINTING);
  return cairo_face;
}

// A Cairo context in figure units (pixels of the PNG), with the font, text measures and
// the few primitives the layout uses.
class Painter {
 public:
  explicit Painter(cairo_t* cr) : cr_(cr) {
    cairo_set_font_face(cr_, font_face());
    cairo_font_options_t* fo = cairo_font_options_create();
    cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
    cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_antialias(fo, CAIRO_ANTIALIAS_GRAY);
    cairo_set_font_options(cr_, fo);
    cairo_font_options_destroy(fo);
    cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr_, CAIRO_LINE_CAP_BUTT);
  }
  cairo_t* cr() const { return cr_; }
  void color(Rgb c) const { cairo_set_source_rgb(cr_, c.r / 255.0, c.g / 255.0, c.b / 255.0); }
  double width(const std::string& s, double size) const {
    if (s.empty()) return 0;
    cairo_set_font_size(cr_, size);
    cairo_text_extents_t e;
    cairo_text_extents(cr_, s.c_str(), &e);
    return e.x_advance;
  }
  // Height of capital letters (for centring a line on a point) and the line spacing.
  static double cap(double size) { return 0.73 * size; }
  static double leading(double size) { return 1.25 * size; }
  // Text with its baseline at y; align 0 = left, 0.5 = centred, 1 = right at x.
  void text(double x, double y, const std::string& s, double size, Rgb c, double align = 0) const {
    if (s.empty()) return;
    color(c);
    cairo_set_font_size(cr_, size);
    cairo_move_to(cr_, x - align * width(s, size), y);
    cairo_show_text(cr_, s.c_str());
    cairo_new_path(cr_);
  }
  // Text read bottom to top, centred on (x, y) along its length; x is the baseline.
  void text_up(double x, double y, const std::string& s, double size, Rgb c) const {
    cairo_save(cr_);
    cairo_translate(cr_, x, y);
    cairo_rotate(cr_, -M_PI / 2);
    text(0, 0, s, size, c, 0.5);
    cairo_restore(cr_);
  }
  void line(double x0, double y0, double x1, double y1, Rgb c, double w) const {
    color(c);
    cairo_set_line_width(cr_, w);
    cairo_move_to(cr_, x0, y0);
    cairo_line_to(cr_, x1, y1);
    cairo_stroke(cr_);
  }
  void fill(double x0, double y0, double x1, double y1, Rgb c) const {
    color(c);
    cairo_rectangle(cr_, x0, y0, x1 - x0, y1 - y0);
    cairo_fill(cr_);
  }
  void rect(double x0, double y0, double x1, double y1, Rgb c, double w) const {
    color(c);
    cairo_set_line_width(cr_, w);
    cairo_rectangle(cr_, x0, y0, x1 - x0, y1 - y0);
    cairo_stroke(cr_);
  }
  void clip(double x0, double y0, double x1, double y1) const {
    cairo_save(cr_);
    cairo_rectangle(cr_, x0, y0, x1 - x0, y1 - y0);
    cairo_clip(cr_);
  }
  void unclip() const { cairo_restore(cr_); }

 private:
  cairo_t* cr_;
};

// Sizes of one figure: text in points at the figure's dpi, shrunk on a small canvas so that
// a 400-pixel figure still has room for its plot.
struct Style {
  double body, small, title, line, unit;
  Style(int w, int h, double dpi) {
    const double pt = dpi / 72.0;
    body = std::min(9.5 * pt, std::min(w, h * 3 / 2) / 42.0);
    small = 0.88 * body;
    title = 1.2 * body;
    unit = body / 20.0;  // about one pixel of a 900-pixel figure at 150 dpi: marker sizes and line widths
    line = std::max(1.0, 1.5 * unit);
  }
};

// Lines of text at a size that fit `max_w`: one line, shrunk to 85% if that suffices; else
// two lines split at the space that balances them (shrunk further if a line still does not
// fit, down to 60%). Never cut.
struct Fitted {
  std::vector<std::string> lines;
  double size;
};
Fitted fit_text(const Painter& p, const std::string& s, double size, double max_w, bool allow_wrap = true,
                const std::vector<std::string>& seps = {" "}, bool shrink_first = true) {
  if (s.empty()) return {{}, size};
  if (p.width(s, size) <= max_w) return {{s}, size};
  if (shrink_first && p.width(s, size * 0.85) <= max_w) return {{s}, size * 0.85};
  std::vector<std::string> lines{s};
  if (allow_wrap) {
    size_t best_at = std::string::npos, best_len = 0;
    double best = 1e300;
    for (const std::string& sep : seps) {
      for (size_t at = s.find(sep); at != std::string::npos; at = s.find(sep, at + 1)) {
        const std::string a = s.substr(0, at + (sep == " " ? 0 : sep.size() - 1)), b = s.substr(at + sep.size());
        const double worst = std::max(p.width(a, size), p.width(b, size));
        if (worst < best) { best = worst; best_at = at; best_len = sep.size(); }
      }
      if (best_at != std::string::npos && best <= max_w) break;  // the first separator kind that fits
    }
    if (best_at != std::string::npos) {
      const std::string sep = s.substr(best_at, best_len);
      lines = {s.substr(0, best_at + (sep == " " ? 0 : sep.size() - 1)), s.substr(best_at + best_len)};
    }
  }
  double widest = 0;
  for (const auto& l : lines) widest = std::max(widest, p.width(l, size));
  const double scaled = widest <= max_w ? size : std::max(0.6 * size, size * max_w / widest);
  return {lines, scaled};
}

// The subtitle as lines that fit: split at "; " (then ", ") as often as needed.
Fitted fit_subtitle(const Painter& p, const std::string& sub, double size, double max_w) {
  Fitted f{{}, size};
  std::string rest = sub;
  while (!rest.empty() && f.lines.size() < 4) {
    if (p.width(rest, size) <= max_w || f.lines.size() == 3) {
      f.lines.push_back(rest);
      break;
    }
    size_t cut = std::string::npos;
    double best = 1e300;
    for (const char* sep : {"; ", ", "})
      for (size_t at = rest.find(sep); at != std::string::npos; at = rest.find(sep, at + 1)) {
        const double w1 = p.width(rest.substr(0, at + 1), size), w2 = p.width(rest.substr(at + 2), size);
        const double worst = w1 > max_w ? 1e200 + w1 : std::max(w1, w2);
        if (worst < best) { best = worst; cut = at; }
      }
    if (cut == std::string::npos) {
      f.lines.push_back(rest);
      break;
    }
    f.lines.push_back(rest.substr(0, cut + 1));
    rest = rest.substr(cut + 2);
  }
  double widest = 0;
  for (const auto& l : f.lines) widest = std::max(widest, p.width(l, size));
  if (widest > max_w) f.size = std::max(0.6 * size, size * max_w / widest);
  return f;
}

struct TitleBlock {
  Fitted title, subtitle;
  double height(const Style& st) const {
    double h = 0.8 * st.body;
    h += title.lines.size() * Painter::leading(title.size);
    if (!subtitle.lines.empty()) h += 0.15 * st.body + subtitle.lines.size() * Painter::leading(subtitle.size);
    return h + 0.5 * st.body;
  }
};
TitleBlock title_block(const Painter& p, const std::string& title, const std::string& subtitle, double width, const Style& st) {
  const double max_w = width - 2 * st.body;
  return {fit_text(p, title, st.title, max_w), fit_subtitle(p, subtitle, st.small, max_w)};
}
void draw_title(const Painter& p, const TitleBlock& t, double cx, const Style& st) {
  double y = 0.8 * st.body;
  for (const auto& l : t.title.lines) {
    y += Painter::leading(t.title.size);
    p.text(cx, y - 0.25 * t.title.size, l, t.title.size, kBlack, 0.5);
  }
  if (!t.subtitle.lines.empty()) y += 0.15 * st.body;
  for (const auto& l : t.subtitle.lines) {
    y += Painter::leading(t.subtitle.size);
    p.text(cx, y - 0.25 * t.subtitle.size, l, t.subtitle.size, kMuted, 0.5);
  }
}

struct LegendEntry {
  std::string label;
  Rgb color;
  bool line = false, marker = true;
  bool disc = false;  // the marker is a series' dot (else a square: a raster's cells)
  bool dashed = false;  // the line is dashed
};

// A legend box: entries stacked, each label wrapped to the box's text width.
struct LegendBox {
  std::vector<std::vector<std::string>> labels;  // lines of each entry
  double size = 0, w = 0, h = 0, swatch = 0, pad = 0;
};
LegendBox legend_box(const Painter& p, const std::vector<LegendEntry>& entries, double size, double max_text_w) {
  LegendBox b;
  b.size = size;
  b.swatch = 1.6 * size;
  b.pad = 0.5 * size;
  double text_w = 0;
  for (const auto& e : entries) {
    Fitted f{{e.label}, size};
    if (p.width(e.label, size) > max_text_w) {
      // Too wide: two lines split after ": ", "; " or ", " when both halves fit (the split
      // that balances them best), else wrapped at spaces.
      f.lines.clear();
      double best = 1e300;
      for (const char* sep : {": ", "; ", ", "}) {
        for (size_t at = e.label.find(sep); at != std::string::npos; at = e.label.find(sep, at + 1)) {
          const std::string a = e.label.substr(0, at + 1), b = e.label.substr(at + 2);
          const double worst = std::max(p.width(a, size), p.width(b, size));
          if (worst <= max_text_w && worst < best) {
            best = worst;
            f.lines = {a, b};
          }
        }
        if (!f.lines.empty()) break;
      }
    }
    if (f.lines.empty()) {
      std::vector<std::string> lines;
      std::string cur;
      std::istringstream words(e.label);
      for (std::string w; words >> w;) {
        const std::string next = cur.empty() ? w : cur + " " + w;
        if (!cur.empty() && p.width(next, size) > max_text_w) {
          lines.push_back(cur);
          cur = w;
        } else {
          cur = next;
        }
      }
      if (!cur.empty()) lines.push_back(cur);
      f.lines = lines;
    }
    for (const auto& l : f.lines) text_w = std::max(text_w, p.width(l, size));
    b.h += f.lines.size() * Painter::leading(size) + 0.2 * size;
    b.labels.push_back(f.lines);
  }
  if (entries.empty()) return b;
  b.w = b.pad + b.swatch + 0.5 * size + text_w + b.pad;
  b.h += 2 * b.pad - 0.2 * size;
  return b;
}
void draw_swatch(const Painter& p, double x, double cy, const LegendEntry& e, double swatch, const Style& st) {
  if (e.line && e.dashed) {
    const double dash[] = {0.32 * swatch, 0.18 * swatch};
    cairo_set_dash(p.cr(), dash, 2, 0);
    p.line(x, cy, x + swatch, cy, e.color, 2 * st.line);
    cairo_set_dash(p.cr(), nullptr, 0, 0);
  } else if (e.line) {
    p.line(x, cy, x + swatch, cy, e.color, 2 * st.line);
  }
  if (e.marker && e.line) {  // a marked line: a disc on the line, as in the plot
    p.color(e.color);
    cairo_arc(p.cr(), x + swatch / 2, cy, 0.18 * swatch, 0, 2 * M_PI);
    cairo_fill(p.cr());
  } else if (e.marker && e.disc) {  // a series' dots
    p.color(e.color);
    cairo_arc(p.cr(), x + swatch / 2, cy, 0.28 * swatch, 0, 2 * M_PI);
    cairo_fill(p.cr());
  } else if (e.marker) {  // a square of the colour (raster classes)
    const double r = 0.3 * swatch;
    p.fill(x + swatch / 2 - r, cy - r, x + swatch / 2 + r, cy + r, e.color);
    p.rect(x + swatch / 2 - r, cy - r, x + swatch / 2 + r, cy + r, kMuted, 0.5 * st.line);
  }
}
void draw_legend(const Painter& p, double x, double y, const LegendBox& b, const std::vector<LegendEntry>& entries,
                 const Style& st, bool framed) {
  if (entries.empty()) return;
  if (framed) {
    p.fill(x, y, x + b.w, y + b.h, kWhite);
    p.rect(x, y, x + b.w, y + b.h, Rgb{160, 160, 160}, 0.6 * st.line);
  }
  double yy = y + b.pad;
  for (size_t i = 0; i < entries.size(); ++i) {
    const double first_baseline = yy + Painter::leading(b.size) - 0.3 * b.size;
    draw_swatch(p, x + b.pad, first_baseline - Painter::cap(b.size) / 2, entries[i], b.swatch, st);
    for (size_t k = 0; k < b.labels[i].size(); ++k)
      p.text(x + b.pad + b.swatch + 0.5 * b.size, first_baseline + k * Painter::leading(b.size), b.labels[i][k], b.size, kBlack);
    yy += b.labels[i].size() * Painter::leading(b.size) + 0.2 * b.size;
  }
}

// A legend in rows under the plot: entries flow left to right, rows centred.
std::vector<std::vector<size_t>> legend_rows(const Painter& p, const std::vector<LegendEntry>& entries, double size,
                                             double max_w) {
  std::vector<std::vector<size_t>> rows;
  double x = 0;
  for (size_t i = 0; i < entries.size(); ++i) {
    const double w = 1.6 * size + 0.5 * size + p.width(entries[i].label, size) + 1.5 * size;
    if (rows.empty() || (x + w > max_w && !rows.back().empty())) {
      rows.emplace_back();
      x = 0;
    }
    rows.back().push_back(i);
    x += w;
  }
  return rows;
}
double legend_rows_height(const Painter& p, const std::vector<LegendEntry>& entries, double size, double max_w) {
  if (entries.empty()) return 0;
  return legend_rows(p, entries, size, max_w).size() * Painter::leading(size) + 0.6 * size;
}
void draw_legend_rows(const Painter& p, double left, double top, double max_w, const std::vector<LegendEntry>& entries,
                      double size, const Style& st) {
  double y = top + 0.3 * size;
  for (const auto& row : legend_rows(p, entries, size, max_w)) {
    double total = 0;
    for (size_t i : row) total += 1.6 * size + 0.5 * size + p.width(entries[i].label, size) + 1.5 * size;
    double x = left + std::max(0.0, (max_w - total + 1.5 * size) / 2);
    const double baseline = y + Painter::leading(size) - 0.3 * size;
    for (size_t i : row) {
      draw_swatch(p, x, baseline - Painter::cap(size) / 2, entries[i], 1.6 * size, st);
      p.text(x + 2.1 * size, baseline, entries[i].label, size, kBlack);
      x += 1.6 * size + 0.5 * size + p.width(entries[i].label, size) + 1.5 * size;
    }
    y += Painter::leading(size);
  }
}

// One axis: linear, or logarithmic in a base (positions are log_base of the values).
struct AxisMap {
  bool log = false;
  double base = 10;
  double pos(double v) const { return log ? std::log(v) / std::log(base) : v; }
  bool drawable(double v) const { return std::isfinite(v) && (!log || v > 0); }
};

// The rectangle of the plot in figure units and the window it shows (in axis positions).
struct Frame {
  double left, top, right, bottom;
  double x0, x1, y0, y1;
  // Edges on pixel centres, so that a frame line of odd width covers whole pixels: a crisp
  // frame in the PNG, of exactly the frame colour (tests find the frame by it).
  void snap() {
    left = std::floor(left) + 0.5; top = std::floor(top) + 0.5;
    right = std::floor(right) + 0.5; bottom = std::floor(bottom) + 0.5;
  }
  double px(double x) const { return left + (x - x0) / (x1 - x0) * (right - left); }
  double py(double y) const { return bottom - (y - y0) / (y1 - y0) * (bottom - top); }
};

// The lines of a y axis title (drawn upward beside the frame): one, or for an offset axis
// whose title is longer than the frame is tall, the label and then the offset note.
std::vector<std::string> y_title_lines(const Painter& p, const std::string& label, const AxisOffset& o, double frame_h,
                                       double size) {
  const std::string whole = axis_title(label, o);
  if (!o.active() || label.empty() || p.width(whole, size) <= frame_h) return {whole};
  return {label, axis_title("", o).substr(1)};
}
// A short symbol (θ, ε, a) reads better upright than turned.
bool upright(const std::vector<std::string>& lines) {
  if (lines.size() != 1 || lines[0].empty()) return false;
  size_t chars = 0;
  for (unsigned char c : lines[0]) chars += (c & 0xC0) != 0x80;
  return chars <= 3;
}
std::string typeset(const std::string& label);
double max_label_width(const Painter& p, const Ticks& t, double size) {
  double w = 0;
  for (const auto& l : t.labels) w = std::max(w, p.width(typeset(l), size));
  return w;
}

// Room left of the frame for the y tick labels and title.
double left_room(const Painter& p, const Ticks& ty, const std::vector<std::string>& ylines, const Style& st) {
  const double labels = max_label_width(p, ty, st.small);
  double title = 0;
  if (upright(ylines)) title = p.width(ylines[0], st.body) + 0.6 * st.body;
  else if (!ylines[0].empty()) title = ylines.size() * Painter::leading(st.body) + 0.2 * st.body;
  return 0.6 * st.body + title + labels + 0.5 * st.body + 0.5 * st.body;
}
double bottom_room(const std::string& xlabel, const Style& st) {
  return 0.5 * st.body + Painter::leading(st.small) + (xlabel.empty() ? 0 : Painter::leading(st.body) + 0.2 * st.body) +
         0.6 * st.body;
}

// A tick label as printed: a real minus sign (U+2212) for the hyphen of a negative number
// or exponent ("-0.5", "1e-20").
std::string typeset(const std::string& label) {
  std::string out;
  for (size_t i = 0; i < label.size(); ++i) {
    if (label[i] == '-' && (i == 0 || label[i - 1] == 'e')) out += "\u2212";
    else out += label[i];
  }
  return out;
}

// The frame's line width: whole pixels, odd (with Frame::snap, it covers whole pixels).
double frame_width(const Style& st) {
  const double w = 0.8 * st.line;
  return w < 2 ? 1.0 : 2 * std::floor(w / 2) + 1;
}

// An axis title as printed: the offset's " - " (axis_title) with a real minus sign, and
// its "1e-20" as 10⁻²⁰.
std::string typeset_title(const std::string& title) {
  static const char* const sup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string out;
  for (size_t i = 0; i < title.size(); ++i) {
    if (title.compare(i, 3, " - ") == 0) {
      out += " \u2212 ";
      i += 2;
    } else if (title.compare(i, 2, "1e") == 0 && (i == 0 || title[i - 1] == ' ') && i + 2 < title.size() &&
               (title[i + 2] == '-' || std::isdigit(static_cast<unsigned char>(title[i + 2])))) {
      size_t j = i + 2;
      std::string exp = title[j] == '-' ? "⁻" : "";
      if (title[j] == '-') ++j;
      const size_t digits = j;
      while (j < title.size() && std::isdigit(static_cast<unsigned char>(title[j]))) exp += sup[title[j++] - '0'];
      if (j == digits) {
        out += title[i];
        continue;
      }
      out += "10" + exp;
      i = j - 1;
    } else {
      out += title[i];
    }
  }
  return out;
}

// Axes: ticks, tick labels, grid lines (optional), frame and axis titles.
void draw_axes(const Painter& p, const Frame& f, const Ticks& tx, const Ticks& ty, const AxisMap& mx, const AxisMap& my,
               const std::string& xlabel, const std::vector<std::string>& ylines, bool grid, const Style& st,
               FigureLayout* lay = nullptr) {
  auto record = [&](const std::string& t, double x, double baseline, double size, double align) {
    if (!lay) return;
    const double w = p.width(t, size);
    lay->tick_labels.push_back({t, x - align * w, baseline - Painter::cap(size), x + (1 - align) * w, baseline});
  };
  const double tick = 0.4 * st.body, lw = 0.8 * st.line;
  if (grid) {
    p.clip(f.left, f.top, f.right, f.bottom);
    for (double v : tx.values) p.line(f.px(mx.pos(v)), f.top, f.px(mx.pos(v)), f.bottom, kGrid, 0.7 * st.line);
    for (double v : ty.values) p.line(f.left, f.py(my.pos(v)), f.right, f.py(my.pos(v)), kGrid, 0.7 * st.line);
    p.unclip();
  }
  double widest = 0;
  for (size_t i = 0; i < tx.values.size(); ++i) {
    const double x = f.px(mx.pos(tx.values[i]));
    p.line(x, f.bottom, x, f.bottom + tick, kFrame, lw);
    p.text(x, f.bottom + tick + 0.2 * st.body + Painter::cap(st.small), typeset(tx.labels[i]), st.small, kBlack, 0.5);
    record(typeset(tx.labels[i]), x, f.bottom + tick + 0.2 * st.body + Painter::cap(st.small), st.small, 0.5);
  }
  for (size_t i = 0; i < ty.values.size(); ++i) {
    const double y = f.py(my.pos(ty.values[i]));
    p.line(f.left - tick, y, f.left, y, kFrame, lw);
    widest = std::max(widest, p.width(typeset(ty.labels[i]), st.small));
    p.text(f.left - tick - 0.3 * st.body, y + Painter::cap(st.small) / 2, typeset(ty.labels[i]), st.small, kBlack, 1);
    record(typeset(ty.labels[i]), f.left - tick - 0.3 * st.body, y + Painter::cap(st.small) / 2, st.small, 1);
  }
  p.rect(f.left, f.top, f.right, f.bottom, kFrame, frame_width(st));
  const double cx = (f.left + f.right) / 2, cy = (f.top + f.bottom) / 2;
  if (!xlabel.empty())
    p.text(cx, f.bottom + tick + 0.2 * st.body + Painter::leading(st.small) + Painter::leading(st.body) - 0.1 * st.body,
           typeset_title(xlabel), st.body, kBlack, 0.5);
  const double label_edge = f.left - tick - 0.3 * st.body - widest - 0.5 * st.body;
  if (upright(ylines)) {
    p.text(label_edge, cy + Painter::cap(st.body) / 2, ylines[0], st.body, kBlack, 1);
  } else if (!ylines[0].empty()) {
    for (size_t i = 0; i < ylines.size(); ++i)  // the first line outermost
      p.text_up(label_edge - (ylines.size() - 1 - i) * Painter::leading(st.body) - 0.25 * st.body, cy,
                typeset_title(ylines[i]), st.body, kBlack);
  }
}

void data_range(const std::vector<Series>& series, bool use_x, const AxisMap& m, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (const auto& s : series)
    for (double v : use_x ? s.x : s.y) {
      if (!m.drawable(v)) continue;
      const double t = m.pos(v);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
  // Error bars inside the window too (linear axes; a log axis draws none).
  if (!use_x && !m.log)
    for (const auto& s : series)
      for (size_t i = 0; i < s.yerr.size() && i < s.y.size(); ++i)
        if (std::isfinite(s.y[i]) && std::isfinite(s.yerr[i]) && s.yerr[i] > 0) {
          lo = std::min(lo, s.y[i] - s.yerr[i]);
          hi = std::max(hi, s.y[i] + s.yerr[i]);
        }
  if (!std::isfinite(lo)) { lo = 0; hi = 1; }
  if (hi - lo <= 0) {
    const double d = std::max(0.5, std::fabs(lo) * 0.1);
    lo -= d;
    hi += d;
  } else {
    const double pad = (hi - lo) * 0.03;
    lo -= pad;
    hi += pad;
  }
}

Ticks axis_ticks(const AxisMap& m, double p0, double p1, int target) {
  if (!m.log) return nice_ticks(p0, p1, target);
  return log_ticks(std::pow(m.base, p0), std::pow(m.base, p1), m.base);
}

// Round markers of radius r at the points `at`. On a vector surface (PDF, SVG)
// more than kVectorMarkers of them are drawn into an image of the frame at 4 pixels per unit
// and placed there (what plotting libraries call a rasterized layer): each marker is about 90
// bytes of SVG path (a 4 10^5-step portrait: 2 10^5 distinct dots, an 18 MB SVG), and cairo's
// SVG writer runs out of memory at about 2 GB (fig. attract_three, a 10^7-step portrait). The
// frame, the axes and the text stay vector.
constexpr size_t kVectorMarkers = 50000;
// Dots per fill: one fill of 4 10^5 random circles took cairo about 20 s; fills of 256
// neighbouring dots (below) about a fifth of that. Dots of two fills that overlap composite
// their antialiased edges twice (a shade darker than one fill would draw them).
constexpr size_t kDotsPerFill = 256;
void draw_markers(const Painter& p, const Frame& f, std::vector<std::pair<double, double>> at, double r, Rgb color) {
  cairo_t* cr = p.cr();
  // In strips of 8 radii, left to right: each fill then covers a small part of the frame (a
  // fill costs in proportion to the area its dots span, and random dots span all of it). One
  // colour: the order of the fills changes nothing drawn.
  const double strip = 8 * r;
  std::sort(at.begin(), at.end(), [&](const auto& u, const auto& v) {
    const double su = std::floor(u.second / strip), sv = std::floor(v.second / strip);
    return su != sv ? su < sv : u.first < v.first;
  });
  auto dots = [&](cairo_t* c) {
    cairo_set_source_rgb(c, color.r / 255.0, color.g / 255.0, color.b / 255.0);
    size_t in_path = 0;
    for (const auto& [x, y] : at) {
      cairo_new_sub_path(c);
      cairo_arc(c, x, y, r, 0, 2 * M_PI);
      if (++in_path == kDotsPerFill) {
        cairo_fill(c);
        in_path = 0;
      }
    }
    cairo_fill(c);
  };
  if (at.size() <= kVectorMarkers || cairo_surface_get_type(cairo_get_target(cr)) == CAIRO_SURFACE_TYPE_IMAGE) {
    dots(cr);
    return;
  }
  constexpr double kScale = 4;
  const int w = static_cast<int>(std::ceil((f.right - f.left) * kScale)), h = static_cast<int>(std::ceil((f.bottom - f.top) * kScale));
  cairo_surface_t* layer = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, std::max(w, 1), std::max(h, 1));
  cairo_t* c = cairo_create(layer);
  cairo_scale(c, kScale, kScale);
  cairo_translate(c, -f.left, -f.top);
  dots(c);
  const cairo_status_t drawn = cairo_status(c);
  cairo_destroy(c);
  if (drawn == CAIRO_STATUS_SUCCESS) {
    cairo_save(cr);
    cairo_translate(cr, f.left, f.top);
    cairo_scale(cr, 1 / kScale, 1 / kScale);
    cairo_set_source_surface(cr, layer, 0, 0);
    cairo_paint(cr);
    cairo_restore(cr);
  }
  cairo_surface_destroy(layer);
  if (drawn != CAIRO_STATUS_SUCCESS)
    throw OutputError(std::string("cannot draw the markers' layer: ") + cairo_status_to_string(drawn));
}

// Series: lines, error bars, markers, clipped to the frame.
void draw_series(const Painter& p, const Frame& f, const std::vector<Series>& series, const AxisMap& mx, const AxisMap& my,
                 const Style& st, bool halo = false) {
  p.clip(f.left, f.top, f.right, f.bottom);
  cairo_t* cr = p.cr();
  for (const auto& s : series) {
    const size_t n = std::min(s.x.size(), s.y.size());
    auto ok = [&](size_t i) { return mx.drawable(s.x[i]) && my.drawable(s.y[i]); };
    auto X = [&](size_t i) { return f.px(mx.pos(s.x[i])); };
    auto Y = [&](size_t i) { return f.py(my.pos(s.y[i])); };
    // Far outside the frame: not drawn (Cairo's fixed point cannot hold it).
    auto near = [&](double x, double y) { return std::fabs(x) < 1e6 && std::fabs(y) < 1e6; };
    if (s.lines) {
      auto path = [&] {
        bool open = false;
        for (size_t i = 0; i < n; ++i) {
          if (!ok(i) || !near(X(i), Y(i))) {
            open = false;
            continue;
          }
          if (open) cairo_line_to(cr, X(i), Y(i));
          else cairo_move_to(cr, X(i), Y(i));
          open = true;
        }
      };
      // Over an image, a white halo under a solid line keeps it visible on dark and light
      // cells (a dashed line, a marker of an event, stays thin).
      if (halo && !s.dashed) {
        p.color(kWhite);
        cairo_set_line_width(cr, 1.6 * st.line + 1.6 * st.unit);
        path();
        cairo_stroke(cr);
      }
      p.color(s.color);
      cairo_set_line_width(cr, 1.6 * st.line);
      const double dash[] = {6 * st.line, 4 * st.line};
      if (s.dashed) cairo_set_dash(cr, dash, 2, 0);
      path();
      cairo_stroke(cr);
      cairo_set_dash(cr, nullptr, 0, 0);
    }
    for (size_t i = 0; i < n && i < s.yerr.size(); ++i) {
      const double e = s.yerr[i];
      if (!ok(i) || !std::isfinite(e) || e <= 0 || my.log) continue;
      const double xp = X(i), lo = f.py(s.y[i] - e), hi = f.py(s.y[i] + e), cap = 3 * st.unit;
      if (!near(xp, lo) || !near(xp, hi)) continue;
      p.line(xp, lo, xp, hi, s.color, 0.8 * st.line);
      p.line(xp - cap, lo, xp + cap, lo, s.color, 0.8 * st.line);
      p.line(xp - cap, hi, xp + cap, hi, s.color, 0.8 * st.line);
    }
    if (s.markers) {
      const double r = (s.marker_size <= 0 ? 0.8 : s.marker_size + 0.8) * st.unit;
      // One marker per cell of a grid a quarter of its radius wide: a dot drawn again within a
      // quarter of its radius adds nothing one can see, and a long orbit's portrait repeats
      // its dots millions of times (fig. attract_three: 10^7 steps).
      const double g = r / 4;
      std::unordered_set<std::uint64_t> seen;
      std::vector<std::pair<double, double>> at;
      for (size_t i = 0; i < n; ++i) {
        if (!ok(i) || !near(X(i), Y(i))) continue;
        const auto cell = [&](double z) { return static_cast<std::uint32_t>(static_cast<std::int32_t>(std::floor(z / g))); };
        if (seen.insert(std::uint64_t{cell(X(i))} << 32 | cell(Y(i))).second) at.emplace_back(X(i), Y(i));
      }
      draw_markers(p, f, std::move(at), r, s.color);
    }
  }
  p.unclip();
}

// The corner of the frame (0 top-right, 1 top-left, 2 bottom-right, 3 bottom-left) whose
// legend box covers the fewest data points; ties go to the earlier corner.
int best_corner(const Frame& f, const std::vector<Series>& series, const AxisMap& mx, const AxisMap& my, double w,
                double h, double margin, long& covered_out) {
  long best = -1;
  int corner = 0;
  for (int c = 0; c < 4; ++c) {
    const double x0 = c % 2 == 0 ? f.right - margin - w : f.left + margin, y0 = c < 2 ? f.top + margin : f.bottom - margin - h;
    long covered = 0;
    for (const auto& s : series) {
      const size_t n = std::min(s.x.size(), s.y.size());
      for (size_t i = 0; i < n; ++i) {
        if (!mx.drawable(s.x[i]) || !my.drawable(s.y[i])) continue;
        const double x = f.px(mx.pos(s.x[i])), y = f.py(my.pos(s.y[i]));
        covered += x >= x0 - margin && x <= x0 + w + margin && y >= y0 - margin && y <= y0 + h + margin;
      }
      // Lines between points cover the box too: sample the segments.
      if (s.lines)
        for (size_t i = 1; i < n; ++i) {
          if (!mx.drawable(s.x[i - 1]) || !my.drawable(s.y[i - 1]) || !mx.drawable(s.x[i]) || !my.drawable(s.y[i])) continue;
          for (int k = 1; k < 8; ++k) {
            const double t = k / 8.0;
            const double x = f.px(mx.pos(s.x[i - 1]) * (1 - t) + mx.pos(s.x[i]) * t);
            const double y = f.py(my.pos(s.y[i - 1]) * (1 - t) + my.pos(s.y[i]) * t);
            covered += x >= x0 && x <= x0 + w && y >= y0 && y <= y0 + h;
          }
        }
    }
    if (best < 0 || covered < best) {
      best = covered;
      corner = c;
    }
  }
  covered_out = best;
  return corner;
}

// ---- direct labels ----
// A curve's label at its end: where it leaves the window (axis positions), and whether it
// leaves through the top (the label goes in a row above the frame) or elsewhere (a column
// right of the frame).
struct EndLabel {
  std::string text;
  Rgb color;
  double x = 0, y = 0;
  bool top = false;
};
std::vector<EndLabel> end_labels(const std::vector<Series>& series, const AxisMap& mx, const AxisMap& my, double x0, double x1,
                                 double y0, double y1) {
  std::vector<EndLabel> out;
  for (const Series& s : series) {
    if (!s.end_label || s.label.empty()) continue;
    const size_t n = std::min(s.x.size(), s.y.size());
    auto inside = [&](size_t i) {
      if (!mx.drawable(s.x[i]) || !my.drawable(s.y[i])) return false;
      const double x = mx.pos(s.x[i]), y = my.pos(s.y[i]);
      return x >= x0 && x <= x1 && y >= y0 && y <= y1;
    };
    size_t last = n;
    for (size_t i = n; i-- > 0;)
      if (inside(i)) {
        last = i;
        break;
      }
    if (last == n) continue;  // not drawn: no label
    EndLabel e{s.label, s.color, mx.pos(s.x[last]), my.pos(s.y[last]), false};
    if (last + 1 < n && mx.drawable(s.x[last + 1]) && my.drawable(s.y[last + 1])) {
      // The crossing of the segment to the next point with the window's edge.
      const double qx = mx.pos(s.x[last + 1]), qy = my.pos(s.y[last + 1]), dx = qx - e.x, dy = qy - e.y;
      double t = 1;
      bool top = false;
      if (qx > x1 && dx > 0) t = std::min(t, (x1 - e.x) / dx);
      if (qx < x0 && dx < 0) t = std::min(t, (x0 - e.x) / dx);
      if (qy < y0 && dy < 0) t = std::min(t, (y0 - e.y) / dy);
      if (qy > y1 && dy > 0 && (y1 - e.y) / dy < t) {
        t = (y1 - e.y) / dy;
        top = true;
      }
      e.x += t * dx;
      e.y += t * dy;
      e.top = top;
    }
    out.push_back(e);
  }
  return out;
}
// Room the end labels need: right of the frame (their widest text and a leader), above it.
double end_label_right_room(const Painter& p, const std::vector<EndLabel>& labels, const Style& st) {
  double w = 0;
  for (const EndLabel& e : labels)
    if (!e.top) w = std::max(w, p.width(e.text, st.small));
  return w > 0 ? w + 1.1 * st.body : 0;
}
double end_label_top_room(const std::vector<EndLabel>& labels, const Style& st) {
  for (const EndLabel& e : labels)
    if (e.top) return Painter::leading(st.small) + 0.3 * st.body;
  return 0;
}
// The labels in the series' colours, moved apart where they would overlap (spread_labels),
// each joined to its curve's end by a thin leader line.
void draw_end_labels(const Painter& p, const Frame& f, const std::vector<EndLabel>& labels, double right_room, const Style& st,
                     FigureLayout* lay) {
  std::vector<size_t> right, top;
  for (size_t i = 0; i < labels.size(); ++i) (labels[i].top ? top : right).push_back(i);
  const double h = Painter::leading(st.small), lw = 0.7 * st.line;
  if (!right.empty()) {
    std::vector<double> wanted;
    for (size_t i : right) wanted.push_back(std::clamp(f.py(labels[i].y), f.top, f.bottom));
    const std::vector<double> at = spread_labels(wanted, h, f.top - 0.5 * h, f.bottom + 0.5 * h);
    const double tx = f.right + 0.9 * st.body;
    for (size_t k = 0; k < right.size(); ++k) {
      const EndLabel& e = labels[right[k]];
      const double baseline = at[k] + Painter::cap(st.small) / 2;
      p.line(std::min(f.px(e.x), f.right), std::clamp(f.py(e.y), f.top, f.bottom), tx - 0.2 * st.body, at[k], e.color, lw);
      p.text(tx, baseline, e.text, st.small, e.color);
      if (lay) lay->direct_labels.push_back({e.text, tx, baseline - Painter::cap(st.small), tx + p.width(e.text, st.small), baseline});
    }
  }
  if (!top.empty()) {
    double widest = 0;
    std::vector<double> wanted;
    for (size_t i : top) {
      wanted.push_back(f.px(labels[i].x));
      widest = std::max(widest, p.width(labels[i].text, st.small));
    }
    const double size = widest + 0.6 * st.small;
    const std::vector<double> at = spread_labels(wanted, size, f.left, f.right + right_room);
    const double baseline = f.top - 0.45 * st.body;
    for (size_t k = 0; k < top.size(); ++k) {
      const EndLabel& e = labels[top[k]];
      p.line(f.px(e.x), f.top, at[k], baseline + 0.15 * st.body, e.color, lw);
      p.text(at[k], baseline, e.text, st.small, e.color, 0.5);
      const double w = p.width(e.text, st.small);
      if (lay) lay->direct_labels.push_back({e.text, at[k] - w / 2, baseline - Painter::cap(st.small), at[k] + w / 2, baseline});
    }
  }
}
// Text centred at (x, y) with a white halo (Annotation), unless its box would overlap one
// already written (`taken`): labels never cover each other; the earlier ones win.
void draw_annotation(const Painter& p, double x, double y, const std::string& text, Rgb color, const Style& st,
                     std::vector<TextBox>& taken, FigureLayout* lay) {
  if (text.empty()) return;
  const double size = st.small, w = p.width(text, size), baseline = y + Painter::cap(size) / 2;
  const TextBox box{text, x - w / 2 - 0.15 * size, baseline - Painter::cap(size) - 0.15 * size, x + w / 2 + 0.15 * size,
                    baseline + 0.15 * size};
  for (const TextBox& t : taken)
    if (box.x0 < t.x1 && t.x0 < box.x1 && box.y0 < t.y1 && t.y0 < box.y1) return;
  taken.push_back(box);
  cairo_t* cr = p.cr();
  cairo_set_font_size(cr, size);
  cairo_move_to(cr, x - w / 2, baseline);
  cairo_text_path(cr, text.c_str());
  p.color(kWhite);
  cairo_set_line_width(cr, 0.3 * size);
  cairo_stroke_preserve(cr);
  p.color(color);
  cairo_fill(cr);
  if (lay) lay->direct_labels.push_back({text, x - w / 2, baseline - Painter::cap(size), x + w / 2, baseline});
}
// Whether a series has a point in the window (axis positions): only drawn series get a
// legend entry.
bool shows_in(const Series& s, const AxisMap& mx, const AxisMap& my, double x0, double x1, double y0, double y1) {
  const size_t n = std::min(s.x.size(), s.y.size());
  const double ex = (x1 - x0) * 1e-9, ey = (y1 - y0) * 1e-9;
  for (size_t i = 0; i < n; ++i) {
    if (!mx.drawable(s.x[i]) || !my.drawable(s.y[i])) continue;
    const double x = mx.pos(s.x[i]), y = my.pos(s.y[i]);
    if (x >= x0 - ex && x <= x1 + ex && y >= y0 - ey && y <= y1 + ey) return true;
  }
  return false;
}

// A rendering target: an image surface for PNG, a PDF or SVG stream into a string.
cairo_status_t append_bytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

std::string meta_value(const std::vector<std::pair<std::string, std::string>>& meta, const std::string& key) {
  for (const auto& [k, v] : meta)
    if (k == key) return v;
  return "";
}

std::vector<std::pair<std::string, std::string>> with_software(std::vector<std::pair<std::string, std::string>> meta) {
  bool has_software = false;
  for (const auto& kv : meta) has_software = has_software || kv.first == "Software";
  if (!has_software) meta.emplace_back("Software", "bouncer " + build_info().version + " (commit " + build_info().commit + ")");
  return meta;
}

std::string xml_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default:
        // XML 1.0 allows no control characters but tab and newline.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') out += ' ';
        else out += c;
    }
  }
  return out;
}

// The PNG file of an RGB raster, with its metadata as tEXt/zTXt chunks.
std::string png_bytes(int w, int h, double dpi, const std::vector<std::uint8_t>& rgb,
                      const std::vector<std::pair<std::string, std::string>>& metadata) {
  const auto meta = with_software(metadata);
  std::vector<std::string> keys, values;
  for (const auto& [k, v] : meta) {
    std::string key = latin(k, 79);
    if (key.empty()) continue;
    keys.push_back(key);
    values.push_back(latin(v, std::numeric_limits<size_t>::max()));
  }
  std::vector<png_text> text(keys.size());
  for (size_t i = 0; i < keys.size(); ++i) {
    text[i].compression = values[i].size() > 1000 ? PNG_TEXT_COMPRESSION_zTXt : PNG_TEXT_COMPRESSION_NONE;
    text[i].key = keys[i].data();
    text[i].text = values[i].data();
    text[i].text_length = values[i].size();
  }
  std::string bytes;
  if (!encode_png(&bytes, w, h, dpi, rgb.data(), text.data(), static_cast<int>(text.size())))
    throw OutputError("cannot encode the PNG picture");
  return bytes;
}

// Renders with `draw(painter)` in figure units (W x H) to the format and writes its bytes to `out`.
void render(std::ostream& out, ImageFormat format, int w, int h, double dpi,
            const std::vector<std::pair<std::string, std::string>>& metadata, const std::function<void(const Painter&)>& draw) {
  font_face();  // a missing font is reported before anything is drawn
  const double points = 72.0 / dpi;
  std::string bytes;
  cairo_surface_t* surface = nullptr;
  switch (format) {
    case ImageFormat::png: surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h); break;
    case ImageFormat::pdf: surface = cairo_pdf_surface_create_for_stream(append_bytes, &bytes, w * points, h * points); break;
    case ImageFormat::svg: surface = cairo_svg_surface_create_for_stream(append_bytes, &bytes, w * points, h * points); break;
  }
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(surface);
    throw OutputError(std::string("cannot create a ") + format_name(format) + " surface");
  }
  const auto meta = with_software(metadata);
  if (format == ImageFormat::pdf) {
    // The document information holds the provenance; the dates cairo would add (the time
    // of the run) are left out so that the same inputs give the same bytes.
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, meta_value(meta, "Title").c_str());
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, meta_value(meta, "Software").c_str());
    std::string subject = meta_value(meta, "bouncer:provenance");
    if (subject.empty()) subject = meta_value(meta, "provenance");
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_SUBJECT, subject.c_str());
    std::string keywords;
    for (const auto& [k, v] : meta)
      if (k != "Title" && k != "Software" && k != "bouncer:provenance" && k != "provenance")
        keywords += (keywords.empty() ? "" : "; ") + k + "=" + v;
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_KEYWORDS, keywords.c_str());
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATE_DATE, "");
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_MOD_DATE, "");
  }
  if (format == ImageFormat::svg) cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_PT);
  cairo_t* cr = cairo_create(surface);
  if (format != ImageFormat::png) cairo_scale(cr, points, points);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  try {
    draw(Painter(cr));
  } catch (...) {
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
    throw;
  }
  const cairo_status_t drawn = cairo_status(cr);
  cairo_destroy(cr);
  cairo_surface_flush(surface);
  std::vector<std::uint8_t> rgb;
  if (format == ImageFormat::png && drawn == CAIRO_STATUS_SUCCESS) {
    const unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    rgb.resize(static_cast<size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        std::uint32_t px;
        std::memcpy(&px, data + static_cast<size_t>(y) * stride + 4 * static_cast<size_t>(x), 4);
        std::uint8_t* o = &rgb[(static_cast<size_t>(y) * w + x) * 3];
        o[0] = static_cast<std::uint8_t>(px >> 16);
        o[1] = static_cast<std::uint8_t>(px >> 8);
        o[2] = static_cast<std::uint8_t>(px);
      }
  }
  cairo_surface_finish(surface);
  const cairo_status_t finished = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (drawn != CAIRO_STATUS_SUCCESS || finished != CAIRO_STATUS_SUCCESS)
    throw OutputError(std::string("cannot render the ") + format_name(format) + " picture: " +
                      cairo_status_to_string(drawn != CAIRO_STATUS_SUCCESS ? drawn : finished));
  if (format == ImageFormat::png) {
    const std::string png = png_bytes(w, h, dpi, rgb, metadata);
    out.write(png.data(), static_cast<std::streamsize>(png.size()));
    return;
  }
  if (format == ImageFormat::svg) {
    // Provenance in the SVG: a <title> and a <metadata> element after the opening <svg> tag.
    const size_t open = bytes.find("<svg");
    const size_t end = open == std::string::npos ? open : bytes.find('>', open);
    if (end != std::string::npos) {
      std::string block = "\n<title>" + xml_escaped(meta_value(meta, "Title")) + "</title>\n<metadata>\n";
      for (const auto& [k, v] : meta) block += xml_escaped(k) + ": " + xml_escaped(v) + "\n";
      block += "</metadata>";
      bytes.insert(end + 1, block);
    }
  }
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void check_size(int w, int h) {
  if (w < kMinFigureWidth || h < kMinFigureHeight || w > kMaxFigureSide || h > kMaxFigureSide)
    throw std::runtime_error("figure size out of range");
}

}  // namespace

AxisZoom::AxisZoom(const mpq_class& lo, const mpq_class& hi) {
  const mpq_class width = hi - lo;
  if (sgn(width) <= 0) return;
  // Plain labels of a window narrower than 1e-7 of its magnitude need 9 or more digits.
  if (std::max(abs(lo), abs(hi)) <= width * 10000000) return;
  const long e = floor_log10(width);
  // The origin: the middle of the window rounded to a multiple of 10^(e+1), so that the
  // origin has no more digits than the window needs and |t| stays below about 10.
  const mpq_class grain = pow10(e + 1), q = (lo + hi) / 2 / grain + mpq_class(1, 2);
  mpz_class m;
  mpz_fdiv_q(m.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
  origin_ = m * grain;
  scale_ = pow10(-e);
  offset_.origin = decimal_text(m, e + 1);
  offset_.exponent = static_cast<int>(e);
  origin_d_ = origin_.get_d();
  origin_err_ = mpq_class(origin_ - mpq_class(origin_d_)).get_d();
  scale_d_ = std::pow(10.0, static_cast<double>(-e));
}

double AxisZoom::operator()(const mpq_class& x) const {
  if (!active()) return x.get_d();
  return mpq_class((x - origin_) * scale_).get_d();
}

double AxisZoom::operator()(double x) const {
  if (!active()) return x;
  // x - origin_d_ is exact near the window (Sterbenz); the origin's own rounding error is
  // taken off after, so t is accurate to a few ulps of t.
  return ((x - origin_d_) - origin_err_) * scale_d_;
}

std::pair<AxisZoom, AxisZoom> set_exact_window(Raster& r, const mpq_class& x0, const mpq_class& x1, const mpq_class& y0,
                                               const mpq_class& y1) {
  const AxisZoom zx(x0, x1), zy(y0, y1);
  r.x_min = zx(x0);
  r.x_max = zx(x1);
  r.y_min = zy(y0);
  r.y_max = zy(y1);
  r.x_offset = zx.offset();
  r.y_offset = zy.offset();
  return {zx, zy};
}

std::string axis_title(const std::string& label, const AxisOffset& o) {
  if (!o.active()) return label;
  std::string out = label;
  out += o.origin[0] == '-' ? " + " + o.origin.substr(1) : " - " + o.origin;
  if (o.exponent != 0) out += ", in units of " + unit_text(o.exponent);
  return out;
}

std::string decimal_rounded(const mpq_class& x, int exponent) {
  const mpq_class grain = pow10(exponent), t = x / grain + mpq_class(1, 2);
  mpz_class m;
  mpz_fdiv_q(m.get_mpz_t(), t.get_num_mpz_t(), t.get_den_mpz_t());
  return decimal_text(m, exponent);
}

std::string tick_value(const std::string& label, const AxisOffset& o) {
  if (!o.active()) return label;
  const auto t = Decimal::parse(label), origin = Decimal::parse(o.origin);
  if (!t || !origin) throw std::invalid_argument("tick_value: '" + label + "' or '" + o.origin + "' is not a decimal");
  return decimal_text(origin->value() + t->value() * pow10(o.exponent));
}

Ticks nice_ticks(double lo, double hi, int target) {
  Ticks t;
  if (!(std::isfinite(lo) && std::isfinite(hi))) return t;
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) {
    t.values = {lo};
    t.step = 0;
    t.labels = {format_number(lo, std::max(std::fabs(lo), 1.0) * 1e-3)};
    return t;
  }
  target = std::max(2, target);
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw * 0.75) break;
  }
  // Fewer than two ticks inside: halve the step until there are (1 -> 0.5 -> 0.2 -> 0.1 ...).
  for (int guard = 0; guard < 8; ++guard) {
    const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
    if (last - first >= 1) break;
    const double m = step / std::pow(10.0, std::floor(std::log10(step) + 1e-12));
    step = m > 4.5 ? step * 0.4 : m > 1.5 ? step * 0.5 : step * 0.5;
  }
  t.step = step;
  const long long first = static_cast<long long>(std::ceil(lo / step - 1e-9));
  const long long last = static_cast<long long>(std::floor(hi / step + 1e-9));
  for (long long k = first; k <= last; ++k) {
    const double v = static_cast<double>(k) * step;
    t.values.push_back(v);
    t.labels.push_back(format_number(v, step));
  }
  return t;
}

Ticks log_ticks(double lo, double hi) {
  Ticks t;
  if (!(lo > 0) || !(hi > lo)) return nice_ticks(lo, hi);
  const int e0 = static_cast<int>(std::floor(std::log10(lo))), e1 = static_cast<int>(std::ceil(std::log10(hi)));
  const bool fine = e1 - e0 <= 2;
  const int stride = std::max(1, (e1 - e0) / 8);
  for (int e = e0; e <= e1; e += fine ? 1 : stride)
    for (double m : fine ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
      const double v = m * std::pow(10.0, e);
      if (v < lo * (1 - 1e-12) || v > hi * (1 + 1e-12)) continue;
      t.values.push_back(v);
      char buf[32];
      if (e >= -3 && e <= 4) std::snprintf(buf, sizeof buf, "%g", v);
      else if (m == 1) std::snprintf(buf, sizeof buf, "1e%d", e);
      else std::snprintf(buf, sizeof buf, "%ge%d", m, e);
      t.labels.push_back(buf);
    }
  t.step = fine ? 0 : stride;
  return t;
}

const char* format_name(ImageFormat f) {
  switch (f) {
    case ImageFormat::png: return "png";
    case ImageFormat::pdf: return "pdf";
    case ImageFormat::svg: return "svg";
  }
  return "png";
}

const char* figure_font_path() { return kFontFile; }
void check_figure_font() { font_face(); }

Ticks log_ticks(double lo, double hi, double base) {
  if (base == 10 || !(base > 1)) return log_ticks(lo, hi);
  Ticks t;
  if (!(lo > 0) || !(hi > lo)) return nice_ticks(lo, hi);
  const double lb = std::log(base);
  const int k0 = static_cast<int>(std::ceil(std::log(lo) / lb - 1e-9)), k1 = static_cast<int>(std::floor(std::log(hi) / lb + 1e-9));
  if (k1 - k0 < 1) return nice_ticks(lo, hi);
  const int stride = std::max(1, (k1 - k0 + 9) / 10);
  static const char* const sup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  for (int k = k0; k <= k1; k += stride) {
    const double v = std::pow(base, k);
    t.values.push_back(v);
    char buf[64];
    if (v == std::round(v) && v < 1e7) {
      std::snprintf(buf, sizeof buf, "%.0f", v);
      t.labels.push_back(buf);
    } else {
      std::snprintf(buf, sizeof buf, "%g", base);
      std::string s = buf;
      if (k < 0) s += "⁻";
      for (char c : std::to_string(std::abs(k))) s += sup[c - '0'];
      t.labels.push_back(s);
    }
  }
  t.step = stride;
  return t;
}

Rgb ramp_color(double t) {
  t = std::clamp(t, 0.0, 1.0);
  // White to near-black through cool greys: light marks stay visible, dense ones are black.
  const double l = 1 - t;
  auto ch = [&](double bias) { return static_cast<std::uint8_t>(std::lround(255 * std::clamp(std::pow(l, bias) * 0.97, 0.0, 1.0))); };
  return Rgb{ch(1.15), ch(1.05), ch(0.95)};
}

Rgb viridis_color(double t) {
  // Matplotlib's viridis sampled at 0, 1/8, ..., 1, interpolated linearly.
  static const double v[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},  {44, 113, 142}, {33, 144, 141},
                                 {39, 173, 129}, {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
  t = std::clamp(t, 0.0, 1.0) * 8;
  const int i = std::min(7, static_cast<int>(t));
  const double f = t - i;
  auto ch = [&](int c) { return static_cast<std::uint8_t>(std::lround(v[i][c] * (1 - f) + v[i + 1][c] * f)); };
  return Rgb{ch(0), ch(1), ch(2)};
}

Rgb category_color(int index) {
  // Okabe-Ito first (without its vermillion, blue and bluish green: sticking, unbounded and
  // chaos), then further distinct colours.
  static const Rgb palette[] = {
      {230, 159, 0},   {86, 180, 233},  {204, 121, 167}, {0, 90, 60},    {140, 86, 11},  {240, 228, 66},
      {128, 128, 0},   {0, 200, 200},   {255, 200, 140}, {100, 60, 140}, {180, 220, 120}, {200, 170, 230},
      {120, 120, 60},  {0, 110, 110},   {255, 150, 220}, {170, 120, 60},
  };
  constexpr int n = sizeof(palette) / sizeof(palette[0]);
  if (index < 0) index = 0;
  const Rgb base = palette[index % n];
  if (index < n) return base;
  // Further categories: darker variants of the palette.
  const double f = index < 2 * n ? 0.6 : 0.35;
  return Rgb{static_cast<std::uint8_t>(base.r * f), static_cast<std::uint8_t>(base.g * f), static_cast<std::uint8_t>(base.b * f)};
}

Rgb series_color(int index) {
  // Okabe-Ito without its yellow, then colours picked greedily from an sRGB grid (L* in
  // [25, 66], chroma <= 65) for the largest smallest CIE76 distance to those before.
  static const Rgb palette[] = {
      {0, 0, 0},      {230, 159, 0},  {86, 180, 233},  {0, 158, 115},   {0, 114, 178},  {213, 94, 0},  {204, 121, 167},
      {105, 90, 30},  {120, 15, 30},  {105, 60, 165},  {120, 165, 45},  {30, 90, 90},   {255, 105, 120}, {90, 60, 90},
      {180, 150, 135}, {0, 75, 0},    {135, 0, 90},    {135, 150, 255}, {210, 120, 225}, {180, 105, 60},
  };
  constexpr int n = sizeof(palette) / sizeof(palette[0]);
  if (index < 0) index = 0;
  const Rgb base = palette[index % n];
  if (index < n) return base;
  const double f = 0.65;  // further series: darker variants
  return Rgb{static_cast<std::uint8_t>(base.r * f), static_cast<std::uint8_t>(base.g * f), static_cast<std::uint8_t>(base.b * f)};
}

Lab to_lab(Rgb c) {
  auto linear = [](std::uint8_t v) {
    const double x = v / 255.0;
    return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
  };
  const double r = linear(c.r), g = linear(c.g), b = linear(c.b);
  const double X = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b, Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b,
               Z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
  auto f = [](double t) {
    constexpr double d = 6.0 / 29;
    return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29;
  };
  const double fx = f(X / 0.95047), fy = f(Y), fz = f(Z / 1.08883);
  return Lab{116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

double delta_e76(Rgb x, Rgb y) {
  const Lab a = to_lab(x), b = to_lab(y);
  return std::sqrt((a.l - b.l) * (a.l - b.l) + (a.a - b.a) * (a.a - b.a) + (a.b - b.b) * (a.b - b.b));
}

std::vector<double> spread_labels(const std::vector<double>& wanted, double size, double lo, double hi) {
  const size_t n = wanted.size();
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return wanted[a] < wanted[b]; });
  // Clusters of consecutive labels (in wanted order), each placed as a block of k * size
  // centred on its members' mean wish, clamped into [lo, hi]; a block that overlaps the one
  // before merges with it, and the merged block is placed again (pool adjacent violators).
  struct Block {
    size_t first, count;
    double sum;  // of the wanted centres
    double start = 0;
  };
  auto place = [&](Block& b) {
    const double len = b.count * size;
    b.start = b.sum / b.count - len / 2;
    b.start = std::max(lo, std::min(b.start, hi - len));
  };
  std::vector<Block> blocks;
  for (size_t k = 0; k < n; ++k) {
    Block b{k, 1, wanted[order[k]]};
    place(b);
    blocks.push_back(b);
    while (blocks.size() >= 2) {
      Block& prev = blocks[blocks.size() - 2];
      const Block& last = blocks.back();
      if (prev.start + prev.count * size <= last.start + 1e-9) break;
      prev.count += last.count;
      prev.sum += last.sum;
      blocks.pop_back();
      place(blocks.back());
    }
  }
  // Blocks too long for [lo, hi] start at lo; the ones after follow without overlap.
  std::vector<double> out(n);
  double next = -std::numeric_limits<double>::infinity();
  for (const Block& b : blocks) {
    const double start = std::max(b.start, next);
    for (size_t j = 0; j < b.count; ++j) out[order[b.first + j]] = start + (j + 0.5) * size;
    next = start + b.count * size;
  }
  return out;
}

// The pixels of a figure drawn with `ro`: --size when given, else the figure's own size
// (set for kDefaultDpi) scaled to ro.dpi, so that --dpi changes the resolution and not the
// figure's physical size or layout.
std::pair<int, int> figure_pixels(const RenderOptions& ro, int own_width, int own_height) {
  const auto scaled = [&](int own) {
    return static_cast<int>(std::min<double>(kMaxFigureSide, std::lround(own * ro.dpi / kDefaultDpi)));
  };
  return {ro.width > 0 ? ro.width : scaled(own_width), ro.height > 0 ? ro.height : scaled(own_height)};
}

namespace {

void draw_figure(std::ostream& out, const Figure& fig, ImageFormat format, const RenderOptions& ro, FigureLayout* lay) {
  const std::pair<int, int> pixels = figure_pixels(ro, fig.width, fig.height);
  const int W = pixels.first, H = pixels.second;
  check_size(W, H);
  if (!(ro.dpi >= kMinDpi && ro.dpi <= kMaxDpi)) throw std::runtime_error("figure dpi out of range");
  const Style st(W, H, ro.dpi);
  const AxisMap mx{fig.log_x, fig.log_x ? fig.log_x_base : 10}, my{fig.log_y, 10};

  // Data window, in axis positions (log_base of the values on a log axis).
  double x0, x1, y0, y1;
  data_range(fig.series, true, mx, x0, x1);
  data_range(fig.series, false, my, y0, y1);
  if (std::isfinite(fig.x_min) && mx.drawable(fig.x_min)) x0 = mx.pos(fig.x_min);
  if (std::isfinite(fig.x_max) && mx.drawable(fig.x_max)) x1 = mx.pos(fig.x_max);
  if (std::isfinite(fig.y_min) && my.drawable(fig.y_min)) y0 = my.pos(fig.y_min);
  if (std::isfinite(fig.y_max) && my.drawable(fig.y_max)) y1 = my.pos(fig.y_max);
  if (!(x1 > x0)) x1 = x0 + 1;
  if (!(y1 > y0)) y1 = y0 + 1;

  // A window too narrow for plain tick labels is drawn relative to an offset (AxisZoom),
  // unless the caller's coordinates already are.
  AxisOffset x_offset = fig.x_offset, y_offset = fig.y_offset;
  std::vector<Series> zoomed;
  const std::vector<Series>* series = &fig.series;
  if (!fig.equal_aspect) {
    const AxisZoom zx = x_offset.active() || mx.log ? AxisZoom() : AxisZoom(mpq_class(x0), mpq_class(x1));
    const AxisZoom zy = y_offset.active() || my.log ? AxisZoom() : AxisZoom(mpq_class(y0), mpq_class(y1));
    if (zx.active() || zy.active()) {
      zoomed = fig.series;
      for (Series& s : zoomed) {
        for (double& x : s.x) x = zx(x);
        for (double& y : s.y) y = zy(y);
        for (double& e : s.yerr) e *= zy.scale();
      }
      series = &zoomed;
      x0 = zx(x0); x1 = zx(x1); y0 = zy(y0); y1 = zy(y1);
      if (zx.active()) x_offset = zx.offset();
      if (zy.active()) y_offset = zy.offset();
    }
  }
  const std::string xlabel = axis_title(fig.xlabel, x_offset);

  // The legend: the labelled series that show in the window (a series without points is a
  // key, e.g. of a line style, and keeps its entry); end-labelled ones are named at their ends.
  std::vector<LegendEntry> legend;
  for (const auto& s : *series)
    if (!s.label.empty() && !s.end_label && (s.x.empty() || shows_in(s, mx, my, x0, x1, y0, y1)))
      legend.push_back({s.label, s.color, s.lines, s.markers, true, s.dashed});
  const std::vector<EndLabel> ends = end_labels(*series, mx, my, x0, x1, y0, y1);
  if (lay)
    for (const auto& e : legend) lay->legend.push_back(e.label);

  render(out, format, W, H, ro.dpi, fig.metadata, [&](const Painter& p) {
    const TitleBlock tb = title_block(p, fig.title, fig.subtitle, W, st);
    Frame f{};
    f.top = tb.height(st) + 0.3 * st.body + end_label_top_room(ends, st);
    const double below = fig.legend_below ? legend_rows_height(p, legend, st.small, W - 2 * st.body) : 0;
    f.bottom = H - bottom_room(xlabel, st) - below;
    const std::vector<std::string> ylines = y_title_lines(p, fig.ylabel, y_offset, f.bottom - f.top, st.body);
    f.left = left_room(p, axis_ticks(my, y0, y1, 6), ylines, st);
    const Ticks tx0 = axis_ticks(mx, x0, x1, 6);
    const double end_room = end_label_right_room(p, ends, st);
    f.right = W - std::max(1.2 * st.body + end_room,
                           (tx0.labels.empty() ? 0 : p.width(tx0.labels.back(), st.small) / 2) + 0.5 * st.body);
    // The legend: inside the frame, in the corner that hides the fewest points, when it is
    // small beside the frame and that corner is (nearly) empty; else a slim column at the right.
    const Frame base = f;
    LegendBox box;
    auto finish_frame = [&](bool column) {
      f = base;
      if (column) {
        box = legend_box(p, legend, st.small, 0.2 * W);
        f.right = W - box.w - 1.2 * st.body - end_room;
      }
      if (f.right - f.left < 80 || f.bottom - f.top < 60) throw std::runtime_error("figure too small for its labels");
      if (fig.equal_aspect) {
        // Widen the shorter side so one unit has the same length in x and y.
        const double sx = (x1 - x0) / (f.right - f.left), sy = (y1 - y0) / (f.bottom - f.top);
        if (sx > sy) {
          const double mid = (y0 + y1) / 2, half = sx * (f.bottom - f.top) / 2;
          f.y0 = mid - half; f.y1 = mid + half;
          f.x0 = x0; f.x1 = x1;
        } else {
          const double mid = (x0 + x1) / 2, half = sy * (f.right - f.left) / 2;
          f.x0 = mid - half; f.x1 = mid + half;
          f.y0 = y0; f.y1 = y1;
        }
      } else {
        f.x0 = x0; f.x1 = x1; f.y0 = y0; f.y1 = y1;
      }
      f.snap();
    };
    bool inside = false;
    const bool side_legend = !fig.legend_below && !legend.empty();
    if (side_legend) {
      box = legend_box(p, legend, st.small, 0.5 * (f.right - f.left));
      inside = box.w <= 0.6 * (f.right - f.left) && box.h <= 0.45 * (f.bottom - f.top);
    }
    finish_frame(side_legend && !inside);
    int corner = 0;
    const double margin = 0.6 * st.body;
    if (inside) {
      long covered = 0, points = 0;
      corner = best_corner(f, *series, mx, my, box.w, box.h, margin, covered);
      for (const auto& s : *series) points += static_cast<long>(std::min(s.x.size(), s.y.size()));
      if (covered > 2 + points / 200) {  // every corner hides data: beside the frame instead
        inside = false;
        finish_frame(true);
      }
    }
    const Ticks tx = axis_ticks(mx, f.x0, f.x1, std::max(3, static_cast<int>((f.right - f.left) / (6 * st.body))));
    const Ticks ty = axis_ticks(my, f.y0, f.y1, std::max(3, static_cast<int>((f.bottom - f.top) / (3.5 * st.body))));
    draw_title(p, tb, W / 2.0, st);
    draw_axes(p, f, tx, ty, mx, my, xlabel, ylines, true, st, lay);
    draw_series(p, f, *series, mx, my, st);
    p.rect(f.left, f.top, f.right, f.bottom, kFrame, frame_width(st));
    draw_end_labels(p, f, ends, end_room, st, lay);
    if (lay) lay->frame = {"", f.left, f.top, f.right, f.bottom};
    if (fig.legend_below) {
      draw_legend_rows(p, st.body, H - below - 0.2 * st.body, W - 2 * st.body, legend, st.small, st);
    } else if (inside) {
      const double m = margin;
      const int c = corner;
      draw_legend(p, c % 2 == 0 ? f.right - m - box.w : f.left + m, c < 2 ? f.top + m : f.bottom - m - box.h, box, legend, st,
                  true);
    } else {
      draw_legend(p, f.right + end_room + 0.8 * st.body, f.top, box, legend, st, false);
    }
  });
}

void draw_figure(std::ostream& out, const ImageFigure& fig, ImageFormat format, const RenderOptions& ro, FigureLayout* lay) {
  const Raster& r = fig.raster;
  const std::pair<int, int> pixels = figure_pixels(ro, fig.width, fig.height);
  const int W = pixels.first, H = pixels.second;
  check_size(W, H);
  if (!(ro.dpi >= kMinDpi && ro.dpi <= kMaxDpi)) throw std::runtime_error("figure dpi out of range");
  if (r.nx <= 0 || r.ny <= 0 || r.pixels.size() != static_cast<size_t>(r.nx) * r.ny)
    throw std::runtime_error("raster size does not match its pixels");
  const Style st(W, H, ro.dpi);

  // The window, relative to an offset when it is too narrow for plain tick labels; the
  // overlay curves move with it.
  double x0 = r.x_min, x1 = r.x_max, y0 = r.y_min, y1 = r.y_max;
  if (!(std::isfinite(x0) && std::isfinite(x1) && x1 > x0 && std::isfinite(y0) && std::isfinite(y1) && y1 > y0))
    throw std::runtime_error("raster window is empty");
  AxisOffset x_offset = r.x_offset, y_offset = r.y_offset;
  std::vector<Series> overlay = fig.overlay;
  std::vector<Annotation> notes_on = fig.annotations;
  if (!x_offset.active()) {
    const AxisZoom z{mpq_class(x0), mpq_class(x1)};
    x0 = z(x0); x1 = z(x1); x_offset = z.offset();
    for (Series& s : overlay) for (double& x : s.x) x = z(x);
    for (Annotation& a : notes_on) a.x = z(a.x);
  }
  if (!y_offset.active()) {
    const AxisZoom z{mpq_class(y0), mpq_class(y1)};
    y0 = z(y0); y1 = z(y1); y_offset = z.offset();
    for (Series& s : overlay) for (double& y : s.y) y = z(y);
    for (Annotation& a : notes_on) a.y = z(a.y);
  }

  // The legend names only what is drawn: a class whose colour no cell has is left out
  // (a sticking release in a diagram without one, "not confirmed" where every cell was);
  // overlay curves only when they show in the window, and not when named at their ends.
  const AxisMap lin;
  std::vector<Rgb> present;
  {
    std::vector<std::uint32_t> keys;
    keys.reserve(r.pixels.size());
    for (const Rgb& c : r.pixels) keys.push_back((std::uint32_t{c.r} << 16) | (std::uint32_t{c.g} << 8) | c.b);
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    for (std::uint32_t k : keys) present.push_back(Rgb{static_cast<std::uint8_t>(k >> 16), static_cast<std::uint8_t>(k >> 8), static_cast<std::uint8_t>(k)});
  }
  std::vector<LegendEntry> legend;
  for (const auto& [label, color] : r.legend)
    if (std::find(present.begin(), present.end(), color) != present.end()) legend.push_back({label, color, false, true});
  for (const auto& s : overlay)
    if (!s.label.empty() && !s.end_label && (s.x.empty() || shows_in(s, lin, lin, x0, x1, y0, y1)))
      legend.push_back({s.label, s.color, s.lines, s.markers, false, s.dashed});
  if (lay)
    for (const auto& e : legend) lay->legend.push_back(e.label);
  for (const std::string& note : r.notes) {
    legend.push_back({note, kWhite, false, false});  // no swatch
    if (lay) lay->notes.push_back(note);
  }
  const std::vector<EndLabel> ends = end_labels(overlay, lin, lin, x0, x1, y0, y1);

  // The raster as an image (at most 2048 cells a side: larger grids are sampled, nearest).
  const int sx = std::min(r.nx, 2048), sy = std::min(r.ny, 2048);
  render(out, format, W, H, ro.dpi, fig.metadata, [&](const Painter& p) {
    const TitleBlock tb = title_block(p, fig.title, fig.subtitle, W, st);
    Frame f{};
    f.top = tb.height(st) + 0.3 * st.body;
    const double below = r.legend_below ? legend_rows_height(p, legend, st.small, W - 2 * st.body) : 0;
    f.bottom = H - bottom_room(axis_title(fig.xlabel, x_offset), st) - below;
    const std::vector<std::string> ylines = y_title_lines(p, fig.ylabel, y_offset, f.bottom - f.top, st.body);
    f.left = left_room(p, nice_ticks(y0, y1), ylines, st);
    // The side column (legend and colour bar): slim, at most a quarter of the width.
    const double col_max = 0.28 * W - 1.2 * st.body;
    LegendBox box;
    double col = 0;
    if (!r.legend_below && !legend.empty()) {
      box = legend_box(p, legend, st.small, col_max - 2.6 * st.small);
      col = box.w;
    }
    Ticks tbar = r.colorbar.empty() ? Ticks{} : nice_ticks(r.colorbar_lo, r.colorbar_hi, 5);
    if (!r.colorbar.empty() && !r.colorbar_ticks.empty()) {
      tbar = Ticks{};
      for (const auto& [v, label] : r.colorbar_ticks) {
        tbar.values.push_back(v);
        tbar.labels.push_back(label);
      }
    }
    Fitted bar_label{{}, st.small};
    if (!r.colorbar.empty()) {
      // The bar's title wraps at about its own width (two lines rather than a wide column
      // that narrows the plot).
      bar_label = fit_text(p, r.colorbar_label, st.small,
                           std::min(col_max, std::max(9.0 * st.body, 2.4 * st.body + max_label_width(p, tbar, st.small))), true,
                           {" "}, false);
      double lw = 0;
      for (const auto& l : bar_label.lines) lw = std::max(lw, p.width(l, bar_label.size));
      col = std::max({col, 1.6 * st.body + 0.8 * st.body + max_label_width(p, tbar, st.small), lw});
    }
    const Ticks tx0 = nice_ticks(x0, x1);
    const double end_room = end_label_right_room(p, ends, st);
    f.top += end_label_top_room(ends, st);
    f.right = W - end_room -
              (col > 0 ? col + 1.6 * st.body
                       : std::max(1.2 * st.body, (tx0.labels.empty() ? 0 : p.width(tx0.labels.back(), st.small) / 2) +
                                                     0.5 * st.body));
    if (f.right - f.left < 80 || f.bottom - f.top < 60) throw std::runtime_error("figure too small for its labels");
    f.snap();
    f.x0 = x0; f.x1 = x1; f.y0 = y0; f.y1 = y1;

    // The cells, nearest neighbour (a cell is a square of colour, not a blur).
    cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, sx, sy);
    if (cairo_surface_status(img) != CAIRO_STATUS_SUCCESS) {
      cairo_surface_destroy(img);
      throw OutputError("cannot allocate the raster image");
    }
    cairo_surface_flush(img);
    unsigned char* data = cairo_image_surface_get_data(img);
    const int stride = cairo_image_surface_get_stride(img);
    for (int y = 0; y < sy; ++y) {
      const long row = static_cast<long>(y) * r.ny / sy;
      for (int x = 0; x < sx; ++x) {
        const long c = static_cast<long>(x) * r.nx / sx;
        const Rgb px = r.pixels[static_cast<size_t>(row) * r.nx + c];
        const std::uint32_t v = (std::uint32_t{px.r} << 16) | (std::uint32_t{px.g} << 8) | px.b;
        std::memcpy(data + static_cast<size_t>(y) * stride + 4 * static_cast<size_t>(x), &v, 4);
      }
    }
    cairo_surface_mark_dirty(img);
    cairo_t* cr = p.cr();
    cairo_save(cr);
    cairo_rectangle(cr, f.left, f.top, f.right - f.left, f.bottom - f.top);
    cairo_clip(cr);
    cairo_translate(cr, f.left, f.top);
    cairo_scale(cr, (f.right - f.left) / sx, (f.bottom - f.top) / sy);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_pattern_set_extend(cairo_get_source(cr), CAIRO_EXTEND_PAD);
    cairo_paint(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);

    const Ticks tx = nice_ticks(f.x0, f.x1, std::max(3, static_cast<int>((f.right - f.left) / (6 * st.body))));
    const Ticks ty = nice_ticks(f.y0, f.y1, std::max(3, static_cast<int>((f.bottom - f.top) / (3.5 * st.body))));
    draw_title(p, tb, W / 2.0, st);
    draw_axes(p, f, tx, ty, lin, lin, axis_title(fig.xlabel, x_offset), ylines, false, st, lay);
    draw_series(p, f, overlay, lin, lin, st, true);
    p.clip(f.left, f.top, f.right, f.bottom);
    std::vector<TextBox> taken;
    for (const Annotation& a : notes_on) {
      // Kept inside the frame: a tag of the first or last column is not cut by the edge.
      const double half = p.width(a.text, st.small) / 2 + 0.2 * st.small;
      const double x = f.right - f.left > 2 * half ? std::clamp(f.px(a.x), f.left + half, f.right - half) : f.px(a.x);
      draw_annotation(p, x, f.py(a.y), a.text, a.color, st, taken, lay);
    }
    p.unclip();
    p.rect(f.left, f.top, f.right, f.bottom, kFrame, frame_width(st));
    draw_end_labels(p, f, ends, end_room, st, lay);
    if (lay) lay->frame = {"", f.left, f.top, f.right, f.bottom};

    double y = f.top;
    const double x = f.right + end_room + 0.8 * st.body;
    if (r.legend_below) {
      draw_legend_rows(p, st.body, H - below - 0.2 * st.body, W - 2 * st.body, legend, st.small, st);
    } else if (!legend.empty()) {
      draw_legend(p, x, y, box, legend, st, false);
      y += box.h + 0.8 * st.body;
    }
    if (!r.colorbar.empty()) {
      for (const auto& l : bar_label.lines) {
        y += Painter::leading(bar_label.size);
        p.text(x, y - 0.25 * bar_label.size, l, bar_label.size, kBlack);
      }
      const double top = y + 0.5 * st.body, bottom = f.bottom, bw = 1.6 * st.body;
      if (bottom - top > 3 * st.body) {
        const int n = static_cast<int>(r.colorbar.size());
        for (int i = 0; i < n; ++i) {  // ramp[0] at the bottom
          const double y_hi = bottom - (i + 1.0) / n * (bottom - top), y_lo = bottom - static_cast<double>(i) / n * (bottom - top);
          p.fill(x, y_hi - 0.5, x + bw, y_lo + (i == 0 ? 0 : 0.5), r.colorbar[i]);
        }
        p.rect(x, top, x + bw, bottom, kFrame, 0.8 * st.line);
        for (size_t i = 0; i < tbar.values.size(); ++i) {
          const double yy = bottom - (tbar.values[i] - r.colorbar_lo) / (r.colorbar_hi - r.colorbar_lo) * (bottom - top);
          p.line(x + bw, yy, x + bw + 0.3 * st.body, yy, kFrame, 0.8 * st.line);
          p.text(x + bw + 0.5 * st.body, yy + Painter::cap(st.small) / 2, typeset(tbar.labels[i]), st.small, kBlack);
        }
        if (lay) {
          lay->colorbar = true;
          lay->colorbar_ticks = tbar.labels;
        }
      }
    }
  });
}

}  // namespace

void write_figure(std::ostream& out, const Figure& f, ImageFormat format, const RenderOptions& r) {
  draw_figure(out, f, format, r, nullptr);
}
void write_figure(std::ostream& out, const ImageFigure& f, ImageFormat format, const RenderOptions& r) {
  draw_figure(out, f, format, r, nullptr);
}
FigureLayout figure_layout(const Figure& f, const RenderOptions& r) {
  FigureLayout lay;
  std::ostringstream sink;
  draw_figure(sink, f, ImageFormat::svg, r, &lay);
  return lay;
}
FigureLayout figure_layout(const ImageFigure& f, const RenderOptions& r) {
  FigureLayout lay;
  std::ostringstream sink;
  draw_figure(sink, f, ImageFormat::svg, r, &lay);
  return lay;
}

std::pair<int, int> write_contact_sheet(const std::vector<std::string>& pngs, const std::string& out,
                                        const ContactSheetOptions& o) {
  if (pngs.empty()) throw std::invalid_argument("contact sheet: no pictures");
  if (o.columns < 1 || o.columns > 16 || o.thumb_width < 64 || o.thumb_width > 2000)
    throw std::invalid_argument("contact sheet: columns in [1, 16], thumb_width in [64, 2000]");
  // Read every picture first: a missing or broken one is reported before anything is written.
  std::vector<cairo_surface_t*> images;
  auto release = [&] {
    for (cairo_surface_t* s : images) cairo_surface_destroy(s);
  };
  for (const std::string& path : pngs) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS || cairo_image_surface_get_width(s) <= 0) {
      cairo_surface_destroy(s);
      release();
      throw OutputError("contact sheet: cannot read '" + path + "' as a PNG picture");
    }
    images.push_back(s);
  }
  const int tw = o.thumb_width, cols = std::min<int>(o.columns, static_cast<int>(images.size()));
  const Style st(tw * cols, tw, kDefaultDpi);
  const double caption = Painter::leading(st.small) + 0.4 * st.body, gap = 0.8 * st.body;
  double row_h = 0;
  for (cairo_surface_t* s : images)
    row_h = std::max(row_h, static_cast<double>(tw) * cairo_image_surface_get_height(s) / cairo_image_surface_get_width(s));
  const int rows = static_cast<int>((images.size() + cols - 1) / cols);
  const int W = static_cast<int>(std::ceil(cols * (tw + gap) + gap));
  const int H = static_cast<int>(std::ceil(rows * (row_h + caption + gap) + gap));
  try {
    check_size(W, H);
    write_output("out", out, [&](std::ostream& os) {
      render(os, ImageFormat::png, W, H, kDefaultDpi, {{"Title", "contact sheet"}}, [&](const Painter& p) {
        for (size_t i = 0; i < images.size(); ++i) {
          const double x = gap + static_cast<double>(i % cols) * (tw + gap), y = gap + static_cast<double>(i / cols) * (row_h + caption + gap);
          const std::string name = std::filesystem::path(pngs[i]).filename().string();
          const Fitted f = fit_text(p, name, st.small, tw, false);
          if (!f.lines.empty()) p.text(x, y + Painter::cap(f.size), f.lines[0], f.size, kBlack);
          const double scale = static_cast<double>(tw) / cairo_image_surface_get_width(images[i]);
          cairo_t* cr = p.cr();
          cairo_save(cr);
          cairo_translate(cr, x, y + caption);
          cairo_scale(cr, scale, scale);
          cairo_set_source_surface(cr, images[i], 0, 0);
          cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
          cairo_paint(cr);
          cairo_restore(cr);
          p.rect(x, y + caption, x + tw, y + caption + scale * cairo_image_surface_get_height(images[i]), Rgb{200, 200, 200},
                 1.0);
        }
      });
    });
  } catch (...) {
    release();
    throw;
  }
  release();
  return {W, H};
}

void write_figure(const std::string& path, const Figure& f, ImageFormat format, const RenderOptions& r) {
  write_output("out", path, [&](std::ostream& s) { write_figure(s, f, format, r); });
}
void write_figure(const std::string& path, const ImageFigure& f, ImageFormat format, const RenderOptions& r) {
  write_output("out", path, [&](std::ostream& s) { write_figure(s, f, format, r); });
}

}  // namespace bouncer
