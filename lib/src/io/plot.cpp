// PNG figures: an RGB canvas, a bitmap font, axes with nice ticks, legends, colour bars,
// written with libpng (provenance in tEXt chunks) to PATH.partial and renamed into place.
#include "bouncer/io/plot.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "bouncer/io/output.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/scalar/decimal.hpp"

namespace bouncer {

namespace {

#include "plot_font.inc"

constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kGrid{228, 228, 228};
constexpr Rgb kFrame{40, 40, 40};
constexpr Rgb kMuted{90, 90, 90};

// Glyph indices of a UTF-8 string: ASCII, and the four Greek letters of the font.
std::vector<int> glyphs(const std::string& s) {
  std::vector<int> out;
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      out.push_back(c >= 32 && c <= 126 ? c - 32 : '?' - 32);
      ++i;
      continue;
    }
    unsigned cp = 0;
    int len = (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 1;
    cp = len == 2 ? c & 0x1F : len == 3 ? c & 0x0F : c & 0x07;
    for (int k = 1; k < len && i + k < s.size(); ++k) cp = (cp << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F);
    i += len;
    switch (cp) {
      case 0x03B8: case 0x03D1: out.push_back(95); break;  // theta
      case 0x03B5: case 0x03F5: out.push_back(96); break;  // epsilon
      case 0x03C0: out.push_back(97); break;               // pi
      case 0x03C6: case 0x03D5: out.push_back(98); break;  // phi
      default: out.push_back('?' - 32);
    }
  }
  return out;
}

class Canvas {
 public:
  static constexpr double kFar = 1e9;  // pixel coordinates beyond this are not drawn
  Canvas(int w, int h) : w_(w), h_(h), px_(static_cast<size_t>(w) * h * 3, 255) {}
  int width() const { return w_; }
  int height() const { return h_; }
  const std::vector<std::uint8_t>& bytes() const { return px_; }

  void set(int x, int y, Rgb c) {
    if (x < clip_x0_ || y < clip_y0_ || x >= clip_x1_ || y >= clip_y1_) return;
    std::uint8_t* p = &px_[(static_cast<size_t>(y) * w_ + x) * 3];
    p[0] = c.r; p[1] = c.g; p[2] = c.b;
  }
  void clip(int x0, int y0, int x1, int y1) {
    clip_x0_ = std::max(0, x0); clip_y0_ = std::max(0, y0);
    clip_x1_ = std::min(w_, x1); clip_y1_ = std::min(h_, y1);
  }
  void unclip() { clip(0, 0, w_, h_); }

  void fill(int x0, int y0, int x1, int y1, Rgb c) {  // [x0, x1) x [y0, y1)
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) set(x, y, c);
  }
  void rect(int x0, int y0, int x1, int y1, Rgb c) {  // outline, inclusive corners
    for (int x = x0; x <= x1; ++x) { set(x, y0, c); set(x, y1, c); }
    for (int y = y0; y <= y1; ++y) { set(x0, y, c); set(x1, y, c); }
  }
  void line(double fx0, double fy0, double fx1, double fy1, Rgb c, int thick = 1) {
    // Bresenham on rounded ends; `thick` > 1 draws a small square brush.
    if (!(std::fabs(fx0) < kFar && std::fabs(fy0) < kFar && std::fabs(fx1) < kFar && std::fabs(fy1) < kFar)) return;
    int x0 = static_cast<int>(std::lround(fx0)), y0 = static_cast<int>(std::lround(fy0));
    const int x1 = static_cast<int>(std::lround(fx1)), y1 = static_cast<int>(std::lround(fy1));
    const int dx = std::abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
    const int dy = -std::abs(y1 - y0), sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    const int lo = -(thick - 1) / 2, hi = thick / 2;
    for (long guard = 0; guard < 100000; ++guard) {
      for (int a = lo; a <= hi; ++a)
        for (int b = lo; b <= hi; ++b) set(x0 + a, y0 + b, c);
      if (x0 == x1 && y0 == y1) break;
      const int e2 = 2 * err;
      if (e2 >= dy) { err += dy; x0 += sx; }
      if (e2 <= dx) { err += dx; y0 += sy; }
    }
  }
  void disc(double fx, double fy, int r, Rgb c) {
    if (!(std::fabs(fx) < kFar && std::fabs(fy) < kFar)) return;  // far outside (and no int overflow)
    const int x = static_cast<int>(std::lround(fx)), y = static_cast<int>(std::lround(fy));
    for (int a = -r; a <= r; ++a)
      for (int b = -r; b <= r; ++b)
        if (a * a + b * b <= r * r + r) set(x + a, y + b, c);
  }

