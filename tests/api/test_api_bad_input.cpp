// The bad-input suite: every request below gets the right status and an RFC
// 9457 problem document (naming the field where there is one), and the store
// is byte-for-byte the same afterwards (same rows in every table).
#include "tests/api/api_fixture.hpp"

namespace splat::api_test {
namespace {

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    options_ = options_for(dir_);
    options_.run_campaigns = false;
    options_.max_jobs_per_campaign = 100;
    options_.max_body_bytes = 64 * 1024;
    server_ = std::make_unique<ServerHandle>(options_);
    // One good campaign so "unchanged" has something to compare.
    httplib::Client c = server_->client();
    ASSERT_EQ(post_json(c, "/api/v1/campaigns", small_campaign())->status, 202);
    before_ = store_fingerprint(options_.db);
  }
  void TearDown() override { EXPECT_EQ(store_fingerprint(options_.db), before_); }

  httplib::Result post_text(const std::string& body, const std::string& type = "application/json") {
    httplib::Client c = server_->client();
    return c.Post("/api/v1/campaigns", body, type.c_str());
  }
  httplib::Result post(const json& body) { return post_text(body.dump()); }

  TempDir dir_;
  api::ServerOptions options_;
  std::unique_ptr<ServerHandle> server_;
  std::string before_;
};

json with(json doc, const std::string& pointer, const json& value) {
  doc[json::json_pointer(pointer)] = value;
  return doc;
}

TEST_F(BadInput, malformed_json) {
  expect_problem(post_text("{\"name\": \"x\", "), 400, "");
  expect_problem(post_text("{\"name\": NaN}"), 400, "");
  expect_problem(post_text(""), 400, "");
  // The same field twice is ambiguous.
  expect_problem(post_text(R"({"name": "a", "name": "b"})"), 400, "/name");
}

TEST_F(BadInput, wrong_content_type) {
  expect_problem(post_text(small_campaign().dump(), "text/plain"), 415);
}

TEST_F(BadInput, wrong_types) {
  expect_problem(post(json::array()), 422, "");
  expect_problem(post(with(small_campaign(), "/name", 12)), 422, "/name");
  expect_problem(post(with(small_campaign(), "/velocity/values", "fast")), 422, "/velocity/values");
  expect_problem(post(with(small_campaign(), "/G_c/values/0", "0.1")), 422, "/G_c/values/0");
  expect_problem(post(with(small_campaign(), "/job/retries", 1.5)), 422, "/job/retries");
  expect_problem(post(with(small_campaign(), "/base_scene/two_mass/M", "heavy")), 422,
                 "/base_scene/two_mass/M");
}

TEST_F(BadInput, negative_and_non_finite_values) {
  expect_problem(post(with(small_campaign(), "/velocity/values/1", -0.4)), 422,
                 "/velocity/values/1");
  expect_problem(post(with(small_campaign(), "/G_c/values/0", -0.1)), 422, "/G_c/values/0");
  expect_problem(post(with(small_campaign(), "/job/time_limit", 0)), 422, "/job/time_limit");
  expect_problem(post(with(small_campaign(), "/base_scene/two_mass/m", -2.0)), 422,
                 "/base_scene/two_mass/m");
  // JSON has no NaN or infinity: as text it is malformed, as a string a wrong type.
  expect_problem(post_text(R"({"name":"x","base_scene":{},"velocity":{"values":[Infinity]}})"),
                 400);
  expect_problem(post(with(small_campaign(), "/velocity/values/0", "NaN")), 422,
                 "/velocity/values/0");
  std::string huge = with(small_campaign(), "/velocity/values/0", 12345.678).dump();
  huge.replace(huge.find("12345.678"), 9, "1e400");  // beyond double
  expect_problem(post_text(huge), 400);
}

TEST_F(BadInput, missing_and_unknown_fields) {
  json c = small_campaign();
  c.erase("velocity");
  expect_problem(post(c), 422, "/velocity");
  expect_problem(post(with(small_campaign(), "/colour", "red")), 422, "/colour");
}

