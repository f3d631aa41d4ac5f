#include "api/server.hpp"

#include <arpa/inet.h>
#include <httplib.h>
#include <sys/socket.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <deque>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <string_view>

#include "api/runner.hpp"
#include "campaign/queries.hpp"
#include "campaign/sha256.hpp"
#include "campaign/sqlite.hpp"
#include "campaign/store.hpp"
#include "campaign/window_rows.hpp"
#include "solver/build_info.hpp"
#include "solver/common/parallel.hpp"
#include "solver/input/material_io.hpp"
#include "solver/input/schema.hpp"
#include "solver/io/result_file.hpp"

namespace splat::api {

using nlohmann::json;
namespace fs = std::filesystem;

bool is_loopback_host(const std::string& host) {
  if (host == "localhost" || host == "::1" || host == "[::1]") return true;
  // Only a numeric IPv4 address in 127.0.0.0/8 ("127.example.org" is a name
  // that may resolve anywhere).
  in_addr a{};
  if (inet_pton(AF_INET, host.c_str(), &a) != 1) return false;
  return (ntohl(a.s_addr) >> 24) == 127;
}

bool constant_time_equal(const std::string& a, const std::string& b) {
  const std::string da = campaign::sha256_hex(a);
  const std::string db = campaign::sha256_hex(b);
  unsigned diff = 0;
  for (std::size_t i = 0; i < da.size(); ++i) {
    diff |= static_cast<unsigned>(static_cast<unsigned char>(da[i]) ^
                                  static_cast<unsigned char>(db[i]));
  }
  return diff == 0;
}

std::string token_problem(const std::string& token) {
  const auto visible = std::count_if(token.begin(), token.end(), [](char ch) {
    return !std::isspace(static_cast<unsigned char>(ch));
  });
  if (visible >= k_min_token_characters) return "";
  return "the token has " + std::to_string(visible) + " characters that are not spaces; at least " +
         std::to_string(k_min_token_characters) + " are needed";
}

namespace {

constexpr const char* k_prefix = "/api/v1";

// The offset of the first byte that does not continue valid UTF-8 (RFC 3629:
// no overlong forms, no surrogates, nothing above U+10FFFF).
std::optional<std::size_t> first_invalid_utf8(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    int more = 0;
    unsigned lo = 0x80, hi = 0xBF;  // range of the second byte
    if (c < 0x80) {
      more = 0;
    } else if (c >= 0xC2 && c <= 0xDF) {
      more = 1;
    } else if (c >= 0xE0 && c <= 0xEF) {
      more = 2;
      lo = c == 0xE0 ? 0xA0 : 0x80;
      hi = c == 0xED ? 0x9F : 0xBF;
    } else if (c >= 0xF0 && c <= 0xF4) {
      more = 3;
      lo = c == 0xF0 ? 0x90 : 0x80;
      hi = c == 0xF4 ? 0x8F : 0xBF;
    } else {
      return i;
    }
    for (int k = 1; k <= more; ++k) {
      if (i + std::size_t(k) >= s.size()) return i;
      const auto b = static_cast<unsigned char>(s[i + std::size_t(k)]);
      if (b < (k == 1 ? lo : 0x80) || b > (k == 1 ? hi : 0xBF)) return i;
    }
    i += std::size_t(more) + 1;
  }
  return std::nullopt;
}

bool starts_with_ignoring_case(const std::string& s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
  }
  return true;
}

constexpr std::size_t k_max_history_points = 2000;

// An error answered as an RFC 9457 problem document.
struct Problem {
  int status = 400;
  std::string slug;  // short machine name, e.g. "invalid-body"
  std::string title;
  std::string detail;
  json errors = json::array();  // [{"pointer": "/a/b", "detail": "..."}] or {"parameter": ...}
};

[[noreturn]] void fail(int status, std::string slug, std::string title, std::string detail,
                       json errors = json::array()) {
  throw Problem{status, std::move(slug), std::move(title), std::move(detail), std::move(errors)};
}

[[noreturn]] void key_reused() {
  fail(422, "idempotency-key-reused", "Idempotency-Key reused",
       "this Idempotency-Key was used with a different body");
}

json errors_of(const std::vector<SchemaViolation>& violations) {
  json e = json::array();
  for (const SchemaViolation& v : violations)
    e.push_back({{"pointer", v.pointer}, {"detail", v.message}});
  return e;
}

const char* reason_phrase(int status) {
  switch (status) {
    case 400:
      return "Bad Request";
    case 401:
      return "Unauthorized";
    case 403:
      return "Forbidden";
    case 404:
      return "Not Found";
    case 405:
      return "Method Not Allowed";
    case 409:
      return "Conflict";
    case 413:
      return "Content Too Large";
    case 415:
      return "Unsupported Media Type";
    case 422:
      return "Unprocessable Content";
    case 500:
      return "Internal Server Error";
    case 503:
      return "Service Unavailable";
    default:
      return "Error";
  }
}

void write_problem(const httplib::Request& req, httplib::Response& res, const Problem& p) {
  json doc = {{"type", p.slug.empty() ? std::string("about:blank") : "urn:splat:problem:" + p.slug},
              {"title", p.title.empty() ? std::string(reason_phrase(p.status)) : p.title},
              {"status", p.status},
              {"detail", p.detail},
              {"instance", req.path}};
  if (!p.errors.empty()) doc["errors"] = p.errors;
  res.status = p.status;
  // Paths and parameters echoed back may hold bytes that are not UTF-8.
  res.set_content(doc.dump(-1, ' ', false, json::error_handler_t::replace),
                  "application/problem+json");
}

std::string etag_of(const std::string& body) {
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on "\"" + s + "\"".
  std::string tag(1, '"');
  tag.append(campaign::sha256_hex(body), 0, 32);
  tag.push_back('"');
  return tag;
}

bool etag_matches(const std::string& if_none_match, const std::string& etag) {
  if (if_none_match.empty()) return false;
  if (if_none_match.find('*') != std::string::npos) return true;
  // A list of (possibly weak, W/"...") tags: the opaque part must appear.
  return if_none_match.find(etag) != std::string::npos;
}

// A 200 JSON answer with an ETag; 304 when the client already has it.
void reply_json(const httplib::Request& req, httplib::Response& res, const json& doc,
                int status = 200) {
  std::string body = doc.dump();
  if (status == 200) {
    const std::string etag = etag_of(body);
    res.set_header("ETag", etag);
    res.set_header("Cache-Control", "no-cache");
    if (etag_matches(req.get_header_value("If-None-Match"), etag)) {
      res.status = 304;
      return;
    }
  }
  res.status = status;
  res.set_content(std::move(body), "application/json");
}

