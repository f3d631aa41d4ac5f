// The `splat` binary as users call it: version, material library, the
// material-point driver, and clear errors for bad input (exit code 2, field
// and rule in the message).
#include <gtest/gtest.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/scene_runs.hpp"
#include "support/small_tmpfs.hpp"
#include "support/temp_dir.hpp"

namespace {

using splat::test_support::run_command;
using splat::test_support::run_splat;
using splat::test_support::SmallTmpfs;
using splat::test_support::TempDir;

TEST(cli, version_names_the_commit) {
  const auto o = run_splat("--version");
  EXPECT_EQ(o.code, 0);
  EXPECT_NE(o.stdout_text.find("splat 0."), std::string::npos) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("commit "), std::string::npos) << o.stdout_text;
}

// libgomp reads OMP_WAIT_POLICY when it is loaded, before main: a setenv in
// main left the process spinning (two threads 2x slower than passive ones
// beside a busy process). splat starts again with the policy set; a user's
// own setting wins.
TEST(cli, starts_with_a_passive_openmp_wait_policy) {
  using splat::test_support::run_command;
  const auto unset =
      run_command("env -u OMP_WAIT_POLICY " + std::string(SPLAT_BINARY) + " --version");
  EXPECT_EQ(unset.code, 0);
  EXPECT_NE(unset.stdout_text.find("OpenMP wait policy: passive"), std::string::npos)
      << unset.stdout_text;
  const auto active =
      run_command("env OMP_WAIT_POLICY=active " + std::string(SPLAT_BINARY) + " --version");
  EXPECT_NE(active.stdout_text.find("OpenMP wait policy: active"), std::string::npos)
      << active.stdout_text;
}

TEST(cli, materials_lists_the_library) {
  const auto o = run_splat("materials");
  EXPECT_EQ(o.code, 0);
  for (const char* name :
       {"al-thesis",       "al-deck",        "cu-thesis",  "cu-deck",      "cu-ofhc-ptw",
        "steel-hopkinson", "ti6al4v-thesis", "cu-ofhc-jc", "al6061-t6-jc", "ti6al4v-jc",
        "ni200-jc",        "ss316l-jc",      "in718-jc",   "al-thesis-gf", "fe-armco-jc",
        "ta-ptw",          "zn-sg",          "ag-sg",      "mg-az31b-sg",  "al1100-o-jc"}) {
    EXPECT_NE(o.stdout_text.find(name), std::string::npos) << name;
  }
  // The law of each material, with its parameters.
  EXPECT_NE(o.stdout_text.find("johnson-cook: A 90 MPa, B 292 MPa"), std::string::npos)
      << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("preston-tonks-wallace: theta 0.025, p 2"), std::string::npos)
      << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("steinberg-guinan: Y0 150 MPa, Y_max 920 MPa"), std::string::npos)
      << o.stdout_text;
}

// --plot writes the flow stress of one material at 3 rates x 2 temperatures
// x 101 plastic strains from the law itself; at 1e3 /s and 293 K the curve is
// what `splat mat-point` gives in isothermal uniaxial compression at the same
// plastic strain (the plastic rate there is 1e3 E / (E + H), within 0.05 % of
// 1e3 /s past yield; linear interpolation between the plot's points adds
// less than 1e-4), within 0.2 %.
TEST(cli, materials_plot_writes_the_flow_stress_that_mat_point_gives) {
  TempDir t;
  const std::string csv = (t.path / "cu.csv").string();
  const auto o = run_splat("materials --plot cu-ofhc-jc --out " + csv);
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("scripts/plot_flow_stress.py"), std::string::npos) << o.stdout_text;
  std::ifstream f(csv);
  std::string line;
  ASSERT_TRUE(std::getline(f, line));
  EXPECT_EQ(line, "strain_rate,temperature,plastic_strain,flow_stress");
  std::vector<double> eps, sigma;  // the 1e3 /s, 293 K curve
  int rows = 0;
  while (std::getline(f, line)) {
    ++rows;
    double rate = 0, T = 0, e = 0, s = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &rate, &T, &e, &s), 4) << line;
    if (rate == 1e3 && T == 293.0) {
      eps.push_back(e);
      sigma.push_back(s);
    }
  }
  EXPECT_EQ(rows, 3 * 2 * 101);
  ASSERT_EQ(eps.size(), 101u);

  const auto mp = run_splat(
      "mat-point --material cu-ofhc-jc --mode uniaxial-stress --strain-rate 1000 "
      "--max-strain -0.3 --steps 600 --isothermal --no-damage --temperature 293");
  ASSERT_EQ(mp.code, 0) << mp.stdout_text;
  std::istringstream rows_in(mp.stdout_text);
  std::getline(rows_in, line);  // header: time,strain,stress,plastic_strain,...
  double stress = 0, plastic = 0;
  while (std::getline(rows_in, line)) {
    double time = 0, strain = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &time, &strain, &stress, &plastic), 4);
    if (plastic >= 0.2) break;
  }
  ASSERT_GE(plastic, 0.2);
  const std::size_t i = static_cast<std::size_t>(plastic / 0.01);
  const double w = (plastic - eps[i]) / (eps[i + 1] - eps[i]);
  const double from_plot = (1.0 - w) * sigma[i] + w * sigma[i + 1];
  EXPECT_NEAR(-stress, from_plot, 2e-3 * from_plot) << "eps_p " << plastic;
}

