// One campaign manager process per store. Two managers on one store each
// bisect the same brackets and add the same refinement jobs twice, and each
// takes the other's running jobs for its own; a second process that tries to
// manage campaigns on a store gets a clear error instead. The lock is an
// advisory flock(2) on STORE.manager.lock, released by the kernel when the
// process ends (kill -9 included); the file holds the owner's host:pid.
// Within one process any number of managers (the API server's campaigns)
// share it.
#pragma once

#include <filesystem>

namespace splat::campaign {

class ManagerLock {
 public:
  // Takes (or shares, within this process) the lock of `store_file`; throws
  // std::runtime_error naming the store and the process that holds it.
  explicit ManagerLock(const std::filesystem::path& store_file);
  ~ManagerLock();
  ManagerLock(const ManagerLock&) = delete;
  ManagerLock& operator=(const ManagerLock&) = delete;

 private:
  std::filesystem::path key_;
};

}  // namespace splat::campaign
