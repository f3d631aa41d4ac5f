#include "campaign/slurm.hpp"

#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "campaign/job_end.hpp"
#include "campaign/process.hpp"

namespace splat::campaign {

namespace fs = std::filesystem;

namespace {

// Run by Slurm for each array task. Arguments: jobs per task, the list of
// job folders, the job program, threads, time limit (s).
constexpr const char* k_task_script = R"(#!/bin/sh
# splat campaign array task (written by campaign/slurm.cpp): runs the jobs
# PER*TASK+1 .. PER*TASK+PER of LIST one after another, each under `timeout`,
# and leaves "EXIT_CODE START END" in the job's folder as exit_code.
per="$1"; list="$2"; program="$3"; threads="$4"; limit="$5"
first=$(( ${SLURM_ARRAY_TASK_ID:-0} * per + 1 ))
last=$(( first + per - 1 ))
sed -n "${first},${last}p" "$list" | while IFS= read -r dir; do
  start=$(date +%s.%N)
  timeout --kill-after=1 "$limit" "$program" run "$dir/scene.json" --json --out "$dir/out" \
    --threads "$threads" > "$dir/stdout.json" 2> "$dir/stderr.txt" < /dev/null
  code=$?
  end=$(date +%s.%N)
  printf '%s %s %s\n' "$code" "$start" "$end" > "$dir/exit_code.tmp"
  mv "$dir/exit_code.tmp" "$dir/exit_code"
done
)";

struct Submitted {
  JobRecord job;
  fs::path dir;
  int task = 0;
  bool done = false;
};

struct Command {
  int code = -1;
  std::string out;
  std::string err;
};

Command run_command(const std::vector<std::string>& argv, const fs::path& scratch) {
  ProcessSpec ps;
  ps.argv = argv;
  ps.stdout_file = scratch / "cmd.out";
  ps.stderr_file = scratch / "cmd.err";
  ps.time_limit = 120.0;
  const ProcessResult pr = run_process(ps);
  Command c;
  c.code = pr.end == ProcessEnd::exited ? pr.exit_code : -1;
  auto slurp = [](const fs::path& p) {
    std::ifstream f(p);
    std::string s((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    return s;
  };
  c.out = slurp(ps.stdout_file);
  c.err = pr.end == ProcessEnd::spawn_failed ? pr.error : slurp(ps.stderr_file);
  return c;
}

bool terminal_task_state(const std::string& s) {
  return s != "PENDING" && s != "RUNNING" && s != "CONFIGURING" && s != "COMPLETING" &&
         s != "SUSPENDED" && s != "REQUEUED" && s != "RESIZING" && s != "SIGNALING" &&
         s != "STAGE_OUT";
}

// The jobs this round claims, each with its folder and scene written.
std::vector<Submitted> claim_jobs(SlurmRound& r) {
  std::vector<Submitted> jobs;
  while (auto j = r.store.claim_next_job(r.campaign_id, r.owner, "slurm")) {
    Submitted s;
    s.dir = r.jobs_dir / j->hash;
    fs::create_directories(s.dir / "out");
    fs::remove(s.dir / "exit_code");
    std::ofstream(s.dir / "scene.json") << j->scene << "\n";
    s.job = std::move(*j);
    jobs.push_back(std::move(s));
  }
  return jobs;
}

// Slurm's state of each task of an array (squeue), or `unknown` when Slurm
// no longer knows the array (every task ended long ago).
struct TaskStates {
  std::map<int, std::string> state;
  bool unknown = false;
};

TaskStates query_tasks(const std::string& array_id, const fs::path& scratch) {
  const Command q = run_command(
      {"squeue", "--noheader", "--array", "--states=all", "--jobs=" + array_id, "--format=%K %T"},
      scratch);
  TaskStates t;
  if (q.code != 0) {
    t.unknown = q.err.find("Invalid job id") != std::string::npos;
    return t;
  }
  std::istringstream lines(q.out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream w(line);
    std::string task, state;
    if (!(w >> task >> state)) continue;
    try {
      t.state[std::stoi(task)] = state;
    } catch (...) {
      // "0-5%2" style lines of the pending part of the array
    }
  }
  return t;
}

// The end of a job whose task Slurm ended without an exit_code: Slurm's state.
JobEnd end_from_task_state(const std::string& state) {
  JobEnd e;
  if (state == "TIMEOUT") {
    e.state = JobState::timed_out;
    e.reason = "Slurm task ended TIMEOUT before the job finished";
  } else if (state == "CANCELLED") {
    e.state = JobState::cancelled;
    e.reason = "Slurm task was cancelled";
  } else {
    e.state = JobState::failed;
    e.reason = "Slurm task ended " + state + " without running the job to its end";
  }
  return e;
}

// One submitted array: its jobs packed into tasks (at most max_array_size
// tasks of `per` jobs), the files Slurm runs, and the watch of its jobs.
class SlurmArray {
 public:
  SlurmArray(SlurmRound& r, std::vector<Submitted> jobs) : r_(r), jobs_(std::move(jobs)) {
    const int n = static_cast<int>(jobs_.size());
    const int max_tasks = std::max(1, r.options.max_array_size);
    per_ = (n + max_tasks - 1) / max_tasks;
    tasks_ = (n + per_ - 1) / per_;
    for (int i = 0; i < n; ++i) jobs_[static_cast<std::size_t>(i)].task = i / per_;
    remaining_ = n;
  }

  // Writes the job list and the task script and calls sbatch; false (every
  // job recorded failed) when sbatch refuses.
  bool submit() {
    const auto stamp = std::chrono::duration_cast<std::chrono::milliseconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count();
    std::string name = "c";  // appended, not "c" + ...: GCC 12 warns falsely on that
    name += std::to_string(r_.campaign_id) + "-" + std::to_string(stamp);
    dir_ = r_.jobs_dir / "slurm" / name;
    fs::create_directories(dir_);
    const fs::path list = dir_ / "jobs.txt";
    {
      std::ofstream f(list);
      for (const Submitted& s : jobs_) f << fs::absolute(s.dir).string() << "\n";
    }
    const fs::path script = dir_ / "task.sh";
    std::ofstream(script) << k_task_script;
    fs::permissions(script, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                fs::perms::others_read | fs::perms::others_exec);
    const Command sub = run_command(sbatch_argv(script, list), dir_);
    if (sub.code != 0) {
      for (const Submitted& s : jobs_) {
        r_.store.finish_job(s.job.hash, JobState::failed, "sbatch failed: " + sub.err, std::nullopt,
                            std::nullopt, std::nullopt);
      }
      return false;
    }
    array_id_ = sub.out.substr(0, sub.out.find(';'));
    return true;
  }

  // Polls until every job has ended (false) or a cancel was asked (true:
  // the array is scancelled and its unfinished jobs recorded cancelled).
  bool watch() {
    for (;;) {
      if (r_.cancel_requested && r_.cancel_requested()) {
        cancel();
        return true;
      }
      for (Submitted& s : jobs_) {
        if (!s.done) ingest(s);
      }
      if (remaining_ == 0) return false;
      end_ended_tasks();
      if (remaining_ == 0) return false;
      std::this_thread::sleep_for(std::chrono::duration<double>(r_.options.poll_seconds));
    }
  }

 private:
  std::vector<std::string> sbatch_argv(const fs::path& script, const fs::path& list) const {
    const JobOptions& jo = r_.spec.job;
    const int minutes =
        static_cast<int>(std::ceil(per_ * (jo.time_limit + 2.0) / 60.0)) + 1;  // Slurm's unit
    std::vector<std::string> argv = {"sbatch",
                                     "--parsable",
                                     "--array=0-" + std::to_string(tasks_ - 1) + "%" +
                                         std::to_string(std::max(1, r_.options.throttle)),
                                     "--job-name=splat-c" + std::to_string(r_.campaign_id),
                                     "--output=" + (dir_ / "%A_%a.out").string(),
                                     "--time=" + std::to_string(minutes),
                                     "--cpus-per-task=" + std::to_string(jo.threads),
                                     "--chdir=" + dir_.string()};
    for (const std::string& a : r_.options.sbatch_args) argv.push_back(a);
    for (const std::string& a :
         {script.string(), std::to_string(per_), list.string(), fs::absolute(r_.program).string(),
          std::to_string(jo.threads), std::to_string(jo.time_limit)}) {
      argv.push_back(a);
    }
    return argv;
  }

  void end_job(Submitted& s, const JobEnd& e, std::optional<double> wall) {
    if (e.retry) {
      r_.store.requeue_job(s.job.hash, e.reason);
    } else {
      r_.store.finish_job(s.job.hash, e.state,
                          e.reason + " (Slurm " + array_id_ + "_" + std::to_string(s.task) + ")",
                          wall, e.threads ? e.threads : std::optional<int>(r_.spec.job.threads),
                          e.result);
    }
    s.done = true;
    --remaining_;
    if (r_.on_job_end) r_.on_job_end();
  }

  // A job whose exit_code file is there: the same interpretation as local.
  bool ingest(Submitted& s) {
    std::ifstream f(s.dir / "exit_code");
    int code = -1;
    double t0 = 0.0, t1 = 0.0;
    if (!(f >> code >> t0 >> t1)) return false;
    ProcessResult pr;
    pr.end = ProcessEnd::exited;
    pr.exit_code = code;
    if (code == 124 || code == 137) pr.end = ProcessEnd::timed_out;  // from `timeout`
    pr.wall_seconds = t1 - t0;
    end_job(s, interpret(s.job, pr, s.dir, r_.spec.job), pr.wall_seconds);
    return true;
  }

  void cancel() {
    run_command({"scancel", array_id_}, dir_);
    for (Submitted& s : jobs_) {
      if (s.done || ingest(s)) continue;
      JobEnd e;
      e.state = JobState::cancelled;
      e.reason = "cancelled (scancel of Slurm array " + array_id_ + ", recorded by the manager)";
      end_job(s, e, std::nullopt);
    }
  }

  // Tasks Slurm has ended: their jobs without an exit_code get Slurm's state.
  void end_ended_tasks() {
    const TaskStates t = query_tasks(array_id_, dir_);
    for (Submitted& s : jobs_) {
      if (s.done) continue;
      const auto it = t.state.find(s.task);
      const bool ended = t.unknown || (it != t.state.end() && terminal_task_state(it->second));
      if (!ended || ingest(s)) continue;
      end_job(s, end_from_task_state(t.unknown ? "UNKNOWN" : it->second), std::nullopt);
    }
  }

  SlurmRound& r_;
  std::vector<Submitted> jobs_;
  int per_ = 1;    // jobs per task
  int tasks_ = 1;  // tasks of the array
  int remaining_ = 0;
  fs::path dir_;  // the array's folder: job list, task script, Slurm's output
  std::string array_id_;
};

}  // namespace

SlurmRoundResult run_slurm_round(SlurmRound& r) {
  SlurmRoundResult out;
  std::vector<Submitted> jobs = claim_jobs(r);
  if (jobs.empty()) return out;
  const int n = static_cast<int>(jobs.size());
  SlurmArray array(r, std::move(jobs));
  if (!array.submit()) return out;
  out.jobs_submitted = n;
  out.cancelled = array.watch();
  return out;
}

}  // namespace splat::campaign