TEST(cli, mat_point_prints_csv_with_the_documented_header) {
  const auto o = run_splat(
      "mat-point --material cu-thesis --mode uniaxial-stress --strain-rate 1000 "
      "--max-strain -0.2 --steps 100");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_EQ(
      o.stdout_text.rfind("time,strain,stress,plastic_strain,temperature,damage,yield_stress", 0),
      0u);
  int lines = 0;
  for (char c : o.stdout_text) lines += c == '\n';
  EXPECT_EQ(lines, 102);  // header + initial state + 100 steps
}

TEST(cli, bad_input_names_the_field_and_rule) {
  auto o = run_splat(
      "mat-point --material unobtainium --mode uniaxial-stress --strain-rate 1 "
      "--max-strain 0.1");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.stdout_text.find("unknown material 'unobtainium'"), std::string::npos)
      << o.stdout_text;

  o = run_splat(
      "mat-point --material cu-thesis --mode uniaxial-stress --strain-rate -5 "
      "--max-strain 0.1");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.stdout_text.find("--strain-rate: must be a finite number > 0 (1/s)"),
            std::string::npos)
      << o.stdout_text;

  o = run_splat("mat-point --material cu-thesis --mode twist --strain-rate 1 --max-strain 0.1");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.stdout_text.find("--mode: must be one of"), std::string::npos) << o.stdout_text;

  const auto bad = std::filesystem::temp_directory_path() / "splat_cli_bad_material.json";
  std::ofstream(bad) << R"({"name": "bad", "source": "test", "density": -1})";
  o = run_splat("materials --show " + bad.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.stdout_text.find("/density: must be > 0 (kg/m^3)"), std::string::npos)
      << o.stdout_text;
  std::filesystem::remove(bad);
}

// More threads than the machine has cores are refused before the OpenMP
// runtime is asked for them (100000 crash it).
TEST(cli, run_threads_are_capped_by_the_machine) {
  const std::string scene =
      std::string(SPLAT_SOURCE_DIR) + "/scenes/elastic_sphere_bounce_axisym.json";
  const auto out = std::filesystem::temp_directory_path() / "splat_cli_threads";
  const auto o = run_splat("run " + scene + " --out " + out.string() + " --threads 100000");
  EXPECT_EQ(o.code, 2) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("--threads"), std::string::npos) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("cores of this machine"), std::string::npos) << o.stdout_text;
  std::filesystem::remove_all(out);
}

// A command-line value CLI11 refuses is bad input like any other: exit 2,
// the option and its choices named; the summary says how the steps used the
// threads.
TEST(cli, thread_policy_is_checked_and_reported) {
  const std::string scene =
      std::string(SPLAT_SOURCE_DIR) + "/scenes/elastic_sphere_bounce_axisym.json";
  const auto out = std::filesystem::temp_directory_path() / "splat_cli_thread_policy";
  auto o = run_splat("run " + scene + " --out " + out.string() + " --thread-policy sometimes");
  EXPECT_EQ(o.code, 2) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("--thread-policy: sometimes not in {adaptive,fixed}"),
            std::string::npos)
      << o.stdout_text;
  o = run_splat(
      "run " + scene + " --out " + out.string() + " --threads 1 --thread-policy fixed --json",
      false);
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  const auto doc = nlohmann::json::parse(o.stdout_text);
  EXPECT_EQ(doc["thread_use"]["policy"], "fixed");
  EXPECT_EQ(doc["thread_use"]["steps_on_team"], doc["steps"]);
  EXPECT_EQ(doc["thread_use"]["steps_on_one"], 0);
  std::filesystem::remove_all(out);
}

