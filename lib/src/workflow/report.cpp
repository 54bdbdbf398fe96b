#include "bouncer/workflow/report.hpp"

#pragma GCC diagnostic push
#if !defined(__clang__)  // clang has no such warning (the fuzzing build, tests/fuzz/)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nlohmann/json.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <string>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "bouncer/base/output.hpp"
#include "bouncer/io/contact_sheet.hpp"

namespace bouncer {

std::string latex_text(const std::string& latex) {
  static const std::map<std::string, std::string> symbols{
      {"epsilon", "ε"}, {"varepsilon", "ε"}, {"theta", "θ"}, {"sigma", "σ"}, {"lambda", "λ"}, {"pi", "π"},
      {"alpha", "α"},   {"beta", "β"},       {"gamma", "γ"}, {"delta", "δ"}, {"mu", "μ"},      {"omega", "ω"},
      {"infty", "∞"},   {"pm", "±"},         {"cdot", "·"},  {"times", "×"}, {"ldots", "…"},   {"dots", "…"}};
  static const std::map<std::string, std::string> relations{{"sim", "∼"}, {"approx", "≈"}, {"le", "≤"}, {"leq", "≤"},
                                                            {"ge", "≥"},  {"geq", "≥"},    {"to", "→"}, {"rightarrow", "→"}};
  static const std::map<char, std::string> sub{{'0', "₀"}, {'1', "₁"}, {'2', "₂"}, {'3', "₃"}, {'4', "₄"}, {'5', "₅"},
                                               {'6', "₆"}, {'7', "₇"}, {'8', "₈"}, {'9', "₉"}, {'n', "ₙ"}, {'i', "ᵢ"},
                                               {'k', "ₖ"}, {'j', "ⱼ"}, {'+', "₊"}, {'-', "₋"}, {'*', "*"}};
  static const std::map<char, std::string> sup{{'0', "⁰"}, {'1', "¹"}, {'2', "²"}, {'3', "³"}, {'4', "⁴"}, {'5', "⁵"},
                                               {'6', "⁶"}, {'7', "⁷"}, {'8', "⁸"}, {'9', "⁹"}, {'n', "ⁿ"}, {'+', "⁺"},
                                               {'-', "⁻"}, {'*', "*"}};
  std::string out;
  bool math = false;
  auto relation = [&](const std::string& r) {  // " = ", " ∼ ": one space either side
    while (!out.empty() && out.back() == ' ') out.pop_back();
    out += " " + r + " ";
  };
  for (size_t i = 0; i < latex.size(); ++i) {
    const char c = latex[i];
    if (c == '$') {
      math = !math;
      continue;
    }
    if (c == '~') {
      out += ' ';
    } else if (c == '{' || c == '}') {
      // groups only group
    } else if (c == '\\' && i + 1 < latex.size() && std::isalpha(static_cast<unsigned char>(latex[i + 1]))) {
      size_t j = i + 1;
      while (j < latex.size() && std::isalpha(static_cast<unsigned char>(latex[j]))) ++j;
      const std::string name = latex.substr(i + 1, j - i - 1);
      i = j - 1;
      if (name == "ref" && j < latex.size() && latex[j] == '{') {
        const size_t end = latex.find('}', j);
        const std::string label = latex.substr(j + 1, (end == std::string::npos ? latex.size() : end) - j - 1);
        const size_t colon = label.find(':');
        out += colon == std::string::npos ? label : label.substr(colon + 1);
        i = end == std::string::npos ? latex.size() : end;
      } else if (const auto r = relations.find(name); r != relations.end()) {
        relation(r->second);
        while (i + 1 < latex.size() && latex[i + 1] == ' ') ++i;
      } else if (const auto g = symbols.find(name); g != symbols.end()) {
        out += g->second;
        if (i + 1 < latex.size() && latex[i + 1] == ' ' && math) ++i;  // the space that ends the command
      }  // any other command (\textit, \emph, \mathrm ...): its argument stays, the name goes
    } else if (c == '\\' && i + 1 < latex.size()) {
      ++i;
      out += latex[i] == ',' || latex[i] == ' ' ? ' ' : latex[i];  // \, \  \% \$ ...
    } else if (math && (c == '_' || c == '^') && i + 1 < latex.size()) {
      const std::map<char, std::string>& table = c == '_' ? sub : sup;
      std::string script;
      if (latex[i + 1] == '{') {
        const size_t end = latex.find('}', i + 2);
        script = latex.substr(i + 2, (end == std::string::npos ? latex.size() : end) - i - 2);
        i = end == std::string::npos ? latex.size() : end;
      } else {
        script = latex.substr(i + 1, 1);
        ++i;
      }
      bool all = true;
      for (char ch : script) all = all && table.count(ch);
      if (all)
        for (char ch : script) out += table.at(ch);
      else
        out += std::string(1, c) + script;  // no Unicode form: a_{xy} stays readable as a_xy
    } else if (math && (c == '=' || c == '<' || c == '>')) {
      relation(std::string(1, c));
    } else {
      out += c;
    }
  }
  return out;
}


namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

std::string html_escape(const std::string& s) {
  std::string o;
  for (char ch : s) switch (ch) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += ch;
    }
  return o;
}

