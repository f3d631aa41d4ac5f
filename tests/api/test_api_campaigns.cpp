// /api/v1/campaigns: submit, poll to the end, windows in JSON and CSV,
// pagination, each job's model and resolution, idempotent retry, ETag 304,
// cancel. A real server on a port
// the OS picks, a real SQLite file, real `splat run` jobs of the two-mass
// model; every response checked against its schema.
#include <cmath>

#include "solver/input/material_io.hpp"
#include "tests/api/api_fixture.hpp"

namespace splat::api_test {
namespace {

// Closed-form edge of the two-mass problem with k = 0 (scene description):
// the masses stick below it, so it is the window's upper (maximum) edge;
// V0* = sqrt(2 G_c A (M + m) / (M m)), M = 1 kg, m = 2 kg, A = 1 m^2.
double separation_edge(double G_c) {
  return std::sqrt(2.0 * G_c * 1.0 * 3.0 / 2.0);
}

TEST(api_campaigns, submit_poll_windows_json_and_csv) {
  TempDir dir;
  ServerHandle server(options_for(dir));
  ASSERT_TRUE(server.ready());
  httplib::Client c = server.client();

  auto r = post_json(c, "/api/v1/campaigns", small_campaign());
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 202) << r->body;
  const json created = body_json(r);
  EXPECT_EQ(schema_errors("api_campaign", created), "");
  const std::int64_t id = created["id"];
  EXPECT_EQ(r->get_header_value("Location"), "/api/v1/campaigns/" + std::to_string(id));
  EXPECT_EQ(created["jobs"]["total"], 10);

  const json done = wait_for_campaign(c, id);
  ASSERT_EQ(done["state"], "finished") << done.dump();
  EXPECT_EQ(schema_errors("api_campaign", done), "");
  EXPECT_EQ(done["jobs"]["succeeded"], 10);
  EXPECT_DOUBLE_EQ(done["progress"].get<double>(), 1.0);
  EXPECT_EQ(done["estimated_seconds_left"], 0.0);

  auto w = c.Get(("/api/v1/campaigns/" + std::to_string(id) + "/windows").c_str());
  ASSERT_TRUE(w);
  ASSERT_EQ(w->status, 200);
  const json windows = body_json(w);
  EXPECT_EQ(schema_errors("api_windows", windows), "");
  ASSERT_EQ(windows["windows"].size(), 2u);
  for (const json& row : windows["windows"]) {
    // Sampled every 0.2 m/s: sticking from the lowest speed (lower edge open,
    // critical velocity null) up to V0*; the estimate is the bracket
    // midpoint, within 0.1 m/s of the closed-form edge.
    EXPECT_TRUE(row["critical_velocity"].is_null()) << row.dump();
    const double G_c = row["params"]["G_c"];
    const double rebound = row["maximum_bracket"]["rebound_velocity"];
    const double stick = row["maximum_bracket"]["stick_velocity"];
    const double bracket_low = std::min(rebound, stick);
    const double bracket_high = std::max(rebound, stick);
    EXPECT_LT(bracket_low, separation_edge(G_c)) << row.dump();
    EXPECT_GT(bracket_high, separation_edge(G_c)) << row.dump();
    EXPECT_NEAR(row["maximum_velocity"].get<double>(), separation_edge(G_c), 0.1 + 1e-12);
  }

  httplib::Headers csv_accept = {{"Accept", "text/csv"}};
  auto csv = c.Get(("/api/v1/campaigns/" + std::to_string(id) + "/windows").c_str(), csv_accept);
  ASSERT_TRUE(csv);
  ASSERT_EQ(csv->status, 200);
  EXPECT_EQ(csv->get_header_value("Content-Type"), "text/csv; charset=utf-8");
  const std::string& text = csv->body;
  EXPECT_EQ(text.rfind("campaign_id,params,critical_velocity,", 0), 0u) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3) << text;  // header + 2 rows
  EXPECT_NE(text.find("\"{\"\"G_c\"\":0.1}\""), std::string::npos) << text;

  // Across campaigns, with filters.
  auto all = c.Get("/api/v1/windows?tag=api-test");
  ASSERT_TRUE(all);
  ASSERT_EQ(all->status, 200);
  EXPECT_EQ(schema_errors("api_windows", body_json(all)), "");
  EXPECT_EQ(body_json(all)["windows"].size(), 2u);
  auto none = c.Get("/api/v1/windows?material_pair=cu-thesis/cu-thesis");
  ASSERT_TRUE(none);
  EXPECT_EQ(body_json(none)["windows"].size(), 0u);  // two-mass scenes have no materials
}

