#include "solver/input/impact_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "solver/input/material_io.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/input/schema.hpp"
#include "solver/material/strength_model.hpp"

namespace splat {
namespace {

using nlohmann::json;

constexpr double k_pi = std::numbers::pi;
constexpr double k_gap = 1e-3;                   // initial gap / particle radius, -
constexpr double k_grading_ratio = 1.15;         // substrate element growth per element, -
constexpr double k_size_velocity = 250.0;        // m/s per extra particle radius of substrate
constexpr double k_rigid_factor = 3.0;           // substrate yield / particle flow stress for rigid
constexpr double k_hourglass_coefficient = 0.1;  // stiffness-form hourglass coefficient, -
constexpr double k_erosion_dt_fraction = 0.05;   // default geometric erosion, of h / c_p, -
// Shortest default maximum time, in particle transits R / c_p: a particle
// held by a ring of links rings down over tens of its periods (FE Al/Al,
// R 12.5 um, 700-850 m/s, 16 and 32 across: settled 70-190 ns after the
// impact, 35-90 transits), so a maximum time of a few contact times left
// those runs `undecided`.
constexpr double k_settle_transits = 100.0;  // -
// Fastest impact `auto` models with an FE particle. docs/verification.md "FE impact robustness"
// table (Al/Al at 8, 12 and 16 elements across): verdicts up to 800 m/s, but
// from 600 m/s on they rest on element erosion (the jetting rim reaches the
// damage cap and is removed, links with it) and from 1000-1500 m/s the runs
// end `unstable` (eroded-mass limit, energy balance). SPH keeps all the
// particle's material (thesis 1.3.2.2), so above this speed `auto` models the
// particle with SPH. One constant: move it when the FE table moves.
constexpr double k_fe_max_velocity = 500.0;  // m/s
constexpr int k_sph_default_across =
    5;  // spacings across R (thesis: 1.25 um SPH radius at R 12.5 um)
constexpr int k_max_spacings_across = 64;  // schema maximum of elements_across, -
constexpr double k_sph_gap = 0.1;          // initial height of the ball above R, in spacings, -
// SPH substrate block: half-width and depth R (2.4 + v / 1500 m/s), 2.8 R at
// 600 m/s (the thesis's 70 x 70 x 35 um block at R 12.5 um), at most 6 R.
constexpr double k_sph_size_base = 2.4;              // -
constexpr double k_sph_size_velocity = 1500.0;       // m/s per extra particle radius
constexpr double k_sph_size_cap = 6.0;               // -
constexpr double k_sph_energy_balance_limit = 0.15;  // of the initial energy, -
constexpr double k_sph_max_h_growth = 1.0;           // h / h_0 cap at reference updates, -
// Field snapshots of an impact run unless its `output` names some: the
// initial state, this many less one evenly over the impact's duration (3
// contact times, at most max_time) and one at max_time. A run that
// settles earlier writes its final state as the last one (impact_al_al.json:
// 13 snapshots, 1.4 MB with the histories; impact_al_al_sph.json, the
// quarter SPH model: 8 MB).
constexpr int k_default_snapshot_intervals = 16;  // -

[[noreturn]] void fail(const std::string& pointer, const std::string& message) {
  throw InputError({{pointer, message}});
}

// Flow stress at eps_p = 1, 1e7 /s and T_ref: the stress a strongly
// deforming particle reaches in a cold-spray impact.
double impact_flow_stress(const Material& m) {
  const double T_ref = strength_references(m.strength).T_ref;
  return flow_stress(m.strength, ModelSwitches{}, 1.0, 1e7, T_ref).value;
}

double effective_modulus(const Material& a, const Material& b) {
  auto term = [](const Material& m) { return (1.0 - m.elastic.nu * m.elastic.nu) / m.elastic.E; };
  return 1.0 / (term(a) + term(b));
}

// Hertz contact time of a sphere (radius R, mass M) on a half-space at speed
// v (Johnson 1985, eq. 11.24): t = 2.87 (M^2 / (R E*^2 v))^(1/5).
double hertz_time(double R, double M, double E_star, double v) {
  return 2.87 * std::pow(M * M / (R * E_star * E_star * v), 0.2);
}

json switches(bool damage, bool heat_conduction) {
  return {{"damage", damage},
          {"thermal_softening", true},
          {"rate_hardening", true},
          {"adiabatic_heating", true},
          {"heat_conduction", heat_conduction}};
}

json vec(double x, double y, double z) {
  return json::array({x, y, z});
}

// The SPH model `auto` chooses: the ball on an SPH or an FE block, a quarter
// of each for a normal impact, the whole of each for an oblique one.
Fidelity sph_fidelity(bool sph_substrate, bool oblique) {
  if (sph_substrate) return oblique ? Fidelity::sph_3d_full : Fidelity::sph_3d_quarter;
  return oblique ? Fidelity::sph_on_fe_3d_full : Fidelity::sph_on_fe_3d_quarter;
}

}  // namespace

ExpandedImpact expand_particle_impact(const json& doc, const std::filesystem::path& base_dir) {
  const json& pi = doc.at("particle_impact");
  const std::string base = "/particle_impact";
  const json& particle = pi.at("particle");
  const json substrate = pi.value("substrate", json::object());

  const Material mp =
      scene_material(particle.at("material"), base_dir, base + "/particle/material");
  const Material ms = scene_material(substrate.value("material", particle.at("material")), base_dir,
                                     base + "/substrate/material");
  const double R = particle.at("radius").get<double>();
  const double v = pi.at("velocity").get<double>();
  const double angle = pi.value("angle", 0.0);  // degrees from the normal
  const bool has_adhesion = pi.contains("adhesion");
  const json adhesion = pi.value("adhesion", json::object());
  // Damage is on when `erosion` or D_adh_max needs it (or `damage` says so).
  // With damage on, elements that reach the damage cap D_max are eroded
  // unless `erosion` is false: a failed element carries next to no stress
  // (G_d = (1 - D_max) G), and kept in the mesh it only tangles in the
  // jetting rim of a fast impact (800 m/s, 12 across: internal energy
  // negative, bulk-viscosity work twice the impact energy). Its mass and
  // energy are booked as eroded; the impact run limits the eroded share of
  // the particle (max_eroded_fraction).
  const bool adhesion_erosion =
      has_adhesion && adhesion.contains("D_adh_max") && !adhesion.at("D_adh_max").is_null();
  // The yield-drop activation detects the onset of an adiabatic shear
  // instability, which the material law produces only with its damage
  // softening (thesis 1.4.4, 2.2.2: damage is added to the law so that the
  // interface can localise): damage is on by default with that criterion too.
  const bool yield_drop = has_adhesion && adhesion.contains("activation") &&
                          adhesion.at("activation").value("rule", "none") == "yield-drop";
  const bool damage =
      pi.value("damage", pi.value("erosion", false) || adhesion_erosion || yield_drop);
  const bool erosion = damage && pi.value("erosion", true);
  const std::string fidelity = pi.value("fidelity", "auto");
  const std::string substrate_kind = substrate.value("type", "auto");
  const std::string particle_disc = particle.value("discretization", "auto");
  const std::string substrate_disc = substrate.value("discretization", "auto");
  const double sigma_p = impact_flow_stress(mp);

  ExpandedImpact out;
  ImpactModelChoice& c = out.choice;
  std::vector<std::string> reasons;

  // Fidelity.
  const std::optional<Fidelity> asked = parse<Fidelity>(fidelity);
  if (!asked && fidelity != "auto") {
    fail(base + "/fidelity", "unknown fidelity " + fidelity);
  }
  if (!asked) {
    const bool sph_asked = particle_disc == "sph";
    const bool too_fast = particle_disc == "auto" && v > k_fe_max_velocity;
    if (sph_asked || too_fast) {
      // SPH substrate when it is asked for, or when the substrate yields at
      // least as readily as the particle (its yield stress below the
      // particle's impact flow stress): it jets too and a mesh would tangle.
      const bool sph_substrate =
          substrate_disc == "sph" ||
          (substrate_disc == "auto" && initial_yield_stress(ms.strength) < sigma_p);
      c.model = sph_fidelity(sph_substrate, angle != 0.0);
      reasons.push_back(sph_asked ? std::string("SPH particle as asked")
                                  : "SPH particle: impact velocity " + std::to_string(v) +
                                        " m/s is above " + std::to_string(k_fe_max_velocity) +
                                        " m/s, above which the FE particle's jetting rim "
                                        "erodes (docs/verification.md, FE impact robustness)");
      reasons.push_back(sph_substrate
                            ? (substrate_disc == "sph"
                                   ? std::string("SPH substrate as asked")
                                   : "SPH substrate: its yield stress " +
                                         std::to_string(initial_yield_stress(ms.strength) / 1e6) +
                                         " MPa is below the particle's flow stress " +
                                         std::to_string(sigma_p / 1e6) + " MPa, so it jets too")
                            : "FE substrate");
      reasons.push_back(angle != 0.0 ? "oblique impact: full 3D"
                                     : "normal impact: quarter model, two symmetry planes");
    } else if (angle != 0.0) {
      c.model = Fidelity::fe_3d_full;
      reasons.push_back("oblique impact (angle " + std::to_string(angle) +
                        " deg): only a full 3D model represents it");
    } else {
      c.model = Fidelity::fe_axisym;
      reasons.push_back("normal impact: axisymmetric");
    }
  } else {
    c.model = *asked;
    reasons.push_back("fidelity " + fidelity + " as asked");
    if (angle != 0.0 && !is_full_3d(c.model)) {
      fail(base + "/fidelity",
           "an oblique impact (angle != 0) needs a full 3D fidelity (fe-3d-full, sph-3d-full, "
           "sph-on-fe-3d-full) or auto, not " +
               fidelity);
    }
  }
  const std::string model_name(to_string(c.model));
  const bool sph = has_sph_particle(c.model);
  const bool sph_substrate = has_sph_substrate(c.model);
  if (sph && particle_disc == "fe") {
    fail(base + "/particle/discretization",
         "is fe, but fidelity " + model_name + " has an SPH particle");
  }
  if (!sph && particle_disc == "sph") {
    fail(base + "/particle/discretization",
         "is sph, but fidelity " + model_name +
             " has no SPH particle (use sph-3d-* or sph-on-fe-3d-*)");
  }
  if (sph && substrate_disc != "auto" && (substrate_disc == "sph") != sph_substrate) {
    fail(base + "/substrate/discretization",
         "is " + substrate_disc + ", but fidelity " + model_name + " has " +
             (sph_substrate ? "an SPH" : "an FE") + " substrate");
  }
  if (!sph && substrate_disc == "sph") {
    fail(base + "/substrate/discretization", "sph needs an SPH fidelity (sph-3d-* or auto)");
  }

  // Resolution: FE elements across the radius, or the SPH particle spacing
  // (spacing, else R / elements_across, default R / 5).
  if (particle.contains("spacing") && particle.contains("elements_across")) {
    fail(base + "/particle/spacing", "give spacing or elements_across, not both");
  }
  if (particle.contains("spacing") && !sph) {
    fail(base + "/particle/spacing", "is for SPH particles; FE particles take elements_across");
  }
  const int n = particle.value("elements_across", sph ? k_sph_default_across : 12);
  const double h = sph ? particle.value("spacing", R / n) : R / n;
  if (sph && !(R / h >= 2.0)) {
    fail(base + "/particle/spacing", "must be at most R / 2 (m): fewer than 2 spacings across R");
  }
  // The bound elements_across has in the schema: finer spacings ask for more
  // particles (~ (R / h)^3) than memory holds (1e-8 m at R 12.5 um ended in
  // std::bad_alloc).
  if (sph && R / h > k_max_spacings_across * (1.0 + 1e-9)) {
    fail(base + "/particle/spacing",
         "must be at least R / " + std::to_string(k_max_spacings_across) + " (m): at most " +
             std::to_string(k_max_spacings_across) + " spacings across R, as elements_across");
  }
  // Numerics of both bodies (see the header: stiffness hourglass by default).
  json hourglass = {{"type", "stiffness"}, {"coefficient", k_hourglass_coefficient}};
  if (pi.contains("hourglass")) hourglass.update(pi.at("hourglass"));
  const json viscosity = pi.value("artificial_viscosity", json::object());
  // Erosion: geometric (inverted elements and those whose stable step fell
  // below a fraction of the initial one) unless switched off, and at the
  // damage cap whenever damage is on (above) unless `erosion` is false.
  const double erosion_fraction = pi.value("erosion_time_step_fraction", k_erosion_dt_fraction);
  const double c_max = std::max(p_wave_speed(mp), p_wave_speed(ms));
  const json erosion_block = {{"enabled", erosion || erosion_fraction > 0.0},
                              {"min_time_step", erosion_fraction * h / c_max},
                              {"damage", erosion}};
  // SPH settings of both SPH bodies (the block's `sph`, thesis defaults
  // otherwise); an explicit `erosion: true` deactivates particles at the
  // damage cap (they are never deleted; the FE default of eroding failed
  // elements whenever damage is on is not carried over to SPH). The ball is
  // HCP, the substrate block cubic unless asked.
  json sph_settings = pi.value("sph", json::object());
  if (!sph_settings.contains("deactivate_failed")) {
    sph_settings["deactivate_failed"] = pi.value("erosion", false);
  }
  // Smoothing lengths kept at their initial value through reference updates:
  // with the body default (growth up to 2x) the quarter Al/Al model's time
  // step collapsed 1000-fold 13 ns into a 1500 m/s impact; with h fixed the
  // run finished with a verdict (and 1000 m/s settled in 1035 steps, not 3714).
  if (!sph_settings.contains("max_h_growth")) sph_settings["max_h_growth"] = k_sph_max_h_growth;

  // Substrate: deformable or rigid.
  if (substrate_kind == "rigid") {
    c.rigid_substrate = true;
    reasons.push_back("rigid substrate as asked");
  } else if (substrate_kind == "auto" && !has_adhesion && c.model != Fidelity::two_mass &&
             initial_yield_stress(ms.strength) >= k_rigid_factor * sigma_p) {
    c.rigid_substrate = true;
    reasons.push_back("rigid substrate: its yield stress " +
                      std::to_string(initial_yield_stress(ms.strength) / 1e6) +
                      " MPa is at least 3x the particle's flow stress " +
                      std::to_string(sigma_p / 1e6) + " MPa, so it cannot yield");
  }
  if (c.rigid_substrate && has_adhesion) {
    fail(base + "/substrate/type",
         "adhesion needs a deformable substrate (a rigid wall carries no links)");
  }
  reasons.push_back(has_adhesion ? "adhesion on contact pairs"
                                 : "no adhesion asked: plain contact");
  if (!damage) reasons.push_back("no erosion, D_adh_max or yield-drop activation: damage off");

  const double E_star = effective_modulus(mp, ms);
  const double M = 4.0 / 3.0 * k_pi * R * R * R * mp.density;
  const double t_hertz = v > 0.0 ? hertz_time(R, M, E_star, v) : 0.0;
  // The impact's own duration (contact, spring-back) and the time a held
  // particle may take to settle after it.
  const double t_impact = v > 0.0 ? 3.0 * std::max(t_hertz, std::min(R / v, 10.0 * t_hertz)) : 0.0;
  const double t_settle = k_settle_transits * R / p_wave_speed(mp);
  const double t_max_default = v > 0.0 ? std::max(t_impact, t_settle) : 0.0;
  const json& end = pi.value("end_time", json("adaptive"));
  const double t_max = end.is_number() ? end.get<double>() : pi.value("max_time", t_max_default);
  if (!(t_max > 0.0)) {
    fail(base + "/velocity",
         "must be > 0 (m/s) unless end_time is given: the impact never happens");
  }

  json scene = {{"name", doc.at("name")}, {"particle_impact", pi}};
  if (doc.contains("description")) scene["description"] = doc.at("description");
  if (doc.contains("output")) scene["output"] = doc.at("output");
  json time = doc.value("time", json::object());
  time["end_time"] = t_max;
  // SPH impacts close their balance to 1-6 % of the initial energy (Al/Al,
  // 300-3000 m/s, 6-10 spacings across: the contact's node-level landings
  // and the viscosity's booking; docs/verification.md, SPH), against 1 % for
  // FE: the balance check of SPH models allows more.
  if (sph && !time.contains("energy_balance_limit")) {
    time["energy_balance_limit"] = k_sph_energy_balance_limit;
  }
  scene["time"] = time;

  if (c.model == Fidelity::two_mass) {
    // The crudest level: the particle as a rigid mass, the substrate as the
    // rigid mass of a hemisphere of the particle's radius, joined over the
    // Hertz contact area at v (a = sqrt(R delta_max)).
    const double m_sub = 2.0 / 3.0 * k_pi * R * R * R * ms.density;
    const double m_star = M * m_sub / (M + m_sub);
    const double delta = std::pow(15.0 * m_star * v * v / (16.0 * E_star * std::sqrt(R)), 0.4);
    const double a = std::min(std::sqrt(R * delta), R);
    json two_mass = {{"M", M},
                     {"m", m_sub},
                     {"k", 0.0},
                     {"V0", v},
                     {"area", std::max(k_pi * a * a, 1e-30)},
                     {"adhesion", has_adhesion ? adhesion : json{{"G_c", 0.0}}}};
    scene["two_mass"] = two_mass;
    scene["time"] = {{"end_time", 100.0 * std::max(t_max, 1e-12)}};
    reasons.push_back("substrate as a rigid hemisphere of mass " + std::to_string(m_sub) +
                      " kg, link area from the Hertz contact radius");
    c.why = reasons.front();
    for (std::size_t i = 1; i < reasons.size(); ++i) c.why += "; " + reasons[i];
    scene["particle_impact"]["model"] = {{"name", model_name}, {"why", c.why}};
    out.scene = std::move(scene);
    return out;
  }

  json& output = scene["output"];
  if (!output.contains("snapshot_times") && !output.contains("snapshot_count")) {
    json times = json::array();
    const double t_spread = t_impact > 0.0 ? std::min(t_impact, t_max) : t_max;
    for (int i = 0; i <= k_default_snapshot_intervals; ++i) {
      times.push_back(i == k_default_snapshot_intervals
                          ? t_max
                          : t_spread * static_cast<double>(i) / k_default_snapshot_intervals);
    }
    output["snapshot_times"] = std::move(times);
  }

  const bool axi = is_axisymmetric(c.model);
  const bool quarter = is_quarter(c.model);
  const bool conduction = pi.value("heat_conduction", false);
  if (conduction && (sph || sph_substrate)) {
    fail(base + "/heat_conduction",
         "SPH bodies conduct no heat; ask for an FE fidelity (fe-axisym, fe-3d-quarter, "
         "fe-3d-full)");
  }
  const double rad = angle * k_pi / 180.0;
  // SPH substrate block: a whole number of spacings, so the cubic lattice
  // keeps the spacing h exactly.
  const double S_sph =
      h *
      std::ceil(std::min(R * (k_sph_size_base + v / k_sph_size_velocity), k_sph_size_cap * R) / h -
                1e-9);
  const double S = substrate.value(
      "size", sph_substrate ? S_sph : std::min(R * (4.0 + v / k_size_velocity), 12.0 * R));
  if (sph) {
    reasons.push_back("particle spacing " + std::to_string(h * 1e6) + " um (" +
                      std::to_string(R / h) + " across R)");
  }

  json p = {
      {"name", "particle"},
      {"material", particle.at("material")},
      {"initial",
       {{"velocity", vec(v * std::sin(rad), 0.0, -v * std::cos(rad))},
        {"temperature", particle.value("temperature", strength_references(mp.strength).T_ref)}}},
      {"switches", switches(damage, conduction)}};
  if (sph) {
    // Ball centre R + 0.1 spacing above the surface (particle centres lie
    // within R of it; the pinballs, radius h / 2, start just touching).
    p["geometry"] = {{"type", "sphere"}, {"radius", R}, {"centre", vec(0, 0, R + k_sph_gap * h)}};
    // Quarter ball on the cubic lattice: its points lie half a spacing off
    // the cut planes, so the mirrored ghosts continue the lattice. The HCP
    // lattice is not mirror-symmetric about y = 0 (ghosts 0.58 spacings from
    // their images): at 600 m/s the time step of the HCP quarter ball
    // collapsed 1000-fold in 24 ns while the full HCP ball finished.
    json ball_sph = sph_settings;
    if (quarter && !ball_sph.contains("lattice")) ball_sph["lattice"] = "cubic";
    p["discretization"] = {{"type", "sph"}, {"element_size", h}, {"sph", ball_sph}};
  } else {
    p["geometry"] = {{"type", "sphere"}, {"radius", R}, {"centre", vec(0, 0, R * (1 + k_gap))}};
    p["discretization"] = {{"type", axi ? "fe-axisym" : "fe-hex"}, {"elements_across", n}};
    p["hourglass"] = hourglass;
    p["artificial_viscosity"] = viscosity;
    p["erosion"] = erosion_block;
  }
  if (quarter) p["discretization"]["sector"] = "quarter";
  json bodies = json::array({p});
  json bcs = json::array();
  json interactions = json::array();
  if (quarter) {
    for (const char* on : {"x_min", "y_min"})
      bcs.push_back({{"body", "particle"}, {"on", on}, {"type", "symmetry"}});
  }

  if (c.rigid_substrate) {
    interactions.push_back(
        {{"type", "rigid-wall"}, {"point", vec(0, 0, 0)}, {"normal", vec(0, 0, 1)}});
  } else {
    json s = {
        {"name", "substrate"},
        {"material", substrate.value("material", particle.at("material"))},
        {"initial",
         {{"temperature", substrate.value("temperature", strength_references(ms.strength).T_ref)}}},
        {"switches", switches(damage, conduction)}};
    if (sph_substrate) {
      json block_sph = sph_settings;
      if (!block_sph.contains("lattice")) block_sph["lattice"] = "cubic";
      s["discretization"] = {{"type", "sph"}, {"element_size", h}, {"sph", block_sph}};
    } else {
      s["discretization"] = {{"type", axi ? "fe-axisym" : "fe-hex"},
                             {"element_size", h},
                             {"grading", {{"focus", vec(0, 0, 0)}, {"ratio", k_grading_ratio}}}};
      s["hourglass"] = hourglass;
      s["artificial_viscosity"] = viscosity;
      s["erosion"] = erosion_block;
    }
    if (axi) {
      s["geometry"] = {{"type", "rectangle"}, {"r_max", S}, {"z_min", -S}, {"z_max", 0.0}};
      for (const char* on : {"outer", "bottom"})
        bcs.push_back({{"body", "substrate"}, {"on", on}, {"type", "absorbing"}});
    } else if (quarter) {
      s["geometry"] = {{"type", "box"}, {"min", vec(0, 0, -S)}, {"max", vec(S, S, 0)}};
      for (const char* on : {"x_max", "y_max", "z_min"})
        bcs.push_back({{"body", "substrate"}, {"on", on}, {"type", "absorbing"}});
      for (const char* on : {"x_min", "y_min"})
        bcs.push_back({{"body", "substrate"}, {"on", on}, {"type", "symmetry"}});
    } else {
      s["geometry"] = {{"type", "box"}, {"min", vec(-S, -S, -S)}, {"max", vec(S, S, 0)}};
      for (const char* on : {"x_min", "x_max", "y_min", "y_max", "z_min"})
        bcs.push_back({{"body", "substrate"}, {"on", on}, {"type", "absorbing"}});
    }
    bodies.push_back(s);
    json contact = {{"type", "contact"},
                    {"master", "substrate"},
                    {"slave", "particle"},
                    {"method", "lagrange"}};
    if (has_adhesion) contact["adhesion"] = adhesion;
    // Two passes are the contact's default between FE bodies (scene_io.cpp);
    // the block may ask for the one pass of the thesis.
    if (const auto tp = pi.find("two_pass_contact"); tp != pi.end()) {
      if (sph && tp->get<bool>()) fail(base + "/two_pass_contact", "is for FE models only");
      contact["two_pass"] = *tp;
    }
    interactions.push_back(contact);
  }
  scene["bodies"] = bodies;
  scene["boundary_conditions"] = bcs;
  scene["interactions"] = interactions;

  c.why = reasons.front();
  for (std::size_t i = 1; i < reasons.size(); ++i) c.why += "; " + reasons[i];
  scene["particle_impact"]["model"] = {
      {"name", model_name}, {"rigid_substrate", c.rigid_substrate}, {"why", c.why}};
  out.scene = std::move(scene);
  return out;
}

}  // namespace splat