// The Markdown inline marks the manifest's texts use (`code`, **bold**, \| inside a table
// cell) as HTML, everything else escaped: the HTML report shows what report.md shows.
std::string md_inline_html(const std::string& s) {
  std::string o;
  bool bold = false;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '`') {
      const size_t end = s.find('`', i + 1);
      if (end != std::string::npos) {
        o += "<code>" + html_escape(s.substr(i + 1, end - i - 1)) + "</code>";
        i = end;
        continue;
      }
    }
    if (s.compare(i, 2, "**") == 0) {
      o += bold ? "</strong>" : "<strong>";
      bold = !bold;
      ++i;
      continue;
    }
    if (s.compare(i, 2, "\\|") == 0) {
      o += "|";
      ++i;
      continue;
    }
    o += html_escape(std::string(1, s[i]));
  }
  if (bold) o += "</strong>";
  return o;
}

std::string md_cell(std::string s) {
  for (char& ch : s)
    if (ch == '\n') ch = ' ';
  return s;
}

std::string fixed(double x, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

bool drawn(const ItemResult& it) { return it.state == ItemState::done || it.state == ItemState::cached; }

// The drawn panels' PNGs that exist, in the manifest's order: the contact sheet's pictures.
std::vector<std::string> contact_sheet_panels(const ReproduceResult& r) {
  std::vector<std::string> pngs;
  for (const ItemResult& it : r.items) {
    if (it.kind != ItemKind::panel || !drawn(it)) continue;
    const fs::path png = fs::path(r.dir) / "panels" / (r.manifest.panels[it.index].name() + ".png");
    std::error_code ec;
    if (fs::is_regular_file(png, ec)) pngs.push_back(png.string());
  }
  return pngs;
}

// The parts of a report that depend on the mode: the title, the result line, whether the
// paper's sections (claims, figures) are shown (not with pictures).
struct Framing {
  std::string title, result_text;
  bool paper;
  bool any_picture;
};

Framing framing(const ReproduceResult& r) {
  const bool pictures = r.mode == ReproduceMode::pictures;
  Framing f;
  f.title = pictures ? "bouncer's documentation pictures" : "Reproduction of Langer & Miller 2014";
  f.result_text = !r.ok     ? (pictures ? "NOT every picture was drawn" : "NOT fully reproduced")
                  : pictures ? "every picture was drawn"
                             : "every item ran and every claim reproduced its expected verdict";
  f.paper = !pictures;
  f.any_picture = std::any_of(r.items.begin(), r.items.end(), [](const ItemResult& it) { return it.kind == ItemKind::picture; });
  return f;
}

}  // namespace

