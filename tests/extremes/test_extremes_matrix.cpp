// The extremes matrix (issue 22): every fidelity rung x impact speeds 1 to
// 3000 m/s x two resolutions (the default and one finer) x {no adhesion,
// adhesion} for Al/Al and Cu/Cu, plus 30 and 60 degree oblique impacts. Every
// run is a `splat run` of its own (a crash is a signal, not a lost test
// program) and must end with a verdict that passes the physics checks or with
// `unstable` and a named reason: never NaN, a crash, a hang (wall-clock limit)
// or a wrong verdict where physics says which to expect:
//   - without adhesion, never stick (nothing holds the particle);
//   - at 1 m/s, a rebound (elastic: activation needs a yield drop);
//   - a rebound leaves no faster than it arrived (COR <= 1);
//   - a verdict only with the guard passed and the energy balance within its
//     limit; exit code 0 exactly for a verdict.
// Each test prints its rung's table (S stick, R rebound, U:reason) and writes
// it to build/test-artifacts/extremes_<rung>.md. Label `extremes`, not in the
// default set: `bash scripts/test.sh --extremes` (hours on 2 cores for the full
// 3D rungs; `ctest -L extremes -R fe_axisym` for one rung).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <unistd.h>

#include "solver/input/schema.hpp"
#include "support/scene_runs.hpp"

