#include "campaign/store.hpp"

#include <sys/statvfs.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "campaign/process.hpp"

namespace splat::campaign {

namespace {

// Migrations, in order: entry i takes the file from version i to i + 1.
// Never edit a shipped entry; append a new one.
const char* const k_migrations[] = {
    R"sql(
CREATE TABLE campaigns (
  id          INTEGER PRIMARY KEY,
  name        TEXT NOT NULL,
  spec_hash   TEXT NOT NULL UNIQUE,
  spec        TEXT NOT NULL,
  tags        TEXT NOT NULL DEFAULT '[]',
  executor    TEXT NOT NULL DEFAULT 'local',
  priority    INTEGER NOT NULL DEFAULT 0,
  state       TEXT NOT NULL CHECK (state IN ('active', 'cancelling', 'cancelled', 'finished')),
  created_at  REAL NOT NULL,
  finished_at REAL
);
CREATE TABLE jobs (
  hash           TEXT PRIMARY KEY,
  scene          TEXT NOT NULL,
  solver_version TEXT NOT NULL,
  state          TEXT NOT NULL CHECK (state IN ('queued', 'running', 'succeeded', 'failed',
                                                'cancelled', 'timed-out')),
  attempts       INTEGER NOT NULL DEFAULT 0,
  priority       INTEGER NOT NULL DEFAULT 0,
  created_at     REAL NOT NULL,
  started_at     REAL,
  finished_at    REAL,
  host           TEXT NOT NULL DEFAULT '',
  owner          TEXT NOT NULL DEFAULT '',
  exit_reason    TEXT NOT NULL DEFAULT '',
  wall_seconds   REAL,
  threads        INTEGER
);
CREATE INDEX jobs_by_state ON jobs (state);
CREATE TABLE campaign_points (
  campaign_id INTEGER NOT NULL REFERENCES campaigns (id) ON DELETE CASCADE,
  params_key  TEXT NOT NULL,
  params      TEXT NOT NULL,
  velocity    REAL NOT NULL,
  job_hash    TEXT NOT NULL REFERENCES jobs (hash),
  origin      TEXT NOT NULL CHECK (origin IN ('grid', 'refine')),
  PRIMARY KEY (campaign_id, params_key, velocity)
);
CREATE INDEX campaign_points_by_job ON campaign_points (job_hash);
CREATE TABLE results (
  job_hash   TEXT PRIMARY KEY REFERENCES jobs (hash),
  outcome    TEXT NOT NULL,
  reason     TEXT NOT NULL,
  summary    TEXT NOT NULL,
  hdf5_path  TEXT NOT NULL DEFAULT '',
  created_at REAL NOT NULL
);
CREATE TABLE windows (
  campaign_id       INTEGER NOT NULL REFERENCES campaigns (id) ON DELETE CASCADE,
  params_key        TEXT NOT NULL,
  params            TEXT NOT NULL,
  critical_velocity REAL,
  maximum_velocity  REAL,
  window            TEXT NOT NULL,
  updated_at        REAL NOT NULL,
  PRIMARY KEY (campaign_id, params_key)
);
)sql",
    R"sql(
CREATE TABLE submissions (
  key         TEXT PRIMARY KEY,
  body_hash   TEXT NOT NULL,
  campaign_id INTEGER NOT NULL REFERENCES campaigns (id) ON DELETE CASCADE,
  created_at  REAL NOT NULL
);
)sql",
};
static_assert(std::size(k_migrations) == k_store_schema_version);

void configure(Database& db) {
  // The busy timeout is already set (Database's constructor), so switching
  // to WAL waits for another process's lock instead of failing.
  db.exec("PRAGMA journal_mode = WAL");
  db.exec("PRAGMA synchronous = NORMAL");  // durable against process crashes in WAL mode
  db.exec("PRAGMA foreign_keys = ON");
}

const char* const k_job_columns =
    "hash, scene, solver_version, state, attempts, priority, created_at, started_at, "
    "finished_at, host, owner, exit_reason, wall_seconds, threads";

