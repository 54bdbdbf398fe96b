// The audit of a `bouncer reproduce` directory (workflow/audit.hpp): the same reproduce
// (mode, --only, manifest) rerun into audit's private directory with the given executable,
// and compared item by item: each claim's status, verdict and every check's value; each
// claim's JSON output and each panel's PREFIX.json and PREFIX.csv with the volatile fields
// removed as for single results (times, invocation, output paths); of a proof certificate,
// its verdicts and statements (its evidence strings hold timings). Pictures are compared
// through their CSV and JSON, not as PNG bytes.
#include <chrono>
#include <filesystem>
#include <map>

#include "audit_internal.hpp"
#include "bouncer/base/error.hpp"
#include "bouncer/base/input.hpp"

namespace bouncer::audit_detail {

namespace {

// j[key] of a const object, or null when it has none (a crafted claims.json may lack it).
json member(const json& j, const char* key) { return j.is_object() && j.contains(key) ? j[key] : json(); }

}  // namespace

AuditResult audit_reproduce(const std::string& directory, const AuditRequest& request) {
  namespace fs = std::filesystem;
  const fs::path dir = directory;
  const std::string claims_path = (dir / "claims.json").string();
  const std::optional<std::string> old_text = read_result(claims_path);
  const json old = json::parse(old_text.value_or(""), nullptr, false);
  auto not_reproduce = [&](const std::string& why) {
    throw InputError("file", "'" + claims_path + "' is not the claims.json of bouncer reproduce (" + why + ")");
  };
  if (!old_text || old.is_discarded() || !old.contains("reproduce") || !old["reproduce"].is_object() ||
      !old["reproduce"].contains("mode") || !old["reproduce"]["mode"].is_string())
    not_reproduce("no reproduce.mode");
  // Its parts have the shape reproduce writes, checked before anything runs (a crafted file
  // must not start a long rerun only to be found malformed afterwards).
  auto entries = [&](const char* list, const char* key) {
    if (!old.contains(list)) return;
    if (!old[list].is_array()) not_reproduce(std::string("'") + list + "' is not a list");
    for (const json& e : old[list])
      if (!e.is_object() || !e.contains(key) || !e[key].is_string() ||
          (e.contains("status") && !e["status"].is_string()) || (e.contains("output") && !e["output"].is_string()) ||
          (e.contains("files") && !e["files"].is_array()))
        not_reproduce(std::string("an entry of '") + list + "' without a string '" + key + "'");
  };
  entries("claims", "id");
  entries("panels", "label");
  entries("pictures", "label");
  const json& r = old["reproduce"];
  // The rerun is built from what reproduce records, each part checked: a mode, ids that are
  // names (not paths or options), and the built-in manifest unless trust_manifest.
  const std::string mode = r["mode"].get<std::string>();
  if (mode != "quick" && mode != "full" && mode != "pictures") not_reproduce("mode '" + mode + "'");
  std::vector<std::string> argv{request.executable, "reproduce", "--" + mode};
  if (r.contains("only") && r["only"].is_array() && !r["only"].empty()) {
    std::string only;
    for (const json& id : r["only"]) {
      if (!id.is_string() || !safe_name(id.get<std::string>())) not_reproduce("an --only id that is not a name");
      only += (only.empty() ? "" : ",") + id.get<std::string>();
    }
    argv.push_back("--only=" + only);
  }
  if (r.contains("manifest") && !r["manifest"].is_string()) not_reproduce("a manifest that is not a string");
  const std::string manifest = r.value("manifest", "");
  if (!manifest.empty() && manifest.find("(built in)") == std::string::npos) {
    if (!request.trust_manifest)
      throw InputError("file", "'" + claims_path + "' was made from the manifest '" + manifest +
                                   "', not bouncer's built-in one; audit runs another manifest's commands only when "
                                   "told to (--trust-manifest; they are then still limited to bouncer's computing "
                                   "commands, writing into audit's temporary directory)");
    argv.push_back("--manifest=" + fs::absolute(manifest).string());
  }
  const PrivateDir private_dir;
  const fs::path tmp = private_dir.path;
  argv.push_back("--out=" + (tmp / "r").string());
  AuditResult result;
  result.reproduce_directory = true;
  result.directory = dir.string();
  const auto started = std::chrono::steady_clock::now();
  result.rerun_status = run_to_file(argv, (tmp / "stdout").string(), tmp.string());
  const auto rerun_ended = std::chrono::steady_clock::now();
  result.rerun_seconds = std::chrono::duration<double>(rerun_ended - started).count();
  const std::optional<std::string> now_text = read_result((tmp / "r" / "claims.json").string());
  const json now = json::parse(now_text.value_or(""), nullptr, false);
  if ((result.rerun_status != 0 && result.rerun_status != 1) || !now_text || now.is_discarded()) {
    result.verdict = AuditVerdict::rerun_failed;
    result.message = "the rerun of reproduce failed (exit status " + std::to_string(result.rerun_status) + ")";
    return result;
  }
  std::vector<std::string>& differences = result.differences;
  if (r.value("build", "") != now["reproduce"].value("build", ""))
    differences.push_back("build: " + r.value("build", "") + " vs " + now["reproduce"].value("build", ""));
  auto by_id = [](const json& list, const char* key) {
    std::map<std::string, json> m;
    if (list.is_array())
      for (const json& e : list) m[e.value(key, "")] = e;
    return m;
  };
  auto compare_file = [&](const std::string& rel) {
    // A name from the audited claims.json: one of reproduce's own subdirectories and a file
    // name in it, nothing else (never a path out of the directory).
    const auto slash = rel.find('/');
    const std::string sub = slash == std::string::npos ? "" : rel.substr(0, slash);
    if ((sub != "claims" && sub != "panels" && sub != "pictures") || !safe_name(rel.substr(slash + 1)))
      return differences.push_back(std::string("'").append(one_line(rel, 120)) + "': not a file of a reproduce directory");
    const std::optional<std::string> a = read_result((dir / rel).string());
    if (!a) return differences.push_back(rel + ": missing in " + dir.string());
    const std::optional<std::string> b = read_result((tmp / "r" / rel).string());
    if (!b) return differences.push_back(rel + ": missing in the rerun");
    ++result.outputs_compared;
    if (rel.size() > 4 && rel.substr(rel.size() - 4) == ".csv") {
      if (normalized_lines(*a) != normalized_lines(*b)) differences.push_back(rel + ": rows differ");
      return;
    }
    json ja = parse_exact(*a), jb = parse_exact(*b);
    if (ja.is_discarded() || jb.is_discarded()) {
      if (*a != *b) differences.push_back(rel + ": differs");
      return;
    }
    // A proof certificate's evidence strings carry timings ("(0.33 s)"): compare what it
    // concludes (verdicts and statements, overall and per sub-claim), not its evidence.
    auto conclusions = [](const json& j) {
      if (!j.is_object() || !j.contains("proof") || !j.contains("subclaims")) return j;
      json c{{"verdict", j.value("verdict", json())}, {"statement", j.value("statement", json())}, {"subclaims", json::array()}};
      if (j["subclaims"].is_array())
        for (const json& s : j["subclaims"])
          c["subclaims"].push_back({{"name", s.value("name", json())}, {"verdict", s.value("verdict", json())},
                                    {"statement", s.value("statement", json())}});
      return c;
    };
    ja = conclusions(ja);
    jb = conclusions(jb);
    strip_volatile(ja, true);
    strip_volatile(jb, true);
    if (const Comparison c = first_difference(ja, jb); !c.identical) differences.push_back(rel + ": " + c.path + ": " + c.detail);
  };
  const auto old_claims = by_id(member(old, "claims"), "id"), new_claims = by_id(member(now, "claims"), "id");
  for (const auto& [id, c] : old_claims) {
    const auto it = new_claims.find(id);
    if (it == new_claims.end()) {
      differences.push_back("claim " + id + ": not in the rerun");
      continue;
    }
    for (const char* k : {"status", "verdict", "checks"})
      if (c.value(k, json()) != it->second.value(k, json()))
        differences.push_back("claim " + id + ": " + k + ": " + short_dump(c.value(k, json())) + " vs " + short_dump(it->second.value(k, json())));
    if (c.contains("output") && c["output"].is_string() && member(c, "status") != "failed") compare_file(c["output"].get<std::string>());
  }
  for (const auto& [id, c] : new_claims)
    if (!old_claims.count(id)) differences.push_back("claim " + id + ": only in the rerun");
  // The paper's panels, and with reproduce --pictures the README's pictures: the same shape.
  for (const char* kind : {"panels", "pictures"}) {
    const std::string what = kind == std::string("panels") ? "panel " : "picture ";
    const auto old_panels = by_id(old.value(kind, json::array()), "label"), new_panels = by_id(now.value(kind, json::array()), "label");
    for (const auto& [label, p] : old_panels) {
      const auto it = new_panels.find(label);
      if (it == new_panels.end()) {
        differences.push_back(what + label + ": not in the rerun");
        continue;
      }
      if (p.value("status", "") != it->second.value("status", ""))
        differences.push_back(what + label + ": status " + p.value("status", "") + " vs " + it->second.value("status", ""));
      if (p.contains("files") && p["files"].is_array())
        for (const json& f : p["files"]) {
          if (!f.is_string()) continue;
          const std::string rel = f.get<std::string>();
          // Pictures embed the command line (with its --out path) in their metadata, so they are
          // compared through the CSV and JSON they are drawn from, not byte for byte.
          const std::string ext = rel.size() > 4 ? rel.substr(rel.size() - 4) : "";
          if (ext == ".png" || ext == ".pdf" || ext == ".svg") continue;
          compare_file(rel);
        }
    }
    for (const auto& [label, p] : new_panels)
      if (!old_panels.count(label)) differences.push_back(what + label + ": only in the rerun");
  }
  result.claims_compared = old_claims.size();
  result.verdict = differences.empty() ? AuditVerdict::identical : AuditVerdict::different;
  result.compare_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - rerun_ended).count();
  return result;
}

}  // namespace bouncer::audit_detail