  static int text_width(const std::string& s, int scale) {
    const int n = static_cast<int>(glyphs(s).size());
    return n == 0 ? 0 : (n * 6 - 1) * scale;
  }
  static int text_height(int scale) { return 8 * scale; }
  // Horizontal text with its top-left corner at (x, y).
  void text(int x, int y, const std::string& s, int scale, Rgb c, bool bold = false) {
    int k = 0;
    for (int g : glyphs(s)) {
      const unsigned char* rows = kFont[g < kFontGlyphs ? g : '?' - 32];
      for (int r = 0; r < 8; ++r)
        for (int col = 0; col < 5; ++col)
          if (rows[r] & (0x10 >> col)) {
            const int px = x + (k * 6 + col) * scale, py = y + r * scale;
            fill(px, py, px + scale + (bold ? 1 : 0), py + scale, c);
          }
      ++k;
    }
  }
  // Text rotated a quarter turn counter-clockwise (read bottom to top); (x, y) is the
  // bottom-left corner of the rotated block.
  void text_up(int x, int y, const std::string& s, int scale, Rgb c) {
    int k = 0;
    for (int g : glyphs(s)) {
      const unsigned char* rows = kFont[g < kFontGlyphs ? g : '?' - 32];
      for (int r = 0; r < 8; ++r)
        for (int col = 0; col < 5; ++col)
          if (rows[r] & (0x10 >> col)) {
            const int px = x + r * scale, py = y - (k * 6 + col + 1) * scale;
            fill(px, py, px + scale, py + scale, c);
          }
      ++k;
    }
  }

 private:
  int w_, h_;
  std::vector<std::uint8_t> px_;
  int clip_x0_ = 0, clip_y0_ = 0, clip_x1_ = w_, clip_y1_ = h_;
};

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

// Bits of a PNG writer that must not hold C++ objects across setjmp.
bool encode_png(const char* path, int w, int h, const std::uint8_t* rgb, png_text* text, int ntext) {
  FILE* fp = std::fopen(path, "wb");
  if (!fp) return false;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, png_silent_error, png_silent_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    std::fclose(fp);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(fp);
    return false;
  }
  png_init_io(png, fp);
  png_set_compression_level(png, 9);
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (ntext > 0) png_set_text(png, info, text, ntext);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) png_write_row(png, const_cast<png_bytep>(rgb + static_cast<size_t>(y) * w * 3));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return std::fclose(fp) == 0;
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

void save(const std::string& path, const Canvas& c, std::vector<std::pair<std::string, std::string>> meta) {
  bool has_software = false;
  for (const auto& kv : meta) has_software = has_software || kv.first == "Software";
  if (!has_software) meta.emplace_back("Software", "bouncer " + build_info().version + " (commit " + build_info().commit + ")");
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
  const std::string tmp = path + ".partial";
  const PartialFile registered(tmp);
  if (!encode_png(tmp.c_str(), c.width(), c.height(), c.bytes().data(), text.data(), static_cast<int>(text.size()))) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw OutputError("cannot write PNG '" + path + "'");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw OutputError("cannot rename '" + tmp + "' to '" + path + "'");
  }
}

// Text sizes: tick labels and legend at scale 2, title at scale 3 on a 900-pixel figure.
struct Style {
  int small, title;
  explicit Style(int width) : small(width >= 600 ? 2 : 1), title(width >= 600 ? 3 : 2) {}
};

