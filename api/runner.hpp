// The server's campaign runner: one thread that runs submitted campaigns one
// after another with campaign::run_sweep (same store, executors and job
// contract as `splat sweep`), each on the server's worker slots.
//
// Cancel: a campaign waiting in line is cancelled at once (its queued jobs
// `cancelled`, the campaign `cancelled`); the running one is interrupted and
// ended `cancelled` by its manager. Shutdown interrupts the running campaign
// too, but puts it back to `active` afterwards: its stopped jobs are requeued
// when it is next opened, and a server started on the same store resumes
// every `active` campaign.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "campaign/manager.hpp"
#include "campaign/store.hpp"

namespace splat::api {

struct RunnerOptions {
  int workers = 2;
  std::optional<campaign::ExecutorKind> executor;  // overrides each spec's
  std::filesystem::path job_program;               // empty = this executable
};

enum class CancelResult { cancelled, already_ended, unknown };

class CampaignRunner {
 public:
  CampaignRunner(campaign::Store& store, RunnerOptions options);
  ~CampaignRunner();  // shutdown()
  CampaignRunner(const CampaignRunner&) = delete;
  CampaignRunner& operator=(const CampaignRunner&) = delete;

  // Queues the campaign (no-op when it is already waiting or running).
  void submit(std::int64_t campaign_id);
  // Queues every `active` campaign of the store and ends the `cancelling` ones
  // a dead server left behind. Returns how many were queued.
  int resume_all();
  CancelResult cancel(std::int64_t campaign_id);
  // Campaigns waiting in line (not counting the running one).
  int waiting() const;
  // The campaign being run, if any.
  std::optional<std::int64_t> running() const;
  // Stops the running campaign (resumable), drops the line, joins the thread.
  void shutdown();

 private:
  void loop();

  campaign::Store& store_;
  RunnerOptions options_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  std::deque<std::int64_t> line_;
  std::optional<std::int64_t> current_;
  std::atomic<bool> stop_current_{false};
  bool user_cancelled_ = false;
  bool shutting_down_ = false;
  std::thread thread_;
};

}  // namespace splat::api
