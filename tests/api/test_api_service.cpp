// `splat serve` as a process: prints its OS-chosen port, answers health,
// metrics, materials and schemas; SIGTERM stops it gracefully and leaves the
// running campaign resumable; the next server on the same store finishes it
// without redoing finished jobs. Also the command-line refusal of a public
// address without a token.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>

#include <atomic>
#include <cerrno>
#include <mutex>
#include <vector>

#include "support/serve_process.hpp"
#include "support/small_tmpfs.hpp"
#include "tests/api/api_fixture.hpp"

namespace splat::api_test {
namespace {

using splat::test_support::ServeProcess;

struct BurstCounts {
  int answered = 0;       // a status line below 500
  int resets = 0;         // connection refused or reset
  int resent = 0;         // connect took >= 0.9 s: a dropped SYN was sent again
  int server_errors = 0;  // 5xx
  int other = 0;          // timeouts, short answers
};

// One GET on a fresh connection; the connection ends the answer.
void one_get(int port, const std::string& path, BurstCounts& counts, std::mutex& m) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  timeval tv{10, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string answer;
  int err = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const bool connected = connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  const bool slow = std::chrono::steady_clock::now() - t0 >= std::chrono::milliseconds(900);
  if (!connected) {
    err = errno;
  } else {
    const std::string req = "GET " + path + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n";
    if (send(fd, req.data(), req.size(), MSG_NOSIGNAL) < 0) err = errno;
    char buf[4096];
    for (ssize_t n; err == 0 && (n = recv(fd, buf, sizeof buf, 0)) != 0;) {
      if (n < 0) err = errno;
      if (n > 0) answer.append(buf, std::size_t(n));
    }
  }
  close(fd);
  std::lock_guard lock(m);
  if (slow) ++counts.resent;
  if (err == ECONNRESET || err == ECONNREFUSED || err == EPIPE) {
    ++counts.resets;
  } else if (answer.rfind("HTTP/1.1 ", 0) != 0) {
    ++counts.other;
  } else if (answer.compare(9, 1, "5") == 0) {
    ++counts.server_errors;
  } else {
    ++counts.answered;
  }
}

// `n` connections opened at the same moment, one GET each.
BurstCounts burst(int port, int n, const std::string& path) {
  BurstCounts counts;
  std::mutex m;
  std::atomic<bool> go{false};
  std::vector<std::thread> threads;
  for (int i = 0; i < n; ++i) {
    threads.emplace_back([&] {
      while (!go.load()) std::this_thread::yield();
      one_get(port, path, counts, m);
    });
  }
  go = true;
  for (std::thread& t : threads) t.join();
  return counts;
}

TEST(api_service, a_burst_of_200_connections_is_answered) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  ServerHandle server(o);
  for (int round = 0; round < 3; ++round) {
    const BurstCounts c = burst(server.port(), 200, "/api/v1/health");
    EXPECT_EQ(c.resets, 0) << "round " << round;
    // A full listen queue drops the SYN; the client sends it again after 1 s.
    EXPECT_EQ(c.resent, 0) << "round " << round;
    EXPECT_EQ(c.server_errors, 0) << "round " << round;
    EXPECT_EQ(c.other, 0) << "round " << round;
    EXPECT_EQ(c.answered, 200) << "round " << round;
  }
}

TEST(api_service, health_metrics_materials_schemas) {
  TempDir dir;
  ServerHandle server(options_for(dir));
  httplib::Client c = server.client();
  auto h = c.Get("/api/v1/health");
  ASSERT_EQ(h->status, 200);
  EXPECT_EQ(schema_errors("api_health", body_json(h)), "");
  auto m = c.Get("/api/v1/materials");
  ASSERT_EQ(m->status, 200);
  EXPECT_EQ(schema_errors("api_materials", body_json(m)), "");
  EXPECT_GT(body_json(m)["materials"].size(), 0u);
  for (const std::string& name : schema_names()) {
    auto s = c.Get(("/api/v1/schemas/" + name).c_str());
    ASSERT_EQ(s->status, 200) << name;
    EXPECT_EQ(body_json(s), schema_document(name)) << name;
  }
  EXPECT_EQ(c.Get("/api/v1/schemas/campaign.schema.json")->status, 200);
  // Metrics after one small campaign: the job counts and durations add up.
  json spec = small_campaign("metrics");
  auto r = post_json(c, "/api/v1/campaigns", spec);
  ASSERT_EQ(r->status, 202);
  ASSERT_EQ(wait_for_campaign(c, body_json(r)["id"])["state"], "finished");
  auto t = c.Get("/api/v1/metrics");
  ASSERT_EQ(t->status, 200);
  EXPECT_EQ(t->get_header_value("Content-Type"), "text/plain; version=0.0.4; charset=utf-8");
  const std::string& text = t->body;
  EXPECT_NE(text.find("splat_jobs{state=\"succeeded\"} 10\n"), std::string::npos) << text;
  EXPECT_NE(text.find("splat_jobs{state=\"queued\"} 0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("splat_queue_length 0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("splat_job_duration_seconds_bucket{le=\"+Inf\"} 10\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("splat_job_duration_seconds_count 10\n"), std::string::npos) << text;
  EXPECT_NE(text.find("# TYPE splat_job_duration_seconds histogram"), std::string::npos);
}

// Submits `spec` and waits, up to `tries` x 10 ms, until `succeeded` of its
// jobs have; returns the campaign id (0 when the submission was refused).
std::int64_t submit_and_wait(httplib::Client& c, const json& spec, int succeeded, int tries) {
  auto r = post_json(c, "/api/v1/campaigns", spec);
  EXPECT_TRUE(r && r->status == 202) << (r ? r->body : "no response");
  if (!r || r->status != 202) return 0;
  const std::int64_t id = body_json(r)["id"];
  const std::string self = "/api/v1/campaigns/" + std::to_string(id);
  for (int i = 0; i < tries && body_json(c.Get(self.c_str()))["jobs"]["succeeded"] < succeeded;
       ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return id;
}

TEST(api_service, sigterm_leaves_the_campaign_resumable) {
  TempDir dir;
  const std::string db = (dir.path / "store.db").string();
  json spec = small_campaign("resumable");
  spec["velocity"] = {{"range", {{"from", 0.05}, {"to", 2.0}, {"step", 0.05}}}};  // 80 jobs
  std::int64_t id = 0;
  int succeeded_at_stop = 0;
  {
    ServeProcess p({"--db", db, "--port", "0", "--workers", "1"});
    ASSERT_GT(p.port(), 0);
    httplib::Client c("127.0.0.1", p.port());
    id = submit_and_wait(c, spec, 3, 500);
    ASSERT_GT(id, 0);
    EXPECT_EQ(p.stop(SIGTERM, 20), 0);
  }
  {
    campaign::Store store(db);
    const auto c = store.campaign(id);
    ASSERT_TRUE(c);
    EXPECT_EQ(c->state, campaign::CampaignState::active);  // not cancelled: to be resumed
    const campaign::JobCounts n = store.job_counts(id);
    EXPECT_EQ(n.running, 0);
    EXPECT_EQ(n.failed, 0);
    EXPECT_EQ(n.total(), 80);
    EXPECT_LT(n.succeeded, 80) << "the campaign finished before the stop; nothing was tested";
    succeeded_at_stop = n.succeeded;
  }
  {
    ServeProcess p({"--db", db, "--port", "0", "--workers", "2"});
    ASSERT_GT(p.port(), 0);
    httplib::Client c("127.0.0.1", p.port());
    const json done = wait_for_campaign(c, id, 120);
    EXPECT_EQ(done["state"], "finished") << done.dump();
    EXPECT_EQ(done["jobs"]["succeeded"], 80);
    EXPECT_EQ(p.stop(SIGINT, 20), 0);
  }
  // Jobs finished before the stop ran once; none ran more than twice.
  campaign::Store store(db);
  int once = 0;
  for (const campaign::PointStatus& ps : store.points(id)) {
    const auto j = store.job(ps.point.job_hash);
    ASSERT_TRUE(j);
    EXPECT_LE(j->attempts, 2);
    if (j->attempts == 1) ++once;
  }
  EXPECT_GE(once, succeeded_at_stop);
}

// `splat serve` with its store on a small tmpfs the test mounts and fills
// while a campaign runs (issue 28 item 4): the server keeps serving, the run
// ends with the campaign `active` and no job blamed (`failed`), a submission
// while the disk is full is a 503 or is stored whole; with room again the
// next server finishes the campaign. Before: jobs whose scene file could not
// be written failed as "bad input".
TEST(api_service, a_full_disk_leaves_the_server_serving_and_blames_no_job) {
  TempDir dir;
  const fs::path disk = dir.path / "disk";
  test_support::SmallTmpfs tmpfs(disk, 64L << 20);  // 80 jobs take about 5 MiB
  if (!tmpfs.mounted()) GTEST_SKIP() << tmpfs.why_not();
  const std::string db = (disk / "store.db").string();
  json spec = small_campaign("full-disk");
  spec["velocity"] = {{"range", {{"from", 0.05}, {"to", 2.0}, {"step", 0.05}}}};  // 80 jobs
  std::int64_t id = 0;
  {
    ServeProcess p({"--db", db, "--port", "0", "--workers", "1"});
    ASSERT_GT(p.port(), 0);
    httplib::Client c("127.0.0.1", p.port());
    id = submit_and_wait(c, spec, 3, 1000);
    ASSERT_GT(id, 0);
    const std::string self = "/api/v1/campaigns/" + std::to_string(id);
    ASSERT_TRUE(test_support::SmallTmpfs::fill(disk / "filler"));
    json doc;
    for (int i = 0; i < 600; ++i) {
      doc = body_json(c.Get(self.c_str()));
      if (!doc["running_now"].get<bool>()) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    EXPECT_FALSE(doc["running_now"].get<bool>()) << doc.dump();
    EXPECT_EQ(doc["state"], "active") << doc.dump();
    EXPECT_EQ(doc["jobs"]["failed"], 0) << doc.dump();
    EXPECT_LT(doc["jobs"]["succeeded"].get<int>(), 80) << "finished before the disk filled";
    ASSERT_EQ(c.Get("/api/v1/health")->status, 200);
    auto full = post_json(c, "/api/v1/campaigns", small_campaign("while-full"));
    ASSERT_TRUE(full);
    if (full->status != 202) expect_problem(full, 503);
    fs::remove(disk / "filler");
    EXPECT_EQ(p.stop(SIGTERM, 20), 0);
  }
  {
    ServeProcess p({"--db", db, "--port", "0", "--workers", "2"});
    ASSERT_GT(p.port(), 0);
    httplib::Client c("127.0.0.1", p.port());
    const json done = wait_for_campaign(c, id, 120);
    EXPECT_EQ(done["state"], "finished") << done.dump();
    EXPECT_EQ(done["jobs"]["succeeded"], 80);
    EXPECT_EQ(done["jobs"]["failed"], 0);
    EXPECT_EQ(p.stop(SIGINT, 20), 0);
  }
}

TEST(api_service, refuses_a_public_address_without_a_token) {
  TempDir dir;
  ServeProcess p({"--db", (dir.path / "s.db").string(), "--host", "0.0.0.0", "--port", "0"});
  EXPECT_EQ(p.port(), 0);
  EXPECT_EQ(p.wait_exit(), 2);
}

}  // namespace
}  // namespace splat::api_test