struct LegendEntry {
  std::string label;
  Rgb color;
  bool line = false, marker = true;
};

int legend_width(const std::vector<LegendEntry>& entries, int scale) {
  int w = 0;
  for (const auto& e : entries) w = std::max(w, Canvas::text_width(e.label, scale));
  return entries.empty() ? 0 : w + 12 * scale + 16;
}

// Legend entries stacked from (x, y); returns the y below the last one.
int draw_legend(Canvas& c, int x, int y, const std::vector<LegendEntry>& entries, int scale) {
  if (entries.empty()) return y;
  const int row = Canvas::text_height(scale) + 6 * scale / 2 + 4;
  const int h = static_cast<int>(entries.size()) * row + 8;
  c.fill(x, y, x + legend_width(entries, scale), y + h, kWhite);
  c.rect(x, y, x + legend_width(entries, scale), y + h, Rgb{170, 170, 170});
  int yy = y + 6;
  for (const auto& e : entries) {
    const int sw = 8 * scale, cy = yy + Canvas::text_height(scale) / 2;
    if (e.line) c.line(x + 6, cy, x + 6 + sw, cy, e.color, 2);
    if (e.marker) c.fill(x + 6 + sw / 2 - 3 * scale, cy - 3 * scale, x + 6 + sw / 2 + 3 * scale, cy + 3 * scale, e.color);
    if (e.marker) c.rect(x + 6 + sw / 2 - 3 * scale, cy - 3 * scale, x + 6 + sw / 2 + 3 * scale - 1, cy + 3 * scale - 1, kMuted);
    c.text(x + 12 + sw, yy, e.label, scale, kBlack);
    yy += row;
  }
  return y + h;
}

// Title (and subtitle) centred over the plot area; returns the height used.
// The subtitle as lines that fit the figure: split at "; " (then ", ") when too long.
std::vector<std::string> subtitle_lines(const std::string& sub, int scale, int width) {
  std::vector<std::string> lines;
  std::string rest = sub;
  while (!rest.empty()) {
    if (Canvas::text_width(rest, scale) <= width - 16) {
      lines.push_back(rest);
      break;
    }
    // The split that fits and balances the line widths best ("; " and ", " only).
    size_t cut = std::string::npos;
    int best = 1 << 30;
    for (const char* sep : {"; ", ", "})
      for (size_t at = rest.find(sep); at != std::string::npos; at = rest.find(sep, at + 1)) {
        const int w1 = Canvas::text_width(rest.substr(0, at + 1), scale);
        const int w2 = Canvas::text_width(rest.substr(at + 2), scale);
        const int worst = w1 > width - 16 ? (1 << 29) + w1 : std::max(w1, w2);
        if (worst < best) { best = worst; cut = at; }
      }
    if (cut == std::string::npos) {
      lines.push_back(rest);
      break;
    }
    lines.push_back(rest.substr(0, cut + 1));
    rest = rest.substr(cut + 2);
  }
  return lines;
}

int title_height(const std::string& title, const std::string& subtitle, int width, const Style& st) {
  int h = 10;
  if (!title.empty()) h += Canvas::text_height(st.title) + 8;
  if (!subtitle.empty())
    h += static_cast<int>(subtitle_lines(subtitle, st.small, width).size()) * (Canvas::text_height(st.small) + 6);
  return h + 8;
}

// Title and subtitle centred over `cx` but kept inside the figure.
int draw_title(Canvas& c, const std::string& title, const std::string& subtitle, int cx, const Style& st) {
  int y = 10;
  auto centred = [&](const std::string& s, int scale, Rgb col) {
    const int w = Canvas::text_width(s, scale);
    const int x = std::clamp(cx - w / 2, 8, std::max(8, c.width() - 8 - w));
    c.text(x, y, s, scale, col);
    y += Canvas::text_height(scale);
  };
  if (!title.empty()) {
    centred(title, st.title, kBlack);
    y += 8;
  }
  if (!subtitle.empty())
    for (const std::string& line : subtitle_lines(subtitle, st.small, c.width())) {
      centred(line, st.small, kMuted);
      y += 6;
    }
  return y + 8;
}

