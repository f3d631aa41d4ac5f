// The campaign behind `splat window` (campaign/window_request.hpp): a valid
// campaign for both accuracies, splat's bonding model as the shipped scene
// has it, and options out of range refused naming the option.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <utility>

#include "campaign/spec.hpp"
#include "campaign/window_request.hpp"
#include "solver/input/schema.hpp"

namespace {

using namespace splat::campaign;
using nlohmann::json;

const std::filesystem::path k_source(SPLAT_SOURCE_DIR);

std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const splat::InputError& e) {
    return to_string(e.violations().front());
  }
  return "";
}

}  // namespace

// The bonding model `splat window` uses is the one of the example scene.
TEST(campaign_window_request, bonding_model_is_the_example_scenes) {
  std::ifstream in(k_source / "scenes" / "impact_al_al_expansion.json");
  const json scene = json::parse(in);
  EXPECT_EQ(bonding_model(30.0), scene.at("particle_impact").at("adhesion"));
}

TEST(campaign_window_request, velocity_ranges_parse_or_name_the_option) {
  const VelocityRange r = parse_velocity_range("200:1500:50");
  EXPECT_DOUBLE_EQ(r.from, 200.0);
  EXPECT_DOUBLE_EQ(r.to, 1500.0);
  EXPECT_DOUBLE_EQ(r.step, 50.0);
  EXPECT_DOUBLE_EQ(parse_velocity_range("100:400").step, 100.0);
  for (const char* bad :
       {"", "300", "500:200", "0:100", "100:x", "100:200:0", "1:5001", "100:2000:1", "1:2:3:4"}) {
    EXPECT_EQ(refusal([&] { parse_velocity_range(bad); }).rfind("--velocity: ", 0), 0u) << bad;
  }
}

TEST(campaign_window_request, fast_is_one_level_converged_a_coarse_to_fine_ladder) {
  WindowRequest r;
  r.particle = "cu-thesis";
  r.substrate = "al-thesis";
  r.velocity = {200, 600, 100};
  const CampaignSpec fast = read_campaign(window_campaign(r), k_source);
  EXPECT_EQ(fast.velocities.size(), 5u);
  EXPECT_EQ(ladder_axis(fast), nullptr);
  EXPECT_DOUBLE_EQ(fast.refinement->tolerance, 25.0);
  EXPECT_EQ(fast.base_scene.at("/particle_impact/substrate/material"_json_pointer), "al-thesis");
  // fast runs the middle level of converged.
  EXPECT_EQ(fast.base_scene.at("/particle_impact/particle/elements_across"_json_pointer), 16);
  EXPECT_EQ(fast.description.rfind("Deposition window of particle cu-thesis (radius ", 0), 0u)
      << fast.description;
  EXPECT_NE(fast.description.find(" on substrate al-thesis, 200-600 m/s"), std::string::npos)
      << fast.description;

  r.accuracy = "converged";
  const CampaignSpec fine = read_campaign(window_campaign(r), k_source);
  ASSERT_NE(ladder_axis(fine), nullptr);
  EXPECT_EQ(ladder_axis(fine)->values, (std::vector<json>{8, 16, 32}));
  EXPECT_TRUE(fine.refinement->coarse_to_fine);
  EXPECT_DOUBLE_EQ(fine.refinement->tolerance, 10.0);
}

TEST(campaign_window_request, options_out_of_range_name_the_option) {
  WindowRequest r;
  r.particle = "al-thesis";
  r.radius = 0.0;
  EXPECT_EQ(refusal([&] { window_campaign(r); }), "--radius: must be in [1e-7, 1e-3] (m)");
  r.radius = 12.5e-6;
  r.accuracy = "best";
  EXPECT_EQ(refusal([&] { window_campaign(r); }), "--accuracy: must be fast or converged");
  r.accuracy = "fast";
  r.G_c = -1.0;
  EXPECT_EQ(refusal([&] { window_campaign(r); }), "--G_c: must be >= 0 (J/m^2)");
  r.G_c = 30.0;
  r.workers = 0;
  EXPECT_EQ(refusal([&] { window_campaign(r); }), "--workers: must be >= 1 (jobs run at once)");
}

// Each refinement round runs as many new speeds as there are workers, at
// most the 64 the campaign schema allows.
TEST(campaign_window_request, points_per_round_are_the_workers) {
  WindowRequest r;
  r.particle = "al-thesis";
  for (const auto& [workers, points] :
       {std::pair{1, 1}, std::pair{2, 2}, std::pair{64, 64}, std::pair{1000, 64}}) {
    r.workers = workers;
    for (const char* accuracy : {"fast", "converged"}) {
      r.accuracy = accuracy;
      const CampaignSpec s = read_campaign(window_campaign(r), k_source);
      EXPECT_EQ(s.refinement->points_per_round, points) << workers << " workers, " << accuracy;
    }
  }
}
