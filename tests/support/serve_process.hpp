// `splat serve` as a child process for tests (the built SPLAT_BINARY unless
// another program is named): the port it prints, stopped by a signal,
// killed on scope exit.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace splat::test_support {

// A child `splat serve`; its stdout's first line gives the port.
class ServeProcess {
 public:
  explicit ServeProcess(std::vector<std::string> args, std::string program = SPLAT_BINARY) {
    int out[2];
    if (pipe(out) != 0) throw std::runtime_error("pipe");
    pid_ = fork();
    if (pid_ == 0) {
      dup2(out[1], STDOUT_FILENO);
      close(out[0]);
      close(out[1]);
      std::vector<char*> argv;
      argv.push_back(program.data());
      argv.push_back(const_cast<char*>("serve"));
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(program.c_str(), argv.data());
      _exit(127);
    }
    close(out[1]);
    out_ = fdopen(out[0], "r");
    char line[256] = {};
    if (out_ && std::fgets(line, sizeof line, out_)) {
      const std::string s = line;
      const auto colon = s.rfind(':');
      if (s.rfind("listening on http://", 0) == 0 && colon != std::string::npos) {
        port_ = std::stoi(s.substr(colon + 1));
      }
    }
  }
  ~ServeProcess() {
    if (pid_ > 0 && !exited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    if (out_) std::fclose(out_);
  }
  int port() const { return port_; }
  // Sends `sig` and waits up to `seconds` for the exit; returns the exit code
  // (-1 if it did not exit by itself in time, or died from a signal).
  int stop(int sig, double seconds) {
    kill(pid_, sig);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < deadline) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return -1;
  }
  int wait_exit() {
    int status = 0;
    waitpid(pid_, &status, 0);
    exited_ = true;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

 private:
  pid_t pid_ = -1;
  FILE* out_ = nullptr;
  int port_ = 0;
  bool exited_ = false;
};

}  // namespace splat::test_support