// A legend laid out in rows under the plot: entries flow left to right.
std::vector<std::vector<size_t>> legend_rows(const std::vector<LegendEntry>& entries, int scale, int max_width) {
  std::vector<std::vector<size_t>> rows;
  int x = 0;
  for (size_t i = 0; i < entries.size(); ++i) {
    const int w = 8 * scale + 12 + Canvas::text_width(entries[i].label, scale) + 24;
    if (rows.empty() || (x + w > max_width && !rows.back().empty())) {
      rows.emplace_back();
      x = 0;
    }
    rows.back().push_back(i);
    x += w;
  }
  return rows;
}

int legend_below_height(const std::vector<LegendEntry>& entries, int scale, int max_width) {
  if (entries.empty()) return 0;
  return static_cast<int>(legend_rows(entries, scale, max_width).size()) * (Canvas::text_height(scale) + 10) + 8;
}

void draw_legend_below(Canvas& c, int left, int y, int max_width, const std::vector<LegendEntry>& entries, int scale) {
  for (const auto& row : legend_rows(entries, scale, max_width)) {
    int total = 0;
    for (size_t i : row) total += 8 * scale + 12 + Canvas::text_width(entries[i].label, scale) + 24;
    int x = left + std::max(0, (max_width - total + 24) / 2);
    for (size_t i : row) {
      const LegendEntry& e = entries[i];
      const int sw = 8 * scale, cy = y + Canvas::text_height(scale) / 2;
      if (e.line) c.line(x, cy, x + sw, cy, e.color, 2);
      if (e.marker) {
        c.fill(x + sw / 2 - 3 * scale, cy - 3 * scale, x + sw / 2 + 3 * scale, cy + 3 * scale, e.color);
        c.rect(x + sw / 2 - 3 * scale, cy - 3 * scale, x + sw / 2 + 3 * scale - 1, cy + 3 * scale - 1, kMuted);
      }
      c.text(x + sw + 8, y, e.label, scale, kBlack);
      x += sw + 12 + Canvas::text_width(e.label, scale) + 24;
    }
    y += Canvas::text_height(scale) + 10;
  }
}

// The rectangle of the plot in pixels and the data window it shows.
struct Frame {
  int left, top, right, bottom;  // pixel edges (inclusive)
  double x0, x1, y0, y1;         // data window (y in log10 when log_y)
  double px(double x) const { return left + (x - x0) / (x1 - x0) * (right - left); }
  double py(double y) const { return bottom - (y - y0) / (y1 - y0) * (bottom - top); }
};

// The lines of a y axis title (drawn upward beside the frame): one, or for an offset axis
// whose title is longer than the frame is tall, the label and then the offset note
// ("- 4, in units of 1e-26") on a second line.
std::vector<std::string> y_title_lines(const std::string& label, const AxisOffset& o, int frame_height, int scale) {
  const std::string whole = axis_title(label, o);
  if (!o.active() || label.empty() || Canvas::text_width(whole, scale) <= frame_height) return {whole};
  return {label, axis_title("", o).substr(1)};
}
int y_title_extra(const std::vector<std::string>& lines, int scale) {
  return static_cast<int>(lines.size() - 1) * (Canvas::text_height(scale) + 4);
}

