// Bearer tokens: with a token every mutating request needs it (wrong or
// missing -> 401 problem, store unchanged); reads stay open; without a token
// the server refuses non-loopback addresses.
#include "tests/api/api_fixture.hpp"

namespace splat::api_test {
namespace {

TEST(api_auth, constant_time_equal_compares_whole_strings) {
  EXPECT_TRUE(api::constant_time_equal("s3cret-token-0123", "s3cret-token-0123"));
  EXPECT_FALSE(api::constant_time_equal("s3cret-token-0123", "s3cret-token-0124"));
  EXPECT_FALSE(api::constant_time_equal("s3cret-token-0123", "s3cret-token-012"));
  EXPECT_FALSE(api::constant_time_equal("s3cret-token-0123", ""));
  EXPECT_FALSE(api::constant_time_equal("", "x"));
}

TEST(api_auth, loopback_hosts) {
  EXPECT_TRUE(api::is_loopback_host("127.0.0.1"));
  EXPECT_TRUE(api::is_loopback_host("127.1.2.3"));
  EXPECT_TRUE(api::is_loopback_host("::1"));
  EXPECT_TRUE(api::is_loopback_host("localhost"));
  EXPECT_FALSE(api::is_loopback_host("0.0.0.0"));
  EXPECT_FALSE(api::is_loopback_host("10.1.2.3"));
  EXPECT_FALSE(api::is_loopback_host("::"));
  EXPECT_FALSE(api::is_loopback_host("127.example.org"));
  EXPECT_FALSE(api::is_loopback_host("127.0.0.1.example.org"));
  EXPECT_FALSE(api::is_loopback_host(""));
}

TEST(api_auth, refuses_a_public_address_without_a_token) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.host = "0.0.0.0";
  EXPECT_THROW(api::Server s(o), std::invalid_argument);
  o.token = "a-long-enough-token-123";
  EXPECT_NO_THROW(api::Server s(o));
}

TEST(api_auth, token_required_on_mutations_only) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  o.token = "tok-9b1d6f0e2a7c4d11";
  ServerHandle server(o);
  httplib::Client c = server.client();
  const std::string before = store_fingerprint(o.db);
  expect_problem(post_json(c, "/api/v1/campaigns", small_campaign()), 401);
  auto wrong = post_json(c, "/api/v1/campaigns", small_campaign(),
                         {{"Authorization", "Bearer tok-9b1d6f0e2a7c4d12"}});
  expect_problem(wrong, 401);
  EXPECT_EQ(wrong->get_header_value("WWW-Authenticate"), "Bearer realm=\"splat\"");
  expect_problem(post_json(c, "/api/v1/campaigns", small_campaign(),
                           {{"Authorization", "Basic dG9rLTliMWQ2ZjBlMmE3YzRkMTE="}}),
                 401);
  expect_problem(
      post_json(c, "/api/v1/campaigns", small_campaign(), {{"Authorization", "Bearer "}}), 401);
  EXPECT_EQ(store_fingerprint(o.db), before);
  // Reads need no token.
  EXPECT_EQ(c.Get("/api/v1/campaigns")->status, 200);
  EXPECT_EQ(c.Get("/api/v1/health")->status, 200);
  // The right token works, for submit and cancel.
  const httplib::Headers auth = {{"Authorization", "Bearer " + o.token}};
  auto ok = post_json(c, "/api/v1/campaigns", small_campaign(), auth);
  ASSERT_EQ(ok->status, 202) << ok->body;
  const std::string cancel =
      "/api/v1/campaigns/" + std::to_string(body_json(ok)["id"].get<int>()) + "/cancel";
  expect_problem(c.Post(cancel.c_str()), 401);
  EXPECT_EQ(c.Post(cancel.c_str(), auth, "", "application/json")->status, 202);
}

// RFC 9110: the scheme is case-insensitive.
TEST(api_auth, the_scheme_is_case_insensitive) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  o.token = "tok-9b1d6f0e2a7c4d11";
  ServerHandle server(o);
  httplib::Client c = server.client();
  for (const char* scheme : {"bearer", "BEARER", "BeArEr"}) {
    auto r = post_json(c, "/api/v1/campaigns", small_campaign(std::string("auth-") + scheme),
                       {{"Authorization", std::string(scheme) + " " + o.token}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 202) << scheme << ": " << r->body;
  }
  expect_problem(post_json(c, "/api/v1/campaigns", small_campaign(),
                           {{"Authorization", "Bearerx " + o.token}}),
                 401);
}

TEST(api_auth, tokens_need_sixteen_non_space_characters) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  for (const std::string& weak :
       {std::string(17, '\t'), std::string(40, ' '), std::string("  short-token  \t\t\t\t\t\t\t\t"),
        std::string("abc def ghi jkl mn")}) {
    o.token = weak;
    EXPECT_THROW(api::Server s(o), std::invalid_argument) << "'" << weak << "'";
  }
  o.token = "0123456789abcdef";
  EXPECT_NO_THROW(api::Server s(o));
}

TEST(api_auth, no_token_means_open_on_loopback) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  ServerHandle server(o);
  httplib::Client c = server.client();
  EXPECT_EQ(post_json(c, "/api/v1/campaigns", small_campaign())->status, 202);
}

}  // namespace
}  // namespace splat::api_test