std::optional<std::int64_t> parse_int(const std::string& s) {
  std::int64_t v = 0;
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, v);
  if (r.ec != std::errc() || r.ptr != end) return std::nullopt;
  return v;
}

json param_error(const std::string& name, const std::string& detail) {
  return json::array({{{"parameter", name}, {"detail", detail}}});
}

json header_error(const std::string& name, const std::string& detail) {
  return json::array({{{"header", name}, {"detail", detail}}});
}

json body_too_large(std::size_t limit) {
  return json::array(
      {{{"pointer", ""}, {"detail", "more than " + std::to_string(limit) + " bytes"}}});
}

// `application/json`, in any case, with or without parameters (charset).
bool is_json_media_type(const std::string& content_type) {
  std::string t = content_type.substr(0, content_type.find(';'));
  while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.pop_back();
  return t.size() == 16 && starts_with_ignoring_case(t, "application/json");
}

// A path parameter ({id}, {name}) that names nothing: 404 naming it.
[[noreturn]] void no_such(const std::string& parameter, const std::string& what) {
  fail(404, "not-found", "Not Found", "no " + what, param_error(parameter, "no " + what));
}

std::int64_t path_id(const httplib::Request& req) {
  const auto v = parse_int(req.matches[1]);
  if (!v || *v <= 0) no_such("id", "campaign " + std::string(req.matches[1]));
  return *v;
}

int page_size_of(const httplib::Request& req, const ServerOptions& o) {
  if (!req.has_param("page_size")) return o.default_page_size;
  const auto v = parse_int(req.get_param_value("page_size"));
  if (!v || *v < 1 || *v > o.max_page_size) {
    fail(400, "invalid-parameter", "Invalid query parameter",
         "page_size must be an integer from 1 to " + std::to_string(o.max_page_size),
         param_error("page_size",
                     "must be an integer from 1 to " + std::to_string(o.max_page_size)));
  }
  return static_cast<int>(*v);
}

// Page tokens are opaque to clients: a letter and a number.
std::int64_t page_token_of(const httplib::Request& req, char kind) {
  if (!req.has_param("page_token")) return 0;
  const std::string t = req.get_param_value("page_token");
  std::optional<std::int64_t> v;
  if (t.size() > 1 && t[0] == kind) v = parse_int(t.substr(1));
  if (!v || *v < 0) {
    fail(400, "invalid-parameter", "Invalid query parameter",
         "page_token is not one this server gave out",
         param_error("page_token", "not a token from a previous page"));
  }
  return *v;
}

json nullable(const std::optional<double>& v) {
  return v ? json(*v) : json(nullptr);
}

json counts_json(const campaign::JobCounts& c) {
  return {{"queued", c.queued}, {"running", c.running},     {"succeeded", c.succeeded},
          {"failed", c.failed}, {"cancelled", c.cancelled}, {"timed_out", c.timed_out},
          {"total", c.total()}};
}

// "particle/substrate" material names of a scene, or null when it has none
// (two-mass scenes) or they are inline documents.
json material_pair(const json& scene) {
  auto name = [](const json& m) -> std::optional<std::string> {
    if (m.is_string()) return m.get<std::string>();
    if (m.is_object() && m.contains("base") && m["base"].is_string()) {
      return m["base"].get<std::string>();
    }
    return std::nullopt;
  };
  if (scene.contains("particle_impact")) {
    const json& pi = scene["particle_impact"];
    const auto p = name(pi.value("/particle/material"_json_pointer, json()));
    if (!p) return nullptr;
    const json sub = pi.contains("substrate") ? pi["substrate"].value("material", json()) : json();
    const auto s = sub.is_null() ? p : name(sub);
    if (!s) return nullptr;
    return *p + "/" + *s;
  }
  if (scene.contains("bodies") && scene["bodies"].is_array()) {
    std::string out;
    for (const json& b : scene["bodies"]) {
      const auto n = name(b.value("material", json()));
      if (!n) return nullptr;
      out += (out.empty() ? "" : "/") + *n;
    }
    return out.empty() ? json(nullptr) : json(out);
  }
  return nullptr;
}

// A material named over the API that is no library material: refused, since
// a path would make the server read its own files.
SchemaViolation not_a_library_material(const std::string& pointer, const std::string& name) {
  return {pointer, "'" + name +
                       "' is no library material: over the API a material is a library name "
                       "(listed at /api/v1/materials) or an inline document; files cannot be "
                       "named"};
}

void check_materials_of(const json& doc, const std::string& prefix,
                        std::vector<SchemaViolation>& out) {
  for (const splat::MaterialReference& m : splat::non_library_materials(doc))
    out.push_back(not_a_library_material(prefix + m.pointer, m.name));
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The materials a `fields` value names, wherever the field's pointer puts it:
// at a material, at a material's base, or above them.
void check_field_materials(const json& fields, const std::set<std::string>& names,
                           std::vector<SchemaViolation>& out) {
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string ptr = fields[i]["pointer"].get<std::string>();
    const json& values = fields[i]["values"];
    for (std::size_t k = 0; k < values.size(); ++k) {
      const std::string at = "/fields/" + std::to_string(i) + "/values/" + std::to_string(k);
      const json& v = values[k];
      const bool at_material = ends_with(ptr, "/material");
      const bool has_base = v.is_object() && v.contains("base") && v["base"].is_string();
      if ((at_material || ends_with(ptr, "/material/base")) && v.is_string()) {
        const std::string name = v.get<std::string>();
        if (!names.count(name)) out.push_back(not_a_library_material(at, name));
      } else if (at_material && has_base) {
        const std::string name = v["base"].get<std::string>();
        if (!names.count(name)) out.push_back(not_a_library_material(at + "/base", name));
      } else {
        check_materials_of(v, at, out);
      }
    }
  }
}

bool inside(const fs::path& file, const fs::path& dir) {
  std::error_code ec;
  const fs::path f = fs::weakly_canonical(file, ec);
  if (ec) return false;
  const fs::path d = fs::weakly_canonical(dir, ec);
  if (ec) return false;
  const std::string fs_ = f.string(), ds = d.string() + "/";
  return fs_.rfind(ds, 0) == 0;
}

}  // namespace

