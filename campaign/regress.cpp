#include "campaign/regress.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "campaign/spec.hpp"

namespace splat::campaign {

using nlohmann::json;

namespace {

std::string text_of(const json& x) {
  if (x.is_null()) return "none";
  if (x.is_number_float()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", x.get<double>());
    return buf;
  }
  return x.dump();
}

json row_of(const WindowRecord& w) {
  const json doc = json::parse(w.window);
  return {{"params", json::parse(w.params)},
          {"critical_velocity", doc.at("critical_velocity")},
          {"maximum_velocity", doc.at("maximum_velocity")},
          {"intervals", doc.at("intervals").size()},
          {"sticks", doc.at("sticks")},
          {"rebounds", doc.at("rebounds")},
          {"unclassified", doc.at("unclassified").size()}};
}

}  // namespace

bool RegressionReport::drift() const {
  for (const RegressionCheck& c : checks) {
    if (!c.ok) return true;
  }
  return false;
}

json make_baseline(const std::string& campaign_name, const std::vector<WindowRecord>& windows,
                   double velocity_tolerance) {
  json rows = json::array();
  for (const WindowRecord& w : windows) rows.push_back(row_of(w));
  return {{"campaign", campaign_name},
          {"solver_version", solver_version_string()},
          {"tolerances", {{"velocity", velocity_tolerance}}},
          {"windows", rows}};
}

RegressionReport compare_to_baseline(const json& baseline,
                                     const std::vector<WindowRecord>& windows) {
  if (!baseline.is_object() || !baseline.contains("windows") || !baseline["windows"].is_array()) {
    throw std::invalid_argument("/windows: required array of windows is missing");
  }
  const json tol_node = baseline.value("tolerances", json::object()).value("velocity", json());
  if (!tol_node.is_number() || tol_node.get<double>() < 0) {
    throw std::invalid_argument("/tolerances/velocity: must be a number >= 0 (m/s)");
  }
  const double tol = tol_node.get<double>();
  std::map<std::string, json> current;
  for (const WindowRecord& w : windows) current[canonical_text(json::parse(w.params))] = row_of(w);

  RegressionReport r;
  for (const json& b : baseline["windows"]) {
    const std::string key = canonical_text(b.at("params"));
    const auto it = current.find(key);
    if (it == current.end()) {
      r.checks.push_back({key, "present", "yes", "no", false});
      continue;
    }
    const json& c = it->second;
    for (const char* edge : {"critical_velocity", "maximum_velocity"}) {
      const json& x = b.at(edge);
      const json& y = c.at(edge);
      bool ok = x.is_null() == y.is_null();
      if (ok && !x.is_null()) ok = std::abs(x.get<double>() - y.get<double>()) <= tol;
      r.checks.push_back({key, edge, text_of(x), text_of(y), ok});
    }
    for (const char* count : {"intervals", "unclassified"}) {
      const bool ok = b.at(count) == c.at(count);
      r.checks.push_back({key, count, text_of(b.at(count)), text_of(c.at(count)), ok});
    }
    current.erase(it);
  }
  for (const auto& [key, row] : current) {
    r.checks.push_back({key, "present", "no", "yes (not in the baseline)", false});
  }
  return r;
}

}  // namespace splat::campaign