namespace splat {
namespace {

using nlohmann::json;

constexpr double k_wall_limit = 3600.0;  // s per run: beyond it the run counts as a hang

struct Rung {
  std::string fidelity;
  int default_across = 0, finer_across = 0;
};

struct Pair {
  std::string name, material;
  double drop_percent = 0.0;  // yield-drop activation, thesis deck (30 % Al, 5 % Cu)
};

const std::vector<double> k_speeds{1, 100, 300, 600, 1000, 1500, 2000, 3000};  // m/s
const std::vector<Pair> k_pairs{{"Al/Al", "al-thesis", 30.0}, {"Cu/Cu", "cu-thesis", 5.0}};

json impact_scene(const Rung& rung, const Pair& pair, double v, int across, bool adhesion,
                  double angle = 0.0) {
  json block = {
      {"particle", {{"material", pair.material}, {"radius", 12.5e-6}, {"elements_across", across}}},
      {"substrate", {{"material", pair.material}}},
      {"velocity", v},
      {"fidelity", rung.fidelity}};
  if (angle != 0.0) block["angle"] = angle;
  if (adhesion) {
    block["adhesion"] = {
        {"G_c", 30.0},
        {"sigma_c", nullptr},
        {"activation",
         {{"rule", "yield-drop"}, {"drop_percent", pair.drop_percent}, {"sides", "either"}}},
        {"D_adh_max", 0.5}};
  }
  return {{"name", "extremes"}, {"particle_impact", block}};
}

// Every number finite (NaN would be written as null and fail the schema too).
bool all_finite(const json& j) {
  if (j.is_number_float()) return std::isfinite(j.get<double>());
  if (j.is_object() || j.is_array()) {
    for (const json& e : j) {
      if (!all_finite(e)) return false;
    }
  }
  return true;
}

struct Cell {
  std::string text;  // S, R or U:reason
  std::string problem;
};

// Runs one scene and checks the invariants of the header; returns its cell.
Cell run_and_check(const json& scene, double v, bool adhesion) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("splat_extremes_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / "scene.json";
  json doc = scene;
  doc["time"] = {{"wall_clock_limit", k_wall_limit}};
  std::ofstream(file) << doc.dump();
  const test_support::CommandOutput o = test_support::run_splat(
      "run " + file.string() + " --json --threads 1 --out " + (dir / "out").string(), false);
  std::filesystem::remove_all(dir);
  Cell c;
  if (o.code < 0) return {"CRASH", "killed by a signal or could not start"};
  const json s = json::parse(o.stdout_text, nullptr, false);
  if (s.is_discarded()) return {"ERR", "no summary (exit " + std::to_string(o.code) + ")"};
  if (!validate("result", s).empty()) c.problem += "schema; ";
  if (!all_finite(s)) c.problem += "non-finite figure; ";
  const std::string outcome = s.value("outcome", "");
  const bool verdict = outcome == "stick" || outcome == "rebound";
  if ((o.code == 0) != verdict)
    c.problem += "exit " + std::to_string(o.code) + " for " + outcome + "; ";
  if (s.value("reason", "").empty()) c.problem += "no reason; ";
  if (verdict) {
    c.text = outcome == "stick" ? "S" : "R";
    if (!s["guard"]["failed"].get<std::string>().empty())
      c.problem += "verdict with a failed guard; ";
    if (std::abs(s["energy"]["balance_error"].get<double>()) > 0.15)
      c.problem += "verdict with the energy balance off; ";
    if (!adhesion && outcome == "stick") c.problem += "stick without adhesion; ";
    if (outcome == "rebound" && s["coefficient_of_restitution"].get<double>() > 1.0 + 1e-9)
      c.problem += "COR above 1; ";
  } else if (outcome == "unstable") {
    c.text = "U:" + s.value("stop_reason", "?");
    if (s.value("stop_reason", "").empty()) c.problem += "unstable without a stop reason; ";
  } else {
    c.text = outcome;  // timed-out (a hang at this limit), error, cancelled
    c.problem += outcome + ": " + s.value("reason", "") + "; ";
  }
  if (v <= 1.0 && outcome != "rebound") c.problem += "no rebound at 1 m/s; ";
  return c;
}

// Leaves a rung's table in build/test-artifacts/extremes_NAME.md: after
// each row, so that a rung stopped before its end (the full 3D rungs take
// hours) keeps the rows it measured.
void write_table(const std::string& name, const std::string& table) {
  const auto dir = std::filesystem::path(SPLAT_BUILD_DIR) / "test-artifacts";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / ("extremes_" + name + ".md")) << table;
}

// Prints a rung's finished table and leaves it as above.
void publish(const std::string& name, const std::string& table) {
  std::printf("%s\n", table.c_str());
  write_table(name, table);
}

void run_rung(const Rung& rung) {
  std::string table = "### " + rung.fidelity + "\n\n| pair | adhesion | across |";
  for (double v : k_speeds) table += " " + std::to_string(static_cast<int>(v)) + " |";
  table += "\n| --- | --- | --- |";
  for (std::size_t k = 0; k < k_speeds.size(); ++k) table += " --- |";
  table += "\n";
  std::map<std::string, int> counts;
  for (const Pair& pair : k_pairs) {
    for (bool adhesion : {false, true}) {
      for (int across : {rung.default_across, rung.finer_across}) {
        table += "| " + pair.name + " | " + (adhesion ? "yes" : "no") + " | " +
                 std::to_string(across) + " |";
        for (double v : k_speeds) {
          const Cell c = run_and_check(impact_scene(rung, pair, v, across, adhesion), v, adhesion);
          EXPECT_TRUE(c.problem.empty())
              << rung.fidelity << " " << pair.name << " v " << v << " across " << across
              << " adhesion " << adhesion << ": " << c.problem << " (" << c.text << ")";
          ++counts[c.text];
          table += " " + c.text + (c.problem.empty() ? "" : " (!)") + " |";
          std::printf("%s %s adhesion %d, %d across, %g m/s: %s\n", rung.fidelity.c_str(),
                      pair.name.c_str(), adhesion ? 1 : 0, across, v, c.text.c_str());
          std::fflush(stdout);
        }
        table += "\n";
        write_table(rung.fidelity, table + "\n(unfinished: the rows above are done)\n");
      }
    }
  }
  table += "\n";
  for (const auto& [k, n] : counts) table += k + ": " + std::to_string(n) + "  ";
  table += "\n";
  publish(rung.fidelity, table);
}

TEST(extremes_matrix, fe_axisym) {
  run_rung({"fe-axisym", 12, 16});
}
TEST(extremes_matrix, fe_3d_quarter) {
  run_rung({"fe-3d-quarter", 12, 16});
}
TEST(extremes_matrix, fe_3d_full) {
  run_rung({"fe-3d-full", 12, 16});
}
TEST(extremes_matrix, sph_3d_quarter) {
  run_rung({"sph-3d-quarter", 5, 6});
}
TEST(extremes_matrix, sph_3d_full) {
  run_rung({"sph-3d-full", 5, 6});
}
TEST(extremes_matrix, sph_on_fe_3d_quarter) {
  run_rung({"sph-on-fe-3d-quarter", 5, 6});
}
TEST(extremes_matrix, sph_on_fe_3d_full) {
  run_rung({"sph-on-fe-3d-full", 5, 6});
}

// Oblique impacts (auto picks the full 3D model) at 30 and 60 degrees.
TEST(extremes_matrix, oblique) {
  std::string table =
      "### oblique (auto)\n\n| pair | adhesion | angle | 300 | 600 | 1000 |\n| --- | --- | --- | "
      "--- | --- | --- |\n";
  for (const Pair& pair : k_pairs) {
    for (bool adhesion : {false, true}) {
      for (double angle : {30.0, 60.0}) {
        table += "| " + pair.name + " | " + (adhesion ? "yes" : "no") + " | " +
                 std::to_string(static_cast<int>(angle)) + " |";
        for (double v : {300.0, 600.0, 1000.0}) {
          const Cell c = run_and_check(impact_scene({"auto", 0, 0}, pair, v, 12, adhesion, angle),
                                       v, adhesion);
          EXPECT_TRUE(c.problem.empty()) << pair.name << " angle " << angle << " v " << v << ": "
                                         << c.problem << " (" << c.text << ")";
          table += " " + c.text + (c.problem.empty() ? "" : " (!)") + " |";
        }
        table += "\n";
      }
    }
  }
  publish("oblique", table);
}

}  // namespace
}  // namespace splat
