#include "json.hpp"

#include <functional>

namespace bouncer::reports {

void write_key_values(std::ostream& out, const Provenance& p, const json& j) {
  out << p.as_comment_lines();
  std::function<void(const std::string&, const json&)> put = [&](const std::string& prefix, const json& x) {
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

void write_certified(std::ostream& out, bool as_json, const Provenance& p, const json& body) {
  if (as_json) {
    json doc;
    doc["provenance"] = json::parse(p.as_json());
    for (const auto& [k, v] : body.items()) doc[k] = v;
    out << doc.dump(1) << "\n";
  } else {
    write_key_values(out, p, body);
  }
}

}  // namespace bouncer::reports