// Axes: frame, ticks, tick labels, grid lines (optional) and axis labels.
void draw_axes(Canvas& c, const Frame& f, const Ticks& tx, const Ticks& ty, bool log_y, const std::string& xlabel,
               const std::vector<std::string>& ylines, bool grid, const Style& st) {
  const int tick = 6;
  if (grid) {
    c.clip(f.left + 1, f.top + 1, f.right, f.bottom);
    for (double v : tx.values) c.line(f.px(v), f.top, f.px(v), f.bottom, kGrid);
    for (double v : ty.values) c.line(f.left, f.py(log_y ? std::log10(v) : v), f.right, f.py(log_y ? std::log10(v) : v), kGrid);
    c.unclip();
  }
  int widest = 0;
  for (size_t i = 0; i < tx.values.size(); ++i) {
    const double x = f.px(tx.values[i]);
    c.line(x, f.bottom, x, f.bottom + tick, kFrame);
    c.text(static_cast<int>(x) - Canvas::text_width(tx.labels[i], st.small) / 2, f.bottom + tick + 4, tx.labels[i], st.small, kBlack);
  }
  for (size_t i = 0; i < ty.values.size(); ++i) {
    const double y = f.py(log_y ? std::log10(ty.values[i]) : ty.values[i]);
    c.line(f.left - tick, y, f.left, y, kFrame);
    const int w = Canvas::text_width(ty.labels[i], st.small);
    widest = std::max(widest, w);
    c.text(f.left - tick - 4 - w, static_cast<int>(y) - Canvas::text_height(st.small) / 2, ty.labels[i], st.small, kBlack);
  }
  c.rect(f.left, f.top, f.right, f.bottom, kFrame);
  const int cx = (f.left + f.right) / 2, cy = (f.top + f.bottom) / 2;
  if (!xlabel.empty())
    c.text(cx - Canvas::text_width(xlabel, st.small) / 2, f.bottom + tick + 4 + Canvas::text_height(st.small) + 10, xlabel, st.small, kBlack);
  const std::string& ylabel = ylines.front();
  if (ylines.size() == 1 && !ylabel.empty() && glyphs(ylabel).size() <= 2)  // a symbol reads better upright
    c.text(f.left - tick - 4 - widest - 10 - Canvas::text_width(ylabel, st.small), cy - Canvas::text_height(st.small) / 2, ylabel,
           st.small, kBlack);
  else if (!ylabel.empty())
    for (size_t i = 0; i < ylines.size(); ++i)  // the first line outermost
      c.text_up(f.left - tick - 4 - widest - 10 - Canvas::text_height(st.small) -
                    static_cast<int>(ylines.size() - 1 - i) * (Canvas::text_height(st.small) + 4),
                cy + Canvas::text_width(ylines[i], st.small) / 2, ylines[i], st.small, kBlack);
}

int max_label_width(const Ticks& t, int scale) {
  int w = 0;
  for (const auto& l : t.labels) w = std::max(w, Canvas::text_width(l, scale));
  return w;
}