// cpp-httplib 0.11 (Debian 12) listens with a backlog of 5, compiled into
// the library: a burst of connections overflows it (reset, or held back a
// second until the client sends its SYN again). listen() on the bound socket
// again sets the backlog (Linux).
class HttpServer : public httplib::Server {
 public:
  void raise_backlog() {
    if (::listen(svr_sock_, k_listen_backlog) != 0) {
      throw std::runtime_error(std::string("cannot set the listen backlog: ") +
                               std::strerror(errno));
    }
  }
};

struct Server::Impl {
  ServerOptions o;
  campaign::Store store;
  fs::path jobs_dir;
  CampaignRunner runner;
  HttpServer http;
  std::set<std::string> material_names;
  std::atomic<bool> bound{false};
  std::atomic<long long> requests{0};
  std::once_flag stopped;

  explicit Impl(ServerOptions opts)
      : o(std::move(opts)),
        store(o.db),
        jobs_dir(o.db.string() + ".jobs"),
        runner(store, RunnerOptions{o.workers, o.executor, o.job_program}) {
    for (const std::string& n : material_names_list()) material_names.insert(n);
    routes();
  }

  static std::vector<std::string> material_names_list() { return splat::material_names(); }

  // --- documents -------------------------------------------------------------

  json campaign_doc(const campaign::CampaignRecord& c, bool with_spec) {
    const campaign::JobCounts n = store.job_counts(c.id);
    const std::string self = std::string(k_prefix) + "/campaigns/" + std::to_string(c.id);
    json spec = json::parse(c.spec, nullptr, false);
    json doc = {{"id", c.id},
                {"name", c.name},
                {"description", spec.is_object() ? spec.value("description", "") : ""},
                {"tags", json::parse(c.tags, nullptr, false)},
                {"state", campaign::to_string(c.state)},
                {"executor", c.executor},
                {"priority", c.priority},
                {"spec_hash", c.spec_hash},
                {"material_pair",
                 spec.is_object() ? material_pair(spec.value("base_scene", json())) : json()},
                {"created_at", c.created_at},
                {"finished_at", c.finished_at > 0 ? json(c.finished_at) : json(nullptr)},
                {"jobs", counts_json(n)},
                {"refinement_jobs", store.refinement_points_count(c.id)},
                {"progress", n.total() > 0 ? double(n.finished()) / n.total() : 0.0},
                {"estimated_seconds_left", nullptr},
                {"running_now", runner.running() == c.id},
                {"links",
                 {{"self", self},
                  {"jobs", self + "/jobs"},
                  {"windows", self + "/windows"},
                  {"cancel", self + "/cancel"}}}};
    const int left = n.queued + n.running;
    if (left == 0 && c.state != campaign::CampaignState::active) {
      doc["estimated_seconds_left"] = 0.0;
    } else if (left > 0) {
      const campaign::CampaignTiming t = campaign::campaign_timing(store, c.id);
      if (t.timed_jobs > 0) {
        doc["estimated_seconds_left"] =
            t.wall_seconds / t.timed_jobs * left / std::max(1, o.workers);
      }
    }
    if (with_spec) doc["spec"] = spec;
    return doc;
  }

  campaign::CampaignRecord campaign_or_404(std::int64_t id) {
    auto c = store.campaign(id);
    if (!c) no_such("id", "campaign " + std::to_string(id));
    return *c;
  }

  // --- routes ----------------------------------------------------------------

  // A handler that answers every error as a problem document. `parameters`
  // lists the query parameters the route reads; any other one, or one given
  // twice, is refused (a misspelt filter would otherwise be ignored and
  // answer with everything). nullopt: not checked.
  template <class F>
  httplib::Server::Handler guarded(
      F f, std::optional<std::vector<std::string>> parameters = std::vector<std::string>{}) {
    return [this, f, parameters](const httplib::Request& req, httplib::Response& res) {
      ++requests;
      try {
        check_parameters_utf8(req);
        if (parameters) check_known_parameters(req, *parameters);
        f(req, res);
      } catch (const Problem& p) {
        write_problem(req, res, p);
      } catch (const InputError& e) {
        write_problem(req, res,
                      {422, "invalid-body", "Invalid campaign", "the body breaks the rules below",
                       errors_of(e.violations())});
      } catch (const campaign::SqliteError& e) {
        // A full disk (or an I/O error) under the store is the server's
        // state, not a bug: 503, nothing stored, try again later.
        const int primary = e.code() & 0xff;
        if (primary != SQLITE_FULL && primary != SQLITE_IOERR) {
          write_problem(req, res,
                        {500, "internal", "Internal Server Error", e.what(), json::array()});
          return;
        }
        res.set_header("Retry-After", "60");
        write_problem(req, res,
                      {503, "store-unavailable", "Store unavailable",
                       std::string("the store cannot take writes now (") + e.what() +
                           "); nothing was stored: try again when the server has room",
                       json::array()});
      } catch (const std::exception& e) {
        write_problem(req, res,
                      {500, "internal", "Internal Server Error", e.what(), json::array()});
      }
    };
  }

  static void check_parameters_utf8(const httplib::Request& req) {
    for (const auto& [name, value] : req.params) {
      if (first_invalid_utf8(name) || first_invalid_utf8(value)) {
        fail(400, "invalid-parameter", "Invalid query parameter",
             "query parameters must be UTF-8 (percent-encoded)",
             param_error(name, "not valid UTF-8"));
      }
    }
  }

  static void check_known_parameters(const httplib::Request& req,
                                     const std::vector<std::string>& known) {
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    for (const auto& [name, value] : req.params) {
      if (std::find(known.begin(), known.end(), name) == known.end()) {
        fail(400, "invalid-parameter", "Invalid query parameter",
             "unknown query parameter '" + name + "'",
             param_error(name, list.empty() ? "this route takes no query parameters"
                                            : "unknown here; this route takes " + list));
      }
      if (req.params.count(name) > 1) {
        fail(400, "invalid-parameter", "Invalid query parameter",
             "query parameter '" + name + "' given more than once",
             param_error(name, "given more than once; give it once"));
      }
    }
  }

  // Methods served per API path pattern ("GET, POST"), for the Allow header.
  std::map<std::string, std::string> allowed;

  void allow(const std::string& pattern, const char* method) {
    std::string& m = allowed[pattern];
    m += (m.empty() ? "" : ", ") + std::string(method);
  }
  void get(const std::string& pattern, httplib::Server::Handler h) {
    allow(pattern, "GET");
    http.Get(pattern, std::move(h));
  }
  void post(const std::string& pattern, httplib::Server::Handler h) {
    allow(pattern, "POST");
    http.Post(pattern, std::move(h));
  }

