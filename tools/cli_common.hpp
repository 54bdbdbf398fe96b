// Shared plumbing of the bouncer subcommands: scene + command-line merging, atomic output
// files, and the one-line error with exit status 2 for bad input.
#pragma once

#include <CLI/CLI.hpp>
// GCC 12 at -O3 reports false "maybe uninitialized" warnings inside nlohmann::json.
#pragma GCC diagnostic push
#if !defined(__clang__)  // clang has no such warning (the fuzzing build, tests/fuzz/)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nlohmann/json.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/base/input.hpp"
#include "bouncer/io/options.hpp"
#include "bouncer/base/output.hpp"
#include "bouncer/io/plot.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/io/scene.hpp"

namespace bouncer::cli {

// Registers string options whose values land in an Options map under their long name, and
// flags that land there as "true" (as a scene's `certify = "true"` does).
class OptionSet {
 public:
  explicit OptionSet(CLI::App* app) : app_(app) {}
  void add(const std::string& name, const std::string& help) {
    app_->add_option("--" + name, single_[name], help);
  }
  // An option whose value may be left out (--confirm or --confirm=512): "" when it is.
  void add_optional(const std::string& name, const std::string& help) {
    app_->add_option("--" + name, single_[name], help)->expected(0, 1);
  }
  void add_list(const std::string& name, const std::string& help) {
    app_->add_option("--" + name, lists_[name], help)->delimiter(',');
  }
  void add_flag(const std::string& name, const std::string& help) {
    app_->add_flag("--" + name, flags_[name], help);
  }
  Options collected() const {
    Options o;
    for (const auto& [k, v] : single_)
      if (app_->count("--" + k)) o.set(k, v);
    for (const auto& [k, v] : lists_)
      if (app_->count("--" + k)) o.set(k, v);
    for (const auto& [k, v] : flags_)
      if (app_->count("--" + k)) o.set(k, "true");
    return o;
  }

 private:
  CLI::App* app_;
  std::map<std::string, std::string> single_;
  std::map<std::string, std::vector<std::string>> lists_;
  std::map<std::string, bool> flags_;
};

// Where a command prints its results. The command-line tool prints on stdout; a host that
// runs commands in its own process (the Python module: tools/run_command.hpp) gives the
// command's thread a CommandCapture, which receives that text and, for the grid commands,
// the CSV rows (with their provenance lines) even when they also go to --out files.
struct CommandCapture {
  std::ostringstream out;
  std::string csv;
};
namespace detail {
inline thread_local CommandCapture* capture = nullptr;
}
inline CommandCapture* command_capture() { return detail::capture; }
inline std::ostream& command_out() { return detail::capture ? detail::capture->out : std::cout; }
class CaptureScope {
 public:
  explicit CaptureScope(CommandCapture* c) : previous_(detail::capture) { detail::capture = c; }
  ~CaptureScope() { detail::capture = previous_; }
  CaptureScope(const CaptureScope&) = delete;
  CaptureScope& operator=(const CaptureScope&) = delete;

