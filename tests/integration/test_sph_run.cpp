// splat run on a scene with an SPH body: the SPH Taylor bar
// (scenes/taylor_copper_sph.json, coarsened to 4 spacings across the radius
// and 40 us to stay short) runs to its end time through the command, prints
// a schema-valid summary, and leaves an HDF5 file with histories, the SPH
// body's reference-update count and point snapshots.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "solver/input/schema.hpp"
#include "solver/io/result_file.hpp"

namespace splat {
namespace {

TEST(SphRun, taylor_bar_sph_scene_runs) {
  const auto dir = std::filesystem::temp_directory_path() / "splat_sph_taylor_run";
  std::filesystem::remove_all(dir);
  const std::string cmd = std::string(SPLAT_BINARY) + " run " + SPLAT_SOURCE_DIR +
                          "/scenes/taylor_copper_sph.json --json --threads 1 --out " +
                          dir.string() +
                          " --set /bodies/0/discretization/elements_across=4"
                          " --set /time/end_time=4e-5 2>/dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string text;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) text.append(buf.data(), n);
  const int status = pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 0) << text;
  const nlohmann::json s = nlohmann::json::parse(text, nullptr, false);
  ASSERT_FALSE(s.is_discarded()) << text;
  for (const SchemaViolation& v : validate("result", s)) ADD_FAILURE() << to_string(v);
  EXPECT_EQ(s.value("outcome", ""), "finished") << s.dump(2);
  // Below the scene's limit; the loss is mostly the wall landing the first
  // particle layer (its normal kinetic energy), larger at this coarse spacing.
  EXPECT_LT(std::abs(s["energy"]["balance_error"].get<double>()), 0.05);
  const nlohmann::json& rod = s["bodies"][0];
  EXPECT_GT(rod["max_plastic_strain"].get<double>(), 0.5);
  // The rod has shortened (from 32.4 mm) and mushroomed (from 3.2 mm).
  EXPECT_LT(rod["extent_max"][2].get<double>(), 0.030);
  EXPECT_GT(rod["extent_max"][0].get<double>(), 0.0045);

  const auto h5 = dir / "taylor_copper_sph.h5";
  const ResultSummary rs = read_result_summary(h5);
  EXPECT_GE(rs.snapshots, 2u);
  const std::vector<double> updates = read_history(h5, "rod_reference_updates");
  ASSERT_FALSE(updates.empty());
  EXPECT_GE(updates.back(), 1.0);  // the impact needed at least one reference update
  const std::vector<double> x = read_snapshot_field(h5, rs.snapshots - 1, "rod", "coordinates");
  EXPECT_EQ(x.size(), 3u * rod["elements"].get<std::size_t>());
  EXPECT_TRUE(std::filesystem::exists(dir / "taylor_copper_sph.xmf"));
}

}  // namespace
}  // namespace splat