// Materials over the API: library names and inline documents, in the base
// scene and in `fields` values, whatever the field's pointer.
TEST(api_campaigns, materials_by_library_name_or_inline_document) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  ServerHandle server(o);
  httplib::Client c = server.client();
  const json inline_cu = splat::material_document("cu-thesis");
  json spec = {{"name", "api-materials"},
               {"base_scene",
                {{"name", "impact"},
                 {"particle_impact",
                  {{"particle", {{"material", "al-thesis"}, {"radius", 1e-5}}},
                   {"substrate", {{"material", inline_cu}}},
                   {"velocity", 500}}}}},
               {"velocity", {{"pointer", "/particle_impact/velocity"}, {"values", {400, 500}}}},
               {"fields",
                {{{"pointer", "/particle_impact/particle"},
                  {"unit", "-"},
                  {"values",
                   {{{"material", "cu-thesis"}, {"radius", 1e-5}},
                    {{"material", inline_cu}, {"radius", 1e-5}}}}}}}};
  auto r = post_json(c, "/api/v1/campaigns", spec);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 202) << r->body;
  EXPECT_EQ(body_json(r)["jobs"]["total"], 4) << r->body;
}

TEST(api_campaigns, pages_of_campaigns_and_jobs) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;  // only the listing matters here
  ServerHandle server(o);
  httplib::Client c = server.client();
  std::vector<std::int64_t> ids;
  for (int i = 0; i < 5; ++i) {
    auto r = post_json(c, "/api/v1/campaigns", small_campaign("page-" + std::to_string(i)));
    ASSERT_EQ(r->status, 202) << r->body;
    ids.push_back(body_json(r)["id"]);
  }
  // Campaigns, two per page, newest first, every one exactly once.
  std::vector<std::int64_t> seen;
  std::string token;
  int pages = 0;
  for (;;) {
    std::string url = "/api/v1/campaigns?page_size=2";
    if (!token.empty()) url += "&page_token=" + token;
    auto r = c.Get(url.c_str());
    ASSERT_EQ(r->status, 200) << r->body;
    const json page = body_json(r);
    EXPECT_EQ(schema_errors("api_campaign_list", page), "");
    EXPECT_LE(page["campaigns"].size(), 2u);
    for (const json& cd : page["campaigns"]) seen.push_back(cd["id"]);
    ++pages;
    if (page["next_page_token"].is_null()) break;
    token = page["next_page_token"];
    ASSERT_LT(pages, 10);
  }
  EXPECT_EQ(pages, 3);
  EXPECT_EQ(seen, std::vector<std::int64_t>(ids.rbegin(), ids.rend()));

  // Jobs of one campaign, three per page, in (parameter set, velocity) order.
  std::vector<double> velocities;
  token.clear();
  pages = 0;
  for (;;) {
    std::string url = "/api/v1/campaigns/" + std::to_string(ids[0]) + "/jobs?page_size=3";
    if (!token.empty()) url += "&page_token=" + token;
    auto r = c.Get(url.c_str());
    ASSERT_EQ(r->status, 200) << r->body;
    const json page = body_json(r);
    EXPECT_EQ(schema_errors("api_job_list", page), "");
    for (const json& j : page["jobs"]) velocities.push_back(j["velocity"]);
    ++pages;
    if (page["next_page_token"].is_null()) break;
    token = page["next_page_token"];
    ASSERT_LT(pages, 10);
  }
  EXPECT_EQ(pages, 4);
  ASSERT_EQ(velocities.size(), 10u);
  EXPECT_TRUE(std::is_sorted(velocities.begin(), velocities.begin() + 5));
  EXPECT_TRUE(std::is_sorted(velocities.begin() + 5, velocities.end()));

  // Filter by state: nothing ran, so all are queued.
  auto q = c.Get(
      ("/api/v1/campaigns/" + std::to_string(ids[0]) + "/jobs?state=queued&page_size=500").c_str());
  EXPECT_EQ(body_json(q)["jobs"].size(), 10u);
  auto s = c.Get(("/api/v1/campaigns/" + std::to_string(ids[0]) + "/jobs?state=succeeded").c_str());
  EXPECT_EQ(body_json(s)["jobs"].size(), 0u);
}

