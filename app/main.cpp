// splat: cold-spray single-particle impact simulator.
// One binary with subcommands; each subcommand lives in its own file and
// registers itself through app/commands.hpp.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <new>
#include <string>

#include "app/commands.hpp"
#include "campaign/manager.hpp"
#include "campaign/sqlite.hpp"
#include "solver/build_info.hpp"
#include "solver/common/omp_wait.hpp"
#include "solver/io/result_file.hpp"

namespace {

constexpr int k_exit_bad_input = 2;
constexpr int k_exit_output = 74;     // EX_IOERR (sysexits.h): output could not be written
constexpr int k_exit_transient = 75;  // EX_TEMPFAIL: may pass on another attempt

// Runs a subcommand; its errors end the process with a message and an exit
// code that says whose fault it was: the input's (2), the file system's (74:
// a full disk, a result file cut short) or the machine's memory (75).
int run_command(const std::string& name, const std::function<int()>& run) {
  const auto error = [&](const std::string& what, int code) {
    std::fprintf(stderr, "splat %s: error: %s\n", name.c_str(), what.c_str());
    return code;
  };
  int code = 0;
  try {
    code = run();
  } catch (const std::bad_alloc&) {
    return error(
        "out of memory (std::bad_alloc): the run needs more memory than this machine gives it; "
        "use fewer elements or particles (elements_across, spacing) or a larger machine",
        k_exit_transient);
  } catch (const splat::ResultFileError& e) {
    return error(std::string("cannot write the output: ") + e.what(), k_exit_output);
  } catch (const std::filesystem::filesystem_error& e) {
    return error(std::string("input/output: ") + e.what(), k_exit_output);
  } catch (const splat::campaign::RunStopped& e) {
    return error(e.what(), k_exit_output);
  } catch (const splat::campaign::SqliteError& e) {
    return error(std::string("the campaign store: ") + e.what(), k_exit_output);
  } catch (const std::exception& e) {
    return error(e.what(), k_exit_bad_input);
  }
  // Output printed to a full disk is lost without this check.
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    return error(std::string("cannot write the standard output: ") + std::strerror(errno),
                 k_exit_output);
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  // Threads that finish their share of a step sleep instead of spinning:
  // campaigns run several jobs per machine, where spinning threads of one job
  // steal the cores of the others. A user's own setting wins.
  splat::restart_with_passive_omp_wait(argv);
  CLI::App app{"splat: cold-spray particle impact simulator"};
  app.require_subcommand(0, 1);
  bool show_version = false;
  app.add_flag("--version", show_version, "Print the version and the git commit it was built from");

  splat::app::CommandTable commands;
  splat::app::register_all(app, commands);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the message; --help is not an error, anything else is
    // bad input (exit 2, as for a bad scene).
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (show_version) {
    std::printf("splat %s (commit %s)\n", std::string(splat::version()).c_str(),
                std::string(splat::git_commit()).c_str());
    const std::string policy = splat::omp_wait_policy_at_start();
    std::printf("OpenMP wait policy: %s\n", policy.empty() ? "libgomp default" : policy.c_str());
    return 0;
  }
  for (auto& [sub, run] : commands) {
    if (sub->parsed()) return run_command(sub->get_name(), run);
  }
  std::fputs(app.help().c_str(), stdout);
  return 0;
}