std::string claims_table(const Manifest& m) {
  std::string t = "| # | Claim (paper) | Verdict | Evidence | Rerun |\n|---|---|---|---|---|\n";
  for (const Claim& c : m.claims)
    t += "| " + c.row + " | " + md_cell(c.text) + " | " + md_cell(c.verdict) + " | " + md_cell(c.evidence) + " | " +
         md_cell(c.rerun) + " |\n";
  return t;
}

std::string claims_json(const ReproduceResult& r) {
  const Manifest& m = r.manifest;
  json jclaims = json::array(), jpanels = json::array(), jpictures = json::array();
  json times = json::object();
  for (const ItemResult& it : r.items) {
    const std::string state = state_name(it.state);
    times[it.id] = {{"state", state}, {"seconds", it.seconds}};
    // (a resumed item is "done" here: whether it was rerun is a run detail, kept under times)
    const std::string status = it.state == ItemState::skipped ? "pending" : it.state == ItemState::cached ? "done" : state;
    if (it.kind == ItemKind::picture) {
      const Picture& p = m.pictures[it.index];
      json j{{"label", p.id()}, {"readme", p.readme}, {"status", it.state == ItemState::cached ? "done" : state},
             {"command", command_text(it.argv, r.proof_prefix)}};
      if (drawn(it)) j["files"] = it.outputs;
      if (it.state == ItemState::failed) j["problem"] = it.problem;
      jpictures.push_back(j);
    } else if (it.kind == ItemKind::panel) {
      const Panel& p = m.panels[it.index];
      json j{{"label", p.label}, {"figure", p.figure}, {"status", status}};
      if (it.state == ItemState::skipped) j["reason"] = p.reason;
      if (!p.twin_of.empty()) j["twin_of"] = p.twin_of;
      if (!it.argv.empty()) j["command"] = command_text(it.argv, r.proof_prefix);
      if (drawn(it)) j["files"] = it.outputs;
      if (it.state == ItemState::failed) j["problem"] = it.problem;
      jpanels.push_back(j);
    } else {
      const Claim& c = m.claims[it.index];
      json jchecks = json::array();
      for (const CheckResult& k : it.checks) jchecks.push_back({{"check", k.check}, {"got", k.got}, {"held", k.held}});
      json j{{"id", c.id}, {"row", c.row}, {"paper", c.paper}, {"groups", c.groups}, {"claim", c.text},
             {"expected", c.expected}, {"verdict", it.verdict}, {"status", status_name(it.status)}, {"evidence", c.evidence},
             {"command", command_text(it.argv, r.proof_prefix)}, {"rerun", rerun_text(c.rerun, r.proof_prefix)}, {"checks", jchecks}};
      if (!it.outputs.empty()) j["output"] = it.outputs[0];
      jclaims.push_back(j);
    }
  }
  json doc;
  doc["reproduce"] = {{"paper", "Langer & Miller 2014"}, {"mode", mode_name(r.mode)}, {"build", r.build},
                      {"manifest", r.manifest_source}, {"only", r.only}, {"result", r.ok ? "reproduced" : "not reproduced"},
                      {"summary", r.summary}};
  doc["claims"] = jclaims;
  doc["panels"] = jpanels;
  if (!jpictures.empty()) doc["pictures"] = jpictures;
  doc["times"] = {{"seconds", r.seconds}, {"items", times}};
  return doc.dump(2) + "\n";
}

