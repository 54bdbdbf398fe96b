// Shared plumbing of the bouncer subcommands: scene + command-line merging, atomic output
// files, and the one-line error with exit status 2 for bad input.
#pragma once

#include <CLI/CLI.hpp>
// GCC 12 at -O3 reports false "maybe uninitialized" warnings inside nlohmann::json.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
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
#include "bouncer/io/output.hpp"
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

// Writes an --out file (io/output.hpp: PATH.partial renamed over PATH only when complete;
// devices and pipes written through; directories refused) or, without a path, stdout
// (checked: a failed write is an OutputError, exit status 1).
inline void write_atomically(const std::optional<std::string>& path, const std::function<void(std::ostream&)>& body) {
  if (!path) {
    body(command_out());
    if (!command_capture()) check_stdout();
    return;
  }
  write_output(output_target("out", *path), body);
}

// One file of an output set: its path, and how to write it in full to a target.
struct OutputFile {
  std::string path;
  std::function<void(const OutputTarget& to)> write;
};
inline std::function<void(const OutputTarget&)> text_file(std::function<void(std::ostream&)> body) {
  return [body = std::move(body)](const OutputTarget& to) { write_output(to, body); };
}

// Writes a set of outputs (PREFIX.csv, PREFIX.png, PREFIX.json) all or none: every path is
// checked before anything is written (a directory or a missing folder: exit 2), each file is
// written in full to PATH.partial, and only when all are complete are they renamed into
// place. A failure (disk full after the CSV, say) removes every partial file and leaves the
// previous outputs as they were: never a CSV without its JSON. Devices and pipes are
// written through, as by write_output.
inline void write_output_set(const std::vector<OutputFile>& files) {
  std::vector<OutputTarget> targets;
  for (const OutputFile& f : files) targets.push_back(output_target("out", f.path));
  std::vector<std::pair<std::string, std::string>> staged;  // PATH.partial -> PATH
  std::vector<std::unique_ptr<PartialFile>> registered;
  auto remove_staged = [&] {
    std::error_code ec;
    for (const auto& [from, to] : staged) std::filesystem::remove(from, ec);
  };
  try {
    for (size_t i = 0; i < files.size(); ++i) {
      if (targets[i].kind == OutputTarget::Kind::stream) {
        files[i].write(targets[i]);
        continue;
      }
      const std::string part = targets[i].path + ".partial";
      registered.push_back(std::make_unique<PartialFile>(part));
      staged.emplace_back(part, targets[i].path);
      files[i].write(OutputTarget{OutputTarget::Kind::file, part});
    }
    for (const auto& [from, to] : staged) {
      std::error_code ec;
      std::filesystem::rename(from, to, ec);
      if (ec) throw OutputError("cannot rename '" + from + "' to '" + to + "': " + ec.message());
    }
  } catch (const OutputError& e) {
    remove_staged();
    std::string message = e.what();  // name the output, not its staging file
    for (const auto& [from, to] : staged)
      for (size_t at; (at = message.find(from)) != std::string::npos;) message.replace(at, from.size(), to);
    throw OutputError(message);
  } catch (...) {
    remove_staged();
    throw;
  }
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
enum class Palette { safe, paper };
struct Presentation {
  std::vector<ImageFormat> formats{ImageFormat::png};
  RenderOptions render;
  Palette palette = Palette::safe;
};
inline void add_picture_options(OptionSet& o) {
  o.add("format", "Picture formats, a comma list of png, pdf, svg (default png): PREFIX.png, PREFIX.pdf, PREFIX.svg");
  o.add("size", "Picture size WxH: pixels of the PNG, 200..20000 x 150..20000 (default: the command's, e.g. 900x600); "
                "PDF/SVG pages are W*72/dpi x H*72/dpi points");
  o.add("dpi", "Resolution, integer in [36, 2400] (default 150): text is set in points at this many pixels per inch");
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
                                             const std::function<void(const std::string&, ImageFormat)>& draw) {
  std::vector<OutputFile> files;
  for (ImageFormat f : p.formats)
    files.push_back({prefix + "." + format_name(f), [draw, f](const OutputTarget& to) { draw(to.path, f); }});
  return files;
}
// The models as the paper names them, for titles.
inline std::string model_title(Law law) {
  switch (law) {
    case Law::constant: return "constant restitution";
    case Law::veldep: return "velocity-dependent restitution";
    case Law::elastic: return "elastic";
  }
  return name(law);
}

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
  o.add("wall", "Wall profile: triangle (default) | sawtooth | asymmetric:R (0<R<1) | knots:0:H0,S1:H1,...");
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
inline InitialCondition start_from(const Options& o, const ModelSpec& spec) {
  InitialCondition ic{parse_decimal("theta", o.get("theta")), parse_decimal("v", o.get("v"))};
  validate(spec, ic, "theta", "v");
  return ic;
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
inline ClassifyOptions classify_options_from(const Options& o) {
  ClassifyOptions c;
  c.transient = integer_from(o, "transient", 0, 10000000000LL, 5000);
  c.steps = integer_from(o, "steps", 8, 1000000000LL, 500);
  c.max_period = integer_from(o, "max-period", 1, 1000000000LL, std::min<long>(64, c.steps / 2));
  if (c.max_period * 2 > c.steps)
    throw InputError("max-period", "must be at most steps/2 (" + std::to_string(c.steps / 2) + ")");
  c.recheck_factor = integer_from(o, "recheck-factor", 0, 1000, 20);
  return c;
}

// The text form of a certified command's result: "# " provenance lines, then one
// "key: value" line per field (nested objects and arrays as dotted/indexed keys). Timings
// go to "# time:" lines, which audit ignores.
inline void print_key_values(std::ostream& out, const Provenance& p, const nlohmann::ordered_json& j) {
  out << p.as_comment_lines();
  std::function<void(const std::string&, const nlohmann::ordered_json&)> put = [&](const std::string& prefix,
                                                                                  const nlohmann::ordered_json& x) {
    for (const auto& [k, v] : x.items()) {
      if (k == "seconds") {
        out << "# time: " << prefix << k << " = " << v.dump() << "\n";
      } else if (v.is_object()) {
        put(prefix + k + ".", v);
      } else if (v.is_array() && !v.empty() && v[0].is_object()) {
        for (size_t i = 0; i < v.size(); ++i) put(prefix + k + "[" + std::to_string(i) + "].", v[i]);
      } else {
        out << prefix << k << ": " << (v.is_string() ? v.get<std::string>() : v.dump()) << "\n";
      }
    }
  };
  put("", j);
}

// A swept parameter needs no value of its own: the model is built at the range's start,
// parsed here first so that a bad range is blamed on --range, not on the parameter.
inline void default_to_range_start(Options& o, const std::string& vary) {
  if (o.has(vary) || !o.has("range") || (vary != "a" && vary != "eps" && vary != "c")) return;
  const std::string range = o.get("range");
  const auto colon = range.find(':');
  if (colon == std::string::npos) throw InputError("range", "must be LO:HI (got '" + range + "')");
  o.set(vary, parse_decimal("range", range.substr(0, colon)).text());
}

// Both ends of a varied parameter's range (bifurcation, lyapunov --vary, continue,
// certify-periodic --a-range ...) must give a valid model; InputError names `field`.
inline void validate_range_ends(const ModelSpec& m, Parameter p, const std::string& field, const Decimal& lo,
                                const Decimal& hi) {
  for (const Decimal& end : {lo, hi}) {
    try {
      validate(with_parameter(m, p, end));
    } catch (const InputError& e) {
      throw InputError(field, "end " + end.text() + " is outside the model's range (" + e.what() + ")");
    }
  }
}

// A certified command's result (certify-sticking, certify-periodic): JSON with the
// provenance first, or the key: value text; to --out (atomically) or stdout.
inline void write_result(const std::optional<std::string>& out, bool json, const Provenance& p,
                         const nlohmann::ordered_json& body) {
  write_atomically(out, [&](std::ostream& s) {
    if (json) {
      nlohmann::ordered_json doc;
      doc["provenance"] = nlohmann::ordered_json::parse(p.as_json());
      for (const auto& [k, v] : body.items()) doc[k] = v;
      s << doc.dump(1) << "\n";
    } else {
      print_key_values(s, p, body);
    }
  });
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
