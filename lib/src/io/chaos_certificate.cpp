// The JSON form of a chaos certificate (io/chaos_certificate.hpp).
#include "bouncer/io/chaos_certificate.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <set>
#include <string>

#include "bouncer/base/error.hpp"
#include "bouncer/io/grid_figures.hpp"
#include "bouncer/io/scene.hpp"

namespace bouncer {

namespace {

using json = nlohmann::json;

constexpr const char* kFormat = "bouncer-chaos-certificate";
constexpr std::size_t kMaxSets = 1024;
constexpr std::size_t kMaxCoverings = 4096;
constexpr std::size_t kMaxRationalChars = 4096;
constexpr long kMaxK = 100000;
constexpr long kMaxPieces = 4096;
constexpr double kMaxWork = 16777216.0;

std::string rational_text(const mpq_class& q) { return q.get_str(); }

[[noreturn]] void bad(const std::string& field, const std::string& what) { throw InputError(field, what); }

// A rational written "p/q" or "p" (decimal digits, optional leading minus, q > 0).
mpq_class rational_from(const json& j, const std::string& field) {
  if (!j.is_string()) bad(field, "must be a rational as a string, \"p/q\" or \"p\"");
  const std::string s = j.get<std::string>();
  if (s.empty() || s.size() > kMaxRationalChars) bad(field, "must be a rational of 1 to 4096 characters");
  std::size_t i = s[0] == '-' ? 1 : 0;
  std::size_t digits = 0, slash = 0, after = 0;
  for (; i < s.size(); ++i) {
    if (s[i] == '/' && !slash && digits) {
      slash = 1;
    } else if (s[i] >= '0' && s[i] <= '9') {
      (slash ? after : digits) += 1;
    } else {
      bad(field, "must be a rational \"p/q\" or \"p\" in decimal digits (got '" + s.substr(0, 40) + "')");
    }
  }
  if (!digits || (slash && !after)) bad(field, "must be a rational \"p/q\" or \"p\" (got '" + s.substr(0, 40) + "')");
  mpq_class q(s, 10);
  if (q.get_den() == 0) bad(field, "has a zero denominator");
  q.canonicalize();
  return q;
}

const json& member(const json& obj, const std::string& key, const std::string& field) {
  if (!obj.is_object()) bad(field, "must be a JSON object");
  const auto it = obj.find(key);
  if (it == obj.end()) bad(field + "." + key, "is missing");
  return *it;
}

void only_keys(const json& obj, const std::set<std::string>& keys, const std::string& field) {
  for (const auto& [k, v] : obj.items())
    if (!keys.count(k)) bad(field.empty() ? k : field + "." + k, "is not a field of a chaos certificate");
}

long integer_from(const json& j, const std::string& field, long lo, long hi) {
  if (!j.is_number_integer()) bad(field, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  const long long v = j.is_number_unsigned() ? (long long)std::min<unsigned long long>(j.get<unsigned long long>(), 1ULL << 62)
                                              : j.get<long long>();
  if (v < lo || v > hi) bad(field, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + std::to_string(v) + ")");
  return long(v);
}

std::string string_from(const json& j, const std::string& field, std::size_t max = 4096) {
  if (!j.is_string() || j.get<std::string>().size() > max) bad(field, "must be a string of at most " + std::to_string(max) + " characters");
  return j.get<std::string>();
}

json model_json(const ModelSpec& m) {
  json j;
  j["model"] = name(m.law);
  j["a"] = m.a.text();
  if (m.law == Law::constant) j["eps"] = m.eps.text();
  if (m.law == Law::veldep) j["c"] = m.c.text();
  j["wall"] = m.wall.text;
  j["downward-sticking"] = name(m.downward);
  j["veldep-collapse"] = m.veldep_collapse ? "on" : "off";
  return j;
}

// The model through the scene reader's own checks (model_from), keys as in a scene.
ModelSpec model_from_json(const json& j) {
  if (!j.is_object()) bad("model", "must be a JSON object of model keys (model, a, eps, c, wall, ...)");
  Options o;
  for (const auto& [k, v] : j.items()) {
    if (!model_keys().count(k)) bad("model." + k, "is not a model key");
    o.set(k, string_from(v, "model." + k, 256));
  }
  ModelSpec m = model_from(o);
  require_piecewise_wall(m, "a chaos certificate");
  return m;
}

}  // namespace

std::string certificate_json(const ChaosCertificate& c, const std::string& provenance,
                             const std::vector<std::pair<std::string, std::string>>& files) {
  json j;
  j["format"] = kFormat;
  j["version"] = 1;
  j["map"] = name(c.map);
  if (c.map == ChaosMap::impact) j["model"] = model_json(c.model);
  if (c.map == ChaosMap::henon) j["henon"] = {{"a", c.henon_a.text()}, {"b", c.henon_b.text()}};
  j["k"] = c.k;
  j["bits"] = c.bits;
  json sets = json::array();
  for (const HSet2& h : c.sets) {
    // json::array: an initializer list of two strings would be read as an object's pair.
    json set;
    set["centre"] = json::array({rational_text(h.c[0]), rational_text(h.c[1])});
    set["frame"] = json::array({json::array({rational_text(h.B[0][0]), rational_text(h.B[0][1])}),
                                json::array({rational_text(h.B[1][0]), rational_text(h.B[1][1])})});
    sets.push_back(set);
  }
  j["sets"] = sets;
  json covs = json::array();
  for (const CertifiedCovering& v : c.coverings)
    covs.push_back({{"from", v.from}, {"to", v.to}, {"sign", v.sign}, {"pieces", v.pieces}, {"branch", v.branch}});
  j["coverings"] = covs;
  j["entropy"] = {{"bound", c.entropy_bound}, {"quotient", rational_text(c.quotient)}};
  j["made_by"] = c.made_by;
  // What the file states, in one place for a reader (and as every picture's JSON has one);
  // the replay recomputes all of it and does not read it.
  j["summary"] = {{"map", name(c.map)}, {"k", c.k}, {"hsets", c.sets.size()}, {"coverings", c.coverings.size()},
                  {"bound", c.entropy_bound}, {"per", "iterate of F"}};
  if (!provenance.empty()) j["provenance"] = json::parse(provenance);
  for (const auto& [kind, path] : files) j["files"][kind] = path;
  return j.dump(1) + "\n";
}

ChaosCertificate parse_certificate(const std::string& text) {
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) bad("certificate", "is not valid JSON or not a JSON object");
  only_keys(j, {"format", "version", "map", "model", "henon", "k", "bits", "sets", "coverings", "entropy", "made_by", "provenance", "files", "summary"}, "");
  for (const char* skipped : {"provenance", "files", "summary"})
    if (j.contains(skipped) && !j[skipped].is_object()) bad(skipped, "must be a JSON object");
  if (string_from(member(j, "format", "certificate"), "format") != kFormat)
    bad("format", std::string("must be \"") + kFormat + "\"");
  if (integer_from(member(j, "version", "certificate"), "version", 1, 1) != 1) bad("version", "must be 1");
  ChaosCertificate c;
  const std::string map = string_from(member(j, "map", "certificate"), "map", 16);
  if (map == "impact") {
    c.map = ChaosMap::impact;
    if (j.contains("henon")) bad("henon", "is only used with map \"henon\"");
    c.model = model_from_json(member(j, "model", "certificate"));
  } else if (map == "henon") {
    c.map = ChaosMap::henon;
    if (j.contains("model")) bad("model", "is only used with map \"impact\"");
    const json& h = member(j, "henon", "certificate");
    only_keys(h, {"a", "b"}, "henon");
    const auto a = Decimal::parse(string_from(member(h, "a", "henon"), "henon.a", 256));
    const auto b = Decimal::parse(string_from(member(h, "b", "henon"), "henon.b", 256));
    if (!a) bad("henon.a", "must be a decimal");
    if (!b) bad("henon.b", "must be a decimal");
    c.henon_a = *a;
    c.henon_b = *b;
  } else {
    bad("map", "must be \"impact\" or \"henon\" (got '" + map.substr(0, 40) + "')");
  }
  c.k = int(integer_from(member(j, "k", "certificate"), "k", 1, kMaxK));
  c.bits = integer_from(member(j, "bits", "certificate"), "bits", 2, 1 << 20);
  const json& sets = member(j, "sets", "certificate");
  if (!sets.is_array() || sets.empty() || sets.size() > kMaxSets) bad("sets", "must be an array of 1 to 1024 h-sets");
  for (std::size_t i = 0; i < sets.size(); ++i) {
    const std::string f = "sets[" + std::to_string(i) + "]";
    only_keys(sets[i], {"centre", "frame"}, f);
    const json& centre = member(sets[i], "centre", f);
    const json& frame = member(sets[i], "frame", f);
    if (!centre.is_array() || centre.size() != 2) bad(f + ".centre", "must be an array of two rationals");
    if (!frame.is_array() || frame.size() != 2 || !frame[0].is_array() || !frame[1].is_array() || frame[0].size() != 2 ||
        frame[1].size() != 2)
      bad(f + ".frame", "must be a 2x2 array of rationals (rows; column 0 unstable, column 1 stable)");
    HSet2 h;
    for (int r = 0; r < 2; ++r) {
      h.c[r] = rational_from(centre[r], f + ".centre[" + std::to_string(r) + "]");
      for (int col = 0; col < 2; ++col)
        h.B[r][col] = rational_from(frame[r][col], f + ".frame[" + std::to_string(r) + "][" + std::to_string(col) + "]");
    }
    if (h.B[0][0] * h.B[1][1] - h.B[0][1] * h.B[1][0] == 0) bad(f + ".frame", "is singular (determinant 0): not an h-set");
    c.sets.push_back(std::move(h));
  }
  const json& covs = member(j, "coverings", "certificate");
  if (!covs.is_array() || covs.empty() || covs.size() > kMaxCoverings) bad("coverings", "must be an array of 1 to 4096 coverings");
  std::set<std::pair<int, int>> seen;
  const long last = long(c.sets.size()) - 1;
  for (std::size_t i = 0; i < covs.size(); ++i) {
    const std::string f = "coverings[" + std::to_string(i) + "]";
    only_keys(covs[i], {"from", "to", "sign", "pieces", "branch"}, f);
    CertifiedCovering v;
    v.from = int(integer_from(member(covs[i], "from", f), f + ".from", 0, last));
    v.to = int(integer_from(member(covs[i], "to", f), f + ".to", 0, last));
    v.sign = int(integer_from(member(covs[i], "sign", f), f + ".sign", -1, 1));
    if (v.sign == 0) bad(f + ".sign", "must be -1 or 1");
    v.pieces = int(integer_from(member(covs[i], "pieces", f), f + ".pieces", 1, kMaxPieces));
    if (covs[i].contains("branch")) v.branch = string_from(covs[i]["branch"], f + ".branch", 1 << 16);
    if (!seen.insert({v.from, v.to}).second) bad(f, "repeats the covering " + std::to_string(v.from) + " => " + std::to_string(v.to));
    c.coverings.push_back(std::move(v));
  }
  // The replay's work: every piece of every covering mapped by F^k, at most 2^24 maps of F
  // (about a minute of Arb for the bouncer), so that a file cannot ask for days of work.
  double work = 0;
  for (const CertifiedCovering& v : c.coverings) work += double(c.k) * (double(v.pieces) * v.pieces + 2.0 * v.pieces);
  if (work > kMaxWork)
    bad("coverings", "ask for more than 2^24 evaluations of F (k times the pieces of every covering): the replay's limit");
  const json& e = member(j, "entropy", "certificate");
  only_keys(e, {"bound", "quotient"}, "entropy");
  c.entropy_bound = string_from(member(e, "bound", "entropy"), "entropy.bound", 256);
  if (!Decimal::parse(c.entropy_bound)) bad("entropy.bound", "must be a decimal (got '" + c.entropy_bound.substr(0, 40) + "')");
  c.quotient = rational_from(member(e, "quotient", "entropy"), "entropy.quotient");
  if (j.contains("made_by")) c.made_by = string_from(j["made_by"], "made_by");
  return c;
}

std::string map_text(const ChaosCertificate& c) {
  if (c.map == ChaosMap::henon) return "the Hénon map, a = " + c.henon_a.text() + ", b = " + c.henon_b.text();
  std::string s = "the impact map, " + model_title(c.model.law) + ", " + parameters_text(c.model);
  if (c.model.wall.text != "triangle") s += ", wall " + c.model.wall.text;
  return s;
}

void write_hsets_csv(std::ostream& out, const ChaosCertificate& c, const std::string& provenance_lines) {
  out << provenance_lines;
  out << "# the h-sets of the certificate (doubles nearest its exact rationals); coverings: ";
  for (std::size_t i = 0; i < c.coverings.size(); ++i)
    out << (i ? " " : "") << c.coverings[i].from << "=>" << c.coverings[i].to;
  out << "\nset,theta,v,u_theta,u_v,s_theta,s_v\n";
  const auto number = [](const mpq_class& q) {
    char text[32];
    const auto r = std::to_chars(text, text + sizeof text, q.get_d());
    return std::string(text, r.ptr);
  };
  for (std::size_t i = 0; i < c.sets.size(); ++i) {
    const HSet2& h = c.sets[i];
    out << i << ',' << number(h.c[0]) << ',' << number(h.c[1]) << ',' << number(h.B[0][0]) << ',' << number(h.B[1][0])
        << ',' << number(h.B[0][1]) << ',' << number(h.B[1][1]) << '\n';
  }
}

Figure covering_figure(const ChaosCertificate& c, std::size_t covering, int samples) {
  const CertifiedCovering& cov = c.coverings.at(covering);
  const HSet2& N = c.sets.at(cov.from);
  const HSet2& M = c.sets.at(cov.to);
  const mpq_class det = M.B[0][0] * M.B[1][1] - M.B[0][1] * M.B[1][0];
  Figure fig;
  fig.title = "Covering N" + std::to_string(cov.from) + " => N" + std::to_string(cov.to) + " under F^" + std::to_string(c.k);
  fig.subtitle = map_text(c) + "; in N" + std::to_string(cov.to) + "'s local coordinates, the image of N" +
                 std::to_string(cov.from) + "'s boundary at sampled points (the proof is the interval check)";
  fig.xlabel = "y_u (unstable)";
  fig.ylabel = "y_s (stable)";
  Series square{"N" + std::to_string(cov.to), {-1, 1, 1, -1, -1}, {-1, -1, 1, 1, -1}, Rgb{0, 0, 0}, true, false};
  // The four edges of N in its local coordinates, from (u0, s0) to (u1, s1).
  const struct {
    const char* label;
    int u0, s0, u1, s1;
    Rgb color;
  } edges[] = {{"image of the left edge", -1, -1, -1, 1, Rgb{200, 30, 30}},
               {"image of the right edge", 1, -1, 1, 1, Rgb{30, 60, 200}},
               {"image of the stable sides", -1, -1, 1, -1, Rgb{140, 140, 140}},
               {"", -1, 1, 1, 1, Rgb{140, 140, 140}}};
  fig.series.push_back(square);
  for (const auto& e : edges) {
    // The unstable edges' images are short where the map stretches: markers keep them visible.
    Series s{e.label, {}, {}, e.color, true, e.u0 == e.u1, 2};
    for (int i = 0; i <= samples; ++i) {
      const mpq_class t(i, samples);
      const mpq_class xu = e.u0 + (e.u1 - e.u0) * t, xs = e.s0 + (e.s1 - e.s0) * t;
      const mpq_class p0 = N.c[0] + N.B[0][0] * xu + N.B[0][1] * xs;
      const mpq_class p1 = N.c[1] + N.B[1][0] * xu + N.B[1][1] * xs;
      const auto y = replay_iterate(c, p0, p1, 128);
      if (!y) {  // a branch not decided at this point: a gap in the curve
        if (!s.x.empty()) {
          fig.series.push_back(s);
          s.x.clear(), s.y.clear(), s.label.clear();
        }
        continue;
      }
      const mpq_class d0 = ((*y)[0][0] + (*y)[0][1]) / 2 - M.c[0], d1 = ((*y)[1][0] + (*y)[1][1]) / 2 - M.c[1];
      s.x.push_back(mpq_class((M.B[1][1] * d0 - M.B[0][1] * d1) / det).get_d());
      s.y.push_back(mpq_class((M.B[0][0] * d1 - M.B[1][0] * d0) / det).get_d());
    }
    if (!s.x.empty()) fig.series.push_back(s);
  }
  return fig;
}

Figure horseshoe_figure(const ChaosCertificate& c, const std::vector<std::pair<double, double>>& attractor) {
  Figure fig;
  double largest = 0;  // the largest extent of an h-set along either coordinate: 2 (|B_r0| + |B_r1|)
  for (const HSet2& h : c.sets)
    for (int r = 0; r < 2; ++r) largest = std::max(largest, mpq_class(2 * (abs(h.B[r][0]) + abs(h.B[r][1]))).get_d());
  fig.title = "A horseshoe of F^" + std::to_string(c.k) + ": " + std::to_string(c.sets.size()) + " h-sets, over an orbit (grey)";
  char size[64];
  std::snprintf(size, sizeof size, "%.1e", largest);
  fig.subtitle = map_text(c) + "; h-set centres marked (each at most " + std::string(size) + " across); h_top >= " +
                 c.entropy_bound.substr(0, 8) + " per impact";
  fig.xlabel = "theta";
  fig.ylabel = "v";
  Series orbit{"an orbit of F (double, numerical)", {}, {}, Rgb{170, 170, 170}, false, true, 0};
  for (const auto& [t, v] : attractor) {
    orbit.x.push_back(t);
    orbit.y.push_back(v);
  }
  Series chain{"N1, N2, ... (the homoclinic orbit)", {}, {}, Rgb{30, 60, 200}, true, true, 3};
  Series home{"N0 (the saddle)", {}, {}, Rgb{200, 30, 30}, false, true, 5};
  for (std::size_t i = 0; i < c.sets.size(); ++i) {
    Series& s = i == 0 ? home : chain;
    s.x.push_back(c.sets[i].c[0].get_d());
    s.y.push_back(c.sets[i].c[1].get_d());
  }
  fig.series = {orbit, chain, home};
  fig.x_min = 0;
  fig.x_max = 1;
  fig.legend_below = true;
  return fig;
}

}  // namespace bouncer