std::string report_markdown(const ReproduceResult& r) {
  const Manifest& m = r.manifest;
  const Framing f = framing(r);
  std::ostringstream md;
  md << "# " << f.title << "\n\n";
  md << "Mode: `" << mode_name(r.mode) << "`. Built by bouncer " << r.build << ". Manifest: " << r.manifest_source << ".\n\n";
  md << "**Result: " << f.result_text << "** (" << r.summary << ").\n\n";
  if (f.paper) md << "## Claims\n\n| # | Claim | Paper | Expected | This run | Evidence | Rerun |\n|---|---|---|---|---|---|---|\n";
  for (const ItemResult& it : r.items) {
    if (it.kind != ItemKind::claim) continue;
    const Claim& c = m.claims[it.index];
    md << "| " << c.row << " | " << md_cell(c.text) << " | " << md_cell(c.paper) << " | " << c.expected << " | "
       << (it.status == ClaimStatus::reproduced ? "**" + it.verdict + "**" : md_cell(it.verdict)) << " | "
       << md_cell(c.evidence) << " | " << md_cell(rerun_text(c.rerun, r.proof_prefix)) << " |\n";
  }
  if (f.paper) md << "\n## Figures\n";
  if (f.paper && !contact_sheet_panels(r).empty()) md << "\nEvery drawn panel in one picture: [contact-sheet.png](contact-sheet.png).\n";
  std::string figure;
  for (const ItemResult& it : r.items) {
    if (it.kind != ItemKind::panel) continue;
    const Panel& p = m.panels[it.index];
    if (p.figure != figure) {
      figure = p.figure;
      // Text, not Markdown: θ* and v* must not start emphasis.
      std::string caption;
      for (char ch : md_cell(latex_text(p.caption))) caption += ch == '*' || ch == '_' ? std::string("\\") + ch : std::string(1, ch);
      md << "\n### " << figure << "\n\n> " << caption << "\n";
    }
    md << "\n#### " << p.label << (p.panel.empty() ? "" : " " + p.panel)
       << (p.twin_of.empty() ? "" : " (certified twin of " + p.twin_of + ", not a panel of the paper)")
       << (p.beside.empty() ? "" : " (sine wall, beside " + p.beside + ": not a panel of the paper)") << "\n\n";
    if (drawn(it)) {
      md << "![" << p.label << "](panels/" << p.name() << ".png)\n\n";
      if (!p.twin_of.empty()) md << "![where double is wrong](panels/" << p.name() << "-artefacts.png)\n\n";
      md << "[PDF](panels/" << p.name() << ".pdf) · [SVG](panels/" << p.name() << ".svg) · [CSV](panels/" << p.name()
         << ".csv)\n\n";
    } else if (it.state == ItemState::skipped) {
      md << "**Pending:** " << p.reason << ".\n\n";
    } else {
      md << "**Failed:** " << md_cell(it.problem) << "\n\n";
    }
    if (!p.params.empty()) {
      md << "Parameters:";
      for (const auto& kv : p.params) md << " " << kv.first << " = " << kv.second << ";";
      md << "\n\n";
    }
    if (!p.note.empty()) md << "Note: " << p.note << "\n\n";
    if (!it.argv.empty())
      md << "Provenance: `" << command_text(it.argv, r.proof_prefix) << " --out panels/" << p.name() << "` (bouncer " << r.build
         << "); outputs panels/" << p.name() << ".{png,csv,json}\n";
  }
  if (f.any_picture) {
    md << "\n## The pictures (data/pictures)\n\nNot figures of the paper: the pictures the README shows, "
          "drawn by the same build (`cp pictures/*.png` into data/pictures/ regenerates them).\n";
    for (const ItemResult& it : r.items) {
      if (it.kind != ItemKind::picture) continue;
      const Picture& p = m.pictures[it.index];
      md << "\n#### " << p.name << " (README: " << p.readme << ")\n\n" << p.about << "\n\n";
      if (drawn(it))
        for (const std::string& file : p.files) md << "![" << p.name << "](pictures/" << file << ")\n\n";
      else
        md << "**Failed:** " << md_cell(it.problem) << "\n\n";
      md << "Provenance: `" << command_text(it.argv, r.proof_prefix) << " --out pictures/" << p.name << "`\n";
    }
  }
  if (f.paper) md << "\n## Claims: provenance\n\n";
  for (const ItemResult& it : r.items) {
    if (it.kind != ItemKind::claim) continue;
    md << "- " << it.id << ": `" << command_text(it.argv, r.proof_prefix) << "`" << (it.outputs.empty() ? "" : " → " + it.outputs[0]);
    for (const std::string& failed : it.failed_checks) md << "; failed check: " << failed;
    md << "\n";
  }
  md << "\n## Times\n\n(Volatile: the only part of this report that changes between identical runs.)\n\n";
  md << "| item | state | seconds |\n|---|---|---|\n";
  for (const ItemResult& it : r.items) md << "| " << it.id << " | " << state_name(it.state) << " | " << fixed(it.seconds, 2) << " |\n";
  md << "\nTotal: " << fixed(r.seconds, 1) << " s with " << r.jobs << " jobs.\n";
  return md.str();
}

