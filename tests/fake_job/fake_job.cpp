// A stand-in job program for the executor tests, called like
// `splat run SCENE.json --json --out DIR --threads N`. It is NOT physics: it
// does what the scene's "fake" block tells it, so the tests can make a job
// sleep, hang, crash, fail transiently or print a canned summary:
//   {"name": "x", "V0": 3.0, "fake": {
//      "sleep": 0.2,                 s before answering
//      "ignore_term": true,          ignore SIGTERM (must be SIGKILLed)
//      "segfault": true,             die by SIGSEGV
//      "exit": 5,                    exit with this code and no summary
//      "transient_failures": 2,      exit 75 on the first 2 attempts (counted in DIR)
//      "killed_attempts": 2,         die by SIGKILL on the first 2 attempts (as the OOM killer)
//      "garbage": true,              print text that is not JSON, exit 0
//      "outcome": "unstable",        outcome to report (default: from threshold)
//      "threshold": 2.5,             stick when V0 < threshold, else rebound
//      "write_bytes": 65536,         write a result file of this size in DIR
//      "log": "/tmp/x.log",          append "start DIR" / "end DIR" lines
//      "log_env": "NAME"}}           and "env NAME=VALUE" (or "env NAME unset")
// Like splat, it exits 74 (EX_IOERR) when its output cannot be written.
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

int main(int argc, char** argv) {
  if (argc < 3 || std::string(argv[1]) != "run") {
    std::fprintf(stderr, "usage: fake_job run SCENE.json --json --out DIR\n");
    return 2;
  }
  std::string out_dir = ".";
  for (int i = 3; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--out") out_dir = argv[i + 1];
  }
  nlohmann::json scene;
  try {
    std::ifstream f(argv[2]);
    scene = nlohmann::json::parse(f);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fake_job: bad scene: %s\n", e.what());
    return 2;
  }
  const nlohmann::json fake = scene.value("fake", nlohmann::json::object());
  const std::string log = fake.value("log", "");
  auto note = [&](const char* what) {
    if (log.empty()) return;
    std::ofstream(log, std::ios::app) << what << " " << out_dir << "\n";
  };
  note("start");
  const std::string env_name = fake.value("log_env", "");
  if (!log.empty() && !env_name.empty()) {
    const char* value = std::getenv(env_name.c_str());
    std::ofstream(log, std::ios::app)
        << "env " << env_name << (value ? "=" + std::string(value) : std::string(" unset")) << "\n";
  }
  if (fake.value("ignore_term", false)) std::signal(SIGTERM, SIG_IGN);
  const int transient = fake.value("transient_failures", 0);
  const int killed = fake.value("killed_attempts", 0);
  if (transient > 0 || killed > 0) {
    const std::string counter = out_dir + "/attempts";
    int n = 0;
    std::ifstream(counter) >> n;
    std::ofstream(counter) << n + 1;
    if (n < transient) {
      std::fprintf(stderr, "fake_job: transient failure %d\n", n + 1);
      return 75;
    }
    if (n < killed) std::raise(SIGKILL);
  }
  const double sleep_s = fake.value("sleep", 0.0);
  if (sleep_s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(sleep_s));
  if (fake.value("segfault", false)) std::raise(SIGSEGV);
  if (fake.contains("exit")) {
    std::fprintf(stderr, "fake_job: told to exit %d\n", fake["exit"].get<int>());
    return fake["exit"].get<int>();
  }
  if (fake.value("garbage", false)) {
    std::printf("this is not a summary\n");
    return 0;
  }
  const auto cannot_write = [](const std::string& what) {
    std::fprintf(stderr, "fake_job: cannot write %s: %s\n", what.c_str(), std::strerror(errno));
    return 74;
  };
  if (const long bytes = fake.value("write_bytes", 0L); bytes > 0) {
    const std::string file = out_dir + "/result.bin";
    std::FILE* f = std::fopen(file.c_str(), "w");
    if (f == nullptr) return cannot_write(file);
    const std::string block(std::size_t(bytes), 'r');
    const bool written = std::fwrite(block.data(), 1, block.size(), f) == block.size();
    if (std::fclose(f) != 0 || !written) return cannot_write(file);
  }
  std::string outcome = fake.value("outcome", "");
  if (outcome.empty()) {
    outcome = scene.value("V0", 0.0) < fake.value("threshold", 0.0) ? "stick" : "rebound";
  }
  const nlohmann::json summary = {{"solver_version", "fake"},
                                  {"scene", scene.value("name", "fake")},
                                  {"outcome", outcome},
                                  {"reason", "canned by fake_job"},
                                  {"threads", 1},
                                  {"output", {{"hdf5", nullptr}, {"xdmf", nullptr}}}};
  std::printf("%s\n", summary.dump(2).c_str());
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) return cannot_write("the standard output");
  note("end");
  const bool done = outcome == "stick" || outcome == "rebound" || outcome == "finished";
  return done ? 0 : 3;
}
