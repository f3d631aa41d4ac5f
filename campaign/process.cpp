#include "campaign/process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>
#include <thread>

namespace splat::campaign {

namespace {

using clock = std::chrono::steady_clock;

double seconds_since(clock::time_point t0) {
  return std::chrono::duration<double>(clock::now() - t0).count();
}

// Field 22 of /proc/PID/stat (start time in clock ticks since boot); empty if
// the process does not exist.
std::string start_time_of(long pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(f, text)) return {};
  // The command name (field 2) is in parentheses and may hold spaces.
  const auto close = text.rfind(')');
  if (close == std::string::npos) return {};
  std::istringstream rest(text.substr(close + 2));
  std::string field;
  for (int i = 3; i <= 22 && (rest >> field); ++i) {
  }
  return field;
}

std::string local_host() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "localhost";
  return buf;
}

}  // namespace

std::string this_process_owner() {
  const long pid = static_cast<long>(getpid());
  return local_host() + ":" + std::to_string(pid) + ":" + start_time_of(pid);
}

bool owner_alive(const std::string& owner) {
  const auto a = owner.find(':');
  const auto b = owner.rfind(':');
  if (a == std::string::npos || a == b) return false;
  if (owner.substr(0, a) != local_host()) return true;
  long pid = 0;
  try {
    pid = std::stol(owner.substr(a + 1, b - a - 1));
  } catch (...) {
    return false;
  }
  const std::string start = start_time_of(pid);
  return !start.empty() && start == owner.substr(b + 1);
}

std::string find_program(const std::string& name) {
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string candidate = dirs.substr(start, end - start) + "/" + name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return name;
}

std::filesystem::path this_executable() {
  std::error_code ec;
  std::string path = std::filesystem::read_symlink("/proc/self/exe", ec).string();
  if (ec) return "/proc/self/exe";
  // The kernel appends this once the file this process started from is
  // removed or replaced (a rebuild): the path itself names the new file.
  constexpr std::string_view deleted = " (deleted)";
  if (path.ends_with(deleted)) path.resize(path.size() - deleted.size());
  return path;
}

ProcessResult run_process(const ProcessSpec& spec_in) {
  ProcessResult r;
  if (spec_in.argv.empty()) {
    r.error = "empty argument vector";
    return r;
  }
  ProcessSpec spec = spec_in;
  spec.argv[0] = find_program(spec.argv[0]);
  // Everything the child needs is prepared before fork: after fork in a
  // multi-threaded program only async-signal-safe calls are allowed.
  std::vector<char*> argv;
  for (const std::string& a : spec.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  // The inherited environment without the names spec.environment sets, then those.
  std::vector<char*> envp;
  for (char** e = environ; e && *e; ++e) {
    const std::string_view entry(*e);
    const std::string_view name = entry.substr(0, entry.find('='));
    const bool replaced =
        std::any_of(spec.environment.begin(), spec.environment.end(), [&](const std::string& s) {
          return s.size() > name.size() && s.compare(0, name.size(), name) == 0 &&
                 s[name.size()] == '=';
        });
    if (!replaced) envp.push_back(*e);
  }
  for (const std::string& s : spec.environment) envp.push_back(const_cast<char*>(s.c_str()));
  envp.push_back(nullptr);
  const int out_fd = open(spec.stdout_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int err_fd = open(spec.stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (out_fd < 0 || err_fd < 0) {
    r.error = "cannot open the job's output files in " + spec.stdout_file.parent_path().string() +
              ": " + std::strerror(errno);
    if (out_fd >= 0) close(out_fd);
    if (err_fd >= 0) close(err_fd);
    return r;
  }
  const pid_t parent = getpid();
  const auto t0 = clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    r.error = std::string("fork failed: ") + std::strerror(errno);
    close(out_fd);
    close(err_fd);
    return r;
  }
  if (pid == 0) {
    // Child: die with the thread that started us, own process group so the
    // whole job tree can be stopped, then exec.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    setpgid(0, 0);
    dup2(out_fd, STDOUT_FILENO);
    dup2(err_fd, STDERR_FILENO);
    const int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) dup2(devnull, STDIN_FILENO);
    execve(argv[0], argv.data(), envp.data());
    const char msg[] = "splat campaign: cannot execute the job program\n";
    ssize_t ignored = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)ignored;
    _exit(127);
  }
  setpgid(pid, pid);  // also from the parent, so the group exists before any kill
  close(out_fd);
  close(err_fd);

  enum class Stop { none, time_limit, cancel } stop = Stop::none;
  auto term_sent = clock::time_point{};
  bool killed = false;
  auto nap = std::chrono::microseconds(200);
  int status = 0;
  for (;;) {
    const pid_t w = waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) {
      r.error = std::string("waitpid failed: ") + std::strerror(errno);
      break;
    }
    if (stop == Stop::none) {
      if (spec.cancel && spec.cancel->load()) {
        stop = Stop::cancel;
      } else if (spec.time_limit > 0.0 && seconds_since(t0) > spec.time_limit) {
        stop = Stop::time_limit;
      }
      if (stop != Stop::none) {
        kill(-pid, SIGTERM);
        term_sent = clock::now();
      }
    } else if (!killed && seconds_since(term_sent) > spec.kill_grace) {
      kill(-pid, SIGKILL);
      killed = true;
    }
    // Short naps first (millisecond jobs), longer ones for long jobs.
    std::this_thread::sleep_for(nap);
    nap = std::min(nap * 2, std::chrono::microseconds(20000));
  }
  // Anything the job left behind in its group goes too.
  kill(-pid, SIGKILL);
  r.wall_seconds = seconds_since(t0);
  if (stop == Stop::time_limit) {
    r.end = ProcessEnd::timed_out;
  } else if (stop == Stop::cancel) {
    r.end = ProcessEnd::cancelled;
  } else if (WIFEXITED(status)) {
    r.end = ProcessEnd::exited;
    r.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    r.end = ProcessEnd::signaled;
    r.signal = WTERMSIG(status);
  }
  if (r.end == ProcessEnd::exited && r.exit_code == 127) {
    std::ifstream e(spec.stderr_file);
    std::string first;
    std::getline(e, first);
    if (first.rfind("splat campaign: cannot execute", 0) == 0) {
      r.end = ProcessEnd::spawn_failed;
      r.error = "cannot execute '" + spec.argv[0] + "'";
    }
  }
  return r;
}

}  // namespace splat::campaign
