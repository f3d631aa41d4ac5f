// The `splat` binary as users call it: version, material library, the
// material-point driver, and clear errors for bad input (exit code 2, field
// and rule in the message).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/scene_runs.hpp"

namespace {

using splat::test_support::run_splat;

TEST(cli, version_names_the_commit) {
  const auto o = run_splat("--version");
  EXPECT_EQ(o.code, 0);
  EXPECT_NE(o.stdout_text.find("splat 0."), std::string::npos) << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("commit "), std::string::npos) << o.stdout_text;
}

TEST(cli, materials_lists_the_library) {
  const auto o = run_splat("materials");
  EXPECT_EQ(o.code, 0);
  for (const char* name : {"al-thesis", "al-deck", "cu-thesis", "cu-deck", "cu-ofhc-ptw",
                           "cu-ofhc-za", "steel-hopkinson", "ti6al4v-thesis"}) {
    EXPECT_NE(o.stdout_text.find(name), std::string::npos) << name;
  }
  // The law of each material, with its parameters.
  EXPECT_NE(o.stdout_text.find("johnson-cook: A 90 MPa, B 292 MPa"), std::string::npos)
      << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("zerilli-armstrong: C0 46.5 MPa, C2 890 MPa"), std::string::npos)
      << o.stdout_text;
  EXPECT_NE(o.stdout_text.find("preston-tonks-wallace: theta 0.025, p 2"), std::string::npos)
      << o.stdout_text;
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

}  // namespace
