#include "app/window_table.hpp"

#include <algorithm>

namespace splat::app {

using nlohmann::json;

namespace {

std::string number(const json& x, const char* fmt = "%.6g") {
  if (!x.is_number()) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, x.get<double>());
  return buf;
}

// "0.775 [0.77, 0.78]" for a closed edge, "open (below 0.5)" style otherwise.
std::string edge_text(const json& edge, bool lower, const json& range) {
  if (edge.is_null()) return "-";
  if (edge.at("estimate").is_null()) {
    return lower ? "below " + number(range.at(0)) : "above " + number(range.at(1));
  }
  const double a = edge.at("rebound_velocity").get<double>();
  const double b = edge.at("stick_velocity").get<double>();
  std::string s = number(edge.at("estimate")) + " [" + number(json(std::min(a, b))) + ", " +
                  number(json(std::max(a, b))) + "]";
  if (!edge.at("unclassified").empty()) {
    s += " (" + std::to_string(edge.at("unclassified").size()) + " unclassified inside)";
  }
  return s;
}

std::string unclassified_text(const json& list) {
  std::string s;
  for (const json& u : list) {
    if (!s.empty()) s += ", ";
    s += u.at("label").get<std::string>() + "@" + number(u.at("velocity"));
  }
  return s.empty() ? "-" : s;
}

}  // namespace

json windows_json(const std::vector<campaign::WindowRecord>& windows) {
  json rows = json::array();
  for (const campaign::WindowRecord& w : windows) {
    json row = json::parse(w.window);
    row["campaign_id"] = w.campaign_id;
    rows.push_back(std::move(row));
  }
  return rows;
}

void print_windows_table(std::FILE* out, const std::vector<campaign::WindowRecord>& windows) {
  std::fprintf(out, "%-48s %-34s %-34s %9s  %s\n", "parameters", "critical velocity m/s",
               "maximum velocity m/s", "intervals", "not stick/rebound");
  for (const json& row : windows_json(windows)) {
    const json& range = row.at("swept_range");
    std::string params = row.at("params").dump();
    if (params == "{}") params = "(base scene)";
    std::fprintf(out, "%-48s %-34s %-34s %9zu  %s\n", params.c_str(),
                 edge_text(row.at("critical_bracket"), true, range).c_str(),
                 edge_text(row.at("maximum_bracket"), false, range).c_str(),
                 row.at("intervals").size(), unclassified_text(row.at("unclassified")).c_str());
    if (row.at("intervals").size() > 1) {
      for (const json& iv : row.at("intervals")) {
        std::fprintf(out, "%-48s   interval %s .. %s\n", "",
                     edge_text(iv.at("lower"), true, range).c_str(),
                     edge_text(iv.at("upper"), false, range).c_str());
      }
    }
  }
}

void print_windows_csv(std::FILE* out, const std::vector<campaign::WindowRecord>& windows) {
  std::fprintf(out,
               "campaign_id,params,critical_velocity,critical_rebound,critical_stick,"
               "maximum_velocity,maximum_stick,maximum_rebound,intervals,sticks,rebounds,"
               "unclassified\n");
  for (const json& row : windows_json(windows)) {
    auto field = [](const json& edge, const char* key) {
      return edge.is_null() ? std::string() : number(edge.at(key), "%.17g");
    };
    std::string params = row.at("params").dump();
    std::string quoted = "\"";
    for (char c : params) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    quoted += "\"";
    const json& lo = row.at("critical_bracket");
    const json& hi = row.at("maximum_bracket");
    std::string cv = number(row.at("critical_velocity"), "%.17g");
    std::string mv = number(row.at("maximum_velocity"), "%.17g");
    if (cv == "-") cv.clear();
    if (mv == "-") mv.clear();
    std::string a = field(lo, "rebound_velocity"), b = field(lo, "stick_velocity");
    std::string c = field(hi, "stick_velocity"), d = field(hi, "rebound_velocity");
    for (std::string* s : {&a, &b, &c, &d}) {
      if (*s == "-") s->clear();
    }
    std::fprintf(out, "%lld,%s,%s,%s,%s,%s,%s,%s,%zu,%d,%d,%zu\n",
                 static_cast<long long>(row.at("campaign_id").get<std::int64_t>()), quoted.c_str(),
                 cv.c_str(), a.c_str(), b.c_str(), mv.c_str(), c.c_str(), d.c_str(),
                 row.at("intervals").size(), row.at("sticks").get<int>(),
                 row.at("rebounds").get<int>(), row.at("unclassified").size());
  }
}

std::string counts_text(const campaign::JobCounts& c) {
  std::string s = std::to_string(c.total()) + " jobs:";
  bool first = true;
  auto part = [&](int n, const char* what) {
    if (n == 0) return;
    s += (first ? " " : ", ") + std::to_string(n) + " " + what;
    first = false;
  };
  part(c.succeeded, "succeeded");
  part(c.failed, "failed");
  part(c.timed_out, "timed-out");
  part(c.cancelled, "cancelled");
  part(c.running, "running");
  part(c.queued, "queued");
  return s;
}

}  // namespace splat::app