namespace {

// A manifest text (Markdown inline marks) as plain text of at most `limit` characters, cut
// at a word with "…": the one-line summary of a claim in the compact claims table.
std::string short_text(const std::string& s, size_t limit) {
  std::string t;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '`') continue;
    if (s.compare(i, 2, "**") == 0 || s.compare(i, 2, "\\|") == 0) {
      if (s[i] == '\\') t += '|';
      ++i;
      continue;
    }
    t += s[i] == '\n' ? ' ' : s[i];
  }
  // Characters, not bytes: UTF-8 continuation bytes are not counted and never split.
  size_t chars = 0, cut = std::string::npos;
  for (size_t i = 0; i < t.size(); ++i)
    if ((static_cast<unsigned char>(t[i]) & 0xC0) != 0x80 && ++chars > limit) {
      cut = i;
      break;
    }
  if (cut == std::string::npos) return t;
  const size_t space = t.rfind(' ', cut);
  t.resize(space != std::string::npos && space > cut / 2 ? space : cut);
  while (!t.empty() && std::strchr(" ,;:(", t.back())) t.pop_back();
  return t + " …";
}

// An id for an HTML anchor: the manifest's ids and labels are already names (letters,
// digits, . _ : + -, manifest.hpp), kept as they are so that #fig:basin2 names the panel.
std::string anchor(const std::string& prefix, const std::string& id) { return html_escape(prefix + id); }

}  // namespace

