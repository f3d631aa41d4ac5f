// The REST API server (`splat serve`): JSON under /api/v1 over the campaign
// store, the dashboard (web/) at /. Routes, limits and documents are listed
// in api/README.md; every response document has a schema in schemas/api_*.
//
// Threads: cpp-httplib's pool answers requests (each reads through its own
// store connection); the CampaignRunner runs campaigns; every write goes
// through the Store's writer thread.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "campaign/spec.hpp"

namespace splat::api {

struct ServerOptions {
  std::filesystem::path db;                        // the SQLite store
  std::string host = "127.0.0.1";                  // address to bind
  int port = 8080;                                 // 0 = the OS picks one
  int workers = 2;                                 // job slots of the runner
  std::optional<campaign::ExecutorKind> executor;  // overrides each spec's
  std::string token;                     // bearer token of mutating requests; empty = none
  std::filesystem::path web_dir;         // dashboard files; empty = no dashboard
  std::filesystem::path vendor_dir;      // npm packages served at /vendor/ (web/node_modules)
  std::filesystem::path job_program;     // empty = this executable
  std::size_t max_body_bytes = 1 << 20;  // request body limit, bytes
  int max_jobs_per_campaign = 5000;      // grid points + refinement budget
  int max_page_size = 500;
  int default_page_size = 50;
  bool run_campaigns = true;  // false: accept and store, never run (tests of the API alone)
};

constexpr int k_min_token_characters = 16;  // characters that are not spaces, -
constexpr int k_listen_backlog = 4096;      // connections waiting to be accepted, -

// Why a bearer token is too weak ("" when it is not): fewer than
// k_min_token_characters characters that are not white space.
std::string token_problem(const std::string& token);

// True for 127.0.0.0/8, ::1 and "localhost".
bool is_loopback_host(const std::string& host);

// Equal strings, in time that depends on neither content nor the position of
// the first difference (both sides are hashed to fixed-length digests first).
bool constant_time_equal(const std::string& a, const std::string& b);

class Server {
 public:
  // Opens the store. Throws std::invalid_argument for a non-loopback host
  // without a token and for a weak token (token_problem).
  explicit Server(ServerOptions options);
  ~Server();  // stop()
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Binds the socket; returns the port (the OS's choice when port = 0).
  // Throws std::runtime_error when the address cannot be bound.
  int bind();
  // Resumes the store's active campaigns and answers requests until stop().
  void serve();
  // Graceful: stops accepting, finishes the answers in flight, stops the
  // running campaign leaving its jobs resumable. Safe from any thread, twice.
  void stop();
  bool ready() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace splat::api
