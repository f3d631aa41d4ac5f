// Registration of the subcommands of `splat`. Each command file defines one
// register_* function that adds its CLI11 subcommand and the action to run
// when it was chosen; the action returns the process exit code.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <utility>
#include <vector>

#include "solver/core/thread_governor.hpp"

namespace splat::app {

using CommandTable = std::vector<std::pair<CLI::App*, std::function<int()>>>;

void register_materials(CLI::App& app, CommandTable& commands);
void register_mat_point(CLI::App& app, CommandTable& commands);
void register_run(CLI::App& app, CommandTable& commands);
void register_sweep(CLI::App& app, CommandTable& commands);
void register_windows(CLI::App& app, CommandTable& commands);
void register_regress(CLI::App& app, CommandTable& commands);
void register_serve(CLI::App& app, CommandTable& commands);
void register_converge(CLI::App& app, CommandTable& commands);
void register_window(CLI::App& app, CommandTable& commands);

// Throws std::invalid_argument naming --threads unless 0 <= threads <= the
// cores of this machine (splat::max_threads()).
void check_threads_option(int threads);

// --thread-policy adaptive|fixed (solver/core/thread_governor.hpp).
void add_thread_policy_option(CLI::App& sub, ThreadPolicy& policy);

inline void register_all(CLI::App& app, CommandTable& commands) {
  register_materials(app, commands);
  register_mat_point(app, commands);
  register_run(app, commands);
  register_sweep(app, commands);
  register_windows(app, commands);
  register_regress(app, commands);
  register_serve(app, commands);
  register_converge(app, commands);
  register_window(app, commands);
}

}  // namespace splat::app