  // An API path asked with a method it does not serve answers 405 with the
  // methods it does serve (a path that does not exist stays 404).
  void refuse_other_methods() {
    for (const auto& [pattern, methods] : allowed) {
      const httplib::Server::Handler refuse = guarded(
          [methods = methods](const httplib::Request& req, httplib::Response& res) {
            res.set_header("Allow", methods);
            fail(405, "method-not-allowed", "Method Not Allowed",
                 req.method + " is not served on " + req.path + "; allowed: " + methods);
          },
          std::nullopt);
      const auto serves = [&](const char* m) { return methods.find(m) != std::string::npos; };
      if (!serves("GET")) http.Get(pattern, refuse);
      if (!serves("POST")) http.Post(pattern, refuse);
      http.Put(pattern, refuse);
      http.Patch(pattern, refuse);
      http.Delete(pattern, refuse);
    }
  }

  // Body size, TCP and keep-alive settings of the listener.
  void connection_settings() {
    http.set_payload_max_length(o.max_body_bytes);
    // Small JSON answers on kept-alive connections: without TCP_NODELAY,
    // Nagle's algorithm and delayed ACKs hold each one back ~40 ms.
    http.set_tcp_nodelay(true);
    http.set_keep_alive_max_count(1000);
  }

  // Requests that change something need the bearer token, when one is set.
  void bearer_check() {
    http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      if (o.token.empty()) return httplib::Server::HandlerResponse::Unhandled;
      if (req.method == "GET" || req.method == "HEAD" || req.method == "OPTIONS") {
        return httplib::Server::HandlerResponse::Unhandled;
      }
      // The scheme is case-insensitive (RFC 9110, 11.1).
      const std::string h = req.get_header_value("Authorization");
      constexpr std::string_view scheme = "bearer ";
      const bool ok = h.size() > scheme.size() && starts_with_ignoring_case(h, scheme) &&
                      constant_time_equal(h.substr(scheme.size()), o.token);
      if (ok) return httplib::Server::HandlerResponse::Unhandled;
      res.set_header("WWW-Authenticate", "Bearer realm=\"splat\"");
      write_problem(req, res,
                    {401, "unauthorized", "Unauthorized",
                     "this server needs `Authorization: Bearer <token>` on every request that "
                     "changes something",
                     json::array()});
      return httplib::Server::HandlerResponse::Handled;
    });
  }

  void problem_documents() {
    // Statuses the library answers itself (unknown route, body too large, ...)
    // get a problem document too.
    http.set_error_handler(httplib::Server::HandlerWithResponse(
        [max_body = o.max_body_bytes](const httplib::Request& req, httplib::Response& res) {
          if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
          std::string detail;
          json errors = json::array();
          if (res.status == 404) detail = "no resource at " + req.path;
          if (res.status == 413) {
            detail = "the request body is larger than the " + std::to_string(max_body) +
                     " bytes this server accepts";
            errors = body_too_large(max_body);
          }
          if (res.status == 405) detail = "method " + req.method + " is not allowed here";
          // A multipart body the library could not read: the API takes JSON only.
          if (res.status == 400 &&
              starts_with_ignoring_case(req.get_header_value("Content-Type"), "multipart/")) {
            res.status = 415;
            detail = "send the campaign as `Content-Type: application/json`";
            errors = header_error("Content-Type", "multipart bodies are not taken; send JSON");
          }
          write_problem(req, res,
                        {res.status, res.status == 404 ? "not-found" : "",
                         reason_phrase(res.status), detail, errors});
          return httplib::Server::HandlerResponse::Handled;
        }));
    http.set_exception_handler(
        [](const httplib::Request& req, httplib::Response& res, std::exception_ptr) {
          write_problem(req, res, {500, "internal", "Internal Server Error", "", json::array()});
        });
  }

  // Health, metrics, the material library and the schemas.
  void service_routes(const std::string& p) {
    get(p + "/health", guarded([this](const httplib::Request& req, httplib::Response& res) {
          const auto running = runner.running();
          reply_json(req, res,
                     {{"status", "ok"},
                      {"version", std::string(splat::version())},
                      {"git_commit", std::string(splat::git_commit())},
                      {"store_schema_version", store.schema_version()},
                      {"running_campaign", running ? json(*running) : json(nullptr)},
                      {"waiting_campaigns", runner.waiting()}});
        }));
    get(p + "/metrics", guarded([this](const httplib::Request&, httplib::Response& res) {
          res.set_content(metrics_text(), "text/plain; version=0.0.4; charset=utf-8");
        }));
    get(p + "/materials", guarded([](const httplib::Request& req, httplib::Response& res) {
          json list = json::array();
          for (const std::string& n : splat::material_names()) {
            list.push_back({{"name", n}, {"document", splat::material_document(n)}});
          }
          reply_json(req, res, {{"materials", list}});
        }));
    get(p + R"(/schemas/([^/]+))", guarded([](const httplib::Request& req, httplib::Response& res) {
          std::string name = req.matches[1];
          for (const char* suffix : {".schema.json", ".json"}) {
            const std::string s = suffix;
            if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) {
              name.resize(name.size() - s.size());
              break;
            }
          }
          const auto names = splat::schema_names();
          if (std::find(names.begin(), names.end(), name) == names.end()) {
            no_such("name", "schema '" + name + "'");
          }
          reply_json(req, res, splat::schema_document(name));
        }));
  }

  // Submitting, listing and cancelling campaigns; their jobs and windows.
  void campaign_routes(const std::string& p) {
    // Parameters checked in submit, after the media type (a form body would
    // otherwise be read as parameters).
    post(p + "/campaigns",
         guarded([this](const httplib::Request& req, httplib::Response& res) { submit(req, res); },
                 std::nullopt));
    get(p + "/campaigns",
        guarded(
            [this](const httplib::Request& req, httplib::Response& res) {
              const int size = page_size_of(req, o);
              const std::int64_t before = page_token_of(req, 'b');
              const auto page = campaign::campaigns_page(store, before, size + 1);
              json list = json::array();
              for (std::size_t i = 0; i < page.size() && i < std::size_t(size); ++i) {
                list.push_back(campaign_doc(page[i], false));
              }
              json next = nullptr;
              if (page.size() > std::size_t(size))
                next = "b" + std::to_string(page[std::size_t(size) - 1].id);
              reply_json(req, res, {{"campaigns", list}, {"next_page_token", next}});
            },
            {{"page_size", "page_token"}}));
    get(p + R"(/campaigns/([^/]+))",
        guarded([this](const httplib::Request& req, httplib::Response& res) {
          reply_json(req, res, campaign_doc(campaign_or_404(path_id(req)), true));
        }));
    post(p + R"(/campaigns/([^/]+)/cancel)",
         guarded([this](const httplib::Request& req, httplib::Response& res) {
           const std::int64_t id = path_id(req);
           campaign_or_404(id);
           const CancelResult r = runner.cancel(id);
           if (r == CancelResult::unknown) no_such("id", "campaign " + std::to_string(id));
           if (r == CancelResult::already_ended) {
             fail(409, "campaign-finished", "Campaign already finished",
                  "campaign " + std::to_string(id) + " has finished; nothing to cancel");
           }
           reply_json(req, res, campaign_doc(campaign_or_404(id), false), 202);
         }));
    get(p + R"(/campaigns/([^/]+)/jobs)",
        guarded(
            [this](const httplib::Request& req, httplib::Response& res) {
              const std::int64_t id = path_id(req);
              campaign_or_404(id);
              const int size = page_size_of(req, o);
              const std::int64_t offset = page_token_of(req, 'o');
              std::optional<campaign::JobState> state;
              if (req.has_param("state")) {
                const std::string s = req.get_param_value("state");
                try {
                  state = campaign::job_state_from_string(s);
                } catch (const std::exception&) {
                  fail(400, "invalid-parameter", "Invalid query parameter",
                       "state must be one of queued, running, succeeded, failed, cancelled, "
                       "timed-out",
                       param_error("state", "unknown job state '" + s + "'"));
                }
              }
              const auto rows = campaign::campaign_jobs(store, id, state, offset, size + 1);
              json list = json::array();
              for (std::size_t i = 0; i < rows.size() && i < std::size_t(size); ++i) {
                list.push_back(job_row(rows[i]));
              }
              json next = nullptr;
              if (rows.size() > std::size_t(size)) next = "o" + std::to_string(offset + size);
              reply_json(req, res,
                         {{"campaign_id", id}, {"jobs", list}, {"next_page_token", next}});
            },
            {{"state", "page_size", "page_token"}}));
    get(p + R"(/campaigns/([^/]+)/windows)",
        guarded(
            [this](const httplib::Request& req, httplib::Response& res) {
              const std::int64_t id = path_id(req);
              campaign_or_404(id);
              reply_windows(req, res, store.windows(id), {{"campaign_id", id}});
            },
            {{"format"}}));
  }

  // Windows across campaigns; one job and its result file.
  void store_routes(const std::string& p) {
    get(p + "/windows", guarded(
                            [this](const httplib::Request& req, httplib::Response& res) {
                              check_name_filter(req);
                              std::vector<campaign::WindowRecord> all;
                              json ids = json::array();
                              for (const campaign::CampaignRecord& c : store.campaigns()) {
                                if (!matches_filters(req, c)) continue;
                                ids.push_back(c.id);
                                for (auto& w : store.windows(c.id)) all.push_back(std::move(w));
                              }
                              reply_windows(req, res, all, {{"campaign_ids", ids}});
                            },
                            {{"format", "material_pair", "name", "tag"}}));
    get(p + R"(/jobs/([^/]+))",
        guarded([this](const httplib::Request& req, httplib::Response& res) {
          reply_json(req, res, job_doc(req.matches[1]));
        }));
    get(p + R"(/jobs/([^/]+)/result\.h5)",
        guarded([this](const httplib::Request& req, httplib::Response& res) {
          send_result_file(req, res);
        }));
  }

  void routes() {
    const std::string p = k_prefix;
    connection_settings();
    bearer_check();
    problem_documents();
    service_routes(p);
    campaign_routes(p);
    store_routes(p);
    refuse_other_methods();

    if (!o.web_dir.empty()) http.set_mount_point("/", o.web_dir.string());
    if (!o.vendor_dir.empty()) {
      http.set_mount_point("/vendor/chart.js", (o.vendor_dir / "chart.js" / "dist").string());
    }
  }

  // Campaign names follow the campaign schema's pattern: a filter that breaks
  // it can match nothing and is a mistake (or an injection attempt).
  static void check_name_filter(const httplib::Request& req) {
    if (!req.has_param("name")) return;
    const std::string n = req.get_param_value("name");
    const bool ok = !n.empty() && std::all_of(n.begin(), n.end(), [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '.' || ch == '-';
    });
    if (ok) return;
    fail(400, "invalid-parameter", "Invalid query parameter",
         "name must be a campaign name: letters, digits, '_', '.' and '-'",
         param_error("name", "not a campaign name (letters, digits, '_', '.', '-')"));
  }

  bool matches_filters(const httplib::Request& req, const campaign::CampaignRecord& c) {
    if (req.has_param("name") && req.get_param_value("name") != c.name) return false;
    const json spec = json::parse(c.spec, nullptr, false);
    if (req.has_param("tag")) {
      const json tags = json::parse(c.tags, nullptr, false);
      const std::string t = req.get_param_value("tag");
      if (!tags.is_array() || std::find(tags.begin(), tags.end(), json(t)) == tags.end()) {
        return false;
      }
    }
    if (req.has_param("material_pair")) {
      const json pair = spec.is_object() ? material_pair(spec.value("base_scene", json())) : json();
      if (!pair.is_string() || pair.get<std::string>() != req.get_param_value("material_pair")) {
        return false;
      }
    }
    return true;
  }

  void reply_windows(const httplib::Request& req, httplib::Response& res,
                     const std::vector<campaign::WindowRecord>& windows, json doc) {
    const bool csv = req.get_param_value("format") == "csv" ||
                     (req.get_header_value("Accept").find("text/csv") != std::string::npos);
    if (req.has_param("format") && req.get_param_value("format") != "csv" &&
        req.get_param_value("format") != "json") {
      fail(400, "invalid-parameter", "Invalid query parameter", "format must be json or csv",
           param_error("format", "must be json or csv"));
    }
    if (csv) {
      std::string body = campaign::window_rows_csv(windows);
      const std::string etag = etag_of(body);
      res.set_header("ETag", etag);
      res.set_header("Cache-Control", "no-cache");
      res.set_header("Content-Disposition", "attachment; filename=\"windows.csv\"");
      if (etag_matches(req.get_header_value("If-None-Match"), etag)) {
        res.status = 304;
        return;
      }
      res.set_content(std::move(body), "text/csv; charset=utf-8");
      return;
    }
    doc["windows"] = campaign::window_rows(windows);
    doc["ladders"] = ladders_json(windows);
    reply_json(req, res, doc);
  }

  // The resolution ladders of the windows, campaign by campaign (each with
  // its own job costs).
  json ladders_json(const std::vector<campaign::WindowRecord>& windows) {
    std::map<std::int64_t, std::vector<campaign::WindowRecord>> by_campaign;
    for (const campaign::WindowRecord& w : windows) by_campaign[w.campaign_id].push_back(w);
    json out = json::array();
    for (const auto& [id, list] : by_campaign) {
      for (const campaign::Ladder& l :
           campaign::resolution_ladders(list, campaign::cost_by_parameter_set(store, id))) {
        out.push_back(campaign::to_json(l));
      }
    }
    return out;
  }

  json job_row(const campaign::CampaignJobRow& r) {
    return {{"id", r.point.job_hash},
            {"params", json::parse(r.point.params)},
            {"velocity", r.point.velocity},
            {"origin", r.point.origin},
            {"state", campaign::to_string(r.state)},
            {"outcome", r.outcome ? json(*r.outcome) : json(nullptr)},
            {"attempts", r.attempts},
            {"started_at", nullable(r.started_at)},
            {"finished_at", nullable(r.finished_at)},
            {"wall_seconds", nullable(r.wall_seconds)},
            {"exit_reason", r.exit_reason},
            {"model", r.model ? json(*r.model) : json(nullptr)},
            {"resolution", resolution_json(r)},
            {"links", {{"self", std::string(k_prefix) + "/jobs/" + r.point.job_hash}}}};
  }

  // The particle's resolution: {elements_across} (FE) or {spacing} (SPH, m);
  // null for a model without a mesh (two-mass).
  static json resolution_json(const campaign::CampaignJobRow& r) {
    if (r.elements_across) return {{"elements_across", *r.elements_across}};
    if (r.spacing) return {{"spacing", *r.spacing}};
    return nullptr;
  }

  // The result file of a job, if it is a regular file inside the jobs folder.
  std::optional<fs::path> result_file(const std::optional<campaign::ResultRecord>& r) {
    if (!r || r->hdf5_path.empty()) return std::nullopt;
    const fs::path f = r->hdf5_path;
    if (!inside(f, jobs_dir)) return std::nullopt;
    std::error_code ec;
    if (!fs::is_regular_file(f, ec)) return std::nullopt;
    return f;
  }

  // Why a job whose result names a file inside the jobs folder has none to
  // read: the file is gone (a store copied without its jobs folder).
  std::optional<std::string> missing_result_file(const std::optional<campaign::ResultRecord>& r) {
    if (!r || r->hdf5_path.empty() || !inside(r->hdf5_path, jobs_dir)) return std::nullopt;
    std::error_code ec;
    if (fs::is_regular_file(r->hdf5_path, ec)) return std::nullopt;
    return "result file '" + r->hdf5_path +
           "' is missing (was the store copied without its jobs folder " + jobs_dir.string() + "?)";
  }

  json job_doc(const std::string& hash) {
    const auto j = store.job(hash);
    if (!j) no_such("id", "job " + hash);
    const auto r = store.result(hash);
    json uses = json::array();
    for (const campaign::JobUse& u : campaign::job_uses(store, hash)) {
      uses.push_back({{"campaign_id", u.campaign_id},
                      {"params", json::parse(u.point.params)},
                      {"velocity", u.point.velocity},
                      {"origin", u.point.origin}});
    }
    json doc = {
        {"id", j->hash},
        {"state", campaign::to_string(j->state)},
        {"attempts", j->attempts},
        {"solver_version", j->solver_version},
        {"host", j->host},
        {"created_at", j->created_at},
        {"started_at", nullable(j->started_at)},
        {"finished_at", nullable(j->finished_at)},
        {"wall_seconds", nullable(j->wall_seconds)},
        {"threads", j->threads ? json(*j->threads) : json(nullptr)},
        {"exit_reason", j->exit_reason},
        {"scene", json::parse(j->scene)},
        {"uses", uses},
        {"result", nullptr},
        {"histories", nullptr},
        {"links", {{"self", std::string(k_prefix) + "/jobs/" + hash}, {"result_h5", nullptr}}}};
    if (r) {
      doc["result"] = {{"outcome", r->outcome},
                       {"reason", r->reason},
                       {"summary", json::parse(r->summary, nullptr, false)}};
    }
    if (const auto f = result_file(r)) {
      doc["links"]["result_h5"] = std::string(k_prefix) + "/jobs/" + hash + "/result.h5";
      doc["histories"] = histories(*f);
    } else if (const auto why = missing_result_file(r)) {
      doc["histories"] = {{"error", *why}};
    }
    return doc;
  }

  // Every history column of the result file, at most k_max_history_points
  // rows (evenly strided, last row kept), with its unit.
  static json histories(const fs::path& h5) {
    // Called from several server threads at once: Debian's HDF5 is built
    // thread-safe (h5cc -showconfig: "Threadsafety: yes").
    try {
      const splat::ResultSummary s = splat::read_result_summary(h5);
      json cols = json::object();
      json units = json::object();
      const std::size_t n = s.history_rows;
      const std::size_t stride =
          std::max<std::size_t>(1, (n + k_max_history_points - 1) / k_max_history_points);
      for (const std::string& c : s.history_columns) {
        const std::vector<double> v = splat::read_history(h5, c);
        json a = json::array();
        for (std::size_t i = 0; i < v.size(); i += stride)
          a.push_back(std::isfinite(v[i]) ? json(v[i]) : json(nullptr));
        if (!v.empty() && (v.size() - 1) % stride != 0)
          a.push_back(std::isfinite(v.back()) ? json(v.back()) : json(nullptr));
        cols[c] = std::move(a);
        try {
          units[c] = splat::read_unit(h5, "/history/" + c);
        } catch (const std::exception&) {
          units[c] = nullptr;
        }
      }
      return {{"rows", n}, {"stride", stride}, {"columns", cols}, {"units", units}};
    } catch (const std::exception& e) {
      return {{"error", e.what()}};
    }
  }

  void send_result_file(const httplib::Request& req, httplib::Response& res) {
    const std::string hash = req.matches[1];
    if (!store.job(hash)) no_such("id", "job " + hash);
    const auto r = store.result(hash);
    if (const auto why = missing_result_file(r)) fail(404, "not-found", "Not Found", *why);
    const auto f = result_file(r);
    if (!f) fail(404, "not-found", "Not Found", "job " + hash + " has no result file");
    const std::uintmax_t size = fs::file_size(*f);
    auto in = std::make_shared<std::ifstream>(*f, std::ios::binary);
    res.set_header("Content-Disposition", "attachment; filename=\"" + hash.substr(0, 16) + ".h5\"");
    res.set_content_provider(static_cast<std::size_t>(size), "application/x-hdf5",
                             [in](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                               std::array<char, 65536> buf{};
                               in->seekg(static_cast<std::streamoff>(offset));
                               const std::size_t want = std::min(length, buf.size());
                               in->read(buf.data(), static_cast<std::streamsize>(want));
                               const std::streamsize got = in->gcount();
                               if (got <= 0) return false;
                               return sink.write(buf.data(), static_cast<std::size_t>(got));
                             });
  }

  // --- submission ------------------------------------------------------------

  void submit(const httplib::Request& req, httplib::Response& res) {
    const std::string type = req.get_header_value("Content-Type");
    if (!is_json_media_type(type)) {
      fail(415, "unsupported-media-type", "Unsupported Media Type",
           "send the campaign as `Content-Type: application/json`",
           header_error("Content-Type", "'" + type + "' is not application/json"));
    }
    check_known_parameters(req, {});
    const json doc = parsed_body(req);
    const std::string key = req.get_header_value("Idempotency-Key");
    if (key.size() > 255) {
      fail(400, "invalid-header", "Invalid header", "Idempotency-Key is longer than 255 characters",
           header_error("Idempotency-Key", "at most 255 characters"));
    }
    const std::string body_hash = campaign::sha256_hex(campaign::canonical_text(doc));
    const auto replay = [&](std::int64_t id) {
      res.set_header("Location", std::string(k_prefix) + "/campaigns/" + std::to_string(id));
      res.set_header("Idempotent-Replayed", "true");
      reply_json(req, res, campaign_doc(campaign_or_404(id), true), 202);
    };
    std::optional<campaign::SubmissionKey> submission;
    if (!key.empty()) {
      submission = campaign::SubmissionKey{key, body_hash};
      // A retry of a submission already stored: no need to check it again.
      if (const auto known = store.submission(key)) {
        if (known->body_hash != body_hash) key_reused();
        replay(known->campaign_id);
        return;
      }
    }
    const campaign::CampaignSpec spec = checked_spec(doc);
    const std::string version = campaign::solver_version_string();
    // Resolved without reading any file, whatever the checks above missed.
    const auto jobs = campaign::expand(spec, campaign::library_scene_resolver(), version);

    campaign::CampaignRecord rec;
    rec.name = spec.name;
    rec.spec_hash = campaign::spec_hash(spec);
    rec.spec = spec.document.dump();
    rec.tags = json(spec.tags).dump();
    rec.executor = splat::to_string(spec.executor);
    rec.priority = spec.priority;
    std::vector<campaign::NewPoint> pts;
    for (const campaign::ExpandedJob& j : jobs) {
      pts.push_back({{j.params_key, j.params_key, j.velocity, j.hash, "grid"},
                     campaign::canonical_text(j.scene),
                     version});
    }
    // The campaign, its points and the key in one transaction (a concurrent
    // request with the same key is settled there).
    campaign::OpenedCampaign opened;
    try {
      opened = store.open_campaign(rec, pts, false, submission);
    } catch (const campaign::SubmissionKeyReused&) {
      key_reused();
    }
    const std::int64_t id = opened.id;
    if (opened.replayed) {
      replay(id);
      return;
    }
    if (o.run_campaigns) runner.submit(id);
    res.set_header("Location", std::string(k_prefix) + "/campaigns/" + std::to_string(id));
    reply_json(req, res, campaign_doc(campaign_or_404(id), true), 202);
  }

  // The body as JSON: within the size limit (also for chunked bodies), UTF-8,
  // and parsed with the depth limit before anything walks it.
  json parsed_body(const httplib::Request& req) const {
    if (req.body.size() > o.max_body_bytes) {
      fail(413, "body-too-large", "Content Too Large",
           "the request body is larger than the " + std::to_string(o.max_body_bytes) +
               " bytes this server accepts",
           body_too_large(o.max_body_bytes));
    }
    if (const auto at = first_invalid_utf8(req.body)) {
      const std::string where = "byte " + std::to_string(*at) + " of the request body";
      fail(400, "invalid-utf8", "Body is not UTF-8", where + " is not valid UTF-8",
           json::array({{{"pointer", ""}, {"detail", "not valid UTF-8 from " + where}}}));
    }
    try {
      return splat::parse_json_text(req.body, "the request body");
    } catch (const InputError& e) {
      fail(400, "malformed-json", "Malformed JSON", e.what(), errors_of(e.violations()));
    }
  }

  // Everything that can be wrong with a submitted campaign, found before
  // anything is written.
  campaign::CampaignSpec checked_spec(const json& doc) {
    std::vector<SchemaViolation> v = splat::validate("campaign", doc);
    if (!v.empty()) throw InputError(v);
    if (doc["base_scene"].is_string()) {
      throw InputError(std::vector<SchemaViolation>{
          {"/base_scene",
           "must be the scene document itself over the API (a path would be read on the server)"}});
    }
    check_velocity_range(doc);
    check_materials_of(doc["base_scene"], "/base_scene", v);
    if (doc.contains("fields")) check_field_materials(doc["fields"], material_names, v);
    check_job_threads(doc, v);
    if (!v.empty()) throw InputError(v);
    campaign::CampaignSpec spec = campaign::read_campaign(doc);
    check_grid(spec);
    return spec;
  }

  // The velocity range's length, before read_campaign lists it.
  void check_velocity_range(const json& doc) const {
    if (!doc["velocity"].contains("range")) return;
    const json& r = doc["velocity"]["range"];
    const double n =
        std::floor((r["to"].get<double>() - r["from"].get<double>()) / r["step"].get<double>()) + 1;
    if (n <= o.max_jobs_per_campaign) return;
    fail(422, "grid-too-large", "Grid too large",
         "the velocity range alone has " + count_text(n) + " points; this server takes at most " +
             std::to_string(o.max_jobs_per_campaign) + " jobs per campaign",
         json::array({{{"pointer", "/velocity/range"},
                       {"detail",
                        "more than " + std::to_string(o.max_jobs_per_campaign) + " velocities"}}}));
  }

  // Local jobs run on this machine: no more threads than it has cores (the
  // schema's maximum bounds Slurm jobs).
  void check_job_threads(const json& doc, std::vector<SchemaViolation>& out) const {
    if (!doc.contains("job") || !doc["job"].contains("threads")) return;
    const auto executor =
        o.executor ? o.executor : parse<campaign::ExecutorKind>(doc.value("executor", "local"));
    const bool slurm = executor == campaign::ExecutorKind::slurm;
    if (slurm || doc["job"]["threads"].get<long long>() <= splat::max_threads()) return;
    out.push_back({"/job/threads", "must be <= " + std::to_string(splat::max_threads()) +
                                       " (-): the cores of the machine this server runs "
                                       "local jobs on"});
  }

  // A count of points as text (a double: it may be beyond any integer).
  static std::string count_text(double n) {
    char text[32];
    std::snprintf(text, sizeof text, "%.15g", n);
    return text;
  }

  // Grid points x parameter sets + refinement budget within the limit; over
  // it, each axis that multiplies the grid is named with its size.
  void check_grid(const campaign::CampaignSpec& spec) const {
    double grid = static_cast<double>(spec.velocities.size());
    for (const campaign::ParameterAxis& a : spec.axes) grid *= static_cast<double>(a.values.size());
    const double extra = spec.refinement ? spec.refinement->max_extra_jobs : 0;
    if (grid + extra <= o.max_jobs_per_campaign) return;
    const std::string limit = std::to_string(o.max_jobs_per_campaign);
    const auto sized = [&](const std::string& pointer, std::size_t n, const char* what) {
      return json{{"pointer", pointer},
                  {"detail", std::to_string(n) + " " + what + " of a grid over " + limit +
                                 " jobs (grid points x parameter sets + refinement budget)"}};
    };
    json errors = json::array();
    errors.push_back(
        sized(spec.document["velocity"].contains("range") ? "/velocity/range" : "/velocity/values",
              spec.velocities.size(), "velocities"));
    std::size_t field = 0;
    for (const campaign::ParameterAxis& a : spec.axes) {
      const std::string at =
          (a.is_field ? "/fields/" + std::to_string(field++) : "/" + a.name) + "/values";
      errors.push_back(sized(at, a.values.size(), "values"));
    }
    if (spec.refinement) {
      errors.push_back(sized("/refinement/max_extra_jobs",
                             static_cast<std::size_t>(spec.refinement->max_extra_jobs),
                             "refinement jobs"));
    }
    fail(422, "grid-too-large", "Grid too large",
         "the campaign asks for " + count_text(grid) + " grid jobs and up to " + count_text(extra) +
             " refinement jobs; this server takes at most " + limit + " per campaign",
         errors);
  }

  // --- metrics ---------------------------------------------------------------

  std::string metrics_text() {
    const campaign::JobCounts c = campaign::all_job_counts(store);
    std::string s;
    s += "# HELP splat_jobs Jobs in the store by state.\n# TYPE splat_jobs gauge\n";
    const std::pair<const char*, int> states[] = {
        {"queued", c.queued}, {"running", c.running},     {"succeeded", c.succeeded},
        {"failed", c.failed}, {"cancelled", c.cancelled}, {"timed-out", c.timed_out}};
    for (const auto& [name, n] : states) {
      s += "splat_jobs{state=\"" + std::string(name) + "\"} " + std::to_string(n) + "\n";
    }
    s += "# HELP splat_queue_length Jobs waiting to run (queued in the store).\n"
         "# TYPE splat_queue_length gauge\nsplat_queue_length " +
         std::to_string(c.queued) + "\n";
    s += "# HELP splat_campaigns_waiting Campaigns waiting for this server's runner.\n"
         "# TYPE splat_campaigns_waiting gauge\nsplat_campaigns_waiting " +
         std::to_string(runner.waiting()) + "\n";
    const std::vector<double> walls = campaign::all_wall_seconds(store);
    constexpr double bounds[] = {0.01, 0.03, 0.1, 0.3, 1, 3, 10, 30, 100, 300, 1000, 3600};
    s += "# HELP splat_job_duration_seconds Wall time of finished jobs.\n"
         "# TYPE splat_job_duration_seconds histogram\n";
    double sum = 0;
    for (double w : walls) sum += w;
    for (double b : bounds) {
      const auto n = std::count_if(walls.begin(), walls.end(), [b](double w) { return w <= b; });
      char le[32];
      std::snprintf(le, sizeof le, "%g", b);
      s += "splat_job_duration_seconds_bucket{le=\"" + std::string(le) + "\"} " +
           std::to_string(n) + "\n";
    }
    char sum_text[64];
    std::snprintf(sum_text, sizeof sum_text, "%.9g", sum);
    s += "splat_job_duration_seconds_bucket{le=\"+Inf\"} " + std::to_string(walls.size()) + "\n";
    s += "splat_job_duration_seconds_sum " + std::string(sum_text) + "\n";
    s += "splat_job_duration_seconds_count " + std::to_string(walls.size()) + "\n";
    s += "# HELP splat_http_requests_total API requests answered.\n"
         "# TYPE splat_http_requests_total counter\nsplat_http_requests_total " +
         std::to_string(requests.load()) + "\n";
    return s;
  }
};

