// splat: cold-spray single-particle impact simulator.
// One binary with subcommands; each subcommand lives in its own file and
// registers itself through app/commands.hpp.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "app/commands.hpp"
#include "solver/build_info.hpp"
#include "solver/common/omp_wait.hpp"

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
    return app.exit(e);
  }
  if (show_version) {
    std::printf("splat %s (commit %s)\n", std::string(splat::version()).c_str(),
                std::string(splat::git_commit()).c_str());
    const std::string policy = splat::omp_wait_policy_at_start();
    std::printf("OpenMP wait policy: %s\n", policy.empty() ? "libgomp default" : policy.c_str());
    return 0;
  }
  for (auto& [sub, run] : commands) {
    if (sub->parsed()) {
      try {
        return run();
      } catch (const std::exception& e) {
        std::fprintf(stderr, "splat %s: error: %s\n", sub->get_name().c_str(), e.what());
        return 2;
      }
    }
  }
  std::fputs(app.help().c_str(), stdout);
  return 0;
}
