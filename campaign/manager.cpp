#include "campaign/manager.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "campaign/job_end.hpp"
#include "campaign/ladders.hpp"
#include "campaign/manager_lock.hpp"
#include "campaign/process.hpp"
#include "campaign/progress.hpp"
#include "campaign/slurm.hpp"
#include "solver/common/parallel.hpp"

namespace splat::campaign {

using nlohmann::json;

namespace {

constexpr int k_exit_transient = 75;  // EX_TEMPFAIL (sysexits.h)
constexpr int k_exit_output = 74;     // EX_IOERR: the job could not write its output
constexpr int k_exit_bad_input = 2;

std::string read_text(const std::filesystem::path& p, std::size_t max_bytes) {
  std::ifstream f(p, std::ios::binary);
  std::string s((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (s.size() > max_bytes) s = "..." + s.substr(s.size() - max_bytes);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

std::string signal_name(int sig) {
  const char* d = strsignal(sig);
  return "signal " + std::to_string(sig) + (d ? std::string(" (") + d + ")" : std::string());
}

// Writes `text` to `file`, or throws naming the file and the system's reason
// (a full disk must not leave a job a truncated scene to fail on).
void write_file(const std::filesystem::path& file, const std::string& text) {
  std::FILE* f = std::fopen(file.c_str(), "w");
  if (f == nullptr) {
    throw std::system_error(errno, std::generic_category(), "cannot write " + file.string());
  }
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const int write_errno = errno;
  if (std::fclose(f) != 0 || !written) {
    throw std::system_error(written ? errno : write_errno, std::generic_category(),
                            "cannot write " + file.string());
  }
}

// Cores this process may run on (its CPU affinity: a container or taskset
// limit counts), at least 1.
int usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

// Retries a job whose process could not be started gets at least.
constexpr int k_spawn_retries = 3;

// A program file that cannot be executed yet and was written within the last
// minute is being written (ld writes its output in place and makes it
// executable at the end: splat rebuilt under a running campaign).
bool being_written(const std::string& program) {
  std::error_code ec;
  const auto written = std::filesystem::last_write_time(program, ec);
  if (ec || access(program.c_str(), X_OK) == 0) return false;
  return std::filesystem::file_time_type::clock::now() - written < std::chrono::minutes(1);
}

// Waits while `program` is being written, so that a job that could not
// start it does not use up its attempts at once.
void wait_while_being_written(const std::string& program, const std::atomic<bool>& cancel) {
  while (!cancel && being_written(program)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

// A failure that may pass on another attempt: queued again while retries
// are left.
JobEnd transient(const JobRecord& job, const JobOptions& opts, const std::string& what) {
  JobEnd e;
  e.retry = job.attempts <= opts.retries;
  e.reason = what + " on attempt " + std::to_string(job.attempts) +
             (e.retry ? ", retrying" : ", no retries left");
  return e;
}

// The jobs the managers of this process are running now (several campaigns
// of one server share the process and its owner name): a job this process
// owns that is not among them was left `running` by a run a store error
// ended, and is requeued by the next run.
class JobsRunningHere {
 public:
  void add(const std::string& hash) {
    std::lock_guard lock(m_);
    ++count_[hash];
  }
  void remove(const std::string& hash) {
    std::lock_guard lock(m_);
    if (auto it = count_.find(hash); it != count_.end() && --it->second == 0) count_.erase(it);
  }
  bool contains(const std::string& hash) const {
    std::lock_guard lock(m_);
    return count_.count(hash) > 0;
  }

 private:
  mutable std::mutex m_;
  std::map<std::string, int> count_;
};

JobsRunningHere& jobs_running_here() {
  static JobsRunningHere jobs;
  return jobs;
}

// A job's end the host caused (exit 74: its output could not be written).
class HostFault : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Runs `f` when the scope ends, also by an exception.
class ScopeExit {
 public:
  explicit ScopeExit(std::function<void()> f) : f_(std::move(f)) {}
  ~ScopeExit() { f_(); }
  ScopeExit(const ScopeExit&) = delete;
  ScopeExit& operator=(const ScopeExit&) = delete;

 private:
  std::function<void()> f_;
};

}  // namespace

JobEnd interpret(const JobRecord& job, const ProcessResult& pr, const std::filesystem::path& dir,
                 const JobOptions& opts) {
  JobEnd e;
  const auto err_tail = [&] { return read_text(dir / "stderr.txt", 400); };
  switch (pr.end) {
    case ProcessEnd::spawn_failed: {
      // The job never ran (the program being rebuilt, no process left):
      // a fault of the host, not of the job, retried at least
      // k_spawn_retries times whatever the job's retries.
      JobOptions o = opts;
      o.retries = std::max(o.retries, k_spawn_retries);
      return transient(job, o, "could not start: " + pr.error);
    }
    case ProcessEnd::timed_out:
      e.state = JobState::timed_out;
      e.reason = "stopped at the time limit of " + std::to_string(opts.time_limit) + " s";
      return e;
    case ProcessEnd::cancelled:
      e.state = JobState::cancelled;
      e.reason = "cancelled while running";
      return e;
    case ProcessEnd::signaled:
      // Killed from outside (kill -9, the OOM killer) or crashed: another
      // attempt may finish.
      return transient(job, opts, "killed by " + signal_name(pr.signal));
    case ProcessEnd::exited:
      break;
  }
  if (pr.exit_code == k_exit_transient) {
    e = transient(job, opts, "transient failure (exit code 75)");
    e.reason += ": " + err_tail();
    return e;
  }
  if (pr.exit_code == k_exit_output) {
    e.host_fault = true;
    e.retry = job.attempts <= opts.retries;  // what a Slurm round does with it
    e.reason = "could not write its output (exit code 74): " + err_tail();
    return e;
  }
  if (pr.exit_code == k_exit_bad_input) {
    e.reason = "bad input (exit code 2): " + err_tail();
    return e;
  }
  if (pr.exit_code != 0 && pr.exit_code != 3) {
    e.reason = "exit code " + std::to_string(pr.exit_code) + ": " + err_tail();
    return e;
  }
  const std::string text = read_text(dir / "stdout.json", std::size_t(64) << 20);
  json summary;
  try {
    summary = json::parse(text);
  } catch (const json::exception&) {
    e.reason = "exit code " + std::to_string(pr.exit_code) + " without a JSON summary on stdout";
    return e;
  }
  if (!summary.is_object() || !summary.contains("outcome") || !summary["outcome"].is_string()) {
    e.reason = "summary without an `outcome`";
    return e;
  }
  ResultRecord r;
  r.job_hash = job.hash;
  r.outcome = summary["outcome"].get<std::string>();
  r.reason = summary.value("reason", "");
  r.summary = summary.dump();
  if (summary.contains("output") && summary["output"].is_object()) {
    const json& h = summary["output"].value("hdf5", json());
    if (h.is_string()) r.hdf5_path = h.get<std::string>();
  }
  if (summary.contains("threads") && summary["threads"].is_number_integer()) {
    e.threads = summary["threads"].get<int>();
  }
  // The job ran; its outcome says how the simulation ended. The solver's
  // own limits (timed-out) and errors are recorded as such.
  if (r.outcome == "timed-out") {
    e.state = JobState::timed_out;
  } else if (r.outcome == "error") {
    e.state = JobState::failed;
  } else {
    e.state = JobState::succeeded;
  }
  e.reason = r.outcome + ": " + r.reason;
  e.result = std::move(r);
  return e;
}

Sample classify(const PointStatus& p) {
  Sample s;
  s.velocity = p.point.velocity;
  if (p.state == JobState::succeeded && p.outcome) {
    s.label = *p.outcome;
    if (*p.outcome == "stick") s.verdict = Verdict::stick;
    if (*p.outcome == "rebound") s.verdict = Verdict::rebound;
  } else if (p.outcome) {
    s.label = std::string(to_string(p.state)) + " (" + *p.outcome + ")";
  } else {
    s.label = to_string(p.state);
  }
  return s;
}

namespace {

using PlannedPoints = std::vector<std::pair<json, double>>;

// Coarse to fine: per group of parameter sets equal but for the ladder
// axis, the next step of its ladder (campaign/ladders.hpp).
PlannedPoints ladder_points(const CampaignSpec& spec,
                            std::map<std::string, std::vector<Sample>>& samples) {
  const ParameterAxis& axis = *ladder_axis(spec);
  std::map<std::string, std::vector<json>> groups;
  for (const json& p : parameter_sets(spec)) {
    json rest = p;
    rest.erase(axis.name);
    groups[canonical_text(rest)].push_back(p);
  }
  PlannedPoints out;
  for (auto& [key, sets] : groups) {
    std::sort(sets.begin(), sets.end(), [&](const json& a, const json& b) {
      return a.at(axis.name).get<double>() < b.at(axis.name).get<double>();
    });
    std::vector<std::vector<Sample>> levels;
    for (const json& p : sets) levels.push_back(samples[canonical_text(p)]);
    const LadderStep step = coarse_to_fine_step(levels, spec.refinement->rule());
    for (double v : step.velocities) out.push_back({sets[step.level], v});
  }
  return out;
}

// The points refinement adds next: bisection and guard bands of every
// window, or the ladder's next step when refinement goes coarse to fine.
PlannedPoints next_points(const CampaignSpec& spec, const std::vector<WindowRecord>& windows,
                          std::map<std::string, std::vector<Sample>>& samples) {
  if (spec.refinement->coarse_to_fine && ladder_axis(spec)) return ladder_points(spec, samples);
  PlannedPoints out;
  for (const WindowRecord& w : windows) {
    const Window win = compute_window(samples[w.params_key]);
    for (double v : refinement_points(win, spec.refinement->rule())) {
      out.push_back({json::parse(w.params), v});
    }
  }
  return out;
}

}  // namespace

std::vector<WindowRecord> compute_windows(Store& store, std::int64_t campaign_id) {
  std::map<std::string, std::pair<std::string, std::vector<Sample>>> sets;
  for (const PointStatus& p : store.points(campaign_id)) {
    auto& slot = sets[p.point.params_key];
    slot.first = p.point.params;
    slot.second.push_back(classify(p));
  }
  std::vector<WindowRecord> out;
  for (auto& [key, set] : sets) {
    const Window w = compute_window(std::move(set.second));
    json doc = to_json(w);
    doc["params"] = json::parse(set.first);
    out.push_back(
        {campaign_id, key, set.first, w.critical_velocity, w.maximum_velocity, doc.dump()});
  }
  return out;
}

namespace {

// One run of run_sweep: the campaign's grid opened in the store, a pool of
// worker threads (each runs one job child at a time and records its end)
// fed by the dispatcher (the calling thread), or Slurm rounds, then
// refinement rounds until the windows are done, cancelled or the host fails.
class SweepRun {
 public:
  SweepRun(Store& store, const CampaignSpec& spec, const ManagerOptions& options)
      : store_(store),
        spec_(spec),
        options_(options),
        resolve_(options.resolver ? options.resolver : splat_scene_resolver()),
        version_(options.solver_version.empty() ? solver_version_string() : options.solver_version),
        jobs_dir_(options.jobs_dir.empty() ? std::filesystem::path(store.path().string() + ".jobs")
                                           : options.jobs_dir),
        host_(host_name()),
        owner_(this_process_owner()),
        workers_(std::max(1, options.workers)),
        use_slurm_(options.executor ? *options.executor == ExecutorKind::slurm
                                    : spec.executor == ExecutorKind::slurm) {
    if (!use_slurm_ && spec.job.threads > splat::max_threads()) {
      throw std::invalid_argument(
          "/job/threads: " + std::to_string(spec.job.threads) + " asked; local jobs take at most " +
          std::to_string(splat::max_threads()) + ", the cores of this machine");
    }
    // More job threads than cores: waiting OpenMP threads must sleep, not
    // spin, or they take the cores the other jobs compute on (unless the
    // user's environment already chooses a wait policy).
    if (workers_ * spec.job.threads > usable_cores() && !std::getenv("OMP_WAIT_POLICY")) {
      job_environment_ = {"OMP_WAIT_POLICY=passive"};
    }
  }

  SweepReport run() {
    open();
    start_pool();
    // A store error in this thread (a full disk) leaves the run through
    // here: the running jobs are stopped, the claimed ones not started go
    // back to the queue while the store still takes writes, and the pool is
    // joined before the error reaches the caller (the campaign stays `active`).
    const ScopeExit stop_pool_on_error([&] {
      if (!pool_joined_) stop_pool();
    });
    report_progress();
    const bool cancelled = use_slurm_ ? run_slurm() : run_local();
    if (cancelled) cancel_claimed();
    join_pool();
    return finish(cancelled);
  }

 private:
  // Resolved at each launch: a splat rebuilt under a running campaign is the
  // one its next jobs run.
  std::filesystem::path program() const {
    return options_.job_program.empty() ? this_executable() : options_.job_program;
  }

  std::vector<NewPoint> to_new_points(const std::vector<ExpandedJob>& jobs,
                                      const char* origin) const {
    std::vector<NewPoint> pts;
    for (const ExpandedJob& j : jobs) {
      pts.push_back({{j.params_key, j.params_key, j.velocity, j.hash, origin},
                     canonical_text(j.scene),
                     version_});
    }
    return pts;
  }

  // The campaign and its grid in one transaction; jobs a dead manager of
  // this host left running go back to the queue.
  void open() {
    CampaignRecord rec;
    rec.name = spec_.name;
    rec.spec_hash = spec_hash(spec_);
    rec.spec = spec_.document.dump();
    rec.tags = json(spec_.tags).dump();
    rec.executor = splat::to_string(spec_.executor);
    rec.priority = spec_.priority;
    const OpenedCampaign opened = store_.open_campaign(
        rec, to_new_points(expand(spec_, resolve_, version_), "grid"), options_.rerun);
    cid_ = opened.id;
    report_.campaign_id = cid_;
    report_.grid = opened.points;
    report_.orphans_requeued = store_.recover_orphaned_jobs(
        host_, owner_, [](const std::string& hash) { return jobs_running_here().contains(hash); });
    progress_.campaign_id = cid_;
  }

  void run_one(const JobRecord& job) {
    const std::filesystem::path dir = jobs_dir_ / job.hash;
    std::filesystem::create_directories(dir / "out");
    write_file(dir / "scene.json", job.scene + "\n");
    ProcessSpec ps;
    ps.argv = {
        program().string(),     "run",       (dir / "scene.json").string(),    "--json", "--out",
        (dir / "out").string(), "--threads", std::to_string(spec_.job.threads)};
    ps.stdout_file = dir / "stdout.json";
    ps.stderr_file = dir / "stderr.txt";
    ps.time_limit = spec_.job.time_limit;
    ps.cancel = &cancel_running_;
    ps.environment = job_environment_;
    ++started_;
    const ProcessResult pr = run_process(ps);
    if (pr.end == ProcessEnd::spawn_failed) {
      wait_while_being_written(find_program(ps.argv[0]), cancel_running_);
    }
    JobEnd e = interpret(job, pr, dir, spec_.job);
    if (e.host_fault) {
      // Not the job's fault: it runs again once the host has room, and this
      // run ends (every other job would meet the same full disk).
      store_.requeue_job(job.hash, "requeued: " + e.reason, false);
      throw HostFault("job " + job.hash.substr(0, 12) + " " + e.reason);
    }
    if (e.retry) {
      store_.requeue_job(job.hash, e.reason);
    } else {
      store_.finish_job(job.hash, e.state, e.reason, pr.wall_seconds,
                        e.threads ? e.threads : std::optional<int>(spec_.job.threads), e.result);
    }
  }

  // Runs `job`; nothing escapes: a fault of the host or the store is kept
  // for the dispatcher, which ends the run with it.
  void run_guarded(const JobRecord& job) {
    try {
      run_one(job);
    } catch (const HostFault& ex) {
      std::lock_guard lock(m_);
      worker_errors_.push_back(ex.what());
    } catch (const std::exception& ex) {
      // The job could not be prepared or recorded (a full disk, a store
      // that refuses writes): no fault of the job. It goes back to the
      // queue if the store still takes writes (else the next run requeues
      // it), and the run ends with the error.
      try {
        store_.requeue_job(job.hash, std::string("requeued: manager error: ") + ex.what(), false);
      } catch (const std::exception&) {
      }
      std::lock_guard lock(m_);
      worker_errors_.push_back(ex.what());
    }
  }

  void worker() {
    for (;;) {
      JobRecord job;
      {
        std::unique_lock lock(m_);
        cv_.wait(lock, [&] { return closing_ || !work_.empty(); });
        if (work_.empty()) return;
        job = std::move(work_.front());
        work_.pop_front();
      }
      run_guarded(job);
      jobs_running_here().remove(job.hash);
      {
        std::lock_guard lock(m_);
        --active_;
      }
      cv_.notify_all();
    }
  }

  void start_pool() {
    for (int i = 0; i < workers_; ++i) pool_.emplace_back([this] { worker(); });
  }

  void join_pool() {
    {
      std::lock_guard lock(m_);
      closing_ = true;
    }
    cv_.notify_all();
    for (std::thread& t : pool_) t.join();
    pool_joined_ = true;
  }

  void stop_pool() {
    cancel_running_ = true;
    std::deque<JobRecord> unstarted;
    {
      std::lock_guard lock(m_);
      unstarted.swap(work_);
    }
    for (const JobRecord& j : unstarted) {
      jobs_running_here().remove(j.hash);
      try {
        store_.requeue_job(j.hash, "requeued: its manager stopped on a store error", false);
      } catch (const std::exception&) {
        // Left `running`: the next run (of this process or another) requeues it.
      }
    }
    join_pool();
  }

  void report_progress() {
    if (!options_.on_progress) return;
    progress_.counts = store_.job_counts(cid_);
    progress_.refinement_jobs = store_.refinement_points_count(cid_);
    const auto work = work_left(store_.parameter_set_loads(cid_), ladder_axis(spec_));
    progress_.seconds_left =
        work ? std::optional<double>(seconds_left(*work, workers_)) : std::nullopt;
    options_.on_progress(progress_);
  }

  // After every job has ended: store the windows, then add a refinement
  // round if an edge is still wider than the tolerance and budget is left.
  bool refine_round() {
    std::vector<WindowRecord> windows = compute_windows(store_, cid_);
    store_.store_windows(cid_, windows);
    if (!spec_.refinement) return false;
    std::vector<ExpandedJob> extra;
    int budget = spec_.refinement->max_extra_jobs - store_.refinement_points_count(cid_);
    std::map<std::string, std::vector<Sample>> samples;
    for (const PointStatus& p : store_.points(cid_))
      samples[p.point.params_key].push_back(classify(p));
    for (const auto& [params, v] : next_points(spec_, windows, samples)) {
      if (budget <= 0) break;
      extra.push_back(make_job(spec_, params, v, resolve_, version_));
      --budget;
    }
    if (extra.empty()) return false;
    store_.add_points(cid_, to_new_points(extra, "refine"), options_.rerun);
    ++progress_.round;
    report_progress();
    return true;
  }

  bool cancel_requested() {
    if (options_.interrupt && options_.interrupt->load()) return true;
    const auto c = store_.campaign(cid_);
    return c && c->state == CampaignState::cancelling;
  }

  // Slurm rounds until done; true when cancelled.
  bool run_slurm() {
    SlurmRound round{store_, cid_, spec_, program(), jobs_dir_, options_.slurm, owner_, {}, {}};
    round.cancel_requested = [this] { return cancel_requested(); };
    round.on_job_end = [this] { report_progress(); };
    for (;;) {
      round.program = program();
      const SlurmRoundResult rr = run_slurm_round(round);
      started_ += rr.jobs_submitted;
      if (rr.cancelled) return true;
      if (store_.job_counts(cid_).queued > 0) continue;  // transient failures to retry
      if (!refine_round()) return false;
    }
  }

  int active() {
    std::lock_guard lock(m_);
    return active_;
  }

  // A worker met a fault of the host or the store: end the run with it
  // (stop_pool requeues and joins; the campaign stays `active`).
  void throw_worker_error() {
    std::lock_guard lock(m_);
    if (worker_errors_.empty()) return;
    throw RunStopped("campaign run stopped: " + worker_errors_.front() +
                     "; jobs stored so far are kept and the campaign stays active: "
                     "free space (or fix the store) and run it again to resume");
  }

  // Claims queued jobs for the free worker slots.
  void fill_slots() {
    for (int free_slots = workers_ - active(); free_slots > 0; --free_slots) {
      std::optional<JobRecord> job = store_.claim_next_job(cid_, owner_, host_);
      if (!job) break;
      jobs_running_here().add(job->hash);
      {
        std::lock_guard lock(m_);
        work_.push_back(std::move(*job));
        ++active_;
      }
      cv_.notify_all();
    }
  }

  // The local pool until done; true when cancelled.
  bool run_local() {
    auto last_poll = std::chrono::steady_clock::now();
    for (;;) {
      throw_worker_error();
      bool cancel_now = options_.interrupt && options_.interrupt->load();
      const auto now = std::chrono::steady_clock::now();
      if (!cancel_now &&
          std::chrono::duration<double>(now - last_poll).count() >= options_.poll_seconds) {
        last_poll = now;
        cancel_now = cancel_requested();
      }
      if (cancel_now) return true;
      fill_slots();
      if (active() == 0) {
        const JobCounts counts = store_.job_counts(cid_);
        if (counts.queued > 0) continue;  // claimable now
        if (counts.running > 0) {
          // Shared jobs another manager is running: wait for them.
          std::this_thread::sleep_for(std::chrono::duration<double>(options_.poll_seconds));
          continue;
        }
        if (!refine_round()) return false;
        continue;
      }
      {
        std::unique_lock lock(m_);
        const int before = active_;
        cv_.wait_for(lock, std::chrono::duration<double>(options_.poll_seconds),
                     [&] { return active_ < before; });
      }
      report_progress();
    }
  }

  // Queued jobs never start; running ones are stopped and recorded cancelled.
  void cancel_claimed() {
    store_.cancel_queued_jobs(cid_, "campaign cancelled before the job started");
    cancel_running_ = true;
    std::lock_guard lock(m_);
    for (const JobRecord& j : work_) {
      jobs_running_here().remove(j.hash);
      store_.finish_job(j.hash, JobState::cancelled, "campaign cancelled before the job started",
                        std::nullopt, std::nullopt, std::nullopt);
    }
    active_ -= static_cast<int>(work_.size());
    work_.clear();
  }

  SweepReport finish(bool cancelled) {
    report_.windows = compute_windows(store_, cid_);
    store_.store_windows(cid_, report_.windows);
    report_.state = cancelled ? CampaignState::cancelled : CampaignState::finished;
    store_.set_campaign_state(cid_, report_.state);
    report_.counts = store_.job_counts(cid_);
    report_.refinement_jobs = store_.refinement_points_count(cid_);
    report_.jobs_started = started_.load();
    report_progress();
    return report_;
  }

  Store& store_;
  const CampaignSpec& spec_;
  const ManagerOptions& options_;
  const SceneResolver resolve_;
  const std::string version_;
  const std::filesystem::path jobs_dir_;
  const std::string host_;
  const std::string owner_;
  const int workers_;
  const bool use_slurm_;
  std::vector<std::string> job_environment_;
  std::int64_t cid_ = 0;
  SweepReport report_;
  Progress progress_;
  // The pool, guarded by m_: the claimed jobs not yet started, the jobs
  // claimed and not ended, and the faults the workers met.
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<JobRecord> work_;
  int active_ = 0;
  bool closing_ = false;
  std::vector<std::string> worker_errors_;
  std::atomic<bool> cancel_running_{false};
  std::atomic<int> started_{0};
  std::vector<std::thread> pool_;
  bool pool_joined_ = false;
};

}  // namespace

SweepReport run_sweep(Store& store, const CampaignSpec& spec, const ManagerOptions& options) {
  const ManagerLock one_manager(store.path());
  SweepRun run(store, spec, options);
  return run.run();
}

}  // namespace splat::campaign
