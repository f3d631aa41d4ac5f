// splat regress CAMPAIGN.json --baseline FILE [--update] [--db FILE] [--workers N]
// Runs the campaign (reusing stored results of this solver version), compares
// its windows with the baseline (campaign/regress.hpp: edges within the
// baseline's velocity tolerance, same number of intervals and of
// unclassified jobs), prints a report and exits 1 on drift, 0 without.
// --update writes the baseline from this run instead (tolerance: the
// campaign's refinement tolerance, else its smallest velocity step).
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "app/window_table.hpp"
#include "campaign/manager.hpp"
#include "campaign/regress.hpp"
#include "solver/input/schema.hpp"

namespace splat::app {

namespace {

struct RegressOptions {
  std::string campaign;
  std::string baseline;
  bool update = false;
  std::string db = "splat.db";
  int workers = 2;
  std::string job_program;
};

double default_tolerance(const campaign::CampaignSpec& spec) {
  if (spec.refinement) return spec.refinement->tolerance;
  std::vector<double> v = spec.velocities;
  std::sort(v.begin(), v.end());
  double step = 0.0;
  for (std::size_t i = 1; i < v.size(); ++i) {
    const double d = v[i] - v[i - 1];
    if (d > 0 && (step == 0.0 || d < step)) step = d;
  }
  return step;
}

int run_regress(const RegressOptions& o) {
  const campaign::CampaignSpec spec = campaign::load_campaign(o.campaign);
  nlohmann::json baseline;
  if (!o.update) baseline = read_json_file(o.baseline);
  campaign::Store store(o.db);
  campaign::ManagerOptions mo;
  mo.workers = std::max(1, o.workers);
  if (!o.job_program.empty()) mo.job_program = o.job_program;
  const campaign::SweepReport r = campaign::run_sweep(store, spec, mo);
  std::printf("campaign '%s': %s (%d run, %d reused)\n", spec.name.c_str(),
              counts_text(r.counts).c_str(), r.jobs_started, r.grid.jobs_reused);
  if (r.state != campaign::CampaignState::finished) {
    std::printf("regress: the campaign did not finish (%s)\n", campaign::to_string(r.state));
    return 3;
  }
  if (o.update) {
    const nlohmann::json b = campaign::make_baseline(spec.name, r.windows, default_tolerance(spec));
    std::ofstream(o.baseline) << b.dump(2) << "\n";
    std::printf("baseline written to %s (velocity tolerance %g m/s)\n", o.baseline.c_str(),
                b["tolerances"]["velocity"].get<double>());
    print_windows_table(stdout, r.windows);
    return 0;
  }
  campaign::RegressionReport report;
  try {
    report = campaign::compare_to_baseline(baseline, r.windows);
  } catch (const std::invalid_argument& e) {
    throw InputError(
        std::vector<SchemaViolation>{{"", "baseline '" + o.baseline + "': " + e.what()}});
  }
  std::printf("%-4s %-40s %-18s %-14s %s\n", "", "parameters", "figure", "baseline", "now");
  for (const campaign::RegressionCheck& c : report.checks) {
    std::printf("%-4s %-40s %-18s %-14s %s\n", c.ok ? "ok" : "DRIFT", c.params.c_str(),
                c.figure.c_str(), c.baseline.c_str(), c.current.c_str());
  }
  const double tol = baseline["tolerances"]["velocity"].get<double>();
  std::printf("%s: velocity tolerance %g m/s, baseline %s (solver %s)\n",
              report.drift() ? "DRIFT" : "no drift", tol, o.baseline.c_str(),
              baseline.value("solver_version", "?").c_str());
  return report.drift() ? 1 : 0;
}

}  // namespace

void register_regress(CLI::App& app, CommandTable& commands) {
  auto o = std::make_shared<RegressOptions>();
  CLI::App* sub =
      app.add_subcommand("regress", "Run a campaign and compare its windows with a baseline");
  sub->add_option("campaign", o->campaign, "Campaign JSON file")->required();
  sub->add_option("--baseline", o->baseline, "Baseline JSON file")->required();
  sub->add_flag("--update", o->update, "Write the baseline from this run");
  sub->add_option("--db", o->db, "SQLite store (results are reused)")->capture_default_str();
  sub->add_option("--workers", o->workers, "Jobs run at once")->capture_default_str();
  sub->add_option("--job-program", o->job_program,
                  "Program run for each job (default: this splat)");
  commands.emplace_back(sub, [o] { return run_regress(*o); });
}

}  // namespace splat::app
