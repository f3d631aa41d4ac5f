// Load test of the REST API (issue 7 target: at least 1000 window queries/s
// with p99 latency under 20 ms while a campaign runs). Loopback only and
// bounded: it starts its own `splat serve` (port picked by the OS, a fresh
// SQLite file in a temporary folder), runs one small campaign to the end so
// there are windows to query, submits a second, larger campaign that keeps
// running (real two-mass jobs on the server's worker slots), then C client
// threads (keep-alive connections) send GET /api/v1/campaigns/1/windows as
// fast as they can for D seconds or N requests in all, whichever comes first.
// Prints throughput and latency percentiles, checks that every answer was a
// 200 with the expected rows and that the campaign kept running throughout.
// Then a burst: --burst connections (200) opened at the same moment, one
// window query each; prints how many were answered, reset, or got a 5xx.
// Exits 1 when a target is missed (any reset or 5xx in the burst included).
//   bench_api_load [--clients 4] [--seconds 5] [--max-requests 50000] [--workers 1]
//                  [--burst 200]
#include <arpa/inet.h>
#include <httplib.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr double k_target_rate = 1000.0;  // window queries per second
constexpr double k_target_p99_ms = 20.0;  // ms

json two_mass_campaign(const std::string& name, double step) {
  const json scene = json::parse(R"({
    "name": "two_mass",
    "two_mass": {"M": 1.0, "m": 2.0, "k": 0.0, "V0": 1.0, "area": 1.0,
                 "adhesion": {"G_c": 0.2, "sigma_c": 0.5, "activation": {"rule": "none"},
                              "D_adh_max": null}},
    "time": {"end_time": 50.0},
    "output": {"history_interval": 0}
  })");
  return {{"name", name},
          {"base_scene", scene},
          {"velocity", {{"range", {{"from", 0.05}, {"to", 2.0}, {"step", step}}}}},
          {"G_c", {{"values", {0.1, 0.2, 0.4}}}},
          {"job", {{"time_limit", 60}, {"retries", 0}}}};
}

struct Serve {
  pid_t pid = -1;
  int port = 0;
};

Serve start_server(const fs::path& db, int workers) {
  int out[2];
  if (pipe(out) != 0) throw std::runtime_error("pipe");
  Serve s;
  s.pid = fork();
  if (s.pid == 0) {
    dup2(out[1], STDOUT_FILENO);
    close(out[0]);
    close(out[1]);
    const std::string db_s = db.string(), w = std::to_string(workers);
    execl(SPLAT_BINARY, SPLAT_BINARY, "serve", "--db", db_s.c_str(), "--port", "0", "--workers",
          w.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(out[1]);
  FILE* f = fdopen(out[0], "r");
  char line[256] = {};
  if (f && std::fgets(line, sizeof line, f)) {
    const char* colon = std::strrchr(line, ':');
    if (colon) s.port = std::atoi(colon + 1);
  }
  if (f) std::fclose(f);
  if (s.port <= 0) throw std::runtime_error("splat serve did not start");
  return s;
}

double percentile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const auto i = static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1) + 0.5);
  return sorted[std::min(i, sorted.size() - 1)];
}

int arg_int(int argc, char** argv, const char* name, int fallback) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) return std::atoi(argv[i + 1]);
  }
  return fallback;
}

struct BurstCounts {
  std::atomic<int> answered{0};       // a status line below 500
  std::atomic<int> resets{0};         // connection refused or reset
  std::atomic<int> resent{0};         // connect took >= 0.9 s: a dropped SYN was sent again
  std::atomic<int> server_errors{0};  // 5xx
  std::atomic<int> other{0};          // timeouts, short answers
};

// One GET on a fresh connection (raw socket: a reset is told apart from a
// timeout); the connection ends the answer.
void one_get(int port, const std::string& path, BurstCounts& counts) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  timeval tv{10, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string answer;
  int err = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const bool connected = connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  const bool slow = std::chrono::steady_clock::now() - t0 >= std::chrono::milliseconds(900);
  if (!connected) {
    err = errno;
  } else {
    const std::string req = "GET " + path + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n";
    if (send(fd, req.data(), req.size(), MSG_NOSIGNAL) < 0) err = errno;
    char buf[4096];
    for (ssize_t n; err == 0 && (n = recv(fd, buf, sizeof buf, 0)) != 0;) {
      if (n < 0) err = errno;
      if (n > 0) answer.append(buf, std::size_t(n));
    }
  }
  close(fd);
  if (slow) ++counts.resent;
  if (err == ECONNRESET || err == ECONNREFUSED || err == EPIPE) {
    ++counts.resets;
  } else if (answer.rfind("HTTP/1.1 ", 0) != 0) {
    ++counts.other;
  } else if (answer.compare(9, 1, "5") == 0) {
    ++counts.server_errors;
  } else {
    ++counts.answered;
  }
}

// `n` connections opened at the same moment; true when all were answered.
bool burst(int port, int n, const std::string& path) {
  BurstCounts counts;
  std::atomic<bool> go{false};
  std::vector<std::thread> threads;
  for (int i = 0; i < n; ++i) {
    threads.emplace_back([&] {
      while (!go.load()) std::this_thread::yield();
      one_get(port, path, counts);
    });
  }
  const auto start = Clock::now();
  go = true;
  for (std::thread& t : threads) t.join();
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  std::printf(
      "  burst           %d connections at once in %.0f ms: %d answered, %d reset, %d 5xx, "
      "%d other; %d connected only after a resent SYN (full listen queue)\n",
      n, ms, counts.answered.load(), counts.resets.load(), counts.server_errors.load(),
      counts.other.load(), counts.resent.load());
  return counts.answered == n && counts.resent == 0;
}

