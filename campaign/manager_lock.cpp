#include "campaign/manager_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include "campaign/process.hpp"

namespace splat::campaign {
namespace {

struct Held {
  int fd = -1;
  int users = 0;
  pid_t pid = 0;  // the process that took it (a forked child holds nothing)
};

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}

std::map<std::filesystem::path, Held>& registry() {
  static std::map<std::filesystem::path, Held> held;
  return held;
}

std::string read_owner(int fd) {
  char buf[256] = {};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string("unknown");
}

int take(const std::filesystem::path& lock_file, const std::filesystem::path& store_file) {
  const int fd = open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw std::runtime_error("cannot open the manager lock " + lock_file.string() + ": " +
                             std::strerror(errno));
  }
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const std::string owner = read_owner(fd);
    close(fd);
    throw std::runtime_error("another splat process (" + owner +
                             ") is managing campaigns on the store " + store_file.string() +
                             ": wait for it to end (or stop it), or use another --db");
  }
  const std::string me = this_process_owner();
  // The owner text only serves a second process's message: not writing it
  // is no error.
  const bool recorded = ftruncate(fd, 0) == 0 &&
                        pwrite(fd, me.data(), me.size(), 0) == static_cast<ssize_t>(me.size());
  static_cast<void>(recorded);
  return fd;
}

}  // namespace

ManagerLock::ManagerLock(const std::filesystem::path& store_file)
    : key_(std::filesystem::absolute(store_file).lexically_normal()) {
  std::lock_guard guard(registry_mutex());
  Held& h = registry()[key_];
  if (h.pid != getpid()) h = Held{};
  if (h.users == 0) {
    try {
      h.fd = take(key_.string() + ".manager.lock", store_file);
      h.pid = getpid();
    } catch (...) {
      registry().erase(key_);
      throw;
    }
  }
  ++h.users;
}

ManagerLock::~ManagerLock() {
  std::lock_guard guard(registry_mutex());
  const auto it = registry().find(key_);
  if (it == registry().end() || --it->second.users > 0) return;
  close(it->second.fd);  // releases the flock
  registry().erase(it);
}

}  // namespace splat::campaign
