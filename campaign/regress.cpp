#include "campaign/regress.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "campaign/ladders.hpp"
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

// A ladder's key: its parameters without the resolution field, and the field.
std::string ladder_key(const json& params, const std::string& pointer) {
  return canonical_text(params) + " " + pointer;
}

// The baseline's part of a ladder (campaign/ladders.hpp to_json): each
// edge's status, value and error; not its cost, which varies run to run.
json ladder_row(const Ladder& l) {
  const json row = to_json(l);
  json out = {
      {"params", row.at("params")}, {"pointer", row.at("pointer")}, {"levels", row.at("levels")}};
  for (const char* edge : {"critical", "maximum"}) {
    const json& e = row.at(edge);
    out[edge] = {{"status", e.at("status")}, {"value", e.at("value")}, {"error", e.at("error")}};
  }
  return out;
}

// Two edges (m/s, null: open) agree: both open, or within `tol` of each other.
bool within(const json& x, const json& y, double tol) {
  if (x.is_null() || y.is_null()) return x.is_null() == y.is_null();
  return std::abs(x.get<double>() - y.get<double>()) <= tol;
}

// Each edge's status, value and error from resolution against the baseline's.
void compare_ladders(const json& baseline, const std::vector<WindowRecord>& windows, double tol,
                     RegressionReport& r) {
  std::map<std::string, json> current;
  for (const Ladder& l : resolution_ladders(windows)) {
    current[ladder_key(l.params, l.pointer)] = ladder_row(l);
  }
  for (const json& b : baseline) {
    const std::string key = ladder_key(b.at("params"), b.at("pointer").get<std::string>());
    const auto it = current.find(key);
    if (it == current.end()) {
      r.checks.push_back({key, "ladder", "yes", "no", false});
      continue;
    }
    for (const char* edge : {"critical", "maximum"}) {
      const json& x = b.at(edge);
      const json& y = it->second.at(edge);
      const std::string name = std::string("ladder ") + edge;
      r.checks.push_back({key, name + " status", x.at("status").get<std::string>(),
                          y.at("status").get<std::string>(), x.at("status") == y.at("status")});
      for (const char* figure : {"value", "error"}) {
        r.checks.push_back({key, name + " " + figure, text_of(x.at(figure)), text_of(y.at(figure)),
                            within(x.at(figure), y.at(figure), tol)});
      }
    }
    current.erase(it);
  }
  for (const auto& [key, row] : current) {
    r.checks.push_back({key, "ladder", "no", "yes (not in the baseline)", false});
  }
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
  json doc = {{"campaign", campaign_name},
              {"solver_version", solver_version_string()},
              {"tolerances", {{"velocity", velocity_tolerance}}},
              {"windows", rows}};
  const std::vector<Ladder> ladders = resolution_ladders(windows);
  if (!ladders.empty()) {
    doc["ladders"] = json::array();
    for (const Ladder& l : ladders) doc["ladders"].push_back(ladder_row(l));
  }
  return doc;
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
      r.checks.push_back({key, edge, text_of(x), text_of(y), within(x, y, tol)});
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
  if (baseline.contains("ladders")) {
    if (!baseline["ladders"].is_array()) {
      throw std::invalid_argument("/ladders: must be an array of resolution ladders");
    }
    compare_ladders(baseline["ladders"], windows, tol, r);
  }
  return r;
}

}  // namespace splat::campaign