// Each job row names the model its scene expanded into and the particle's
// resolution (set at submission, so queued jobs have them too): FE at
// elements_across 4 and 6, SPH at spacing R / 4 and R / 6, two-mass none.
TEST(api_campaigns, job_list_names_each_jobs_model_and_resolution) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  ServerHandle server(o);
  httplib::Client c = server.client();
  const double R = 1e-5;  // m
  json spec = {{"name", "api-models"},
               {"base_scene",
                {{"name", "impact"},
                 {"particle_impact",
                  {{"particle", {{"material", "al-thesis"}, {"radius", R}}}, {"velocity", 300}}}}},
               {"velocity", {{"pointer", "/particle_impact/velocity"}, {"values", {300}}}},
               {"fields",
                {{{"pointer", "/particle_impact/particle/discretization"},
                  {"unit", "-"},
                  {"values", {"fe", "sph"}}},
                 {{"pointer", "/particle_impact/particle/elements_across"},
                  {"unit", "-"},
                  {"values", {4, 6}}}}}};
  auto r = post_json(c, "/api/v1/campaigns", spec);
  ASSERT_EQ(r->status, 202) << r->body;
  const std::int64_t id = body_json(r)["id"];
  const json jobs = body_json(c.Get(("/api/v1/campaigns/" + std::to_string(id) + "/jobs").c_str()));
  EXPECT_EQ(schema_errors("api_job_list", jobs), "");
  ASSERT_EQ(jobs["jobs"].size(), 4u) << jobs.dump();
  for (const json& j : jobs["jobs"]) {
    const std::string d = j["params"]["/particle_impact/particle/discretization"];
    const int n = j["params"]["/particle_impact/particle/elements_across"];
    if (d == "fe") {
      EXPECT_EQ(j["model"], "fe-axisym") << j.dump();
      EXPECT_EQ(j["resolution"], json({{"elements_across", n}})) << j.dump();
    } else {
      EXPECT_EQ(j["model"], "sph-3d-quarter") << j.dump();
      ASSERT_TRUE(j["resolution"].contains("spacing")) << j.dump();
      EXPECT_NEAR(j["resolution"]["spacing"].get<double>(), R / n, 1e-12 * R) << j.dump();
    }
  }

  auto t = post_json(c, "/api/v1/campaigns", small_campaign("api-models-two-mass"));
  ASSERT_EQ(t->status, 202) << t->body;
  const json two_mass = body_json(c.Get(
      ("/api/v1/campaigns/" + std::to_string(body_json(t)["id"].get<std::int64_t>()) + "/jobs")
          .c_str()));
  EXPECT_EQ(schema_errors("api_job_list", two_mass), "");
  ASSERT_FALSE(two_mass["jobs"].empty());
  for (const json& j : two_mass["jobs"]) {
    EXPECT_EQ(j["model"], "two-mass");
    EXPECT_TRUE(j["resolution"].is_null());
  }
}

TEST(api_campaigns, idempotent_retry_returns_the_first_result) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  ServerHandle server(o);
  httplib::Client c = server.client();
  const httplib::Headers key = {{"Idempotency-Key", "retry-7f3c"}};
  auto first = post_json(c, "/api/v1/campaigns", small_campaign("idem"), key);
  ASSERT_EQ(first->status, 202) << first->body;
  const std::string before = store_fingerprint(o.db);
  auto again = post_json(c, "/api/v1/campaigns", small_campaign("idem"), key);
  ASSERT_EQ(again->status, 202) << again->body;
  EXPECT_EQ(again->get_header_value("Idempotent-Replayed"), "true");
  EXPECT_EQ(body_json(again)["id"], body_json(first)["id"]);
  EXPECT_EQ(store_fingerprint(o.db), before);
  auto list = c.Get("/api/v1/campaigns");
  EXPECT_EQ(body_json(list)["campaigns"].size(), 1u);
  // The same key with another body is an error, and changes nothing.
  auto other = post_json(c, "/api/v1/campaigns", small_campaign("idem-other"), key);
  expect_problem(other, 422);
  EXPECT_EQ(store_fingerprint(o.db), before);
}

