#include "campaign/slurm.hpp"

#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

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

}  // namespace

SlurmRoundResult run_slurm_round(SlurmRound& r) {
  SlurmRoundResult out;
  const JobOptions& jo = r.spec.job;
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
  if (jobs.empty()) return out;

  // Pack: at most max_array_size tasks, `per` jobs in each.
  const int n = static_cast<int>(jobs.size());
  const int max_tasks = std::max(1, r.options.max_array_size);
  const int per = (n + max_tasks - 1) / max_tasks;
  const int tasks = (n + per - 1) / per;
  for (int i = 0; i < n; ++i) jobs[static_cast<std::size_t>(i)].task = i / per;

  const auto stamp = std::chrono::duration_cast<std::chrono::milliseconds>(
                         std::chrono::system_clock::now().time_since_epoch())
                         .count();
  const fs::path slurm_dir =
      r.jobs_dir / "slurm" / ("c" + std::to_string(r.campaign_id) + "-" + std::to_string(stamp));
  fs::create_directories(slurm_dir);
  const fs::path list = slurm_dir / "jobs.txt";
  {
    std::ofstream f(list);
    for (const Submitted& s : jobs) f << fs::absolute(s.dir).string() << "\n";
  }
  const fs::path script = slurm_dir / "task.sh";
  std::ofstream(script) << k_task_script;
  fs::permissions(script, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                              fs::perms::others_read | fs::perms::others_exec);

  const int minutes =
      static_cast<int>(std::ceil(per * (jo.time_limit + 2.0) / 60.0)) + 1;  // Slurm's unit
  std::vector<std::string> argv = {"sbatch",
                                   "--parsable",
                                   "--array=0-" + std::to_string(tasks - 1) + "%" +
                                       std::to_string(std::max(1, r.options.throttle)),
                                   "--job-name=splat-c" + std::to_string(r.campaign_id),
                                   "--output=" + (slurm_dir / "%A_%a.out").string(),
                                   "--time=" + std::to_string(minutes),
                                   "--cpus-per-task=" + std::to_string(jo.threads),
                                   "--chdir=" + slurm_dir.string()};
  for (const std::string& a : r.options.sbatch_args) argv.push_back(a);
  for (const std::string& a :
       {script.string(), std::to_string(per), list.string(), fs::absolute(r.program).string(),
        std::to_string(jo.threads), std::to_string(jo.time_limit)}) {
    argv.push_back(a);
  }
  const Command sub = run_command(argv, slurm_dir);
  if (sub.code != 0) {
    for (const Submitted& s : jobs) {
      r.store.finish_job(s.job.hash, JobState::failed, "sbatch failed: " + sub.err, std::nullopt,
                         std::nullopt, std::nullopt);
    }
    return out;
  }
  const std::string array_id = sub.out.substr(0, sub.out.find(';'));
  out.jobs_submitted = n;

  int remaining = n;
  auto end_job = [&](Submitted& s, const JobEnd& e, std::optional<double> wall) {
    if (e.retry) {
      r.store.requeue_job(s.job.hash, e.reason);
    } else {
      r.store.finish_job(s.job.hash, e.state,
                         e.reason + " (Slurm " + array_id + "_" + std::to_string(s.task) + ")",
                         wall, e.threads ? e.threads : std::optional<int>(jo.threads), e.result);
    }
    s.done = true;
    --remaining;
    if (r.on_job_end) r.on_job_end();
  };
  // A job whose exit_code file is there: the same interpretation as local.
  auto ingest = [&](Submitted& s) {
    std::ifstream f(s.dir / "exit_code");
    int code = -1;
    double t0 = 0.0, t1 = 0.0;
    if (!(f >> code >> t0 >> t1)) return false;
    ProcessResult pr;
    pr.end = ProcessEnd::exited;
    pr.exit_code = code;
    if (code == 124 || code == 137) pr.end = ProcessEnd::timed_out;  // from `timeout`
    pr.wall_seconds = t1 - t0;
    end_job(s, interpret(s.job, pr, s.dir, jo), pr.wall_seconds);
    return true;
  };

  for (;;) {
    if (r.cancel_requested && r.cancel_requested()) {
      run_command({"scancel", array_id}, slurm_dir);
      for (Submitted& s : jobs) {
        if (s.done || ingest(s)) continue;
        JobEnd e;
        e.state = JobState::cancelled;
        e.reason = "cancelled (scancel of Slurm array " + array_id + ", recorded by the manager)";
        end_job(s, e, std::nullopt);
      }
      out.cancelled = true;
      return out;
    }
    for (Submitted& s : jobs) {
      if (!s.done) ingest(s);
    }
    if (remaining == 0) return out;
    // Tasks Slurm has ended: their jobs without an exit_code get Slurm's state.
    const Command q = run_command(
        {"squeue", "--noheader", "--array", "--states=all", "--jobs=" + array_id, "--format=%K %T"},
        slurm_dir);
    std::map<int, std::string> task_state;
    bool unknown = false;
    if (q.code == 0) {
      std::istringstream lines(q.out);
      for (std::string line; std::getline(lines, line);) {
        std::istringstream w(line);
        std::string task, state;
        if (w >> task >> state) {
          try {
            task_state[std::stoi(task)] = state;
          } catch (...) {
            // "0-5%2" style lines of the pending part of the array
          }
        }
      }
    } else {
      unknown = q.err.find("Invalid job id") != std::string::npos;
    }
    for (Submitted& s : jobs) {
      if (s.done) continue;
      const auto it = task_state.find(s.task);
      const bool ended = unknown || (it != task_state.end() && terminal_task_state(it->second));
      if (!ended || ingest(s)) continue;
      const std::string state = unknown ? "UNKNOWN" : it->second;
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
      end_job(s, e, std::nullopt);
    }
    if (remaining == 0) return out;
    std::this_thread::sleep_for(std::chrono::duration<double>(r.options.poll_seconds));
  }
}

}  // namespace splat::campaign