// A number beyond double in an override names the override, not nlohmann's
// exception.
TEST(cli, an_override_beyond_double_names_the_override) {
  const std::string scene = std::string(SPLAT_SOURCE_DIR) + "/scenes/verification/two_mass.json";
  const auto o = run_splat("run " + scene + " --out '' --set /two_mass/V0=1e400");
  EXPECT_EQ(o.code, 2) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("/two_mass/V0=1e400"), std::string::npos) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("outside the range of a double"), std::string::npos)
      << o.stdout_text;
  EXPECT_EQ(o.stdout_text.find("json.exception"), std::string::npos) << o.stdout_text;
}

// Output to a full disk is the file system's fault, not the input's: exit 74
// (EX_IOERR, which a campaign manager does not blame on the job) with the
// file and the system's reason, whether the result files or the summary on
// stdout cannot be written. Before: exit 2 ("bad input") or exit 0 with the
// summary lost.
TEST(cli, output_to_a_full_disk_exits_74_naming_the_reason) {
  TempDir t;
  const std::filesystem::path disk = t.path / "disk";
  SmallTmpfs tmpfs(disk, 256 * 1024);
  if (!tmpfs.mounted()) GTEST_SKIP() << tmpfs.why_not();
  ASSERT_TRUE(SmallTmpfs::fill(disk / "filler"));
  const std::string scene = std::string(SPLAT_SOURCE_DIR) + "/scenes/verification/two_mass.json";
  auto o = run_splat("run " + scene + " --out " + (disk / "out").string());
  EXPECT_EQ(o.code, 74) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("No space left on device"), std::string::npos) << o.stdout_text;
  o = run_command(std::string(SPLAT_BINARY) + " run " + scene + " --out '' --json 2>&1 > " +
                  (disk / "summary.json").string());
  EXPECT_EQ(o.code, 74) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("cannot write the standard output: No space left on device"),
            std::string::npos)
      << o.stdout_text;
}

// Writes DIR/NAME.json: a campaign over the two-mass verification scene with
// the given `velocity` axis (JSON text); returns its path.
std::filesystem::path two_mass_campaign(const std::filesystem::path& dir, const std::string& name,
                                        const std::string& velocity) {
  const std::filesystem::path path = dir / (name + ".json");
  std::ofstream(path) << R"({"name": ")" << name << R"(", "base_scene": ")" << SPLAT_SOURCE_DIR
                      << R"(/scenes/verification/two_mass.json", "velocity": )" << velocity << "}";
  return path;
}

// A velocity range without end (a step below the spacing of doubles at
// `from`) is refused at its field; it used to list speeds until
// std::bad_alloc. Run under a 2 GB address-space limit so the old behaviour
// fails fast instead of taking the machine's memory.
TEST(cli, a_velocity_range_without_end_is_refused_at_its_field) {
  TempDir t;
  const std::filesystem::path campaign = two_mass_campaign(
      t.path, "endless", R"({"range": {"from": 1000, "to": 1001, "step": 1e-20}})");
  const auto r = run_command("ulimit -v 2000000; " + std::string(SPLAT_BINARY) + " sweep " +
                             campaign.string() + " --db " + (t.path / "c.db").string() + " 2>&1");
  EXPECT_EQ(r.code, 2) << r.stdout_text;
  EXPECT_NE(r.stdout_text.find("/velocity/range: lists more than 1e6 speeds"), std::string::npos)
      << r.stdout_text;
  EXPECT_EQ(r.stdout_text.find("bad_alloc"), std::string::npos) << r.stdout_text;
}

// `splat windows` reads a store it cannot write (issue 28 item 11): here on
// a file system remounted read-only, which binds root too.
TEST(cli, windows_reads_a_store_on_a_read_only_file_system) {
  TempDir t;
  const std::filesystem::path disk = t.path / "disk";
  SmallTmpfs tmpfs(disk, 16L << 20);
  if (!tmpfs.mounted()) GTEST_SKIP() << tmpfs.why_not();
  const std::filesystem::path campaign =
      two_mass_campaign(t.path, "small", R"({"values": [0.2, 0.4, 0.6, 0.8]})");
  const std::string db = (disk / "c.db").string();
  auto o = run_splat("sweep " + campaign.string() + " --db " + db + " --workers 2");
  ASSERT_EQ(o.code, 0) << o.stdout_text;
  ASSERT_TRUE(tmpfs.remount_read_only()) << std::strerror(errno);
  o = run_splat("windows --db " + db + " --format csv");
  EXPECT_EQ(o.code, 0) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("campaign_id,params"), std::string::npos) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("\n1,"), std::string::npos) << o.stdout_text;
}

}  // namespace