TEST_F(BadInput, unknown_material_and_material_paths) {
  json impact = {
      {"name", "impact"},
      {"particle_impact",
       {{"particle", {{"material", "unobtainium"}, {"radius", 1e-5}}}, {"velocity", 500}}}};
  json c = small_campaign();
  c["base_scene"] = impact;
  c["velocity"] = {{"pointer", "/particle_impact/velocity"}, {"values", {400, 500}}};
  c.erase("G_c");
  expect_problem(post(c), 422, "/base_scene/particle_impact/particle/material");
  // A path would make the server read its own files.
  c["base_scene"]["particle_impact"]["particle"]["material"] = "../../etc/passwd";
  expect_problem(post(c), 422, "/base_scene/particle_impact/particle/material");
  // Even a readable, valid material file on the server may not be named.
  c["base_scene"]["particle_impact"]["particle"]["material"] =
      std::string(SPLAT_SOURCE_DIR) + "/materials/cu-thesis.json";
  expect_problem(post(c), 422, "/base_scene/particle_impact/particle/material");
  c["base_scene"] = "scenes/verification/two_mass.json";
  expect_problem(post(c), 422, "/base_scene");
}

TEST_F(BadInput, oversized_grid_and_body) {
  json big = small_campaign();
  big["velocity"] = {{"range", {{"from", 0.0}, {"to", 1e6}, {"step", 1e-3}}}};
  expect_problem(post(big), 422, "/velocity/range");
  json wide = small_campaign();
  wide["G_c"]["values"] = json::array();
  for (int i = 0; i < 30; ++i) wide["G_c"]["values"].push_back(0.1 + 0.01 * i);  // 150 jobs > 100
  expect_problem(post(wide), 422, "");
  json budget = small_campaign();
  budget["refinement"] = {{"tolerance", 0.001}, {"max_extra_jobs", 1000}};
  expect_problem(post(budget), 422, "");
  json fat = small_campaign();
  fat["description"] = std::string(100 * 1024, 'x');
  expect_problem(post(fat), 413);
}

// Nested arrays as deep as the body allows: refused while parsing, before
// anything (dump, hash, validation) walks the document.
std::string nested_base_scene(int depth) {
  return R"({"name": "deep", "base_scene": )" + std::string(std::size_t(depth), '[') +
         std::string(std::size_t(depth), ']') + R"(, "velocity": {"values": [1]}})";
}

// The pointer of the first error of a problem document, "-" when none.
std::string first_pointer(const httplib::Result& r) {
  const json p = json::parse(r->body, nullptr, false);
  if (!p.is_object() || !p.contains("errors") || p["errors"].empty()) return "-";
  return p["errors"][0].value("pointer", "-");
}

TEST_F(BadInput, nesting_deeper_than_64_levels) {
  auto r = post_text(nested_base_scene(65));
  expect_problem(r, 400);
  EXPECT_EQ(first_pointer(r).rfind("/base_scene/0/0/", 0), 0u) << r->body;
  EXPECT_NE(r->body.find("deeper than 64"), std::string::npos) << r->body;
  // 64 levels in all parse; the schema then refuses the array.
  expect_problem(post_text(nested_base_scene(63)), 422, "/base_scene");
  expect_problem(post_text(nested_base_scene(30000)), 400);
}

TEST_F(BadInput, materials_inside_field_values_name_no_file) {
  json c = small_campaign();
  c["base_scene"] = {
      {"name", "impact"},
      {"particle_impact",
       {{"particle", {{"material", "al-thesis"}, {"radius", 1e-5}}}, {"velocity", 500}}}};
  c["velocity"] = {{"pointer", "/particle_impact/velocity"}, {"values", {400, 500}}};
  c.erase("G_c");
  const std::string file = std::string(SPLAT_SOURCE_DIR) + "/materials/cu-thesis.json";
  for (const std::string& path : {std::string("/etc/passwd"), file}) {
    c["fields"] = {{{"pointer", "/particle_impact/particle"},
                    {"unit", "-"},
                    {"values", {{{"material", path}, {"radius", 1e-5}}}}}};
    expect_problem(post(c), 422, "/fields/0/values/0/material");
    c["fields"][0]["values"][0]["material"] = {{"base", path}, {"density", 2700}};
    expect_problem(post(c), 422, "/fields/0/values/0/material/base");
    c["fields"] = {
        {{"pointer", "/particle_impact"},
         {"unit", "-"},
         {"values", {{{"particle", {{"material", path}, {"radius", 1e-5}}}, {"velocity", 500}}}}}};
    expect_problem(post(c), 422, "/fields/0/values/0/particle/material");
  }
}

TEST_F(BadInput, job_threads_beyond_the_machine) {
  expect_problem(post(with(small_campaign(), "/job/threads", 100000)), 422, "/job/threads");
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  expect_problem(post(with(small_campaign(), "/job/threads", cores + 1)), 422, "/job/threads");
}

