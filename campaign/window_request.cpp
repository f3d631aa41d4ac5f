#include "campaign/window_request.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include "solver/input/schema.hpp"

namespace splat::campaign {

using nlohmann::json;

namespace {

[[noreturn]] void refuse(const std::string& option, const std::string& rule) {
  throw InputError(std::vector<SchemaViolation>{{option, rule}});
}

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

// A material for a campaign name: its file stem when a path, characters
// outside [A-Za-z0-9_.-] replaced.
std::string name_part(const std::string& material) {
  std::string s = std::filesystem::path(material).stem().string();
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.' && c != '-') c = '_';
  }
  return s.empty() ? "material" : s;
}

}  // namespace

VelocityRange parse_velocity_range(const std::string& text) {
  std::vector<double> parts;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ':')) {
    try {
      std::size_t used = 0;
      parts.push_back(std::stod(item, &used));
      if (used != item.size()) refuse("--velocity", "'" + item + "' is not a number (m/s)");
    } catch (const std::logic_error&) {
      refuse("--velocity", "'" + item + "' is not a number (m/s)");
    }
  }
  if (parts.size() < 2 || parts.size() > 3)
    refuse("--velocity", "must be FROM:TO or FROM:TO:STEP (m/s)");
  VelocityRange r{parts[0], parts[1], parts.size() == 3 ? parts[2] : 100.0};
  if (!(r.from > 0.0) || !(r.to > r.from) || r.to > 5000.0) {
    refuse("--velocity", "needs 0 < FROM < TO <= 5000 (m/s)");
  }
  if (!(r.step > 0.0) || (r.to - r.from) / r.step > 200.0) {
    refuse("--velocity", "STEP must be > 0 and give at most 200 speeds (m/s)");
  }
  return r;
}

std::string converged_ladder_text() {
  std::string out;
  for (int n : k_converged_ladder) out += (out.empty() ? "" : ", ") + std::to_string(n);
  return out;
}

json bonding_model(double G_c) {
  return {{"G_c", G_c},
          {"sigma_c", "flow-stress"},
          {"activation",
           {{"rule", "surface-expansion"},
            {"surface_expansion", 0.3},
            {"sides", "both"},
            {"bonded_fraction", "film-cracks"}}},
          {"averaging_length", 2e-6},
          {"D_adh_max", nullptr}};
}

json window_campaign(const WindowRequest& r) {
  if (!(r.radius >= 1e-7 && r.radius <= 1e-3)) refuse("--radius", "must be in [1e-7, 1e-3] (m)");
  if (r.accuracy != "fast" && r.accuracy != "converged") {
    refuse("--accuracy", "must be fast or converged");
  }
  if (!(r.G_c >= 0.0)) refuse("--G_c", "must be >= 0 (J/m^2)");
  if (r.workers < 1) refuse("--workers", "must be >= 1 (jobs run at once)");
  const bool converged = r.accuracy == "converged";
  const std::string substrate = r.substrate.empty() ? r.particle : r.substrate;
  const double tolerance = converged ? 10.0 : 25.0;
  json scene = {{"name", "window"},
                {"particle_impact",
                 {{"particle",
                   {{"material", r.particle},
                    {"radius", r.radius},
                    {"elements_across", 16},
                    {"discretization", "fe"}}},
                  {"substrate", {{"material", substrate}}},
                  {"velocity", r.velocity.from},
                  {"fidelity", "fe-axisym"},
                  {"adhesion", bonding_model(r.G_c)}}}};
  json doc = {
      {"name", "window-" + name_part(r.particle) + "-on-" + name_part(substrate) + "-r" +
                   number(r.radius * 1e6) + "um-" + r.accuracy},
      {"description",
       "Deposition window of particle " + r.particle + " (radius " + number(r.radius) +
           " m) on substrate " + substrate + ", " + number(r.velocity.from) + "-" +
           number(r.velocity.to) + " m/s, axisymmetric FE with splat's bonding model (G_c " +
           number(r.G_c) + " J/m^2), edges refined to " + number(tolerance) + " m/s" +
           (converged ? " at " + converged_ladder_text() + " elements across (coarse to fine)"
                      : " at 16 elements across") +
           "."},
      {"tags", {"window"}},
      {"base_scene", scene},
      {"velocity",
       {{"range", {{"from", r.velocity.from}, {"to", r.velocity.to}, {"step", r.velocity.step}}}}},
      {"refinement",
       {{"tolerance", tolerance},
        {"guard_band", 2.0 * tolerance},
        {"max_extra_jobs", converged ? 300 : 100},
        {"points_per_round", std::min(r.workers, k_max_points_per_round)},
        {"coarse_to_fine", converged}}},
      {"job", {{"time_limit", 1800}, {"retries", 1}, {"threads", 1}}}};
  if (converged) {
    doc["fields"] = {{{"pointer", "/particle_impact/particle/elements_across"},
                      {"unit", "-"},
                      {"values", k_converged_ladder}}};
  }
  return doc;
}

}  // namespace splat::campaign
