// /api/v1/jobs/{id}: summary, parameters, time histories; result.h5
// download; downloads never leave the jobs folder.
#include <atomic>
#include <thread>

#include "campaign/store.hpp"
#include "tests/api/api_fixture.hpp"

namespace splat::api_test {
namespace {

TEST(api_jobs, job_document_histories_and_download) {
  TempDir dir;
  ServerHandle server(options_for(dir));
  httplib::Client c = server.client();
  json spec = small_campaign("jobs");
  spec["velocity"] = {{"values", {0.3, 1.0}}};
  spec["G_c"] = {{"values", {0.2}}};
  auto r = post_json(c, "/api/v1/campaigns", spec);
  ASSERT_EQ(r->status, 202) << r->body;
  const std::int64_t id = body_json(r)["id"];
  ASSERT_EQ(wait_for_campaign(c, id)["state"], "finished");
  const json jobs = body_json(c.Get(("/api/v1/campaigns/" + std::to_string(id) + "/jobs").c_str()));
  ASSERT_EQ(jobs["jobs"].size(), 2u);
  // 0.3 m/s is below V0* = 0.775 m/s: stick; 1.0 m/s above: rebound.
  EXPECT_EQ(jobs["jobs"][0]["outcome"], "stick");
  EXPECT_EQ(jobs["jobs"][1]["outcome"], "rebound");
  for (const json& row : jobs["jobs"]) {
    auto jr = c.Get(row["links"]["self"].get<std::string>().c_str());
    ASSERT_EQ(jr->status, 200);
    const json job = body_json(jr);
    EXPECT_EQ(schema_errors("api_job", job), "");
    EXPECT_EQ(job["state"], "succeeded");
    EXPECT_EQ(job["uses"][0]["campaign_id"], id);
    EXPECT_EQ(job["uses"][0]["params"]["G_c"], 0.2);
    EXPECT_EQ(job["result"]["outcome"], row["outcome"]);
    EXPECT_EQ(job["scene"]["two_mass"]["V0"], row["velocity"]);
    ASSERT_TRUE(job["histories"].is_object()) << job.dump();
    const json& cols = job["histories"]["columns"];
    ASSERT_TRUE(cols.contains("time")) << cols.dump();
    EXPECT_GT(cols["time"].size(), 2u);
    for (const auto& [name, values] : cols.items())
      EXPECT_EQ(values.size(), cols["time"].size()) << name;
    EXPECT_EQ(job["histories"]["units"]["time"], "s");
    // The history of M's velocity starts at the impact speed.
    ASSERT_TRUE(cols.contains("v_M")) << cols.dump();
    EXPECT_NEAR(cols["v_M"][0].get<double>(), row["velocity"].get<double>(), 1e-12);
    EXPECT_EQ(job["histories"]["units"]["v_M"], "m/s");
    // Readers in parallel (the server's threads share one HDF5 library, which
    // Debian builds thread-safe): the same document every time.
    std::vector<std::thread> readers;
    std::atomic<int> mismatches{0};
    for (int t = 0; t < 4; ++t) {
      readers.emplace_back([&] {
        httplib::Client rc = server.client();
        for (int i = 0; i < 10; ++i) {
          auto again = rc.Get(row["links"]["self"].get<std::string>().c_str());
          if (!again || again->status != 200 || again->body != jr->body) ++mismatches;
        }
      });
    }
    for (std::thread& th : readers) th.join();
    EXPECT_EQ(mismatches, 0);
    // Download: the same bytes as the file.
    ASSERT_TRUE(job["links"]["result_h5"].is_string()) << job.dump();
    auto h5 = c.Get(job["links"]["result_h5"].get<std::string>().c_str());
    ASSERT_EQ(h5->status, 200);
    EXPECT_EQ(h5->get_header_value("Content-Type"), "application/x-hdf5");
    EXPECT_EQ(h5->body.substr(1, 3), "HDF");
    const std::string path = job["result"]["summary"]["output"]["hdf5"];
    EXPECT_EQ(h5->body.size(), fs::file_size(path));
  }
}

// A store holding one campaign with one finished job `hash` whose result
// names `hdf5_path`.
void store_one_finished_job(const fs::path& db, const std::string& name, const std::string& hash,
                            const fs::path& hdf5_path) {
  campaign::Store store(db);
  campaign::CampaignRecord rec;
  rec.name = name;
  rec.spec_hash = std::string(64, 'e');
  rec.spec = "{}";
  const auto cid = store.open_campaign(rec);
  store.add_points(cid, {{{"{}", "{}", 1.0, hash, "grid"}, "{}", "v"}}, false);
  store.claim_next_job(cid, "test:1:1", "test");
  campaign::ResultRecord res;
  res.job_hash = hash;
  res.outcome = "stick";
  res.summary = "{}";
  res.hdf5_path = hdf5_path.string();
  store.finish_job(hash, campaign::JobState::succeeded, "stick", 0.1, 1, res);
}

TEST(api_jobs, a_missing_result_file_is_an_error_not_silence) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  // A store copied without its jobs folder: the job's result names a file
  // inside the jobs folder that is not there.
  const std::string hash(64, 'd');
  fs::create_directories(dir.path / "store.db.jobs");
  store_one_finished_job(o.db, "copied", hash,
                         dir.path / "store.db.jobs" / hash / "out" / "run.h5");
  ServerHandle server(o);
  httplib::Client c = server.client();
  auto job = c.Get(("/api/v1/jobs/" + hash).c_str());
  ASSERT_EQ(job->status, 200) << job->body;
  const json doc = body_json(job);
  EXPECT_EQ(schema_errors("api_job", doc), "") << job->body;
  ASSERT_TRUE(doc["histories"].is_object()) << job->body;
  EXPECT_NE(doc["histories"].value("error", "").find("is missing"), std::string::npos) << job->body;
  auto h5 = c.Get(("/api/v1/jobs/" + hash + "/result.h5").c_str());
  expect_problem(h5, 404);
  EXPECT_NE(h5->body.find("is missing"), std::string::npos) << h5->body;
}

TEST(api_jobs, a_result_path_outside_the_jobs_folder_is_never_served) {
  TempDir dir;
  api::ServerOptions o = options_for(dir);
  o.run_campaigns = false;
  // A store whose result points outside the jobs folder (a tampered or
  // moved store): the API must refuse to serve that file.
  const std::string hash(64, 'b');
  fs::create_directories(dir.path / "store.db.jobs");  // so that ".." through it resolves
  store_one_finished_job(o.db, "tampered", hash,
                         dir.path / "store.db.jobs" / ".." / ".." / "outside.h5");
  { std::ofstream(dir.path.parent_path() / "outside.h5") << "secret"; }
  ServerHandle server(o);
  httplib::Client c = server.client();
  auto job = c.Get(("/api/v1/jobs/" + hash).c_str());
  ASSERT_EQ(job->status, 200) << job->body;
  EXPECT_TRUE(body_json(job)["links"]["result_h5"].is_null());
  auto h5 = c.Get(("/api/v1/jobs/" + hash + "/result.h5").c_str());
  expect_problem(h5, 404);
  EXPECT_EQ(h5->body.find("secret"), std::string::npos);
  fs::remove(dir.path.parent_path() / "outside.h5");
}

}  // namespace
}  // namespace splat::api_test