Server::Server(ServerOptions options) {
  if (options.token.empty() && !is_loopback_host(options.host)) {
    throw std::invalid_argument("refusing to listen on " + options.host +
                                " without --token-file: only loopback addresses may go without a "
                                "token");
  }
  if (!options.token.empty()) {
    if (const std::string why = token_problem(options.token); !why.empty()) {
      throw std::invalid_argument("refusing a weak token: " + why);
    }
  }
  impl_ = std::make_unique<Impl>(std::move(options));
}

Server::~Server() {
  stop();
}

int Server::bind() {
  int port = 0;
  if (impl_->o.port == 0) {
    port = impl_->http.bind_to_any_port(impl_->o.host);
  } else {
    port = impl_->http.bind_to_port(impl_->o.host, impl_->o.port) ? impl_->o.port : -1;
  }
  if (port <= 0) {
    throw std::runtime_error("cannot listen on " + impl_->o.host + ":" +
                             std::to_string(impl_->o.port));
  }
  impl_->http.raise_backlog();
  impl_->bound = true;
  return port;
}

void Server::serve() {
  if (impl_->o.run_campaigns) impl_->runner.resume_all();
  impl_->http.listen_after_bind();
}

void Server::stop() {
  if (!impl_) return;
  std::call_once(impl_->stopped, [this] {
    impl_->http.stop();
    impl_->runner.shutdown();
  });
}

bool Server::ready() const {
  return impl_->bound && impl_->http.is_running();
}

}  // namespace splat::api
