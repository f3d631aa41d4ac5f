// Shared by the API tests: a real server (api::Server) on a port the OS
// picks, over a real SQLite file in a temporary folder, stopped on scope
// exit; a client; response checks against schemas/api_*.schema.json; and a
// fingerprint of everything the store holds.
#pragma once

#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <thread>

#include "api/server.hpp"
#include "campaign/store.hpp"
#include "solver/input/schema.hpp"
#include "support/temp_dir.hpp"

namespace splat::api_test {

namespace fs = std::filesystem;

using nlohmann::json;
using splat::test_support::TempDir;

// The two-mass scene (thesis 3.5.1.1) inline: jobs run in milliseconds.
inline json two_mass_scene() {
  return json::parse(R"({
    "name": "two_mass",
    "two_mass": {"M": 1.0, "m": 2.0, "k": 0.0, "V0": 1.0, "area": 1.0,
                 "adhesion": {"G_c": 0.2, "sigma_c": 0.5, "activation": {"rule": "none"},
                              "D_adh_max": null}},
    "time": {"end_time": 50.0},
    "output": {"history_interval": 0}
  })");
}

// 2 parameter sets x 5 velocities. For k = 0 the critical velocity is
// V0* = sqrt(2 G_c A (M + m) / (M m)): 0.548 m/s (G_c = 0.1), 0.775 m/s (0.2).
inline json small_campaign(const std::string& name = "api-small") {
  return {{"name", name},
          {"description", "two-mass window, API test"},
          {"tags", {"api-test"}},
          {"base_scene", two_mass_scene()},
          {"velocity", {{"values", {0.2, 0.4, 0.6, 0.8, 1.0}}}},
          {"G_c", {{"values", {0.1, 0.2}}}},
          {"job", {{"time_limit", 30}, {"retries", 0}}}};
}

class ServerHandle {
 public:
  explicit ServerHandle(api::ServerOptions o) {
    server_ = std::make_unique<api::Server>(std::move(o));
    port_ = server_->bind();
    thread_ = std::thread([this] { server_->serve(); });
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!server_->ready() && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  ~ServerHandle() {
    server_->stop();
    if (thread_.joinable()) thread_.join();
  }
  int port() const { return port_; }
  bool ready() const { return server_->ready(); }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(std::chrono::seconds(30));
    return c;
  }

 private:
  std::unique_ptr<api::Server> server_;
  int port_ = 0;
  std::thread thread_;
};

inline api::ServerOptions options_for(const TempDir& dir) {
  api::ServerOptions o;
  o.db = dir.path / "store.db";
  o.host = "127.0.0.1";
  o.port = 0;
  o.workers = 2;
  o.job_program = SPLAT_BINARY;
  o.web_dir = fs::path(SPLAT_SOURCE_DIR) / "web";
  return o;
}

inline json body_json(const httplib::Result& r) {
  return json::parse(r->body);
}

// Violations of a response document against schemas/NAME.schema.json.
inline std::string schema_errors(const std::string& name, const json& doc) {
  std::string s;
  for (const SchemaViolation& v : validate(name, doc)) s += to_string(v) + "\n";
  return s;
}

// A problem document with this status, the problem content type and, when
// given, an error naming `pointer`.
inline void expect_problem(const httplib::Result& r, int status, const std::string& pointer = "-") {
  ASSERT_TRUE(r) << "no response";
  EXPECT_EQ(r->status, status) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/problem+json") << r->body;
  const json p = json::parse(r->body, nullptr, false);
  ASSERT_TRUE(p.is_object()) << r->body;
  EXPECT_EQ(schema_errors("api_problem", p), "") << r->body;
  EXPECT_EQ(p.value("status", 0), status);
  if (pointer != "-") {
    bool found = false;
    for (const json& e : p.value("errors", json::array())) {
      if (e.value("pointer", std::string("?")) == pointer) found = true;
    }
    EXPECT_TRUE(found) << "no error at " << pointer << ": " << r->body;
  }
}

// Everything the store holds, as one text: equal before and after = unchanged.
inline std::string store_fingerprint(const fs::path& db) {
  campaign::Database d(db);
  std::string s;
  for (const char* table : {"campaigns", "jobs", "campaign_points", "results", "windows"}) {
    campaign::Statement st =
        d.prepare(std::string("SELECT COUNT(*), TOTAL(length(CAST(rowid AS TEXT))) FROM ") + table);
    st.step();
    s += std::string(table) + "=" + std::to_string(st.int64(0)) + ";";
  }
  campaign::Statement st = d.prepare("SELECT id, state, spec_hash FROM campaigns ORDER BY id");
  while (st.step()) s += std::to_string(st.int64(0)) + st.text(1) + st.text(2) + ";";
  campaign::Statement js = d.prepare("SELECT hash, state, attempts FROM jobs ORDER BY hash");
  while (js.step()) s += js.text(0).substr(0, 8) + js.text(1) + std::to_string(js.int64(2)) + ";";
  return s;
}

// Polls the campaign until it is no longer active (or the time is up).
inline json wait_for_campaign(const httplib::Client& c_in, std::int64_t id, double seconds = 60) {
  httplib::Client& c = const_cast<httplib::Client&>(c_in);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  json doc;
  while (std::chrono::steady_clock::now() < deadline) {
    auto r = c.Get(("/api/v1/campaigns/" + std::to_string(id)).c_str());
    if (r && r->status == 200) {
      doc = json::parse(r->body);
      if (doc["state"] != "active" && doc["state"] != "cancelling") return doc;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return doc;
}

inline httplib::Result post_json(httplib::Client& c, const std::string& path, const json& body,
                                 const httplib::Headers& headers = {}) {
  return c.Post(path.c_str(), headers, body.dump(), "application/json");
}

}  // namespace splat::api_test
