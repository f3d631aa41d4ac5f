// The `splat` binary as users call it: version, material library, the
// material-point driver, and clear errors for bad input (exit code 2, field
// and rule in the message).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

struct Output {
  int code = -1;
  std::string text;  // stdout and stderr
};

Output run(const std::string& args) {
  const std::string cmd = std::string(SPLAT_BINARY) + " " + args + " 2>&1";
  Output out;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return out;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) out.text.append(buf.data(), n);
  const int status = pclose(pipe);
  out.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

TEST(cli, version_names_the_commit) {
  const Output o = run("--version");
  EXPECT_EQ(o.code, 0);
  EXPECT_NE(o.text.find("splat 0."), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("commit "), std::string::npos) << o.text;
}

TEST(cli, materials_lists_the_library) {
  const Output o = run("materials");
  EXPECT_EQ(o.code, 0);
  for (const char* name :
       {"al-thesis", "al-deck", "cu-thesis", "cu-deck", "steel-hopkinson", "ti6al4v-thesis"}) {
    EXPECT_NE(o.text.find(name), std::string::npos) << name;
  }
}

TEST(cli, mat_point_prints_csv_with_the_documented_header) {
  const Output o =
      run("mat-point --material cu-thesis --mode uniaxial-stress --strain-rate 1000 "
          "--max-strain -0.2 --steps 100");
  ASSERT_EQ(o.code, 0) << o.text;
  EXPECT_EQ(o.text.rfind("time,strain,stress,plastic_strain,temperature,damage,yield_stress", 0),
            0u);
  int lines = 0;
  for (char c : o.text) lines += c == '\n';
  EXPECT_EQ(lines, 102);  // header + initial state + 100 steps
}

TEST(cli, bad_input_names_the_field_and_rule) {
  Output o =
      run("mat-point --material unobtainium --mode uniaxial-stress --strain-rate 1 "
          "--max-strain 0.1");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.text.find("unknown material 'unobtainium'"), std::string::npos) << o.text;

  o =
      run("mat-point --material cu-thesis --mode uniaxial-stress --strain-rate -5 "
          "--max-strain 0.1");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.text.find("--strain-rate: must be a finite number > 0 (1/s)"), std::string::npos)
      << o.text;

  o = run("mat-point --material cu-thesis --mode twist --strain-rate 1 --max-strain 0.1");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.text.find("--mode: must be one of"), std::string::npos) << o.text;

  const auto bad = std::filesystem::temp_directory_path() / "splat_cli_bad_material.json";
  std::ofstream(bad) << R"({"name": "bad", "source": "test", "density": -1})";
  o = run("materials --show " + bad.string());
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.text.find("/density: must be > 0 (kg/m^3)"), std::string::npos) << o.text;
  std::filesystem::remove(bad);
}

}  // namespace
