// splat converge SCENE.json --set-levels /pointer=v1,v2,... [--set ...] [--json]
// Runs one scene at several levels of one field (a resolution such as
// /particle_impact/particle/elements_across, or a fidelity) and prints what
// each level costs and gives: level, elements, steps, wall seconds, outcome,
// rebound velocity (impact scenes; separation velocity of two-mass scenes),
// bonded area, their differences from the finest (last) level and, with three
// or more numeric levels at a constant ratio, the Richardson estimate of the
// last three (solver/core/richardson.hpp).
// Exit code: 0 when every level ran (whatever its outcome), 2 for bad input.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "solver/core/richardson.hpp"
#include "solver/core/simulation.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/input/schema.hpp"
#include "solver/two_mass/two_mass_model.hpp"

namespace splat::app {

namespace {

using nlohmann::json;

struct ConvergeOptions {
  std::string scene;
  std::string levels;  // /pointer=v1,v2,...
  std::vector<std::string> overrides;
  bool json = false;
  int threads = 1;
  ThreadPolicy thread_policy = ThreadPolicy::adaptive;
};

struct Level {
  std::string value;  // as given
  long long elements = 0;
  long long steps = 0;
  double wall = 0.0;
  std::string outcome, reason;
  std::optional<double> rebound_velocity;  // m/s
  std::optional<double> bonded_area;       // m^2
};

Level run_level(const ConvergeOptions& o, const std::string& pointer, const std::string& value) {
  std::vector<std::string> sets = o.overrides;
  sets.push_back(pointer + "=" + value);
  const LoadedScene loaded = load_scene(o.scene, sets);
  SimulationOptions so;
  so.threads = o.threads;
  so.thread_policy = o.thread_policy;
  RunSummary s;
  if (loaded.scene.two_mass) {
    s = run_two_mass(loaded.scene, loaded.resolved, so);
  } else {
    Simulation sim(loaded.scene, loaded.resolved, so);
    s = sim.run();
  }
  Level l;
  l.value = value;
  for (const BodySummary& b : s.bodies) l.elements += b.elements;
  l.steps = s.steps;
  l.wall = s.wall_seconds;
  l.outcome = to_string(s.outcome);
  l.reason = s.reason;
  if (s.impact) {
    l.rebound_velocity = s.impact->rebound_velocity;
    l.bonded_area = s.impact->bonded_area;
  } else if (s.two_mass) {
    l.rebound_velocity = s.two_mass->separation_velocity;
  }
  return l;
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, sep)) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

std::optional<double> number(const std::string& s) {
  try {
    std::size_t used = 0;
    const double x = std::stod(s, &used);
    if (used == s.size() && std::isfinite(x)) return x;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

json opt(const std::optional<double>& x) {
  return x ? json(*x) : json(nullptr);
}

// Richardson estimate of the last three levels when the levels are numbers
// with a constant ratio (finer = larger, like elements across); a quantity
// that cannot be negative (an area) has none when it extrapolates below zero.
enum class Sign { any, non_negative };
std::optional<RichardsonEstimate> estimate(const std::vector<Level>& levels,
                                           std::optional<double> Level::*field, Sign sign) {
  const std::size_t n = levels.size();
  if (n < 3) return std::nullopt;
  const auto a = number(levels[n - 3].value), b = number(levels[n - 2].value),
             c = number(levels[n - 1].value);
  const auto f1 = levels[n - 3].*field, f2 = levels[n - 2].*field, f3 = levels[n - 1].*field;
  if (!a || !b || !c || !f1 || !f2 || !f3 || !(*a > 0.0)) return std::nullopt;
  const double r = *b / *a;
  if (std::abs(*c / *b - r) > 1e-6 * r) return std::nullopt;
  const auto e = richardson(*f1, *f2, *f3, r);
  if (e && sign == Sign::non_negative && e->estimate < 0.0) return std::nullopt;
  return e;
}

void print_value(const std::optional<double>& x, const char* fmt) {
  if (x) {
    std::printf(fmt, *x);
  } else {
    std::printf("%12s", "-");
  }
}

int run_converge(const ConvergeOptions& o) {
  check_threads_option(o.threads);
  const auto eq = o.levels.find('=');
  if (eq == std::string::npos || eq == 0 || o.levels[0] != '/') {
    throw InputError(
        {{"--set-levels", "expected /json/pointer=v1,v2,... (got '" + o.levels + "')"}});
  }
  const std::string pointer = o.levels.substr(0, eq);
  const std::vector<std::string> values = split(o.levels.substr(eq + 1), ',');
  if (values.size() < 2) {
    throw InputError({SchemaViolation{"--set-levels", "give at least two levels, coarse to fine"}});
  }
  std::vector<Level> levels;
  for (const std::string& v : values) {
    levels.push_back(run_level(o, pointer, v));
    if (!o.json) {
      std::fprintf(stderr, "level %s: %s (%.2f s)\n", v.c_str(), levels.back().outcome.c_str(),
                   levels.back().wall);
    }
  }
  const Level& finest = levels.back();
  auto diff = [](const std::optional<double>& x, const std::optional<double>& ref) {
    return x && ref ? std::optional<double>(*x - *ref) : std::nullopt;
  };
  const auto rv = estimate(levels, &Level::rebound_velocity, Sign::any);
  const auto ba = estimate(levels, &Level::bonded_area, Sign::non_negative);

  if (o.json) {
    json doc = {{"scene", o.scene}, {"pointer", pointer}, {"levels", json::array()}};
    for (const Level& l : levels) {
      doc["levels"].push_back(
          {{"level", l.value},
           {"elements", l.elements},
           {"steps", l.steps},
           {"wall_seconds", l.wall},
           {"outcome", l.outcome},
           {"reason", l.reason},
           {"rebound_velocity", opt(l.rebound_velocity)},
           {"bonded_area", opt(l.bonded_area)},
           {"rebound_velocity_error", opt(diff(l.rebound_velocity, finest.rebound_velocity))},
           {"bonded_area_error", opt(diff(l.bonded_area, finest.bonded_area))}});
    }
    auto est = [](const std::optional<RichardsonEstimate>& e) {
      return e ? json{{"order", e->order}, {"estimate", e->estimate}} : json(nullptr);
    };
    doc["richardson"] = {{"rebound_velocity", est(rv)}, {"bonded_area", est(ba)}};
    std::printf("%s\n", doc.dump(2).c_str());
    return 0;
  }
  std::printf("converge %s over %s (errors against the finest level, %s)\n", o.scene.c_str(),
              pointer.c_str(), finest.value.c_str());
  std::printf("%8s %9s %8s %8s %-9s %12s %12s %12s %12s\n", "level", "elements", "steps", "wall s",
              "outcome", "Vr m/s", "Vr error", "bond m^2", "bond error");
  for (const Level& l : levels) {
    std::printf("%8s %9lld %8lld %8.2f %-9s ", l.value.c_str(), l.elements, l.steps, l.wall,
                l.outcome.c_str());
    print_value(l.rebound_velocity, "%12.4g");
    std::printf(" ");
    print_value(diff(l.rebound_velocity, finest.rebound_velocity), "%12.3g");
    std::printf(" ");
    print_value(l.bonded_area, "%12.4e");
    std::printf(" ");
    print_value(diff(l.bonded_area, finest.bonded_area), "%12.3e");
    std::printf("\n");
  }
  auto report = [](const char* name, const std::optional<RichardsonEstimate>& e, const char* unit) {
    if (e) {
      std::printf("Richardson (last three levels) %s: %.5g %s, observed order %.2f\n", name,
                  e->estimate, unit, e->order);
    } else {
      std::printf(
          "Richardson %s: none (needs three numeric levels at a constant ratio, a "
          "monotone sequence whose steps shrink, and a physical limit)\n",
          name);
    }
  };
  report("rebound velocity", rv, "m/s");
  report("bonded area", ba, "m^2");
  return 0;
}

}  // namespace

void register_converge(CLI::App& app, CommandTable& commands) {
  auto o = std::make_shared<ConvergeOptions>();
  CLI::App* sub = app.add_subcommand(
      "converge", "Run one scene at several levels of one field and print the accuracy each buys");
  sub->add_option("scene", o->scene, "Scene JSON file")->required();
  sub->add_option("--set-levels", o->levels,
                  "The field and its levels, coarse to fine: /json/pointer=v1,v2,...")
      ->required();
  sub->add_option("--set", o->overrides, "Override another field: /json/pointer=VALUE");
  sub->add_flag("--json", o->json, "Print the table as JSON");
  sub->add_option("--threads", o->threads, "OpenMP threads per run")->capture_default_str();
  add_thread_policy_option(*sub, o->thread_policy);
  commands.emplace_back(sub, [o] { return run_converge(*o); });
}

}  // namespace splat::app