 private:
  CommandCapture* previous_;
};

// Writes an --out file (base/output.hpp: staged in a locked PATH.partial and renamed over
// PATH only when complete; devices and pipes written through; directories and links to
// regular files refused) or, without a path, stdout (checked: a failed write is an
// OutputError, exit status 1). `reserved`, when given, holds the path reserved before the
// computation (reserve_output), so that a path that cannot be written is found at once.
inline void write_atomically(const std::optional<std::string>& path, const std::function<void(std::ostream&)>& body,
                             OutputSet* reserved = nullptr) {
  if (!path) {
    body(command_out());
    if (!command_capture()) check_stdout();
    return;
  }
  OutputSet own;
  OutputSet& set = reserved ? *reserved : own;
  set.reserve("out", *path);
  set.write(*path, body);
  set.commit();
}

// One file of an output set: its path, and its whole content written to a stream.
struct OutputFile {
  std::string path;
  std::function<void(std::ostream&)> write;
};

// Writes a set of outputs (PREFIX.csv, PREFIX.png, PREFIX.json) all or none: every path is
// checked and staged before anything is written (a directory or a missing folder: exit 2;
// another run writing the same path: exit 2), each file is written in full to its staging
// file, and only when all are complete are they renamed into place. A failure (disk full
// after the CSV, say) removes every staging file and leaves the previous outputs as they
// were: never a CSV without its JSON. Devices and pipes are written through. `reserved`,
// when given, is the set whose paths were reserved before the computation.
inline void write_output_set(const std::vector<OutputFile>& files, OutputSet* reserved = nullptr) {
  OutputSet own;
  OutputSet& set = reserved ? *reserved : own;
  for (const OutputFile& f : files) set.reserve("out", f.path);
  for (const OutputFile& f : files) set.write(f.path, f.write);
  set.commit();
}

// An output file name prefix (PREFIX.csv, PREFIX.json, PREFIX.png, ...), checked before any
// work: not empty, not a directory or a path ending in '/' (which would write the hidden
// files DIR/.csv), its folder existing, and every name made from it (the longest with
// `longest_suffix`) short enough for the file system. InputError naming `field`.
inline void check_prefix(const std::string& field, const std::string& prefix, const std::string& longest_suffix) {
  if (prefix.empty()) throw InputError(field, "must be a file name prefix");
  std::error_code ec;
  if (prefix.back() == '/' || std::filesystem::is_directory(prefix, ec))
    throw InputError(field, "'" + prefix + "' is a directory: give a file name prefix (PREFIX.csv, PREFIX.json, ...)");
  check_path_name(field, prefix + longest_suffix, std::string(".partial").size());
  const auto parent = std::filesystem::path(prefix).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
    throw InputError(field, "directory '" + parent.string() + "' does not exist");
}

// ---- Pictures: formats, size, resolution and palette (presentation only) -------------------
// These options change how a picture looks, never a computed value: they are not part of a
// grid job's key (picture_common.hpp), so re-rendering a finished or resumed job with
// another --format or --size reuses its saved tiles. `show` (scan: which class's share;
// bifurcation: theta or v) and `bins` (bifurcation's density rows) are read only when the
// picture is drawn: the two panels of the paper's fig. paramspace2 are one grid drawn twice.
inline const std::set<std::string>& presentation_keys() {
  static const std::set<std::string> k{"format", "size", "dpi", "palette", "curves", "show", "bins"};
  return k;
}
// The keys of add_picture_options (scene files accept them too).
inline const std::set<std::string>& picture_keys() {
  static const std::set<std::string> k{"format", "size", "dpi", "palette"};
  return k;
}
struct Presentation {
  std::vector<ImageFormat> formats{ImageFormat::png};
  RenderOptions render;
  Palette palette = Palette::safe;
};
inline void add_picture_options(OptionSet& o) {
  o.add("format", "Picture formats, a comma list of png, pdf, svg (default png): PREFIX.png, PREFIX.pdf, PREFIX.svg");
  o.add("size", "Picture size WxH: pixels of the PNG, 200..20000 x 150..20000 (default: the command's, e.g. 900x600); "
                "PDF/SVG pages are W*72/dpi x H*72/dpi points");
  o.add("dpi", "Resolution, integer in [36, 2400] (default 150): text is set in points at this many pixels per inch, "
               "the picture's pixels scale with it (900x600 at 150 is 1800x1200 at 300) unless --size is given, and "
               "the PNG records it");
  o.add("palette", "Colours: safe (default; Okabe-Ito categories, viridis densities, colour-blind safe) | "
                   "paper (the paper's: black periodic, red sticking, green chaos)");
}
inline Presentation presentation_from(const Options& o) {
  Presentation p;
  if (o.has("format")) {
    const std::string text = o.get("format");
    p.formats.clear();
    std::string item;
    std::istringstream in(text + ",");
    while (std::getline(in, item, ',')) {
      ImageFormat f;
      if (item == "png") f = ImageFormat::png;
      else if (item == "pdf") f = ImageFormat::pdf;
      else if (item == "svg") f = ImageFormat::svg;
      else throw InputError("format", "must be a comma list of png, pdf, svg (got '" + text + "')");
      if (std::find(p.formats.begin(), p.formats.end(), f) == p.formats.end()) p.formats.push_back(f);
    }
    if (p.formats.empty()) throw InputError("format", "must be a comma list of png, pdf, svg (got '" + text + "')");
  }
  if (o.has("size")) {
    const std::string text = o.get("size");
    const std::string range = "WxH with whole numbers " + std::to_string(kMinFigureWidth) + " <= W <= " +
                              std::to_string(kMaxFigureSide) + ", " + std::to_string(kMinFigureHeight) + " <= H <= " +
                              std::to_string(kMaxFigureSide);
    const auto x = text.find('x');
    auto whole = [&](const std::string& s, int lo) {
      if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos)
        throw InputError("size", "must be " + range + " (got '" + text + "')");
      const int n = std::stoi(s);
      if (n < lo || n > kMaxFigureSide) throw InputError("size", "must be " + range + " (got '" + text + "')");
      return n;
    };
    if (x == std::string::npos) throw InputError("size", "must be " + range + ", e.g. 1200x800 (got '" + text + "')");
    p.render.width = whole(text.substr(0, x), kMinFigureWidth);
    p.render.height = whole(text.substr(x + 1), kMinFigureHeight);
  }
  p.render.dpi = static_cast<double>(integer_from(o, "dpi", static_cast<long long>(kMinDpi), static_cast<long long>(kMaxDpi), 150));
  const std::string palette = o.get_or("palette", "safe");
  if (palette == "paper") p.palette = Palette::paper;
  else if (palette != "safe") throw InputError("palette", "must be safe or paper (got '" + palette + "')");
  return p;
}
// The picture files of PREFIX, one per format, for write_output_set.
inline std::vector<OutputFile> picture_files(const std::string& prefix, const Presentation& p,
                                             const std::function<void(std::ostream&, ImageFormat)>& draw) {
  std::vector<OutputFile> files;
  for (ImageFormat f : p.formats)
    files.push_back({prefix + "." + format_name(f), [draw, f](std::ostream& out) { draw(out, f); }});
  return files;
}
// The output files of PREFIX for these picture formats (CSV, pictures, JSON), and the
// extra figures' (PREFIX-SUFFIX.png ...).
inline std::vector<std::string> output_paths(const std::string& prefix, const Presentation& p,
                                             const std::vector<std::string>& extra_suffixes = {}) {
  std::vector<std::string> paths{prefix + ".csv"};
  for (ImageFormat fmt : p.formats) paths.push_back(prefix + "." + format_name(fmt));
  for (const std::string& e : extra_suffixes)
    for (ImageFormat fmt : p.formats) paths.push_back(prefix + "-" + e + "." + format_name(fmt));
  paths.push_back(prefix + ".json");
  return paths;
}

