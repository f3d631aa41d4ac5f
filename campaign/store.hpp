// The campaign store: one SQLite file holding campaigns, jobs, results and
// windows (tables documented in campaign/README.md). This is the interface
// the manager, the commands and the API server use; nothing else touches
// the SQL.
//
// Concurrency: WAL mode with the busy timeout set before switching to it;
// every write goes through this Store's single writer thread as one short
// BEGIN IMMEDIATE transaction (callers block until it commits); reads use one
// connection per calling thread. Several Stores (threads or processes) may
// share a file: writers queue on SQLite's lock (busy timeout 30 s) instead of
// failing with "database is locked".
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "campaign/sqlite.hpp"

namespace splat::campaign {

// Current schema version of the file (PRAGMA user_version).
inline constexpr int k_store_schema_version = 2;

// How long a submission key (the API's Idempotency-Key) is remembered, s.
inline constexpr double k_submission_key_seconds = 24.0 * 3600.0;

enum class JobState { queued, running, succeeded, failed, cancelled, timed_out };
const char* to_string(JobState s);
JobState job_state_from_string(const std::string& s);  // throws std::invalid_argument
bool is_terminal(JobState s);

enum class CampaignState { active, cancelling, cancelled, finished };
const char* to_string(CampaignState s);
CampaignState campaign_state_from_string(const std::string& s);

struct CampaignRecord {
  std::int64_t id = 0;
  std::string name;
  std::string spec_hash;
  std::string spec;  // the spec document (JSON text, base scene inlined)
  std::string tags;  // JSON array text
  std::string executor = "local";
  int priority = 0;
  CampaignState state = CampaignState::active;
  double created_at = 0.0;   // unix time, s
  double finished_at = 0.0;  // unix time, s; 0 while not finished
};

struct JobRecord {
  std::string hash;
  std::string scene;  // resolved scene, JSON text
  std::string solver_version;
  JobState state = JobState::queued;
  int attempts = 0;
  int priority = 0;
  double created_at = 0.0;  // unix time, s
  std::optional<double> started_at;
  std::optional<double> finished_at;
  std::string host;
  std::string owner;        // "host:pid" of the manager running it
  std::string exit_reason;  // why it ended (or was requeued), for people
  std::optional<double> wall_seconds;
  std::optional<int> threads;
};

struct ResultRecord {
  std::string job_hash;
  std::string outcome;  // the summary's outcome
  std::string reason;
  std::string summary;  // the summary document, JSON text
  // The run's HDF5 file, empty when none. Stored relative to the store's
  // folder when it lies inside it (a copied folder keeps its results);
  // Store::result gives it back absolute. Older stores hold absolute paths.
  std::string hdf5_path;
  double created_at = 0.0;
};

// One point of a campaign: a parameter set at a velocity, linked to a job.
struct CampaignPoint {
  std::string params_key;  // canonical JSON of the parameter set
  std::string params;      // same document (kept for readers)
  double velocity = 0.0;   // m/s
  std::string job_hash;
  std::string origin;  // "grid" or "refine"
};

// A point joined with its job's state and its result's outcome.
struct PointStatus {
  CampaignPoint point;
  JobState state = JobState::queued;
  std::optional<std::string> outcome;
  std::string exit_reason;
};

struct WindowRecord {
  std::int64_t campaign_id = 0;
  std::string params_key;
  std::string params;  // JSON text
  std::optional<double> critical_velocity;
  std::optional<double> maximum_velocity;
  std::string window;  // full window document (windows.hpp to_json), JSON text
};

struct JobCounts {
  int queued = 0, running = 0, succeeded = 0, failed = 0, cancelled = 0, timed_out = 0;
  int total() const { return queued + running + succeeded + failed + cancelled + timed_out; }
  int finished() const { return succeeded + failed + cancelled + timed_out; }
  // The counter of one state.
  int& of(JobState state);
};

// Counts of the rows (state text, count) a "SELECT state, COUNT(*) ...
// GROUP BY state" statement returns.
JobCounts read_job_counts(Statement& grouped_by_state);

// The jobs of one parameter set of a campaign (campaign/progress.hpp).
struct ParameterSetLoad {
  std::string params;         // JSON text, {axis name: value}
  int pending = 0;            // queued or running
  int finished = 0;           // ended with a recorded wall time
  double wall_seconds = 0.0;  // s, sum over the finished ones
};

struct AddPointsStats {
  int points_added = 0;   // new (parameter set, velocity) points of the campaign
  int jobs_created = 0;   // new jobs
  int jobs_reused = 0;    // points whose job already existed (cached or shared)
  int jobs_requeued = 0;  // existing jobs put back in the queue (rerun, or cancelled before)
};

struct NewPoint {
  CampaignPoint point;
  std::string scene;  // resolved scene text for a new job
  std::string solver_version;
};

// A submission's idempotency key and the hash of the body first sent with it.
struct SubmissionKey {
  std::string key;
  std::string body_hash;
};

// The key was already used, within k_submission_key_seconds, with another body.
class SubmissionKeyReused : public std::runtime_error {
 public:
  explicit SubmissionKeyReused(const std::string& key)
      : std::runtime_error("submission key '" + key + "' was used with a different body") {}
};

struct Submission {
  std::string body_hash;
  std::int64_t campaign_id = 0;
};

struct OpenedCampaign {
  std::int64_t id = 0;
  AddPointsStats points;  // empty when replayed
  bool replayed = false;  // the key was known: nothing was written
};

// A result path as the store keeps it: relative to `folder` (the store's
// absolute folder) when the file lies inside it, else absolute; "" stays "".
std::string stored_result_path(const std::filesystem::path& folder, const std::string& path);
// The inverse: an absolute path (old stores' absolute paths pass unchanged).
std::string result_path_from_store(const std::filesystem::path& folder, const std::string& stored);

class Store {
 public:
  // Opens or creates the file, applies pending migrations, starts the writer.
  // `busy_timeout_ms`: how long one attempt of a write waits for the write
  // lock of another connection.
  explicit Store(const std::filesystem::path& file, int busy_timeout_ms = 30000);
  // Opens an existing store for reading only (`splat windows`): no write,
  // no migration, no writer thread, so a store on a read-only file system or
  // one this user may not write can be read. Writes throw SqliteError
  // (SQLITE_READONLY); an older schema version is refused with a message.
  struct ReadOnly {};
  Store(const std::filesystem::path& file, ReadOnly);
  ~Store();
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // The absolute folder of the store file: stored result paths are relative to it.
  const std::filesystem::path& folder() const { return folder_; }
  int schema_version();

