#include "campaign/window_rows.hpp"

#include <cstdio>

namespace splat::campaign {

using nlohmann::json;

namespace {

std::string number(const json& x) {
  if (!x.is_number()) return {};
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x.get<double>());
  return buf;
}

std::string edge_field(const json& edge, const char* key) {
  return edge.is_null() ? std::string() : number(edge.at(key));
}

}  // namespace

json window_rows(const std::vector<WindowRecord>& windows) {
  json rows = json::array();
  for (const WindowRecord& w : windows) {
    json row = json::parse(w.window);
    row["campaign_id"] = w.campaign_id;
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string window_rows_csv(const std::vector<WindowRecord>& windows) {
  std::string out =
      "campaign_id,params,critical_velocity,critical_rebound,critical_stick,"
      "maximum_velocity,maximum_stick,maximum_rebound,intervals,sticks,rebounds,"
      "unclassified\n";
  for (const json& row : window_rows(windows)) {
    std::string quoted = "\"";
    for (char c : row.at("params").dump())
      quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    quoted += "\"";
    const json& lo = row.at("critical_bracket");
    const json& hi = row.at("maximum_bracket");
    out += std::to_string(row.at("campaign_id").get<std::int64_t>()) + "," + quoted + "," +
           number(row.at("critical_velocity")) + "," + edge_field(lo, "rebound_velocity") + "," +
           edge_field(lo, "stick_velocity") + "," + number(row.at("maximum_velocity")) + "," +
           edge_field(hi, "stick_velocity") + "," + edge_field(hi, "rebound_velocity") + "," +
           std::to_string(row.at("intervals").size()) + "," +
           std::to_string(row.at("sticks").get<int>()) + "," +
           std::to_string(row.at("rebounds").get<int>()) + "," +
           std::to_string(row.at("unclassified").size()) + "\n";
  }
  return out;
}

}  // namespace splat::campaign