// The models as the paper names them, for titles.
// The command line as one string, for provenance.
inline std::string invocation(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

// The model options every command shares.
inline void add_model_options(OptionSet& o) {
  o.add("model", "Collision model: elastic | constant | veldep");
  o.add("a", "Dimensionless gravity a = g T^2 / A, a decimal > 0 (<= 1e9)");
  o.add("eps", "Restitution coefficient for --model constant, decimal in [0, 1]");
  o.add("c", "Scale of eps(v) = exp(-|(v- - fdot)/c|^(3/5)) for --model veldep, decimal > 0");
  o.add("wall", "Wall profile: triangle (default) | sawtooth | asymmetric:R (0<R<1) | knots:0:H0,S1:H1,... | sine (needs a < 4 pi^2)");
  o.add("downward-sticking", "Collapse on a downward wall at its upward turn: paper (default) | impact");
  o.add("veldep-collapse", "For --model veldep: on = stick when the chatter provably collapses before the wall turns; off (default)");
}

// Help text of --precision for the commands that follow point orbits.
inline const char* kPointPrecisionHelp = "double (default) | long | dd | quad | mpfr:BITS (16 <= BITS <= 1048576)";

// The single initial condition (--theta, --v) of an orbit command, validated against the model.
inline void add_start_options(OptionSet& o) {
  o.add("theta", "Initial phase in [0, 1)");
  o.add("v", "Initial velocity after impact, >= the wall velocity at theta");
}

// The classifier's window (classify, basin, scan, lyapunov --vary): one help text, one validation.
// lyapunov --vary has its own transient and steps (the exponent's), hence the split.
inline void add_classify_period_options(OptionSet& o) {
  o.add("max-period", "Longest period looked for, integer in [1, steps/2] (default 64, or steps/2 if smaller)");
  o.add("recheck-factor", "A chaotic label is re-checked F x max(transient, steps) steps later (settled: transient_chaos); "
                          "integer in [0, 1000], 0 = off (default 20)");
}
inline void add_classify_options(OptionSet& o) {
  o.add("transient", "Steps discarded before classifying, integer in [0, 1e10] (default 5000, as the paper)");
  o.add("steps", "Steps examined by the classifier, integer in [8, 1e9] (default 500, as the paper)");
  add_classify_period_options(o);
}

// --confirm[=BITS] and --confirm-sample of the grids of starts (basin, scan: run/cells.hpp GridConfirm).
inline void add_grid_confirm_options(OptionSet& o, const std::string& unit) {
  o.add_optional("confirm", "Classify the starts of a sample again at mpfr:B, B = max(BITS, 2 x the run's bits), and at 2B "
                            "where they differ (as classify does): agrees / artefact / precision_dependent per start; "
                            "BITS in [64, 1048576] (default 256)");
  o.add("confirm-sample", "With --confirm: at most N starts, those of every s-th " + unit +
                              " in each direction (s the smallest that fits), or all (default 1000)");
}

inline Provenance provenance_for(const std::string& command, const Options& o, const Precision& p,
                                 const std::string& argv_text) {
  Provenance pr;
  pr.command = command;
  pr.inputs = o.inputs();
  pr.precision = p.text();
  pr.bits = p.bits;
  pr.decimal_note = decimal_note(p);
  pr.invocation = argv_text;
  return pr;
}

}  // namespace bouncer::cli
