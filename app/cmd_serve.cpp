// splat serve --db FILE [--host 127.0.0.1] [--port 8080] [--workers N]
//             [--executor local|slurm] [--token-file F] [--web-dir DIR]
// The REST API (/api/v1, api/README.md) and the dashboard (/) over one
// campaign store, running submitted campaigns with the same executors as
// `splat sweep`. Binds to loopback unless told otherwise; a non-loopback
// address needs --token-file (mutating requests then need
// `Authorization: Bearer <token>`). Prints "listening on http://HOST:PORT"
// on stdout once it accepts connections (--port 0: the OS picks the port).
// SIGINT/SIGTERM stop it gracefully: answers in flight finish, the running
// campaign's jobs are stopped and left to resume on the next start.
// Exit code 0 after a clean stop, 2 for bad options.
#include <pthread.h>
#include <signal.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "api/server.hpp"
#include "app/commands.hpp"

#ifndef SPLAT_WEB_DIR
#define SPLAT_WEB_DIR ""
#endif

namespace splat::app {

namespace {

struct ServeOptions {
  std::string db = "splat.db";
  std::string host = "127.0.0.1";
  int port = 8080;
  int workers = 2;
  std::string executor;
  std::string token_file;
  std::string web_dir = SPLAT_WEB_DIR;
  std::string job_program;
  int max_jobs = 5000;
  std::size_t max_body = std::size_t(1) << 20;
};

std::string read_token(const std::string& file) {
  std::ifstream f(file);
  if (!f) throw std::runtime_error("cannot read the token file " + file);
  std::string t((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const auto space = [](char ch) { return std::isspace(static_cast<unsigned char>(ch)) != 0; };
  while (!t.empty() && space(t.back())) t.pop_back();
  t.erase(t.begin(), std::find_if_not(t.begin(), t.end(), space));
  if (const std::string why = api::token_problem(t); !why.empty()) {
    throw std::runtime_error("the token in " + file + " is too weak: " + why);
  }
  return t;
}

int run_serve(const ServeOptions& o) {
  api::ServerOptions so;
  so.db = o.db;
  so.host = o.host;
  so.port = o.port;
  so.workers = o.workers;
  so.executor = parse<campaign::ExecutorKind>(o.executor);  // "": each campaign's
  if (!o.token_file.empty()) so.token = read_token(o.token_file);
  if (!o.web_dir.empty()) {
    so.web_dir = o.web_dir;
    so.vendor_dir = std::filesystem::path(o.web_dir) / "node_modules";
  }
  if (!o.job_program.empty()) so.job_program = o.job_program;
  so.max_jobs_per_campaign = o.max_jobs;
  so.max_body_bytes = o.max_body;

  // SIGINT/SIGTERM are taken by a thread that waits for them (sigwait), so
  // the graceful stop runs outside a signal handler. Blocked before any
  // other thread starts so that every thread inherits the mask.
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);

  api::Server server(so);
  const int port = server.bind();
  std::thread waiter([&server, set] {
    int sig = 0;
    sigwait(&set, &sig);
    std::fprintf(stderr, "splat serve: signal %d, stopping\n", sig);
    server.stop();
  });
  std::printf("listening on http://%s:%d\n", o.host.c_str(), port);
  std::fflush(stdout);
  server.serve();
  server.stop();
  // The waiter may still be waiting when the server stopped by itself.
  pthread_kill(waiter.native_handle(), SIGTERM);
  waiter.join();
  std::fprintf(stderr, "splat serve: stopped\n");
  return 0;
}

}  // namespace

void register_serve(CLI::App& app, CommandTable& commands) {
  auto o = std::make_shared<ServeOptions>();
  CLI::App* sub = app.add_subcommand("serve", "Serve the REST API and the dashboard over a store");
  sub->add_option("--db", o->db, "SQLite store")->capture_default_str();
  sub->add_option("--host", o->host, "Address to listen on")->capture_default_str();
  sub->add_option("--port", o->port, "Port (0 = any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  sub->add_option("--workers", o->workers, "Jobs run at once")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--executor", o->executor, "local or slurm (default: each campaign's)")
      ->check(CLI::IsMember(all_names<campaign::ExecutorKind>()));
  sub->add_option("--token-file", o->token_file,
                  "File holding the bearer token that mutating requests must carry");
  sub->add_option("--web-dir", o->web_dir, "Dashboard folder (web/ after `npm ci`)")
      ->capture_default_str();
  sub->add_option("--job-program", o->job_program,
                  "Program run for each job (default: this splat)");
  sub->add_option("--max-jobs", o->max_jobs, "Most jobs (grid + refinement budget) per campaign")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--max-body", o->max_body, "Largest request body, bytes")->capture_default_str();
  commands.emplace_back(sub, [o] { return run_serve(*o); });
}

}  // namespace splat::app
