// What the test programs share to run scenes: in process on one thread
// (the RunSummary), or as a command line the way users run splat (exit code
// and standard output).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "solver/core/run_summary.hpp"
#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"

namespace splat::test_support {

// Validates and resolves a scene document and runs it on one thread.
inline RunSummary run_scene(const nlohmann::json& doc) {
  const LoadedScene loaded = read_scene(doc);
  SimulationOptions options;
  options.threads = 1;
  Simulation sim(loaded.scene, loaded.resolved, options);
  return sim.run();
}

// The same, handing the simulation (its final state) and the summary to
// `inspect`.
template <class Inspect>
void run_scene_and_inspect(const nlohmann::json& doc, Inspect&& inspect) {
  const LoadedScene loaded = read_scene(doc);
  SimulationOptions options;
  options.threads = 1;
  Simulation sim(loaded.scene, loaded.resolved, options);
  const RunSummary s = sim.run();
  inspect(sim, s);
}

struct CommandOutput {
  int code = -1;  // exit code, -1 when the command could not start or was killed
  std::string stdout_text;
};

// Runs a shell command line (tests only) and collects its standard output.
inline CommandOutput run_command(const std::string& command) {
  CommandOutput out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) out.stdout_text.append(buf.data(), n);
  const int status = pclose(pipe);
  out.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

// Runs the built `splat ARGS`; its standard error joins the output when
// `with_stderr`, else it is dropped.
inline CommandOutput run_splat(const std::string& args, bool with_stderr = true) {
  return run_command(std::string(SPLAT_BINARY) + " " + args +
                     (with_stderr ? " 2>&1" : " 2>/dev/null"));
}

}  // namespace splat::test_support
