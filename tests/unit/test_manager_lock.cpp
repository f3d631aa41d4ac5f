// One manager process per store (campaign/manager_lock.hpp): a second
// process is refused with the holder named; managers within one process
// share the lock; the lock goes with its holder.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stdexcept>
#include <string>

#include "campaign/manager_lock.hpp"
#include "support/temp_dir.hpp"

namespace splat::campaign {
namespace {

// Exit code of a forked child that tries to take the lock of `store`:
// 0 taken, 1 refused with a message naming another process, 2 otherwise.
int child_tries(const std::filesystem::path& store) {
  const pid_t pid = fork();
  if (pid == 0) {
    int code = 2;
    try {
      const ManagerLock lock(store);
      code = 0;
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      code = what.find("another splat process") != std::string::npos &&
                     what.find(store.string()) != std::string::npos
                 ? 1
                 : 2;
    }
    _exit(code);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(manager_lock, a_second_process_is_refused_while_the_first_manages) {
  const test_support::TempDir dir("manager_lock");
  const std::filesystem::path store = dir.path / "campaign.db";
  {
    const ManagerLock first(store);
    const ManagerLock same_process(store);  // the server's second campaign
    EXPECT_EQ(child_tries(store), 1);
  }
  EXPECT_EQ(child_tries(store), 0);  // released with its holder
  EXPECT_EQ(child_tries(dir.path / "other.db"), 0);
}

}  // namespace
}  // namespace splat::campaign