JobRecord read_job(const Statement& s) {
  JobRecord j;
  j.hash = s.text(0);
  j.scene = s.text(1);
  j.solver_version = s.text(2);
  j.state = job_state_from_string(s.text(3));
  j.attempts = static_cast<int>(s.int64(4));
  j.priority = static_cast<int>(s.int64(5));
  j.created_at = s.real(6);
  j.started_at = s.opt_real(7);
  j.finished_at = s.opt_real(8);
  j.host = s.text(9);
  j.owner = s.text(10);
  j.exit_reason = s.text(11);
  j.wall_seconds = s.opt_real(12);
  if (!s.is_null(13)) j.threads = static_cast<int>(s.int64(13));
  return j;
}

const char* const k_campaign_columns =
    "id, name, spec_hash, spec, tags, executor, priority, state, created_at, finished_at";

CampaignRecord read_campaign_row(const Statement& s) {
  CampaignRecord c;
  c.id = s.int64(0);
  c.name = s.text(1);
  c.spec_hash = s.text(2);
  c.spec = s.text(3);
  c.tags = s.text(4);
  c.executor = s.text(5);
  c.priority = static_cast<int>(s.int64(6));
  c.state = campaign_state_from_string(s.text(7));
  c.created_at = s.real(8);
  c.finished_at = s.opt_real(9).value_or(0.0);
  return c;
}

}  // namespace

const char* to_string(JobState s) {
  switch (s) {
    case JobState::queued:
      return "queued";
    case JobState::running:
      return "running";
    case JobState::succeeded:
      return "succeeded";
    case JobState::failed:
      return "failed";
    case JobState::cancelled:
      return "cancelled";
    case JobState::timed_out:
      return "timed-out";
  }
  return "failed";
}

JobState job_state_from_string(const std::string& s) {
  for (JobState x : {JobState::queued, JobState::running, JobState::succeeded, JobState::failed,
                     JobState::cancelled, JobState::timed_out}) {
    if (s == to_string(x)) return x;
  }
  throw std::invalid_argument("unknown job state '" + s + "'");
}

bool is_terminal(JobState s) {
  return s != JobState::queued && s != JobState::running;
}

const char* to_string(CampaignState s) {
  switch (s) {
    case CampaignState::active:
      return "active";
    case CampaignState::cancelling:
      return "cancelling";
    case CampaignState::cancelled:
      return "cancelled";
    case CampaignState::finished:
      return "finished";
  }
  return "active";
}

CampaignState campaign_state_from_string(const std::string& s) {
  for (CampaignState x : {CampaignState::active, CampaignState::cancelling,
                          CampaignState::cancelled, CampaignState::finished}) {
    if (s == to_string(x)) return x;
  }
  throw std::invalid_argument("unknown campaign state '" + s + "'");
}

double unix_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

std::string host_name() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "localhost";
  return buf;
}

std::string stored_result_path(const std::filesystem::path& folder, const std::string& path) {
  if (path.empty()) return path;
  const std::filesystem::path absolute = std::filesystem::absolute(path).lexically_normal();
  const std::filesystem::path relative = absolute.lexically_relative(folder);
  if (relative.empty() || *relative.begin() == "..") return absolute.string();
  return relative.string();
}

std::string result_path_from_store(const std::filesystem::path& folder, const std::string& stored) {
  if (stored.empty() || std::filesystem::path(stored).is_absolute()) return stored;
  return (folder / stored).lexically_normal().string();
}

Store::Store(const std::filesystem::path& file, int busy_timeout_ms)
    : path_(file), folder_(std::filesystem::absolute(file).lexically_normal().parent_path()) {
  writer_db_ = std::make_unique<Database>(file, busy_timeout_ms);
  configure(*writer_db_);
  migrate(*writer_db_);
  writer_ = std::thread([this] { writer_loop(); });
}

Store::Store(const std::filesystem::path& file, ReadOnly)
    : path_(file),
      folder_(std::filesystem::absolute(file).lexically_normal().parent_path()),
      read_only_(true) {
  struct statvfs fs {};
  immutable_ = ::statvfs(file.c_str(), &fs) == 0 && (fs.f_flag & ST_RDONLY) != 0;
  writer_db_ = std::make_unique<Database>(file, 30000, true, immutable_);
  writer_db_->exec("PRAGMA foreign_keys = ON");
  const int version = schema_version();
  if (version != k_store_schema_version) {
    throw SqliteError(SQLITE_ERROR,
                      "store '" + path_.string() + "' has schema version " +
                          std::to_string(version) + ", this splat reads version " +
                          std::to_string(k_store_schema_version) +
                          (version < k_store_schema_version
                               ? " (open it once with a command that writes, e.g. splat sweep)"
                               : ""));
  }
}

