// The bad-input suite: every request below gets the right status and an RFC
// 9457 problem document (naming the field where there is one), and the store
// is byte-for-byte the same afterwards (same rows in every table).
#include "tests/api/api_fixture.hpp"

namespace splat::api_test {
namespace {

// What a problem document must name: a JSON pointer into the body, a query
// or path parameter, a request header, or (unknown routes, methods) the
// request path itself as `instance`.
struct Field {
  enum class Kind { pointer, parameter, header, route } kind;
  std::string name;
};
Field at(std::string pointer) {
  return {Field::Kind::pointer, std::move(pointer)};
}
Field param(std::string name) {
  return {Field::Kind::parameter, std::move(name)};
}
Field header(std::string name) {
  return {Field::Kind::header, std::move(name)};
}
Field route(std::string path) {
  return {Field::Kind::route, std::move(path)};
}

// Named like the other API suites (ctest -R api), not CamelCase.
class api_bad_input : public ::testing::Test {
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
  static void TearDownTestSuite() { std::printf("bad-input cases checked: %d\n", cases_); }

  // One bad request: `status`, a problem document (schema api_problem) that
  // names `field`, and the store unchanged right after it.
  void refused(const httplib::Result& r, int status, const Field& field) {
    ++cases_;
    expect_problem(r, status);
    if (!r) return;
    const json p = json::parse(r->body, nullptr, false);
    ASSERT_TRUE(p.is_object()) << r->body;
    if (field.kind == Field::Kind::route) {
      EXPECT_EQ(p.value("instance", ""), field.name) << r->body;
    } else {
      const char* key = field.kind == Field::Kind::pointer     ? "pointer"
                        : field.kind == Field::Kind::parameter ? "parameter"
                                                               : "header";
      bool named = false;
      for (const json& e : p.value("errors", json::array())) {
        named = named || (e.contains(key) && e[key] == field.name);
      }
      EXPECT_TRUE(named) << "no error names " << key << " '" << field.name << "': " << r->body;
    }
    EXPECT_EQ(store_fingerprint(options_.db), before_) << r->body;
  }

  httplib::Result post_text(const std::string& body, const std::string& type = "application/json",
                            const httplib::Headers& headers = {}) {
    httplib::Client c = server_->client();
    return c.Post("/api/v1/campaigns", headers, body, type.c_str());
  }
  httplib::Result post(const json& body) { return post_text(body.dump()); }
  httplib::Result get(const std::string& path) {
    httplib::Client c = server_->client();
    return c.Get(path.c_str());
  }

