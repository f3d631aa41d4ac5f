// splat windows --db FILE [--campaign ID]
//               [--format table|json|csv|ladders|ladders-csv]
// Prints the deposition windows stored for a campaign (default: the latest):
// per parameter set the critical and maximum velocity with the bracket of
// each edge, every sticking interval, and the jobs that are neither stick
// nor rebound. JSON rows carry `params`, `critical_velocity`,
// `maximum_velocity` (null where the window does not close within the swept
// range), `critical_bracket`, `maximum_bracket` and `intervals`. Parameter
// sets that differ only in a resolution field form a ladder
// (campaign/ladders.hpp): the table lists it after the windows, `ladders`
// prints it as JSON and `ladders-csv` as CSV.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "app/window_table.hpp"
#include "campaign/manager.hpp"
#include "campaign/queries.hpp"
#include "campaign/spec.hpp"
#include "solver/input/schema.hpp"

namespace splat::app {

namespace {

struct WindowsOptions {
  std::string db = "splat.db";
  long long campaign = 0;
  std::string format = "table";
};

// The grid of a stored campaign; unknown when its spec no longer reads (a
// store written by an older splat).
LadderGrid stored_grid(const campaign::CampaignRecord& c) {
  try {
    return ladder_grid(campaign::read_campaign(nlohmann::json::parse(c.spec)));
  } catch (const std::exception&) {
    return {};
  }
}

int run_windows(const WindowsOptions& o) {
  if (!std::filesystem::exists(o.db)) {
    throw InputError(std::vector<SchemaViolation>{{"--db", "no store '" + o.db + "'"}});
  }
  // Read only: a store on a read-only file system, or one this user may not
  // write, is read too (windows are computed, never stored, here).
  campaign::Store store(o.db, campaign::Store::ReadOnly{});
  const auto all = store.campaigns();
  if (all.empty())
    throw InputError(std::vector<SchemaViolation>{{"--db", "the store holds no campaign"}});
  std::int64_t id = o.campaign ? o.campaign : all.back().id;
  const auto c = store.campaign(id);
  if (!c)
    throw InputError(std::vector<SchemaViolation>{
        {"--campaign", "no campaign " + std::to_string(id) + " in the store"}});
  std::vector<campaign::WindowRecord> windows = store.windows(id);
  if (windows.empty()) windows = campaign::compute_windows(store, id);  // e.g. a killed sweep
  const std::vector<campaign::Ladder> ladders =
      campaign::resolution_ladders(windows, campaign::cost_by_parameter_set(store, id));
  if (o.format == "ladders") {
    nlohmann::json doc = nlohmann::json::array();
    for (const campaign::Ladder& l : ladders) doc.push_back(campaign::to_json(l));
    std::printf("%s\n", doc.dump(2).c_str());
  } else if (o.format == "ladders-csv") {
    std::fputs(campaign::ladders_csv(ladders).c_str(), stdout);
  } else if (o.format == "json") {
    std::printf("%s\n", windows_json(windows).dump(2).c_str());
  } else if (o.format == "csv") {
    print_windows_csv(stdout, windows);
  } else {
    std::printf("campaign %lld '%s' (%s): %s\n", static_cast<long long>(id), c->name.c_str(),
                campaign::to_string(c->state), counts_text(store.job_counts(id)).c_str());
    print_windows_table(stdout, windows);
    print_ladders_table(stdout, ladders, stored_grid(*c));
  }
  return 0;
}

}  // namespace

void register_windows(CLI::App& app, CommandTable& commands) {
  auto o = std::make_shared<WindowsOptions>();
  CLI::App* sub = app.add_subcommand("windows", "Print the deposition windows of a campaign");
  sub->add_option("--db", o->db, "SQLite store")->capture_default_str();
  sub->add_option("--campaign", o->campaign, "Campaign id (default: the latest)");
  sub->add_option("--format", o->format, "table, json, csv, ladders (JSON) or ladders-csv")
      ->check(CLI::IsMember({"table", "json", "csv", "ladders", "ladders-csv"}))
      ->capture_default_str();
  commands.emplace_back(sub, [o] { return run_windows(*o); });
}

}  // namespace splat::app