// Keys live in the store: a retry after a server restart is still a replay,
// and the key still refuses another body.
TEST(api_campaigns, idempotency_keys_survive_a_restart) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  const httplib::Headers key = {{"Idempotency-Key", "restart-91ab"}};
  json first;
  {
    ServerHandle server(o);
    httplib::Client c = server.client();
    auto r = post_json(c, "/api/v1/campaigns", small_campaign("before-restart"), key);
    ASSERT_EQ(r->status, 202) << r->body;
    first = body_json(r);
  }
  const std::string before = store_fingerprint(o.db);
  ServerHandle server(o);
  httplib::Client c = server.client();
  auto again = post_json(c, "/api/v1/campaigns", small_campaign("before-restart"), key);
  ASSERT_EQ(again->status, 202) << again->body;
  EXPECT_EQ(again->get_header_value("Idempotent-Replayed"), "true");
  EXPECT_EQ(body_json(again)["id"], first["id"]);
  expect_problem(post_json(c, "/api/v1/campaigns", small_campaign("after-restart"), key), 422);
  EXPECT_EQ(store_fingerprint(o.db), before);
}

TEST(api_campaigns, etag_gives_304_until_something_changes) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  ServerHandle server(o);
  httplib::Client c = server.client();
  auto r = post_json(c, "/api/v1/campaigns", small_campaign());
  const std::string url = "/api/v1/campaigns/" + std::to_string(body_json(r)["id"].get<int>());
  for (const std::string& path :
       {url, url + "/jobs", url + "/windows", std::string("/api/v1/campaigns")}) {
    auto a = c.Get(path.c_str());
    ASSERT_EQ(a->status, 200) << path;
    const std::string etag = a->get_header_value("ETag");
    ASSERT_FALSE(etag.empty()) << path;
    auto b = c.Get(path.c_str(), {{"If-None-Match", etag}});
    EXPECT_EQ(b->status, 304) << path;
    EXPECT_TRUE(b->body.empty());
    auto d = c.Get(path.c_str(), {{"If-None-Match", "\"something-else\""}});
    EXPECT_EQ(d->status, 200) << path;
  }
  // A change (cancel) gives a new tag.
  auto a = c.Get(url.c_str());
  const std::string etag = a->get_header_value("ETag");
  ASSERT_EQ(c.Post((url + "/cancel").c_str())->status, 202);
  auto b = c.Get(url.c_str(), {{"If-None-Match", etag}});
  EXPECT_EQ(b->status, 200);
  EXPECT_EQ(body_json(b)["state"], "cancelled");
}

TEST(api_campaigns, cancel_stops_a_running_campaign_and_a_resubmit_resumes_it) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.workers = 1;
  ServerHandle server(o);
  httplib::Client c = server.client();
  json spec = small_campaign("to-cancel");
  spec["velocity"] = {{"range", {{"from", 0.05}, {"to", 2.0}, {"step", 0.05}}}};  // 40 x 2 jobs
  auto r = post_json(c, "/api/v1/campaigns", spec);
  ASSERT_EQ(r->status, 202) << r->body;
  const std::int64_t id = body_json(r)["id"];
  const std::string url = "/api/v1/campaigns/" + std::to_string(id);
  // Let some jobs finish, then cancel.
  for (int i = 0; i < 200; ++i) {
    if (body_json(c.Get(url.c_str()))["jobs"]["succeeded"] >= 2) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  auto cancel = c.Post((url + "/cancel").c_str());
  ASSERT_EQ(cancel->status, 202) << cancel->body;
  const json ended = wait_for_campaign(c, id);
  EXPECT_EQ(ended["state"], "cancelled") << ended.dump();
  EXPECT_GT(ended["jobs"]["cancelled"].get<int>(), 0);
  EXPECT_EQ(ended["jobs"]["queued"], 0);
  EXPECT_EQ(ended["jobs"]["running"], 0);
  // Submitting the same spec again resumes it: cancelled jobs run, finished ones are kept.
  const int succeeded_before = ended["jobs"]["succeeded"];
  auto again = post_json(c, "/api/v1/campaigns", spec);
  ASSERT_EQ(again->status, 202);
  EXPECT_EQ(body_json(again)["id"], id);
  const json done = wait_for_campaign(c, id, 120);
  EXPECT_EQ(done["state"], "finished") << done.dump();
  EXPECT_EQ(done["jobs"]["succeeded"], 80);
  EXPECT_GE(done["jobs"]["succeeded"].get<int>(), succeeded_before);
  // Cancelling a finished campaign is a conflict.
  expect_problem(c.Post((url + "/cancel").c_str()), 409);
}

}  // namespace
}  // namespace splat::api_test