  // --- writes (each one transaction on the writer thread) -------------------
  // Finds the campaign with this spec hash or creates it; returns its id.
  // An existing campaign that was cancelled or finished becomes active again.
  std::int64_t open_campaign(const CampaignRecord& c);
  // open_campaign and add_points in one transaction: a failure stores neither.
  // Every cancelled job of the campaign (refinement points too) is queued
  // again: a stopped campaign resumes where it stopped.
  // With a key, the key is recorded in the same transaction; a key recorded
  // with the same body hash returns its campaign and writes nothing
  // (`replayed`), one recorded with another body hash throws
  // SubmissionKeyReused. Keys older than k_submission_key_seconds are dropped.
  OpenedCampaign open_campaign(const CampaignRecord& c, const std::vector<NewPoint>& points,
                               bool rerun, const std::optional<SubmissionKey>& key = {});
  // Links the points to the campaign, creating missing jobs (queued). Points
  // already linked are left alone. Existing jobs are reused; they are put back
  // in the queue when `rerun` is set (their results are dropped) or when they
  // were cancelled.
  AddPointsStats add_points(std::int64_t campaign_id, const std::vector<NewPoint>& points,
                            bool rerun);
  // The next queued job of the campaign (highest priority, then oldest), now
  // marked running by `owner` on `host` with one more attempt; empty if none.
  std::optional<JobRecord> claim_next_job(std::int64_t campaign_id, const std::string& owner,
                                          const std::string& host);
  // Ends a running job: its final state, reason and figures, and its result
  // when there is one (a job without a summary has none).
  void finish_job(const std::string& hash, JobState state, const std::string& exit_reason,
                  std::optional<double> wall_seconds, std::optional<int> threads,
                  const std::optional<ResultRecord>& result);
  // Puts a running job back in the queue (a transient failure to retry).
  // `attempt_counts` false: the attempt is given back (the host failed, or
  // the job never started), so it does not use up the job's retries.
  void requeue_job(const std::string& hash, const std::string& reason, bool attempt_counts = true);
  // Jobs left `running` by managers of `host` (owner "host:...") that no longer exist (killed,
  // even with SIGKILL) go back to the queue, their attempt given back. So do those of `own_owner`
  // (this process) for which `running_here` is false: left by an earlier run of this process that a
  // store error ended. Returns how many.
  int recover_orphaned_jobs(const std::string& host, const std::string& own_owner = {},
                            const std::function<bool(const std::string&)>& running_here = {});
  // Cancellation: marks the campaign `cancelling` (a running manager sees it
  // and stops its jobs); mark_cancelled cancels its queued jobs and ends it.
  void request_cancel(std::int64_t campaign_id);
  int cancel_queued_jobs(std::int64_t campaign_id, const std::string& reason);
  void set_campaign_state(std::int64_t campaign_id, CampaignState state);
  void store_windows(std::int64_t campaign_id, const std::vector<WindowRecord>& windows);

  // --- reads (a connection per calling thread) -------------------------------
  std::optional<CampaignRecord> campaign(std::int64_t id);
  std::vector<CampaignRecord> campaigns();
  std::optional<JobRecord> job(const std::string& hash);
  std::optional<ResultRecord> result(const std::string& job_hash);
  // The campaign a submission key opened, and its body hash (keys older than
  // k_submission_key_seconds are forgotten).
  std::optional<Submission> submission(const std::string& key);
  std::vector<PointStatus> points(std::int64_t campaign_id);
  JobCounts job_counts(std::int64_t campaign_id);
  int refinement_points_count(std::int64_t campaign_id);
  std::vector<ParameterSetLoad> parameter_set_loads(std::int64_t campaign_id);
  std::vector<WindowRecord> windows(std::int64_t campaign_id);

  // Runs `work` on the writer thread inside BEGIN IMMEDIATE ... COMMIT and
  // waits for it (exceptions come back to the caller, after a rollback). A
  // store locked by another connection is waited on, however long: `work`
  // then runs again from the start, so it must only assign its outputs.
  void write(std::function<void(Database&)> work);
  // The calling thread's read connection.
  Database& reader();

 private:
  void writer_loop();
  void run_until_written(const std::function<void(Database&)>& work);
  void migrate(Database& db);

  std::filesystem::path path_;
  std::filesystem::path folder_;
  bool read_only_ = false;
  bool immutable_ = false;  // read only, on a read-only file system
  std::unique_ptr<Database> writer_db_;
  std::mutex queue_mutex_;
  std::condition_variable queue_cv_;
  std::deque<std::packaged_task<void()>> queue_;
  bool stopping_ = false;
  std::thread writer_;
  std::mutex readers_mutex_;
  std::map<std::thread::id, std::unique_ptr<Database>> readers_;
};

// Unix time now, s.
double unix_now();
// This machine's host name.
std::string host_name();

}  // namespace splat::campaign