TEST_F(BadInput, invalid_utf8) {
  expect_problem(post_text("{\"name\": \"caf\xc3\x28\"}"), 400, "");
  expect_problem(post_text("{\"name\": \"x\xff\"}"), 400, "");
  expect_problem(post_text("\xef\xbb\xbf\xff{}"), 400, "");
  httplib::Client c = server_->client();
  const auto expect_parameter = [](const httplib::Result& r, const std::string& name) {
    expect_problem(r, 400);
    const json p = json::parse(r->body, nullptr, false);
    ASSERT_TRUE(p.contains("errors")) << r->body;
    EXPECT_EQ(p["errors"][0].value("parameter", ""), name) << r->body;
  };
  expect_parameter(c.Get("/api/v1/campaigns/1/jobs?state=%FF"), "state");
  expect_parameter(c.Get("/api/v1/windows?name=%C3%28"), "name");
  expect_problem(c.Get("/api/v1/nothing%FF"), 404);
}

TEST_F(BadInput, unknown_routes_and_ids) {
  httplib::Client c = server_->client();
  expect_problem(c.Get("/api/v1/nothing"), 404);
  expect_problem(c.Get("/api/v2/campaigns"), 404);
  expect_problem(c.Get("/api/v1/campaigns/999"), 404);
  expect_problem(c.Get("/api/v1/campaigns/abc"), 404);
  expect_problem(c.Get("/api/v1/campaigns/99999999999999999999999"), 404);
  expect_problem(c.Post("/api/v1/campaigns/999/cancel"), 404);
  expect_problem(c.Get("/api/v1/jobs/0123"), 404);
  expect_problem(c.Get(("/api/v1/jobs/" + std::string(64, 'a')).c_str()), 404);
  expect_problem(c.Get("/api/v1/schemas/nope"), 404);
  expect_problem(c.Delete("/api/v1/nothing"), 404);
}

// A path that exists asked with a method it does not serve: 405 and Allow.
TEST_F(BadInput, wrong_methods_get_405_with_allow) {
  httplib::Client c = server_->client();
  const auto expect_405 = [](const httplib::Result& r, const std::string& allow) {
    expect_problem(r, 405);
    if (r) {
      EXPECT_EQ(r->get_header_value("Allow"), allow) << r->body;
    }
  };
  expect_405(c.Delete("/api/v1/campaigns/1"), "GET");
  expect_405(c.Post("/api/v1/health"), "GET");
  expect_405(c.Get("/api/v1/campaigns/1/cancel"), "POST");
  expect_405(c.Put("/api/v1/campaigns"), "POST, GET");
  expect_405(c.Patch(("/api/v1/jobs/" + std::string(64, 'a')).c_str()), "GET");
}

TEST_F(BadInput, bad_query_parameters) {
  httplib::Client c = server_->client();
  expect_problem(c.Get("/api/v1/campaigns?page_size=0"), 400);
  expect_problem(c.Get("/api/v1/campaigns?page_size=100000"), 400);
  expect_problem(c.Get("/api/v1/campaigns?page_size=ten"), 400);
  expect_problem(c.Get("/api/v1/campaigns?page_token=zzz"), 400);
  expect_problem(c.Get("/api/v1/campaigns/1/jobs?state=sleeping"), 400);
  expect_problem(c.Get("/api/v1/campaigns/1/windows?format=xml"), 400);
}

TEST_F(BadInput, path_traversal_attempts) {
  httplib::Client c = server_->client();
  for (const char* path :
       {"/../../../../etc/passwd", "/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
        "/vendor/chart.js/../../../../etc/passwd", "/api/v1/jobs/../../etc/passwd/result.h5",
        "/api/v1/schemas/..%2f..%2fetc%2fpasswd",
        "/api/v1/jobs/%2e%2e%2f%2e%2e%2fetc%2fpasswd/result.h5"}) {
    auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_GE(r->status, 400) << path;
    EXPECT_EQ(r->body.find("root:"), std::string::npos) << path;
  }
}

// 100,000 nested brackets (200 KB, under the default 1 MiB body limit) are
// refused with a 400 before anything recurses through them, and the server
// answers the next request.
TEST(api_bad_input, a_hundred_thousand_nested_brackets_leave_the_server_alive) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  ServerHandle server(o);
  httplib::Client c = server.client();
  const std::string before = store_fingerprint(o.db);
  expect_problem(c.Post("/api/v1/campaigns", nested_base_scene(100000), "application/json"), 400);
  EXPECT_EQ(c.Get("/api/v1/health")->status, 200);
  EXPECT_EQ(store_fingerprint(o.db), before);
}

}  // namespace
}  // namespace splat::api_test