std::string report_html(const ReproduceResult& r) {
  const Manifest& m = r.manifest;
  const Framing f = framing(r);
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << html_escape(f.title) << "</title>\n"
    << "<style>body{font-family:sans-serif;max-width:1100px;margin:auto;padding:0 1em}table{border-collapse:collapse}"
       "td,th{border:1px solid #999;padding:3px 6px;vertical-align:top;text-align:left}img{max-width:100%}"
       ".ok{color:#060}.bad{color:#a00}figure{margin:1em 0}figcaption{font-style:italic}"
       "table.claims{width:100%;table-layout:fixed}table.claims th:first-child{width:3em}table.claims th:nth-child(n+3){width:8em}"
       "table.claims code{overflow-wrap:anywhere;word-break:break-word}table.claims summary{cursor:pointer}"
       "table.claims details[open]{background:#f6f6f6}table.claims dl{margin:.4em 0}table.claims dd{margin:0 0 .4em 1.5em}"
       "nav ul ul{columns:2;column-gap:2em;list-style:none;padding-left:1em}nav li{break-inside:avoid}"
       ".sheet{display:flex;flex-wrap:wrap;gap:8px}.sheet a{width:160px;font-size:80%;text-align:center;"
       "text-decoration:none;color:inherit}.sheet img{width:160px;height:120px;object-fit:contain;border:1px solid #ccc}"
       "</style>\n</head>\n<body>\n";
  h << "<h1 id=\"top\">" << html_escape(f.title) << "</h1>\n";
  h << "<p>Mode: <code>" << mode_name(r.mode) << "</code>. Built by bouncer " << html_escape(r.build) << ". Manifest: "
    << html_escape(r.manifest_source) << ".</p>\n";
  h << "<p class=\"" << (r.ok ? "ok" : "bad") << "\"><strong>Result: " << f.result_text << "</strong> ("
    << html_escape(r.summary) << ").</p>\n";
  auto items_of = [&](ItemKind kind) {
    std::vector<const ItemResult*> v;
    for (const ItemResult& it : r.items)
      if (it.kind == kind) v.push_back(&it);
    return v;
  };
  const std::vector<const ItemResult*> claims = items_of(ItemKind::claim), panels = items_of(ItemKind::panel),
                                       pictures = items_of(ItemKind::picture);
  // The figures in manifest order, each with its panels.
  std::vector<std::pair<std::string, std::vector<const ItemResult*>>> figures;
  for (const ItemResult* it : panels) {
    const Panel& p = m.panels[it->index];
    if (figures.empty() || figures.back().first != p.figure) figures.push_back({p.figure, {}});
    figures.back().second.push_back(it);
  }
  auto panel_title = [&](const Panel& p) {
    std::string t = p.label;
    if (!p.panel.empty()) t.append(" ").append(p.panel);
    if (!p.twin_of.empty()) t.append(" (certified twin)");
    if (!p.beside.empty()) t.append(" (sine wall)");
    return t;
  };

  // Contents: every claim and every figure and panel, linked.
  h << "<nav id=\"contents\">\n<h2>Contents</h2>\n<ul>\n";
  if (f.paper && !claims.empty()) {
    h << "<li><a href=\"#claims\">Claims</a> (" << claims.size() << ")\n<ul>\n";
    for (const ItemResult* it : claims) {
      const Claim& c = m.claims[it->index];
      h << "<li><a href=\"#" << anchor("claim-", c.id) << "\">" << html_escape(c.row) << " " << html_escape(c.id) << "</a> <span class=\""
        << (it->status == ClaimStatus::reproduced ? "ok" : "bad") << "\">" << html_escape(it->verdict) << "</span></li>\n";
    }
    h << "</ul></li>\n";
  }
  if (!figures.empty()) {
    h << "<li><a href=\"#figures\">Figures</a> (" << figures.size() << ", " << panels.size() << " panels; <a href=\"#contact-sheet\">contact sheet</a>)\n<ul>\n";
    for (const auto& [figure, its] : figures) {
      h << "<li><a href=\"#" << anchor("figure-", figure) << "\">" << html_escape(figure) << "</a>:";
      for (const ItemResult* it : its) {
        const Panel& p = m.panels[it->index];
        h << " <a href=\"#" << anchor("", p.label) << "\">" << html_escape(p.name()) << "</a>";
      }
      h << "</li>\n";
    }
    h << "</ul></li>\n";
  }
  if (!pictures.empty()) {
    h << "<li><a href=\"#pictures\">The pictures (data/pictures)</a>\n<ul>\n";
    for (const ItemResult* it : pictures) {
      const Picture& p = m.pictures[it->index];
      h << "<li><a href=\"#" << anchor("", p.id()) << "\">" << html_escape(p.name) << "</a></li>\n";
    }
    h << "</ul></li>\n";
  }
  h << "<li><a href=\"#times\">Times</a></li>\n</ul>\n</nav>\n";

  // Claims: one line each (row, claim, expected, this run's verdict); the details (the
  // whole claim, the paper's place, the evidence, how to rerun it, what ran and each check)
  // open on a click.
  if (f.paper && !claims.empty()) {
    h << "<section id=\"claims\">\n<h2>Claims</h2>\n<p>One line per claim; click a claim for its evidence, checks and the "
         "command that reruns it.</p>\n<table class=\"claims\">\n<tr><th>#</th><th>Claim</th><th>Expected</th><th>This run</th></tr>\n";
    for (const ItemResult* it : claims) {
      const Claim& c = m.claims[it->index];
      const bool ok = it->status == ClaimStatus::reproduced;
      h << "<tr id=\"" << anchor("claim-", c.id) << "\"><td>" << html_escape(c.row) << "</td><td><details><summary>"
        << html_escape(short_text(c.text, 80)) << "</summary>\n<dl>\n<dt>Claim (<code>" << html_escape(c.id) << "</code>)</dt><dd>"
        << md_inline_html(c.text) << "</dd>\n<dt>Paper</dt><dd>" << html_escape(c.paper) << "</dd>\n<dt>Evidence</dt><dd>"
        << md_inline_html(c.evidence) << "</dd>\n<dt>Rerun</dt><dd>" << md_inline_html(rerun_text(c.rerun, r.proof_prefix))
        << "</dd>\n";
      if (!it->argv.empty()) {
        h << "<dt>This run</dt><dd><code>" << html_escape(command_text(it->argv, r.proof_prefix)) << "</code>";
        if (!it->outputs.empty()) h << " → <a href=\"" << html_escape(it->outputs[0]) << "\">" << html_escape(it->outputs[0]) << "</a>";
        h << "</dd>\n";
      }
      if (!it->checks.empty()) {
        h << "<dt>Checks</dt><dd><ul>\n";
        for (const CheckResult& k : it->checks)
          h << "<li class=\"" << (k.held ? "ok" : "bad") << "\">" << (k.held ? "held" : "FAILED") << ": <code>" << html_escape(k.check)
            << "</code> (got <code>" << html_escape(k.got) << "</code>)</li>\n";
        h << "</ul></dd>\n";
      }
      if (!ok && !it->problem.empty()) h << "<dt>Problem</dt><dd class=\"bad\">" << html_escape(it->problem) << "</dd>\n";
      h << "</dl>\n</details></td><td>" << html_escape(c.expected) << "</td><td class=\"" << (ok ? "ok" : "bad") << "\">"
        << html_escape(it->verdict) << "</td></tr>\n";
    }
    h << "</table>\n</section>\n";
  }

  // Figures: a contact sheet of thumbnails, each linking to its panel, then every panel.
  if (!figures.empty()) {
    h << "<section id=\"figures\">\n<h2>Figures</h2>\n<div id=\"contact-sheet\" class=\"sheet\">\n";
    for (const ItemResult* it : panels) {
      const Panel& p = m.panels[it->index];
      h << "<a href=\"#" << anchor("", p.label) << "\">";
      if (drawn(*it)) h << "<img src=\"panels/" << html_escape(p.name()) << ".png\" alt=\"" << html_escape(p.label) << "\" loading=\"lazy\">";
      else h << "<span class=\"bad\">(" << (it->state == ItemState::skipped ? "pending" : "failed") << ")</span>";
      h << "<br>" << html_escape(panel_title(p)) << "</a>\n";
    }
    h << "</div>\n";
    if (!contact_sheet_panels(r).empty())
      h << "<p>Every drawn panel in one picture: <a href=\"contact-sheet.png\">contact-sheet.png</a>.</p>\n";
  }
  for (const auto& [figure, its] : figures) {
    h << "<section id=\"" << anchor("figure-", figure) << "\">\n<h3>" << html_escape(figure) << "</h3>\n";
    for (const ItemResult* it : its) {
      const Panel& p = m.panels[it->index];
      h << "<figure id=\"" << anchor("", p.label) << "\">\n";
      if (drawn(*it))
        h << "<img src=\"panels/" << html_escape(p.name()) << ".png\" alt=\"" << html_escape(p.label) << "\">\n"
          << (p.twin_of.empty() ? std::string()
                                : "<img src=\"panels/" + html_escape(p.name()) + "-artefacts.png\" alt=\"where double is wrong\">\n")
          << "<p class=\"files\"><a href=\"panels/" << html_escape(p.name()) << ".pdf\">PDF</a> · <a href=\"panels/"
          << html_escape(p.name()) << ".svg\">SVG</a> · <a href=\"panels/" << html_escape(p.name()) << ".csv\">CSV</a></p>\n";
      else if (it->state == ItemState::skipped)
        h << "<p><strong>Pending:</strong> " << html_escape(p.reason) << ".</p>\n";
      else
        h << "<p class=\"bad\"><strong>Failed:</strong> " << html_escape(it->problem) << "</p>\n";
      h << "<figcaption>" << html_escape(p.label);
      if (!p.panel.empty()) h << " " << html_escape(p.panel);
      if (!p.twin_of.empty()) h << " (certified twin of " << html_escape(p.twin_of) << ", not a panel of the paper)";
      if (!p.beside.empty()) h << " (sine wall, beside " << html_escape(p.beside) << ": not a panel of the paper)";
      h << ". Paper: " << html_escape(latex_text(p.caption)) << "</figcaption>\n";
      if (!p.params.empty()) {
        h << "<p>Parameters:";
        for (const auto& kv : p.params) h << " " << html_escape(kv.first) << " = " << html_escape(kv.second) << ";";
        h << "</p>\n";
      }
      if (!p.note.empty()) h << "<p>Note: " << html_escape(p.note) << "</p>\n";
      if (!it->argv.empty())
        h << "<p>Provenance: <code>" << html_escape(command_text(it->argv, r.proof_prefix)) << " --out panels/" << html_escape(p.name())
          << "</code> (bouncer " << html_escape(r.build) << ")</p>\n";
      h << "<p><a href=\"#contents\">contents</a></p>\n</figure>\n";
    }
    h << "</section>\n";
  }
  if (!figures.empty()) h << "</section>\n";
  if (!pictures.empty()) {
    h << "<section id=\"pictures\">\n<h2>The pictures (data/pictures)</h2>\n<p>Not figures of the paper: the pictures the README shows, "
         "drawn by the same build (<code>cp pictures/*.png</code> into data/pictures/ regenerates them).</p>\n";
    for (const ItemResult* it : pictures) {
      const Picture& p = m.pictures[it->index];
      h << "<figure id=\"" << anchor("", p.id()) << "\">\n";
      if (drawn(*it))
        for (const std::string& file : p.files)
          h << "<img src=\"pictures/" << html_escape(file) << "\" alt=\"" << html_escape(p.name) << "\">\n";
      else
        h << "<p class=\"bad\"><strong>Failed:</strong> " << html_escape(it->problem) << "</p>\n";
      h << "<figcaption>" << html_escape(p.name) << " (README: " << html_escape(p.readme) << "). " << md_inline_html(p.about)
        << "</figcaption>\n<p>Provenance: <code>" << html_escape(command_text(it->argv, r.proof_prefix)) << " --out pictures/"
        << html_escape(p.name) << "</code></p>\n</figure>\n";
    }
    h << "</section>\n";
  }
  h << "<section id=\"times\">\n<h2>Times</h2>\n<p>Volatile: the only part of this report that changes between identical runs.</p>\n"
    << "<table>\n<tr><th>item</th><th>state</th><th>seconds</th></tr>\n";
  for (const ItemResult& it : r.items)
    h << "<tr><td>" << html_escape(it.id) << "</td><td>" << state_name(it.state) << "</td><td>" << fixed(it.seconds, 2)
      << "</td></tr>\n";
  h << "</table>\n<p>Total: " << fixed(r.seconds, 1) << " s with " << r.jobs << " jobs.</p>\n</section>\n</body>\n</html>\n";
  return h.str();
}

void write_reports(const ReproduceResult& r) {
  const fs::path dir = r.dir;
  // The contact sheet (one PNG of every drawn panel's thumbnail, io/contact_sheet.hpp), first:
  // the reports link it.
  const std::vector<std::string> sheet = contact_sheet_panels(r);
  if (!sheet.empty()) write_contact_sheet(sheet, (dir / "contact-sheet.png").string());
  const std::string md = report_markdown(r), html = report_html(r), claims = claims_json(r);
  OutputSet set;
  const std::pair<fs::path, const std::string*> files[] = {
      {dir / "report.md", &md}, {dir / "report.html", &html}, {dir / "claims.json", &claims}};
  for (const auto& file : files) set.reserve("out", file.first.string());
  for (const auto& file : files) set.write(file.first.string(), [&](std::ostream& s) { s << *file.second; });
  set.commit();
}

}  // namespace bouncer
