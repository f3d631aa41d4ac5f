// Child processes for jobs: started with fork + execv from an argument vector
// (never a shell), in their own process group, killed with the manager
// (PR_SET_PDEATHSIG), stdout and stderr sent to files. A crash, hang or
// memory blow-up of a job stays in the child.
#pragma once

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

namespace splat::campaign {

struct ProcessSpec {
  std::vector<std::string> argv;  // argv[0] is the program path
  std::filesystem::path stdout_file;
  std::filesystem::path stderr_file;
  double time_limit = 0.0;  // s; <= 0 = none
  // Set from outside to stop the child (SIGTERM, then SIGKILL after the grace time).
  const std::atomic<bool>* cancel = nullptr;
  double kill_grace = 1.0;  // s between SIGTERM and SIGKILL
  // "NAME=VALUE" entries set in the child's environment (the rest is
  // inherited; an entry replaces an inherited variable of the same name).
  std::vector<std::string> environment;
};

enum class ProcessEnd {
  exited,        // exit_code is valid
  signaled,      // killed by signal `signal` (not by us)
  timed_out,     // we stopped it at the time limit
  cancelled,     // we stopped it on request
  spawn_failed,  // could not start (see error)
};

struct ProcessResult {
  ProcessEnd end = ProcessEnd::spawn_failed;
  int exit_code = -1;
  int signal = 0;
  double wall_seconds = 0.0;
  std::string error;
};

// The path of a program name looked up in PATH (a name with a '/' is kept).
std::string find_program(const std::string& name);

// The path on disk of this process's executable, read anew at each call: a
// file renamed or rebuilt over it since this process started is the one
// named ("/proc/self/exe" when the path cannot be read).
std::filesystem::path this_executable();

// Runs the child to its end (blocking the calling thread). argv[0] without a
// '/' is looked up in PATH first.
ProcessResult run_process(const ProcessSpec& spec);

// "host:pid:start" of this process: start is the process start time from
// /proc, so a reused pid is not mistaken for a live manager.
std::string this_process_owner();
// Whether the process named by an owner string of this host still exists.
// Owners of other hosts count as alive (we cannot tell).
bool owner_alive(const std::string& owner);

}  // namespace splat::campaign