  TempDir dir_;
  api::ServerOptions options_;
  std::unique_ptr<ServerHandle> server_;
  std::string before_;
  static inline int cases_ = 0;
};

json with(json doc, const std::string& pointer, const json& value) {
  doc[json::json_pointer(pointer)] = value;
  return doc;
}

// An impact campaign over two velocities, materials by library name.
json impact_campaign() {
  json c = small_campaign();
  c["base_scene"] = {
      {"name", "impact"},
      {"particle_impact",
       {{"particle", {{"material", "al-thesis"}, {"radius", 1e-5}}}, {"velocity", 500}}}};
  c["velocity"] = {{"pointer", "/particle_impact/velocity"}, {"values", {400, 500}}};
  c.erase("G_c");
  return c;
}

TEST_F(api_bad_input, malformed_json) {
  refused(post_text("{\"name\": \"x\", "), 400, at(""));
  refused(post_text("{\"name\": NaN}"), 400, at(""));
  refused(post_text(""), 400, at(""));
  refused(post_text(small_campaign().dump() + " x"), 400, at(""));  // trailing garbage
  refused(post_text("{'name': 'x'}"), 400, at(""));
  refused(post_text(R"({"name": "x" /* comment */})"), 400, at(""));
  refused(post_text(R"({"name": "x",})"), 400, at(""));
  refused(post_text(R"({"name": "\ud800"})"), 400, at(""));  // lone surrogate escape
  refused(post_text(std::string("{\"name\": \"a\0b\"}", 15)), 400, at(""));  // raw NUL
  // The same field twice is ambiguous, at any depth.
  refused(post_text(R"({"name": "a", "name": "b"})"), 400, at("/name"));
  std::string twice = small_campaign().dump();
  twice.replace(twice.find("\"retries\":0"), 11, "\"retries\":0,\"retries\":1");
  refused(post_text(twice), 400, at("/job/retries"));
}

TEST_F(api_bad_input, wrong_content_type) {
  const std::string body = small_campaign().dump();
  for (const char* type : {"text/plain", "application/json-patch+json", "application/jsonx",
                           "application/x-www-form-urlencoded", "multipart/form-data", "text/json",
                           "application/xml"}) {
    refused(post_text(body, type), 415, header("Content-Type"));
  }
  // No Content-Type at all.
  refused(post_text(body, ""), 415, header("Content-Type"));
}

TEST_F(api_bad_input, wrong_types) {
  refused(post(json::array()), 422, at(""));
  refused(post(json(42)), 422, at(""));
  refused(post(with(small_campaign(), "/name", 12)), 422, at("/name"));
  refused(post(with(small_campaign(), "/name", nullptr)), 422, at("/name"));
  refused(post(with(small_campaign(), "/description", 5)), 422, at("/description"));
  refused(post(with(small_campaign(), "/tags", "api-test")), 422, at("/tags"));
  refused(post(with(small_campaign(), "/tags/0", 7)), 422, at("/tags/0"));
  refused(post(with(small_campaign(), "/velocity/values", "fast")), 422, at("/velocity/values"));
  refused(post(with(small_campaign(), "/velocity/values/0", json::array({1}))), 422,
          at("/velocity/values/0"));
  refused(post(with(small_campaign(), "/G_c/values/0", "0.1")), 422, at("/G_c/values/0"));
  refused(post(with(small_campaign(), "/job/retries", 1.5)), 422, at("/job/retries"));
  refused(post(with(small_campaign(), "/priority", "high")), 422, at("/priority"));
  refused(post(with(small_campaign(), "/executor", "cloud")), 422, at("/executor"));
  refused(post(with(small_campaign(), "/refinement", "yes")), 422, at("/refinement"));
  refused(post(with(small_campaign(), "/fields", json::object())), 422, at("/fields"));
  refused(post(with(small_campaign(), "/base_scene", 42)), 422, at("/base_scene"));
  refused(post(with(small_campaign(), "/base_scene/two_mass/M", "heavy")), 422,
          at("/base_scene/two_mass/M"));
  refused(post(with(small_campaign(), "/base_scene/two_mass/adhesion/sigma_c", "x")), 422,
          at("/base_scene/two_mass/adhesion/sigma_c"));
}

TEST_F(api_bad_input, negative_and_non_finite_values) {
  refused(post(with(small_campaign(), "/velocity/values/1", -0.4)), 422, at("/velocity/values/1"));
  refused(post(with(small_campaign(), "/G_c/values/0", -0.1)), 422, at("/G_c/values/0"));
  refused(post(with(small_campaign(), "/job/time_limit", 0)), 422, at("/job/time_limit"));
  refused(post(with(small_campaign(), "/job/retries", -1)), 422, at("/job/retries"));
  refused(post(with(small_campaign(), "/base_scene/two_mass/m", -2.0)), 422,
          at("/base_scene/two_mass/m"));
  refused(post(with(small_campaign(), "/base_scene/time/end_time", -1.0)), 422,
          at("/base_scene/time/end_time"));
  // JSON has no NaN or infinity: as text it is malformed, as a string a wrong type.
  refused(post_text(R"({"name":"x","base_scene":{},"velocity":{"values":[Infinity]}})"), 400,
          at(""));
  refused(post(with(small_campaign(), "/velocity/values/0", "NaN")), 422, at("/velocity/values/0"));
}

// Numbers beyond double range are refused where they stand, not with the
// JSON library's "[json.exception.out_of_range.406]".
TEST_F(api_bad_input, numbers_beyond_double_range_name_their_field) {
  const auto replaced = [](const std::string& pointer, const std::string& number) {
    std::string text = with(small_campaign(), pointer, 12345.678).dump();
    text.replace(text.find("12345.678"), 9, number);
    return text;
  };
  for (const char* number : {"1e400", "-1e400"}) {
    const auto r = post_text(replaced("/velocity/values/0", number));
    refused(r, 400, at("/velocity/values/0"));
    EXPECT_EQ(r->body.find("json.exception"), std::string::npos) << r->body;
    EXPECT_NE(r->body.find("beyond"), std::string::npos) << r->body;
  }
  refused(post_text(replaced("/base_scene/two_mass/M", "1e400")), 400,
          at("/base_scene/two_mass/M"));
  // Finite, but its kinetic energy is not: the velocity that gives it is named.
  const auto r = post(with(small_campaign(), "/velocity/values/4", 1e300));
  refused(r, 422, at("/velocity/values/4"));
  EXPECT_NE(r->body.find("finite"), std::string::npos) << r->body;
}

TEST_F(api_bad_input, values_out_of_bounds) {
  refused(post(with(small_campaign(), "/priority", 1001)), 422, at("/priority"));
  refused(post(with(small_campaign(), "/velocity/scale", 1e7)), 422, at("/velocity/scale"));
  refused(post(with(small_campaign(), "/refinement", {{"tolerance", 0}})), 422,
          at("/refinement/tolerance"));
  refused(post(with(small_campaign(), "/refinement", {{"tolerance", 0.1}, {"max_extra_jobs", -5}})),
          422, at("/refinement/max_extra_jobs"));
  refused(
      post(with(small_campaign(), "/refinement", {{"tolerance", 0.1}, {"coarse_to_fine", true}})),
      422, at("/refinement/coarse_to_fine"));
  json steps = small_campaign();
  steps["velocity"] = {{"range", {{"from", 1.0}, {"to", 2.0}, {"step", 0}}}};
  refused(post(steps), 422, at("/velocity/range/step"));
  steps["velocity"] = {{"range", {{"from", 2.0}, {"to", 1.0}, {"step", 0.5}}}};
  refused(post(steps), 422, at("/velocity/range"));
  // A step too small to move from `from`: a range without end.
  steps["velocity"] = {{"range", {{"from", 1000.0}, {"to", 1001.0}, {"step", 1e-20}}}};
  refused(post(steps), 422, at("/velocity/range"));
  json drop = small_campaign();
  drop.erase("G_c");
  drop["yield_drop_percent"] = {{"values", {100}}};
  refused(post(drop), 422, at("/yield_drop_percent/values/0"));
  drop.erase("yield_drop_percent");
  drop["D_adh_max"] = {{"values", {1.5}}};
  refused(post(drop), 422, at("/D_adh_max/values/0"));
}

TEST_F(api_bad_input, missing_and_unknown_fields) {
  json c = small_campaign();
  c.erase("velocity");
  refused(post(c), 422, at("/velocity"));
  refused(post(with(small_campaign(), "/colour", "red")), 422, at("/colour"));
  refused(post(with(small_campaign(), "/name", "")), 422, at("/name"));
  json both = small_campaign();
  both["velocity"]["range"] = {{"from", 0.2}, {"to", 1.0}, {"step", 0.2}};
  refused(post(both), 422, at("/velocity"));
}

TEST_F(api_bad_input, axis_pointers) {
  refused(post(with(small_campaign(), "/velocity/pointer", "/nothing/here")), 422,
          at("/velocity/pointer"));
  refused(post(with(small_campaign(), "/G_c/pointer", "/two_mass/V0")), 422, at("/G_c/pointer"));
  json f = small_campaign();
  f["fields"] = {{{"pointer", "no-slash"}, {"unit", "-"}, {"values", {1}}}};
  refused(post(f), 422, at("/fields/0/pointer"));
  f["fields"] = {{{"pointer", "/two_mass/k"}, {"unit", "-"}, {"values", json::array()}}};
  refused(post(f), 422, at("/fields/0/values"));
}

TEST_F(api_bad_input, unknown_material_and_material_paths) {
  json c = impact_campaign();
  const std::string material = "/base_scene/particle_impact/particle/material";
  c["base_scene"]["particle_impact"]["particle"]["material"] = "unobtainium";
  refused(post(c), 422, at(material));
  c["base_scene"]["particle_impact"]["particle"]["material"] = "\xc3\xa1l-thesis";  // "ál-thesis"
  refused(post(c), 422, at(material));
  // A path would make the server read its own files.
  c["base_scene"]["particle_impact"]["particle"]["material"] = "../../etc/passwd";
  refused(post(c), 422, at(material));
  // Even a readable, valid material file on the server may not be named.
  c["base_scene"]["particle_impact"]["particle"]["material"] =
      std::string(SPLAT_SOURCE_DIR) + "/materials/cu-thesis.json";
  refused(post(c), 422, at(material));
  c["base_scene"]["particle_impact"]["particle"]["material"] = {{"base", "/etc/shadow"},
                                                                {"density", 2700}};
  refused(post(c), 422, at(material + "/base"));
  c = impact_campaign();
  c["base_scene"]["particle_impact"]["substrate"] = {{"material", "/etc/passwd"}};
  refused(post(c), 422, at("/base_scene/particle_impact/substrate/material"));
  c["base_scene"] = "scenes/verification/two_mass.json";
  refused(post(c), 422, at("/base_scene"));
}

TEST_F(api_bad_input, oversized_grid_and_body) {
  json big = small_campaign();
  big["velocity"] = {{"range", {{"from", 0.0}, {"to", 1e6}, {"step", 1e-3}}}};
  refused(post(big), 422, at("/velocity/range"));
  json wide = small_campaign();
  wide["G_c"]["values"] = json::array();
  for (int i = 0; i < 30; ++i) wide["G_c"]["values"].push_back(0.1 + 0.01 * i);  // 150 jobs > 100
  refused(post(wide), 422, at("/G_c/values"));
  json fast = small_campaign();
  fast["velocity"]["values"] = json::array();
  for (int i = 0; i < 51; ++i) fast["velocity"]["values"].push_back(0.1 * (i + 1));  // 102 jobs
  refused(post(fast), 422, at("/velocity/values"));
  json budget = small_campaign();
  budget["refinement"] = {{"tolerance", 0.001}, {"max_extra_jobs", 1000}};
  refused(post(budget), 422, at("/refinement/max_extra_jobs"));
  json fat = small_campaign();
  fat["description"] = std::string(100 * 1024, 'x');
  refused(post(fat), 413, at(""));
  // One byte over the limit.
  json edge = small_campaign();
  edge["description"] = "";
  const std::size_t room = options_.max_body_bytes - edge.dump().size();
  edge["description"] = std::string(room + 1, 'y');
  refused(post(edge), 413, at(""));
  refused(post_text(small_campaign().dump(), "application/json",
                    {{"Idempotency-Key", std::string(256, 'k')}}),
          400, header("Idempotency-Key"));
}

// Nested arrays as deep as the body allows: refused while parsing, before
// anything (dump, hash, validation) walks the document.
std::string nested_base_scene(int depth, const std::string& open = "[",
                              const std::string& close = "]") {
  std::string s = R"({"name": "deep", "base_scene": )";
  for (int i = 0; i < depth; ++i) s += open;
  for (int i = 0; i < depth; ++i) s += close;
  return s + R"(, "velocity": {"values": [1]}})";
}

// The pointer of the container refused at the 64-level limit under `base`:
// the top-level object is the first level.
std::string deepest_allowed(const std::string& base, const std::string& token) {
  std::string p = base;
  for (int i = 0; i < 63 - (std::count(base.begin(), base.end(), '/') - 1); ++i) p += token;
  return p;
}

TEST_F(api_bad_input, nesting_deeper_than_64_levels) {
  const std::string arrays = deepest_allowed("/base_scene", "/0");
  auto r = post_text(nested_base_scene(65));
  refused(r, 400, at(arrays));
  EXPECT_NE(r->body.find("deeper than 64"), std::string::npos) << r->body;
  // 64 levels in all parse; the schema then refuses the array.
  refused(post_text(nested_base_scene(63)), 422, at("/base_scene"));
  refused(post_text(nested_base_scene(30000)), 400, at(arrays));
  // Objects, and deep values inside fields and tags.
  refused(post_text(nested_base_scene(65, R"({"a":)", "}")), 400,
          at(deepest_allowed("/base_scene", "/a")));
  json f = small_campaign();
  f["fields"] = {{{"pointer", "/two_mass/k"}, {"unit", "N/m"}, {"values", {12345}}}};
  std::string text = f.dump();
  text.replace(text.find("12345"), 5, std::string(70, '[') + std::string(70, ']'));
  refused(post_text(text), 400, at(deepest_allowed("/fields/0/values/0", "/0")));
  text = small_campaign().dump();
  text.replace(text.find("\"api-test\""), 10, std::string(70, '[') + std::string(70, ']'));
  refused(post_text(text), 400, at(deepest_allowed("/tags/0", "/0")));
}

TEST_F(api_bad_input, materials_inside_field_values_name_no_file) {
  json c = impact_campaign();
  const std::string file = std::string(SPLAT_SOURCE_DIR) + "/materials/cu-thesis.json";
  for (const std::string& path : {std::string("/etc/passwd"), file}) {
    c["fields"] = {{{"pointer", "/particle_impact/particle"},
                    {"unit", "-"},
                    {"values", {{{"material", path}, {"radius", 1e-5}}}}}};
    refused(post(c), 422, at("/fields/0/values/0/material"));
    c["fields"][0]["values"][0]["material"] = {{"base", path}, {"density", 2700}};
    refused(post(c), 422, at("/fields/0/values/0/material/base"));
    c["fields"] = {
        {{"pointer", "/particle_impact"},
         {"unit", "-"},
         {"values", {{{"particle", {{"material", path}, {"radius", 1e-5}}}, {"velocity", 500}}}}}};
    refused(post(c), 422, at("/fields/0/values/0/particle/material"));
  }
  // At the material itself, relative, as a URL, a device of the server.
  for (const char* path : {"./materials/al-thesis.json", "materials/al-thesis.json",
                           "file:///etc/passwd", "/proc/self/environ", "~/.ssh/id_rsa"}) {
    c["fields"] = {{{"pointer", "/particle_impact/particle/material"},
                    {"unit", "-"},
                    {"values", {"al-thesis", path}}}};
    refused(post(c), 422, at("/fields/0/values/1"));
  }
  c["fields"] = {{{"pointer", "/particle_impact/particle/material/base"},
                  {"unit", "-"},
                  {"values", {"../../etc/passwd"}}}};
  c["base_scene"]["particle_impact"]["particle"]["material"] = {{"base", "al-thesis"}};
  refused(post(c), 422, at("/fields/0/values/0"));
}

TEST_F(api_bad_input, job_threads) {
  refused(post(with(small_campaign(), "/job/threads", 100000)), 422, at("/job/threads"));
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  refused(post(with(small_campaign(), "/job/threads", cores + 1)), 422, at("/job/threads"));
  refused(post(with(small_campaign(), "/job/threads", 0)), 422, at("/job/threads"));
  refused(post(with(small_campaign(), "/job/threads", -1)), 422, at("/job/threads"));
  refused(post(with(small_campaign(), "/job/threads", 1e10)), 422, at("/job/threads"));
  refused(post(with(small_campaign(), "/job/threads", "2")), 422, at("/job/threads"));
  refused(post(with(small_campaign(), "/job/threads", 1.5)), 422, at("/job/threads"));
}

TEST_F(api_bad_input, invalid_utf8) {
  refused(post_text("{\"name\": \"caf\xc3\x28\"}"), 400, at(""));
  refused(post_text("{\"name\": \"x\xff\"}"), 400, at(""));
  refused(post_text("\xef\xbb\xbf\xff{}"), 400, at(""));
  refused(post_text("{\"name\": \"\xc0\xaf\"}"), 400, at(""));          // overlong '/'
  refused(post_text("{\"name\": \"\xed\xa0\x80\"}"), 400, at(""));      // a surrogate
  refused(post_text("{\"name\": \"\xf4\x90\x80\x80\"}"), 400, at(""));  // above U+10FFFF
  refused(post_text("{\"name\": \"\xe2\x82"), 400, at(""));             // cut short
  refused(get("/api/v1/campaigns/1/jobs?state=%FF"), 400, param("state"));
  refused(get("/api/v1/windows?name=%C3%28"), 400, param("name"));
  refused(get("/api/v1/windows?%FF=1"), 400, param("\xef\xbf\xbd"));  // echoed as U+FFFD
  auto r = get("/api/v1/nothing%FF");
  refused(r, 404, route("/api/v1/nothing\xef\xbf\xbd"));
}

TEST_F(api_bad_input, unicode_where_names_are_ascii) {
  refused(post(with(small_campaign(), "/name", "caf\xc3\xa9")), 422, at("/name"));
  refused(post(with(small_campaign(), "/name", "\xf0\x9f\x9a\x80")), 422, at("/name"));
  refused(post(with(small_campaign(), "/name", "a\xe2\x80\x8b")), 422, at("/name"));  // U+200B
  refused(get("/api/v1/windows?name=caf%C3%A9"), 400, param("name"));
  // A pointer with a zero-width space after V0 names a field the scene lacks.
  refused(post(with(small_campaign(), "/velocity/pointer", "/two_mass/V0\xe2\x80\x8b")), 422,
          at("/velocity/pointer"));
}

TEST_F(api_bad_input, unknown_routes_and_ids) {
  refused(get("/api/v1/nothing"), 404, route("/api/v1/nothing"));
  refused(get("/api/v2/campaigns"), 404, route("/api/v2/campaigns"));
  refused(get("/api/v1/campaigns/999"), 404, param("id"));
  refused(get("/api/v1/campaigns/abc"), 404, param("id"));
  refused(get("/api/v1/campaigns/0"), 404, param("id"));
  refused(get("/api/v1/campaigns/-1/jobs"), 404, param("id"));
  refused(get("/api/v1/campaigns/99999999999999999999999"), 404, param("id"));
  refused(get("/api/v1/campaigns/999/windows"), 404, param("id"));
  httplib::Client c = server_->client();
  refused(c.Post("/api/v1/campaigns/999/cancel"), 404, param("id"));
  refused(get("/api/v1/jobs/0123"), 404, param("id"));
  refused(get("/api/v1/jobs/" + std::string(64, 'a')), 404, param("id"));
  refused(get("/api/v1/jobs/" + std::string(64, 'a') + "/result.h5"), 404, param("id"));
  refused(get("/api/v1/schemas/nope"), 404, param("name"));
  refused(c.Delete("/api/v1/nothing"), 404, route("/api/v1/nothing"));
}

// A path that exists asked with a method it does not serve: 405 and Allow.
TEST_F(api_bad_input, wrong_methods_get_405_with_allow) {
  httplib::Client c = server_->client();
  const auto expect_405 = [&](const httplib::Result& r, const std::string& path,
                              const std::string& allow) {
    refused(r, 405, route(path));
    if (r) {
      EXPECT_EQ(r->get_header_value("Allow"), allow) << r->body;
    }
  };
  expect_405(c.Delete("/api/v1/campaigns/1"), "/api/v1/campaigns/1", "GET");
  expect_405(c.Post("/api/v1/health"), "/api/v1/health", "GET");
  expect_405(c.Get("/api/v1/campaigns/1/cancel"), "/api/v1/campaigns/1/cancel", "POST");
  expect_405(c.Put("/api/v1/campaigns"), "/api/v1/campaigns", "POST, GET");
  const std::string job = "/api/v1/jobs/" + std::string(64, 'a');
  expect_405(c.Patch(job.c_str()), job, "GET");
}

TEST_F(api_bad_input, bad_query_parameters) {
  refused(get("/api/v1/campaigns?page_size=0"), 400, param("page_size"));
  refused(get("/api/v1/campaigns?page_size=100000"), 400, param("page_size"));
  refused(get("/api/v1/campaigns?page_size=ten"), 400, param("page_size"));
  refused(get("/api/v1/campaigns?page_size=1.5"), 400, param("page_size"));
  refused(get("/api/v1/campaigns?page_size=1&page_size=2"), 400, param("page_size"));
  refused(get("/api/v1/campaigns/1/jobs?page_size=-1"), 400, param("page_size"));
  refused(get("/api/v1/campaigns/1/jobs?state=sleeping"), 400, param("state"));
  refused(get("/api/v1/campaigns/1/windows?format=xml"), 400, param("format"));
  // A misspelt filter or option is refused, not ignored.
  refused(get("/api/v1/campaigns?pagesize=10"), 400, param("pagesize"));
  refused(get("/api/v1/windows?nmae=api-small"), 400, param("nmae"));
  refused(get("/api/v1/campaigns/1/jobs?sate=queued"), 400, param("sate"));
  refused(get("/api/v1/health?verbose=1"), 400, param("verbose"));
  refused(get("/api/v1/windows?material_pair=a/a&material_pair=b/b"), 400, param("material_pair"));
}

TEST_F(api_bad_input, paging_tokens) {
  refused(get("/api/v1/campaigns?page_token=zzz"), 400, param("page_token"));
  refused(get("/api/v1/campaigns?page_token="), 400, param("page_token"));
  refused(get("/api/v1/campaigns?page_token=o5"), 400, param("page_token"));  // a jobs token
  refused(get("/api/v1/campaigns?page_token=b-1"), 400, param("page_token"));
  refused(get("/api/v1/campaigns?page_token=b99999999999999999999"), 400, param("page_token"));
  refused(get("/api/v1/campaigns/1/jobs?page_token=b1"), 400, param("page_token"));
}

TEST_F(api_bad_input, injection_strings_in_filters) {
  refused(get("/api/v1/windows?name=%27%20OR%20%271%27%3D%271"), 400, param("name"));
  refused(get("/api/v1/windows?name=x%3BDROP%20TABLE%20campaigns%3B--"), 400, param("name"));
  refused(get("/api/v1/windows?name=%00"), 400, param("name"));
  refused(get("/api/v1/windows?name=../../etc/passwd"), 400, param("name"));
  refused(get("/api/v1/campaigns/1/jobs?state=queued%27%20OR%201%3D1--"), 400, param("state"));
  refused(get("/api/v1/campaigns?page_token=b1%20OR%201%3D1"), 400, param("page_token"));
  refused(get("/api/v1/campaigns/1/windows?format=csv%0D%0ASet-Cookie%3A%20x%3D1"), 400,
          param("format"));
}

// Traversal through the static files and through path parameters: 404,
// never a file of the server's.
TEST_F(api_bad_input, path_traversal_attempts) {
  httplib::Client c = server_->client();
  for (const char* path :
       {"/../../../../etc/passwd", "/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
        "/vendor/chart.js/../../../../etc/passwd", "/api/v1/jobs/../../etc/passwd/result.h5",
        "/api/v1/schemas/..%2f..%2fetc%2fpasswd",
        "/api/v1/jobs/%2e%2e%2f%2e%2e%2fetc%2fpasswd/result.h5",
        "/api/v1/campaigns/..%2F..%2Fetc%2Fpasswd", "/api/v1/schemas/..%2Fcampaign",
        "/api/v1/campaigns/1%00/jobs", "/api/v1/jobs/%2Fetc%2Fpasswd/result.h5"}) {
    auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    expect_problem(r, r->status);
    EXPECT_TRUE(r->status == 400 || r->status == 404) << path << ": " << r->status;
    EXPECT_EQ(r->body.find("root:"), std::string::npos) << path;
    ++cases_;
  }
}

// 100,000 nested brackets (200 KB, under the default 1 MiB body limit) are
// refused with a 400 before anything recurses through them, and the server
// answers the next request.
TEST(api_bad_input_limits, a_hundred_thousand_nested_brackets_leave_the_server_alive) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  ServerHandle server(o);
  httplib::Client c = server.client();
  const std::string before = store_fingerprint(o.db);
  expect_problem(c.Post("/api/v1/campaigns", nested_base_scene(100000), "application/json"), 400,
                 deepest_allowed("/base_scene", "/0"));
  EXPECT_EQ(c.Get("/api/v1/health")->status, 200);
  EXPECT_EQ(store_fingerprint(o.db), before);
}

}  // namespace
}  // namespace splat::api_test
