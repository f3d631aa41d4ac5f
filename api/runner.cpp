#include "api/runner.hpp"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "campaign/spec.hpp"

namespace splat::api {

using campaign::CampaignState;

CampaignRunner::CampaignRunner(campaign::Store& store, RunnerOptions options)
    : store_(store), options_(std::move(options)) {
  thread_ = std::thread([this] { loop(); });
}

CampaignRunner::~CampaignRunner() {
  shutdown();
}

void CampaignRunner::submit(std::int64_t campaign_id) {
  {
    std::lock_guard lock(m_);
    if (shutting_down_) return;
    if (current_ == campaign_id) return;
    if (std::find(line_.begin(), line_.end(), campaign_id) != line_.end()) return;
    line_.push_back(campaign_id);
  }
  cv_.notify_all();
}

int CampaignRunner::resume_all() {
  int queued = 0;
  store_.recover_orphaned_jobs(campaign::host_name());
  for (const campaign::CampaignRecord& c : store_.campaigns()) {
    if (c.state == CampaignState::active) {
      submit(c.id);
      ++queued;
    } else if (c.state == CampaignState::cancelling) {
      store_.cancel_queued_jobs(c.id, "campaign cancelled before the job started");
      store_.set_campaign_state(c.id, CampaignState::cancelled);
    }
  }
  return queued;
}

CancelResult CampaignRunner::cancel(std::int64_t campaign_id) {
  std::unique_lock lock(m_);
  if (current_ == campaign_id) {
    user_cancelled_ = true;
    stop_current_ = true;
    store_.request_cancel(campaign_id);
    return CancelResult::cancelled;
  }
  const auto it = std::find(line_.begin(), line_.end(), campaign_id);
  if (it != line_.end()) line_.erase(it);
  lock.unlock();
  const auto c = store_.campaign(campaign_id);
  if (!c) return CancelResult::unknown;
  if (c->state == CampaignState::finished) return CancelResult::already_ended;
  if (c->state != CampaignState::cancelled) {
    store_.cancel_queued_jobs(campaign_id, "campaign cancelled before the job started");
    store_.set_campaign_state(campaign_id, CampaignState::cancelled);
  }
  return CancelResult::cancelled;
}

int CampaignRunner::waiting() const {
  std::lock_guard lock(m_);
  return static_cast<int>(line_.size());
}

std::optional<std::int64_t> CampaignRunner::running() const {
  std::lock_guard lock(m_);
  return current_;
}

void CampaignRunner::shutdown() {
  {
    std::lock_guard lock(m_);
    shutting_down_ = true;
    line_.clear();
    stop_current_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void CampaignRunner::loop() {
  for (;;) {
    std::int64_t id = 0;
    {
      std::unique_lock lock(m_);
      cv_.wait(lock, [&] { return shutting_down_ || !line_.empty(); });
      if (shutting_down_) return;
      id = line_.front();
      line_.pop_front();
      current_ = id;
      stop_current_ = false;
      user_cancelled_ = false;
    }
    try {
      const auto rec = store_.campaign(id);
      if (rec) {
        const campaign::CampaignSpec spec =
            campaign::read_campaign(nlohmann::json::parse(rec->spec));
        campaign::ManagerOptions mo;
        mo.workers = options_.workers;
        mo.executor = options_.executor;
        mo.job_program = options_.job_program;
        mo.interrupt = &stop_current_;
        const campaign::SweepReport r = campaign::run_sweep(store_, spec, mo);
        std::lock_guard lock(m_);
        if (r.state == CampaignState::cancelled && !user_cancelled_) {
          // Stopped by shutdown, not by a user: leave it to be resumed.
          store_.set_campaign_state(id, CampaignState::active);
        } else if (r.state == CampaignState::finished && user_cancelled_) {
          // The cancel came after the last job: it stays finished (not
          // `cancelling` with nobody left to act on it).
          store_.set_campaign_state(id, CampaignState::finished);
        }
      }
    } catch (const std::exception& e) {
      // A campaign that cannot run (its stored spec no longer reads) must not
      // take the server down; it stays as stored.
      std::fprintf(stderr, "splat serve: campaign %lld could not run: %s\n",
                   static_cast<long long>(id), e.what());
    }
    std::lock_guard lock(m_);
    current_.reset();
  }
}

}  // namespace splat::api