void data_range(const std::vector<Series>& series, bool use_x, bool log, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (const auto& s : series)
    for (double v : use_x ? s.x : s.y) {
      if (!std::isfinite(v) || (log && v <= 0)) continue;
      const double t = log ? std::log10(v) : v;
      lo = std::min(lo, t);
      hi = std::max(hi, t);
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

Rgb ramp_color(double t) {
  t = std::clamp(t, 0.0, 1.0);
  // White to near-black through cool greys: light marks stay visible, dense ones are black.
  const double l = 1 - t;
  auto ch = [&](double bias) { return static_cast<std::uint8_t>(std::lround(255 * std::clamp(std::pow(l, bias) * 0.97, 0.0, 1.0))); };
  return Rgb{ch(1.15), ch(1.05), ch(0.95)};
}

Rgb category_color(int index) {
  static const Rgb palette[] = {
      {230, 159, 0},   {0, 158, 115},  {204, 121, 167}, {240, 228, 66}, {140, 86, 11},   {86, 180, 233},
      {128, 128, 0},   {0, 200, 200},  {255, 200, 140}, {100, 60, 140}, {180, 220, 120}, {200, 170, 230},
      {120, 120, 60},  {0, 110, 110},  {255, 150, 220}, {170, 120, 60},
  };
  constexpr int n = sizeof(palette) / sizeof(palette[0]);
  if (index < 0) index = 0;
  const Rgb base = palette[index % n];
  if (index < n) return base;
  // Further categories: darker variants of the palette.
  const double f = index < 2 * n ? 0.6 : 0.35;
  return Rgb{static_cast<std::uint8_t>(base.r * f), static_cast<std::uint8_t>(base.g * f), static_cast<std::uint8_t>(base.b * f)};
}

void write_png(const std::string& path, const Figure& fig) {
  if (fig.width < 200 || fig.height < 150 || fig.width > 20000 || fig.height > 20000)
    throw std::runtime_error("figure size out of range");
  const Style st(fig.width);
  Canvas c(fig.width, fig.height);

  // Data window.
  double x0, x1, y0, y1;
  data_range(fig.series, true, false, x0, x1);
  data_range(fig.series, false, fig.log_y, y0, y1);
  if (std::isfinite(fig.x_min)) x0 = fig.x_min;
  if (std::isfinite(fig.x_max)) x1 = fig.x_max;
  if (std::isfinite(fig.y_min)) y0 = fig.log_y ? std::log10(fig.y_min) : fig.y_min;
  if (std::isfinite(fig.y_max)) y1 = fig.log_y ? std::log10(fig.y_max) : fig.y_max;
  if (!(x1 > x0)) x1 = x0 + 1;
  if (!(y1 > y0)) y1 = y0 + 1;

  // A window too narrow for plain tick labels is drawn relative to an offset (AxisZoom),
  // unless the caller's coordinates already are.
  AxisOffset x_offset = fig.x_offset, y_offset = fig.y_offset;
  std::vector<Series> zoomed;
  const std::vector<Series>* series = &fig.series;
  if (!fig.equal_aspect) {
    const AxisZoom zx = x_offset.active() ? AxisZoom() : AxisZoom(mpq_class(x0), mpq_class(x1));
    const AxisZoom zy = y_offset.active() || fig.log_y ? AxisZoom() : AxisZoom(mpq_class(y0), mpq_class(y1));
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

  std::vector<LegendEntry> legend;
  for (const auto& s : *series)
    if (!s.label.empty()) legend.push_back({s.label, s.color, s.lines, s.markers});

  // Layout: room for the y tick labels (estimated from the window), labels, title, legend.
  const Ticks ty0 = fig.log_y ? log_ticks(std::pow(10.0, y0), std::pow(10.0, y1)) : nice_ticks(y0, y1);
  const int title_h = title_height(fig.title, fig.subtitle, fig.width, st) + 8;
  Frame f{};
  f.top = title_h;
  const int below = fig.legend_below ? legend_below_height(legend, st.small, fig.width - 40) : 0;
  const int frame_bottom = fig.height - (6 + 4 + 2 * Canvas::text_height(st.small) + 10 + 14) - below;
  const std::vector<std::string> ylines = y_title_lines(fig.ylabel, y_offset, frame_bottom - f.top, st.small);
  f.left = 16 + Canvas::text_height(st.small) + 10 + max_label_width(ty0, st.small) + 10 + y_title_extra(ylines, st.small);
  // Room at the right for half of the last x tick label (it is centred on its tick).
  const int x_overhang = Canvas::text_width(nice_ticks(x0, x1).labels.empty() ? "" : nice_ticks(x0, x1).labels.back(), st.small) / 2 + 6;
  f.right = fig.width - std::max(20, x_overhang) - (legend.empty() || fig.legend_below ? 0 : legend_width(legend, st.small) + 16);
  f.bottom = frame_bottom;
  if (f.right - f.left < 80 || f.bottom - f.top < 60) throw std::runtime_error("figure too small for its labels");

  if (fig.equal_aspect) {
    // Widen the shorter side so one unit has the same length in x and y.
    const double sx = (x1 - x0) / (f.right - f.left), sy = (y1 - y0) / (f.bottom - f.top);
    if (sx > sy) {
      const double mid = (y0 + y1) / 2, half = sx * (f.bottom - f.top) / 2;
      y0 = mid - half; y1 = mid + half;
    } else {
      const double mid = (x0 + x1) / 2, half = sy * (f.right - f.left) / 2;
      x0 = mid - half; x1 = mid + half;
    }
  }
  f.x0 = x0; f.x1 = x1; f.y0 = y0; f.y1 = y1;
  const Ticks tx = nice_ticks(x0, x1, std::max(3, (f.right - f.left) / 110));
  const Ticks ty = fig.log_y ? log_ticks(std::pow(10.0, y0), std::pow(10.0, y1)) : nice_ticks(y0, y1, std::max(3, (f.bottom - f.top) / 80));

  draw_title(c, fig.title, fig.subtitle, fig.width / 2, st);
  draw_axes(c, f, tx, ty, fig.log_y, xlabel, ylines, true, st);

  c.clip(f.left + 1, f.top + 1, f.right, f.bottom);
  for (const auto& s : *series) {
    const size_t n = std::min(s.x.size(), s.y.size());
    auto ok = [&](size_t i) { return std::isfinite(s.x[i]) && std::isfinite(s.y[i]) && (!fig.log_y || s.y[i] > 0); };
    auto Y = [&](size_t i) { return f.py(fig.log_y ? std::log10(s.y[i]) : s.y[i]); };
    if (s.lines)
      for (size_t i = 1; i < n; ++i)
        if (ok(i - 1) && ok(i)) c.line(f.px(s.x[i - 1]), Y(i - 1), f.px(s.x[i]), Y(i), s.color, 2);
    // Error bars under the markers, with short caps so that a bar shorter than the
    // marker is still visible as a cap.
    for (size_t i = 0; i < n && i < s.yerr.size(); ++i) {
      const double e = s.yerr[i];
      if (!ok(i) || !std::isfinite(e) || e <= 0 || fig.log_y) continue;
      const double xp = f.px(s.x[i]), lo = f.py(s.y[i] - e), hi = f.py(s.y[i] + e);
      c.line(xp, lo, xp, hi, s.color, 1);
      c.line(xp - 3, lo, xp + 3, lo, s.color, 1);
      c.line(xp - 3, hi, xp + 3, hi, s.color, 1);
    }
    if (s.markers)
      for (size_t i = 0; i < n; ++i)
        if (ok(i)) c.disc(f.px(s.x[i]), Y(i), s.marker_size, s.color);
  }
  c.unclip();
  c.rect(f.left, f.top, f.right, f.bottom, kFrame);
  if (fig.legend_below) draw_legend_below(c, 20, fig.height - below, fig.width - 40, legend, st.small);
  else draw_legend(c, f.right + 16, f.top, legend, st.small);
  save(path, c, fig.metadata);
}

void write_png(const std::string& path, const ImageFigure& fig) {
  const Raster& r = fig.raster;
  if (fig.width < 200 || fig.height < 150 || fig.width > 20000 || fig.height > 20000)
    throw std::runtime_error("figure size out of range");
  if (r.nx <= 0 || r.ny <= 0 || r.pixels.size() != static_cast<size_t>(r.nx) * r.ny)
    throw std::runtime_error("raster size does not match its pixels");
  const Style st(fig.width);
  Canvas c(fig.width, fig.height);

  // The window, relative to an offset when it is too narrow for plain tick labels.
  double x0 = r.x_min, x1 = r.x_max, y0 = r.y_min, y1 = r.y_max;
  if (!(std::isfinite(x0) && std::isfinite(x1) && x1 > x0 && std::isfinite(y0) && std::isfinite(y1) && y1 > y0))
    throw std::runtime_error("raster window is empty");
  AxisOffset x_offset = r.x_offset, y_offset = r.y_offset;
  if (!x_offset.active()) {
    const AxisZoom z{mpq_class(x0), mpq_class(x1)};
    x0 = z(x0); x1 = z(x1); x_offset = z.offset();
  }
  if (!y_offset.active()) {
    const AxisZoom z{mpq_class(y0), mpq_class(y1)};
    y0 = z(y0); y1 = z(y1); y_offset = z.offset();
  }

  std::vector<LegendEntry> legend;
  for (const auto& [label, color] : r.legend) legend.push_back({label, color, false, true});
  const Ticks ty0 = nice_ticks(y0, y1);
  const Ticks tbar = r.colorbar.empty() ? Ticks{} : nice_ticks(r.colorbar_lo, r.colorbar_hi, 5);
  const int bar_w = r.colorbar.empty() ? 0 : std::max(22 + 12 + max_label_width(tbar, st.small), Canvas::text_width(r.colorbar_label, st.small));
  const int panel = std::max(r.legend_below ? 0 : legend_width(legend, st.small), bar_w);
  const int below = r.legend_below ? legend_below_height(legend, st.small, fig.width - 40) : 0;
  const int title_h = title_height(fig.title, fig.subtitle, fig.width, st) + 8;
  Frame f{};
  f.top = title_h;
  const int frame_bottom = fig.height - (6 + 4 + 2 * Canvas::text_height(st.small) + 10 + 14) - below;
  const std::vector<std::string> ylines = y_title_lines(fig.ylabel, y_offset, frame_bottom - f.top, st.small);
  f.left = 16 + Canvas::text_height(st.small) + 10 + max_label_width(ty0, st.small) + 10 + y_title_extra(ylines, st.small);
  const Ticks tx0 = nice_ticks(x0, x1);
  const int x_overhang = Canvas::text_width(tx0.labels.empty() ? "" : tx0.labels.back(), st.small) / 2 + 6;
  f.right = fig.width - (panel ? 20 + panel + 16 : std::max(20, x_overhang));
  f.bottom = frame_bottom;
  if (f.right - f.left < 80 || f.bottom - f.top < 60) throw std::runtime_error("figure too small for its labels");
  f.x0 = x0; f.x1 = x1; f.y0 = y0; f.y1 = y1;

  // Nearest cell for every pixel inside the frame.
  for (int y = f.top + 1; y < f.bottom; ++y) {
    const double fy = (y + 0.5 - (f.top + 1)) / (f.bottom - f.top - 1);
    const int row = std::clamp(static_cast<int>(fy * r.ny), 0, r.ny - 1);
    for (int x = f.left + 1; x < f.right; ++x) {
      const double fx = (x + 0.5 - (f.left + 1)) / (f.right - f.left - 1);
      const int col = std::clamp(static_cast<int>(fx * r.nx), 0, r.nx - 1);
      c.set(x, y, r.pixels[static_cast<size_t>(row) * r.nx + col]);
    }
  }
  const Ticks tx = nice_ticks(f.x0, f.x1, std::max(3, (f.right - f.left) / 110));
  const Ticks ty = nice_ticks(f.y0, f.y1, std::max(3, (f.bottom - f.top) / 80));
  draw_title(c, fig.title, fig.subtitle, fig.width / 2, st);
  draw_axes(c, f, tx, ty, false, axis_title(fig.xlabel, x_offset), ylines, false, st);

  int y = f.top;
  if (r.legend_below) draw_legend_below(c, 20, fig.height - below, fig.width - 40, legend, st.small);
  else y = draw_legend(c, f.right + 16, f.top, legend, st.small);
  if (!r.colorbar.empty()) {
    const int x = f.right + 16;
    int top = y + (legend.empty() || r.legend_below ? 0 : 24);
    if (!r.colorbar_label.empty()) {
      c.text(x, top, r.colorbar_label, st.small, kBlack);
      top += Canvas::text_height(st.small) + 8;
    }
    const int bottom = f.bottom;
    if (bottom - top > 40) {
      const int n = static_cast<int>(r.colorbar.size());
      for (int yy = top; yy <= bottom; ++yy) {
        const double t = 1.0 - static_cast<double>(yy - top) / (bottom - top);
        c.fill(x, yy, x + 22, yy + 1, r.colorbar[std::clamp(static_cast<int>(t * n), 0, n - 1)]);
      }
      c.rect(x, top, x + 22, bottom, kFrame);
      for (size_t i = 0; i < tbar.values.size(); ++i) {
        const double yy = bottom - (tbar.values[i] - r.colorbar_lo) / (r.colorbar_hi - r.colorbar_lo) * (bottom - top);
        c.line(x + 22, yy, x + 26, yy, kFrame);
        c.text(x + 34, static_cast<int>(yy) - Canvas::text_height(st.small) / 2, tbar.labels[i], st.small, kBlack);
      }
    }
  }
  save(path, c, fig.metadata);
}

}  // namespace bouncer