json get_json(httplib::Client& c, const std::string& path) {
  auto r = c.Get(path.c_str());
  if (!r || r->status != 200) throw std::runtime_error("GET " + path + " failed");
  return json::parse(r->body);
}

}  // namespace

int main(int argc, char** argv) {
  const int clients = arg_int(argc, argv, "--clients", 4);
  const int seconds = arg_int(argc, argv, "--seconds", 5);
  const int max_requests = arg_int(argc, argv, "--max-requests", 50000);
  const int workers = arg_int(argc, argv, "--workers", 1);
  const int burst_size = arg_int(argc, argv, "--burst", 200);

  std::random_device rd;
  const fs::path dir = fs::temp_directory_path() /
                       ("splat_api_load_" + std::to_string(getpid()) + "_" + std::to_string(rd()));
  fs::create_directories(dir);
  Serve server = start_server(dir / "store.db", workers);
  int status = 0;
  try {
    httplib::Client c("127.0.0.1", server.port);
    c.set_read_timeout(std::chrono::seconds(30));
    // 1. A finished campaign with windows: 40 velocities x 3 G_c = 120 jobs.
    auto r = c.Post("/api/v1/campaigns", two_mass_campaign("load-windows", 0.05).dump(),
                    "application/json");
    if (!r || r->status != 202) throw std::runtime_error("submit failed");
    const std::int64_t windows_id = json::parse(r->body)["id"];
    const std::string windows_path = "/api/v1/campaigns/" + std::to_string(windows_id);
    for (;;) {
      if (get_json(c, windows_path)["state"] == "finished") break;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    const std::size_t rows = get_json(c, windows_path + "/windows")["windows"].size();
    // 2. A campaign that keeps running during the load: 3 x 390 jobs.
    r = c.Post("/api/v1/campaigns", two_mass_campaign("load-running", 0.005).dump(),
               "application/json");
    if (!r || r->status != 202) throw std::runtime_error("submit failed");
    const std::string running_path = "/api/v1/campaigns/" + json::parse(r->body)["id"].dump();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const json before = get_json(c, running_path);

    // 3. The load.
    std::atomic<int> issued{0};
    std::atomic<int> bad{0};
    std::vector<std::vector<double>> latencies(static_cast<std::size_t>(clients));
    const auto start = Clock::now();
    const auto stop_at = start + std::chrono::seconds(seconds);
    const std::string query = windows_path + "/windows";
    std::vector<std::thread> threads;
    for (int t = 0; t < clients; ++t) {
      threads.emplace_back([&, t] {
        httplib::Client cl("127.0.0.1", server.port);
        cl.set_keep_alive(true);
        cl.set_tcp_nodelay(true);
        auto& lat = latencies[static_cast<std::size_t>(t)];
        while (Clock::now() < stop_at && issued.fetch_add(1) < max_requests) {
          const auto t0 = Clock::now();
          auto res = cl.Get(query.c_str());
          const auto t1 = Clock::now();
          lat.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
          if (!res || res->status != 200 || json::parse(res->body)["windows"].size() != rows) {
            ++bad;
          }
        }
      });
    }
    for (std::thread& th : threads) th.join();
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const json after = get_json(c, running_path);

    std::vector<double> all;
    for (const auto& l : latencies) all.insert(all.end(), l.begin(), l.end());
    std::sort(all.begin(), all.end());
    const double rate = static_cast<double>(all.size()) / elapsed;
    const int done_before = before["jobs"]["succeeded"];
    const int done_after = after["jobs"]["succeeded"];
    const bool campaign_ran = after["state"] == "active" && done_after > done_before;
    std::printf("api load: %zu window queries (%zu rows each) from %d clients in %.2f s\n",
                all.size(), rows, clients, elapsed);
    std::printf("  throughput      %.0f queries/s (target >= %.0f)\n", rate, k_target_rate);
    std::printf(
        "  latency ms      p50 %.3f  p90 %.3f  p99 %.3f  p99.9 %.3f  max %.3f (target p99 < "
        "%.0f)\n",
        percentile(all, 0.50), percentile(all, 0.90), percentile(all, 0.99), percentile(all, 0.999),
        all.empty() ? 0.0 : all.back(), k_target_p99_ms);
    std::printf(
        "  meanwhile       campaign '%s' ran %d jobs (%d -> %d succeeded of %d), state %s\n",
        after["name"].get<std::string>().c_str(), done_after - done_before, done_before, done_after,
        after["jobs"]["total"].get<int>(), after["state"].get<std::string>().c_str());
    std::printf("  bad answers     %d\n", bad.load());
    const bool burst_ok = burst(server.port, burst_size, query);
    const bool ok = rate >= k_target_rate && percentile(all, 0.99) < k_target_p99_ms && bad == 0 &&
                    campaign_ran && burst_ok;
    std::printf("  %s\n", ok ? "PASS" : "FAIL");
    status = ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "api load: %s\n", e.what());
    status = 2;
  }
  kill(server.pid, SIGTERM);
  waitpid(server.pid, nullptr, 0);
  std::error_code ec;
  fs::remove_all(dir, ec);
  return status;
}