Store::~Store() {
  {
    std::lock_guard lock(queue_mutex_);
    stopping_ = true;
  }
  queue_cv_.notify_all();
  if (writer_.joinable()) writer_.join();
}

void Store::migrate(Database& db) {
  Transaction tx(db);
  Statement v = db.prepare("PRAGMA user_version");
  v.step();
  const int version = static_cast<int>(v.int64(0));
  if (version > k_store_schema_version) {
    throw SqliteError(SQLITE_ERROR, "store '" + path_.string() + "' has schema version " +
                                        std::to_string(version) + ", newer than this splat (" +
                                        std::to_string(k_store_schema_version) + ")");
  }
  for (int i = version; i < k_store_schema_version; ++i) {
    db.exec(k_migrations[i]);
    db.exec("PRAGMA user_version = " + std::to_string(i + 1));
  }
  tx.commit();
}

int Store::schema_version() {
  Statement v = reader().prepare("PRAGMA user_version");
  v.step();
  return static_cast<int>(v.int64(0));
}

void Store::writer_loop() {
  for (;;) {
    std::packaged_task<void()> task;
    {
      std::unique_lock lock(queue_mutex_);
      queue_cv_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    task();
  }
}

void Store::write(std::function<void(Database&)> work) {
  if (read_only_) {
    throw SqliteError(SQLITE_READONLY, "store '" + path_.string() + "' is open for reading only");
  }
  std::packaged_task<void()> task([this, work = std::move(work)] { run_until_written(work); });
  std::future<void> done = task.get_future();
  {
    std::lock_guard lock(queue_mutex_);
    queue_.push_back(std::move(task));
  }
  queue_cv_.notify_one();
  done.get();
}

// Another connection holding the write lock past the busy timeout is waited
// out: the transaction (rolled back) is tried again until it commits, so a
// busy store never drops a write such as a finished job's result.
void Store::run_until_written(const std::function<void(Database&)>& work) {
  for (int attempt = 1;; ++attempt) {
    try {
      Transaction tx(*writer_db_);
      work(*writer_db_);
      tx.commit();
      return;
    } catch (const SqliteError& e) {
      const int code = e.code() & 0xff;
      if (code != SQLITE_BUSY && code != SQLITE_LOCKED) throw;
      if (attempt == 1 || attempt % 10 == 0) {
        std::fprintf(stderr, "splat: store %s is locked by another process; waiting (%s)\n",
                     path_.c_str(), e.what());
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
}

Database& Store::reader() {
  std::lock_guard lock(readers_mutex_);
  auto& slot = readers_[std::this_thread::get_id()];
  if (!slot) {
    slot = std::make_unique<Database>(path_, 30000, read_only_, immutable_);
    slot->exec("PRAGMA foreign_keys = ON");
  }
  return *slot;
}

namespace {

std::int64_t open_campaign_in(Database& db, const CampaignRecord& c) {
  Statement find = db.prepare("SELECT id FROM campaigns WHERE spec_hash = ?");
  find.bind(1, c.spec_hash);
  if (find.step()) {
    const std::int64_t id = find.int64(0);
    db.prepare(
          "UPDATE campaigns SET state = 'active', finished_at = NULL, priority = ? WHERE id = ?")
        .bind(1, c.priority)
        .bind(2, id)
        .run();
    return id;
  }
  db.prepare(
        "INSERT INTO campaigns (name, spec_hash, spec, tags, executor, priority, state, "
        "created_at) VALUES (?, ?, ?, ?, ?, ?, 'active', ?)")
      .bind(1, c.name)
      .bind(2, c.spec_hash)
      .bind(3, c.spec)
      .bind(4, c.tags.empty() ? std::string("[]") : c.tags)
      .bind(5, c.executor)
      .bind(6, c.priority)
      .bind(7, unix_now())
      .run();
  return db.last_insert_rowid();
}

AddPointsStats add_points_in(Database& db, std::int64_t campaign_id,
                             const std::vector<NewPoint>& points, bool rerun) {
  AddPointsStats stats;
  Statement prio = db.prepare("SELECT priority FROM campaigns WHERE id = ?");
  prio.bind(1, campaign_id);
  if (!prio.step()) throw std::invalid_argument("no campaign " + std::to_string(campaign_id));
  const int priority = static_cast<int>(prio.int64(0));
  Statement has_point = db.prepare(
      "SELECT 1 FROM campaign_points WHERE campaign_id = ? AND params_key = ? AND velocity = ?");
  Statement job_state = db.prepare("SELECT state FROM jobs WHERE hash = ?");
  Statement insert_job = db.prepare(
      "INSERT INTO jobs (hash, scene, solver_version, state, priority, created_at) "
      "VALUES (?, ?, ?, 'queued', ?, ?)");
  Statement requeue = db.prepare(
      "UPDATE jobs SET state = 'queued', attempts = 0, exit_reason = ?, owner = '', "
      "priority = MAX(priority, ?) WHERE hash = ?");
  Statement drop_result = db.prepare("DELETE FROM results WHERE job_hash = ?");
  Statement insert_point = db.prepare(
      "INSERT INTO campaign_points (campaign_id, params_key, params, velocity, job_hash, "
      "origin) VALUES (?, ?, ?, ?, ?, ?)");
  const double now = unix_now();
  for (const NewPoint& np : points) {
    const CampaignPoint& p = np.point;
    has_point.reset();
    has_point.bind(1, campaign_id).bind(2, p.params_key).bind(3, p.velocity);
    const bool linked = has_point.step();
    job_state.reset();
    job_state.bind(1, p.job_hash);
    if (!job_state.step()) {
      insert_job.reset();
      insert_job.bind(1, p.job_hash)
          .bind(2, np.scene)
          .bind(3, np.solver_version)
          .bind(4, priority)
          .bind(5, now)
          .run();
      ++stats.jobs_created;
    } else {
      const JobState st = job_state_from_string(job_state.text(0));
      const bool again = (rerun && is_terminal(st)) || st == JobState::cancelled;
      if (again) {
        drop_result.reset();
        drop_result.bind(1, p.job_hash).run();
        requeue.reset();
        requeue.bind(1, rerun ? "rerun requested" : "requeued after cancellation")
            .bind(2, priority)
            .bind(3, p.job_hash)
            .run();
        ++stats.jobs_requeued;
      } else if (!linked) {
        ++stats.jobs_reused;
      }
    }
    if (!linked) {
      insert_point.reset();
      insert_point.bind(1, campaign_id)
          .bind(2, p.params_key)
          .bind(3, p.params)
          .bind(4, p.velocity)
          .bind(5, p.job_hash)
          .bind(6, p.origin)
          .run();
      ++stats.points_added;
    }
  }
  return stats;
}

// Every job of the campaign a stop left cancelled (grid and refinement
// points alike) goes back to the queue, its result dropped. Returns how many.
int requeue_cancelled_in(Database& db, std::int64_t campaign_id) {
  Statement cancelled = db.prepare(
      "SELECT DISTINCT j.hash FROM jobs j JOIN campaign_points p ON p.job_hash = j.hash "
      "WHERE p.campaign_id = ? AND j.state = 'cancelled'");
  cancelled.bind(1, campaign_id);
  std::vector<std::string> hashes;
  while (cancelled.step()) hashes.push_back(cancelled.text(0));
  Statement drop_result = db.prepare("DELETE FROM results WHERE job_hash = ?");
  Statement requeue = db.prepare(
      "UPDATE jobs SET state = 'queued', attempts = 0, owner = '', "
      "exit_reason = 'requeued after cancellation', "
      "priority = MAX(priority, (SELECT priority FROM campaigns WHERE id = ?)) WHERE hash = ?");
  for (const std::string& h : hashes) {
    drop_result.reset();
    drop_result.bind(1, h).run();
    requeue.reset();
    requeue.bind(1, campaign_id).bind(2, h).run();
  }
  return static_cast<int>(hashes.size());
}

}  // namespace

std::int64_t Store::open_campaign(const CampaignRecord& c) {
  std::int64_t id = 0;
  write([&](Database& db) { id = open_campaign_in(db, c); });
  return id;
}

OpenedCampaign Store::open_campaign(const CampaignRecord& c, const std::vector<NewPoint>& points,
                                    bool rerun, const std::optional<SubmissionKey>& key) {
  OpenedCampaign out;
  write([&](Database& db) {
    if (key) {
      Statement known = db.prepare(
          "SELECT body_hash, campaign_id FROM submissions WHERE key = ? AND "
          "created_at >= ?");
      known.bind(1, key->key).bind(2, unix_now() - k_submission_key_seconds);
      if (known.step()) {
        if (known.text(0) != key->body_hash) throw SubmissionKeyReused(key->key);
        out.id = known.int64(1);
        out.replayed = true;
        return;
      }
    }
    out.id = open_campaign_in(db, c);
    out.points = add_points_in(db, out.id, points, rerun);
    out.points.jobs_requeued += requeue_cancelled_in(db, out.id);
    if (key) {
      const double now = unix_now();
      db.prepare("DELETE FROM submissions WHERE created_at < ? OR key = ?")
          .bind(1, now - k_submission_key_seconds)
          .bind(2, key->key)
          .run();
      db.prepare(
            "INSERT INTO submissions (key, body_hash, campaign_id, created_at) VALUES (?, ?, ?, ?)")
          .bind(1, key->key)
          .bind(2, key->body_hash)
          .bind(3, out.id)
          .bind(4, now)
          .run();
    }
  });
  return out;
}

AddPointsStats Store::add_points(std::int64_t campaign_id, const std::vector<NewPoint>& points,
                                 bool rerun) {
  AddPointsStats stats;
  write([&](Database& db) { stats = add_points_in(db, campaign_id, points, rerun); });
  return stats;
}

std::optional<JobRecord> Store::claim_next_job(std::int64_t campaign_id, const std::string& owner,
                                               const std::string& host) {
  std::optional<JobRecord> out;
  write([&](Database& db) {
    Statement pick = db.prepare(
        "SELECT j.hash FROM jobs j JOIN campaign_points p ON p.job_hash = j.hash "
        "WHERE p.campaign_id = ? AND j.state = 'queued' "
        "ORDER BY j.priority DESC, p.rowid LIMIT 1");
    pick.bind(1, campaign_id);
    if (!pick.step()) return;
    const std::string hash = pick.text(0);
    db.prepare(
          "UPDATE jobs SET state = 'running', attempts = attempts + 1, started_at = ?, "
          "finished_at = NULL, host = ?, owner = ? WHERE hash = ? AND state = 'queued'")
        .bind(1, unix_now())
        .bind(2, host)
        .bind(3, owner)
        .bind(4, hash)
        .run();
    Statement get =
        db.prepare(std::string("SELECT ") + k_job_columns + " FROM jobs WHERE hash = ?");
    get.bind(1, hash);
    get.step();
    out = read_job(get);
  });
  return out;
}

void Store::finish_job(const std::string& hash, JobState state, const std::string& exit_reason,
                       std::optional<double> wall_seconds, std::optional<int> threads,
                       const std::optional<ResultRecord>& result) {
  write([&](Database& db) {
    db.prepare(
          "UPDATE jobs SET state = ?, exit_reason = ?, finished_at = ?, wall_seconds = ?, "
          "threads = ?, owner = '' WHERE hash = ?")
        .bind(1, to_string(state))
        .bind(2, exit_reason)
        .bind(3, unix_now())
        .bind(4, wall_seconds)
        .bind(5, threads)
        .bind(6, hash)
        .run();
    if (result) {
      db.prepare(
            "INSERT OR REPLACE INTO results (job_hash, outcome, reason, summary, hdf5_path, "
            "created_at) VALUES (?, ?, ?, ?, ?, ?)")
          .bind(1, hash)
          .bind(2, result->outcome)
          .bind(3, result->reason)
          .bind(4, result->summary)
          .bind(5, stored_result_path(folder_, result->hdf5_path))
          .bind(6, unix_now())
          .run();
    }
  });
}

void Store::requeue_job(const std::string& hash, const std::string& reason, bool attempt_counts) {
  write([&](Database& db) {
    db.prepare(
          "UPDATE jobs SET state = 'queued', exit_reason = ?, owner = '', "
          "attempts = CASE WHEN ? THEN attempts ELSE MAX(attempts - 1, 0) END WHERE hash = ?")
        .bind(1, reason)
        .bind(2, attempt_counts ? 1 : 0)
        .bind(3, hash)
        .run();
  });
}

int Store::recover_orphaned_jobs(const std::string& host, const std::string& own_owner,
                                 const std::function<bool(const std::string&)>& running_here) {
  int n = 0;
  write([&](Database& db) {
    Statement running =
        db.prepare("SELECT hash, owner FROM jobs WHERE state = 'running' AND owner LIKE ?");
    running.bind(1, host + ":%");
    std::vector<std::string> orphans;
    while (running.step()) {
      const std::string owner = running.text(1);
      const bool left_here = !own_owner.empty() && owner == own_owner && running_here &&
                             !running_here(running.text(0));
      if (left_here || !owner_alive(owner)) orphans.push_back(running.text(0));
    }
    // The job did not fail, its manager stopped: the attempt is given back,
    // as for a host failure (requeue_job), so that the job keeps its retries.
    Statement requeue = db.prepare(
        "UPDATE jobs SET state = 'queued', owner = '', attempts = MAX(attempts - 1, 0), "
        "exit_reason = 'requeued: its manager stopped while it ran' WHERE hash = ?");
    for (const std::string& h : orphans) {
      requeue.reset();
      requeue.bind(1, h).run();
    }
    n = static_cast<int>(orphans.size());
  });
  return n;
}

void Store::request_cancel(std::int64_t campaign_id) {
  write([&](Database& db) {
    db.prepare("UPDATE campaigns SET state = 'cancelling' WHERE id = ? AND state IN ('active')")
        .bind(1, campaign_id)
        .run();
  });
}

int Store::cancel_queued_jobs(std::int64_t campaign_id, const std::string& reason) {
  int n = 0;
  write([&](Database& db) {
    db.prepare(
          "UPDATE jobs SET state = 'cancelled', exit_reason = ?, finished_at = ? "
          "WHERE state = 'queued' AND hash IN "
          "(SELECT job_hash FROM campaign_points WHERE campaign_id = ?)")
        .bind(1, reason)
        .bind(2, unix_now())
        .bind(3, campaign_id)
        .run();
    n = db.changes();
  });
  return n;
}

void Store::set_campaign_state(std::int64_t campaign_id, CampaignState state) {
  write([&](Database& db) {
    const bool ended = state == CampaignState::cancelled || state == CampaignState::finished;
    db.prepare("UPDATE campaigns SET state = ?, finished_at = ? WHERE id = ?")
        .bind(1, to_string(state))
        .bind(2, ended ? std::optional<double>(unix_now()) : std::nullopt)
        .bind(3, campaign_id)
        .run();
  });
}

void Store::store_windows(std::int64_t campaign_id, const std::vector<WindowRecord>& windows) {
  write([&](Database& db) {
    db.prepare("DELETE FROM windows WHERE campaign_id = ?").bind(1, campaign_id).run();
    Statement ins = db.prepare(
        "INSERT INTO windows (campaign_id, params_key, params, critical_velocity, "
        "maximum_velocity, window, updated_at) VALUES (?, ?, ?, ?, ?, ?, ?)");
    const double now = unix_now();
    for (const WindowRecord& w : windows) {
      ins.reset();
      ins.bind(1, campaign_id)
          .bind(2, w.params_key)
          .bind(3, w.params)
          .bind(4, w.critical_velocity)
          .bind(5, w.maximum_velocity)
          .bind(6, w.window)
          .bind(7, now)
          .run();
    }
  });
}

std::optional<CampaignRecord> Store::campaign(std::int64_t id) {
  Statement s = reader().prepare(std::string("SELECT ") + k_campaign_columns +
                                 " FROM campaigns WHERE id = ?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_campaign_row(s);
}

std::vector<CampaignRecord> Store::campaigns() {
  Statement s =
      reader().prepare(std::string("SELECT ") + k_campaign_columns + " FROM campaigns ORDER BY id");
  std::vector<CampaignRecord> out;
  while (s.step()) out.push_back(read_campaign_row(s));
  return out;
}

std::optional<JobRecord> Store::job(const std::string& hash) {
  Statement s =
      reader().prepare(std::string("SELECT ") + k_job_columns + " FROM jobs WHERE hash = ?");
  s.bind(1, hash);
  if (!s.step()) return std::nullopt;
  return read_job(s);
}

std::optional<ResultRecord> Store::result(const std::string& job_hash) {
  Statement s = reader().prepare(
      "SELECT job_hash, outcome, reason, summary, hdf5_path, created_at FROM results "
      "WHERE job_hash = ?");
  s.bind(1, job_hash);
  if (!s.step()) return std::nullopt;
  return ResultRecord{
      s.text(0), s.text(1), s.text(2), s.text(3), result_path_from_store(folder_, s.text(4)),
      s.real(5)};
}

std::optional<Submission> Store::submission(const std::string& key) {
  Statement s = reader().prepare(
      "SELECT body_hash, campaign_id FROM submissions WHERE key = ? AND created_at >= ?");
  s.bind(1, key).bind(2, unix_now() - k_submission_key_seconds);
  if (!s.step()) return std::nullopt;
  return Submission{s.text(0), s.int64(1)};
}

std::vector<PointStatus> Store::points(std::int64_t campaign_id) {
  Statement s = reader().prepare(
      "SELECT p.params_key, p.params, p.velocity, p.job_hash, p.origin, j.state, r.outcome, "
      "j.exit_reason FROM campaign_points p JOIN jobs j ON j.hash = p.job_hash "
      "LEFT JOIN results r ON r.job_hash = p.job_hash WHERE p.campaign_id = ? "
      "ORDER BY p.params_key, p.velocity");
  s.bind(1, campaign_id);
  std::vector<PointStatus> out;
  while (s.step()) {
    PointStatus ps;
    ps.point = {s.text(0), s.text(1), s.real(2), s.text(3), s.text(4)};
    ps.state = job_state_from_string(s.text(5));
    ps.outcome = s.opt_text(6);
    ps.exit_reason = s.text(7);
    out.push_back(std::move(ps));
  }
  return out;
}

int& JobCounts::of(JobState state) {
  switch (state) {
    case JobState::queued:
      return queued;
    case JobState::running:
      return running;
    case JobState::succeeded:
      return succeeded;
    case JobState::failed:
      return failed;
    case JobState::cancelled:
      return cancelled;
    case JobState::timed_out:
      return timed_out;
  }
  return queued;
}

JobCounts read_job_counts(Statement& grouped_by_state) {
  JobCounts c;
  while (grouped_by_state.step()) {
    c.of(job_state_from_string(grouped_by_state.text(0))) +=
        static_cast<int>(grouped_by_state.int64(1));
  }
  return c;
}

JobCounts Store::job_counts(std::int64_t campaign_id) {
  Statement s = reader().prepare(
      "SELECT j.state, COUNT(*) FROM jobs j WHERE j.hash IN "
      "(SELECT job_hash FROM campaign_points WHERE campaign_id = ?) GROUP BY j.state");
  s.bind(1, campaign_id);
  return read_job_counts(s);
}

int Store::refinement_points_count(std::int64_t campaign_id) {
  Statement s = reader().prepare(
      "SELECT COUNT(*) FROM campaign_points WHERE campaign_id = ? AND origin = 'refine'");
  s.bind(1, campaign_id);
  s.step();
  return static_cast<int>(s.int64(0));
}

std::vector<ParameterSetLoad> Store::parameter_set_loads(std::int64_t campaign_id) {
  Statement s = reader().prepare(
      "SELECT cp.params_key, MIN(cp.params), "
      "SUM(j.state IN ('queued', 'running')), SUM(j.wall_seconds IS NOT NULL), "
      "TOTAL(j.wall_seconds) FROM campaign_points cp JOIN jobs j ON j.hash = cp.job_hash "
      "WHERE cp.campaign_id = ? GROUP BY cp.params_key ORDER BY cp.params_key");
  s.bind(1, campaign_id);
  std::vector<ParameterSetLoad> out;
  while (s.step()) {
    out.push_back(
        {s.text(1), static_cast<int>(s.int64(2)), static_cast<int>(s.int64(3)), s.real(4)});
  }
  return out;
}

std::vector<WindowRecord> Store::windows(std::int64_t campaign_id) {
  Statement s = reader().prepare(
      "SELECT campaign_id, params_key, params, critical_velocity, maximum_velocity, window "
      "FROM windows WHERE campaign_id = ? ORDER BY params_key");
  s.bind(1, campaign_id);
  std::vector<WindowRecord> out;
  while (s.step()) {
    out.push_back({s.int64(0), s.text(1), s.text(2), s.opt_real(3), s.opt_real(4), s.text(5)});
  }
  return out;
}

}  // namespace splat::campaign
