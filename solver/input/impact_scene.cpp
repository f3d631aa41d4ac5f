#include "solver/input/impact_scene.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
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

const std::string k_base = "/particle_impact";  // the block's JSON pointer
constexpr double k_pi = std::numbers::pi;
constexpr double k_gap = 1e-3;             // initial gap / particle radius, -
constexpr double k_grading_ratio = 1.15;   // substrate element growth per element, -
constexpr double k_size_velocity = 250.0;  // m/s per extra particle radius of substrate
// FE substrate zone at the particle's element size about the impact point:
// radius R (1.5 + v / 1000 m/s), depth R (0.5 + v / 1000 m/s), covering the
// contact and the lip it raises (FE Al/Al, 16 across: lip at 1.45 R at
// 700 m/s, 1.7 R at 1200 m/s) and the crater below it, so that refining the
// particle refines the interface on both sides; substrate elements larger
// than the particle's at the rim let its rim cut through them
// (docs/design.md, "Model choice").
constexpr double k_uniform_radius_base = 1.5;    // -
constexpr double k_uniform_depth_base = 0.5;     // -
constexpr double k_uniform_velocity = 1000.0;    // m/s per extra particle radius
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

double particle_mass(const ImpactRequest& r) {
  return 4.0 / 3.0 * k_pi * std::pow(r.radius, 3) * r.particle_material.density;
}

// The two-mass model's substrate: a rigid hemisphere of the particle's radius.
double hemisphere_mass(const ImpactRequest& r) {
  return 2.0 / 3.0 * k_pi * std::pow(r.radius, 3) * r.substrate_material.density;
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

std::string mpa(double stress) {
  return std::to_string(stress / 1e6) + " MPa";
}

// The SPH model `auto` chooses: the ball on an SPH or an FE block, a quarter
// of each for a normal impact, the whole of each for an oblique one.
Fidelity sph_fidelity(bool sph_substrate, bool oblique) {
  if (sph_substrate) return oblique ? Fidelity::sph_3d_full : Fidelity::sph_3d_quarter;
  return oblique ? Fidelity::sph_on_fe_3d_full : Fidelity::sph_on_fe_3d_quarter;
}

// `auto`: an SPH particle when asked or above k_fe_max_velocity, on an SPH
// substrate when asked or when the substrate yields below the particle's
// flow stress (it jets too and a mesh would tangle); otherwise FE, full 3D
// for an oblique impact, axisymmetric for a normal one.
Fidelity auto_fidelity(const ImpactRequest& r, std::vector<std::string>& reasons) {
  const bool oblique = r.angle != 0.0;
  const bool sph_asked = r.particle_discretization == "sph";
  const bool too_fast = r.particle_discretization == "auto" && r.velocity > k_fe_max_velocity;
  if (sph_asked || too_fast) {
    const double sigma_0s = initial_yield_stress(r.substrate_material.strength);
    const bool sph_substrate =
        r.substrate_discretization == "sph" ||
        (r.substrate_discretization == "auto" && sigma_0s < r.particle_flow_stress);
    reasons.push_back(sph_asked ? std::string("SPH particle as asked")
                                : "SPH particle: impact velocity " + std::to_string(r.velocity) +
                                      " m/s is above " + std::to_string(k_fe_max_velocity) +
                                      " m/s, above which the FE particle's jetting rim "
                                      "erodes (docs/verification.md, FE impact robustness)");
    if (r.substrate_discretization == "sph") {
      reasons.push_back("SPH substrate as asked");
    } else if (sph_substrate) {
      reasons.push_back("SPH substrate: its yield stress " + mpa(sigma_0s) +
                        " is below the particle's flow stress " + mpa(r.particle_flow_stress) +
                        ", so it jets too");
    } else {
      reasons.push_back("FE substrate");
    }
    reasons.push_back(oblique ? "oblique impact: full 3D"
                              : "normal impact: quarter model, two symmetry planes");
    return sph_fidelity(sph_substrate, oblique);
  }
  if (oblique) {
    reasons.push_back("oblique impact (angle " + std::to_string(r.angle) +
                      " deg): only a full 3D model represents it");
    return Fidelity::fe_3d_full;
  }
  reasons.push_back("normal impact: axisymmetric");
  return Fidelity::fe_axisym;
}

Fidelity chosen_fidelity(const ImpactRequest& r, std::vector<std::string>& reasons) {
  const std::optional<Fidelity> asked = parse<Fidelity>(r.fidelity);
  if (!asked && r.fidelity != "auto") {
    fail(k_base + "/fidelity", "unknown fidelity " + r.fidelity);
  }
  if (!asked) return auto_fidelity(r, reasons);
  reasons.push_back("fidelity " + r.fidelity + " as asked");
  if (r.angle != 0.0 && !is_full_3d(*asked)) {
    fail(k_base + "/fidelity",
         "an oblique impact (angle != 0) needs a full 3D fidelity (fe-3d-full, sph-3d-full, "
         "sph-on-fe-3d-full) or auto, not " +
             r.fidelity);
  }
  return *asked;
}

// The discretizations the block names must be those of the model.
void check_discretizations(const ImpactRequest& r, Fidelity model) {
  const std::string name(to_string(model));
  const bool sph = has_sph_particle(model);
  const bool sph_substrate = has_sph_substrate(model);
  const std::string& pd = r.particle_discretization;
  const std::string& sd = r.substrate_discretization;
  if (sph && pd == "fe") {
    fail(k_base + "/particle/discretization",
         "is fe, but fidelity " + name + " has an SPH particle");
  }
  if (!sph && pd == "sph") {
    fail(k_base + "/particle/discretization",
         "is sph, but fidelity " + name + " has no SPH particle (use sph-3d-* or sph-on-fe-3d-*)");
  }
  if (sph && sd != "auto" && (sd == "sph") != sph_substrate) {
    fail(k_base + "/substrate/discretization", "is " + sd + ", but fidelity " + name + " has " +
                                                   (sph_substrate ? "an SPH" : "an FE") +
                                                   " substrate");
  }
  if (!sph && sd == "sph") {
    fail(k_base + "/substrate/discretization", "sph needs an SPH fidelity (sph-3d-* or auto)");
  }
}

// FE elements across the radius, or the SPH particle spacing (spacing, else
// R / elements_across, default R / 5).
void choose_resolution(const ImpactRequest& r, ImpactModelChoice& c) {
  const json& particle = r.block.at("particle");
  const bool sph = has_sph_particle(c.model);
  if (particle.contains("spacing") && particle.contains("elements_across")) {
    fail(k_base + "/particle/spacing", "give spacing or elements_across, not both");
  }
  if (particle.contains("spacing") && !sph) {
    fail(k_base + "/particle/spacing", "is for SPH particles; FE particles take elements_across");
  }
  const double R = r.radius;
  c.elements_across = particle.value("elements_across", sph ? k_sph_default_across : 12);
  c.element_size = sph ? particle.value("spacing", R / c.elements_across) : R / c.elements_across;
  const double h = c.element_size;
  if (sph && !(R / h >= 2.0)) {
    fail(k_base + "/particle/spacing", "must be at most R / 2 (m): fewer than 2 spacings across R");
  }
  // The bound elements_across has in the schema: finer spacings ask for more
  // particles (~ (R / h)^3) than memory holds (1e-8 m at R 12.5 um ended in
  // std::bad_alloc).
  if (sph && R / h > k_max_spacings_across * (1.0 + 1e-9)) {
    fail(k_base + "/particle/spacing",
         "must be at least R / " + std::to_string(k_max_spacings_across) + " (m): at most " +
             std::to_string(k_max_spacings_across) + " spacings across R, as elements_across");
  }
}

// A rigid wall instead of a substrate body: asked, or (auto, no adhesion) a
// substrate that cannot yield under the particle (Tabor: 3 sigma_p bounds
// the contact pressure).
void choose_substrate(const ImpactRequest& r, ImpactModelChoice& c,
                      std::vector<std::string>& reasons) {
  const double sigma_0s = initial_yield_stress(r.substrate_material.strength);
  if (r.substrate_type == "rigid") {
    c.rigid_substrate = true;
    reasons.push_back("rigid substrate as asked");
  } else if (r.substrate_type == "auto" && !r.has_adhesion && c.model != Fidelity::two_mass &&
             sigma_0s >= k_rigid_factor * r.particle_flow_stress) {
    c.rigid_substrate = true;
    reasons.push_back("rigid substrate: its yield stress " + mpa(sigma_0s) +
                      " is at least 3x the particle's flow stress " + mpa(r.particle_flow_stress) +
                      ", so it cannot yield");
  }
  if (c.rigid_substrate && r.has_adhesion) {
    fail(k_base + "/substrate/type",
         "adhesion needs a deformable substrate (a rigid wall carries no links)");
  }
}

// Numerics the bodies share: stiffness hourglass by default, the block's
// viscosity, geometric erosion (inverted elements and those whose stable
// step fell below a fraction of the initial one) unless switched off and
// erosion at the damage cap whenever damage is on unless `erosion` is false.
struct BodyNumerics {
  json hourglass, viscosity, erosion, sph;
};

BodyNumerics body_numerics(const ImpactRequest& r, double h) {
  const json& pi = r.block;
  BodyNumerics b;
  b.hourglass = {{"type", "stiffness"}, {"coefficient", k_hourglass_coefficient}};
  if (pi.contains("hourglass")) b.hourglass.update(pi.at("hourglass"));
  b.viscosity = pi.value("artificial_viscosity", json::object());
  const double erosion_fraction = pi.value("erosion_time_step_fraction", k_erosion_dt_fraction);
  const double c_max =
      std::max(p_wave_speed(r.particle_material), p_wave_speed(r.substrate_material));
  b.erosion = {{"enabled", r.erosion || erosion_fraction > 0.0},
               {"min_time_step", erosion_fraction * h / c_max},
               {"damage", r.erosion}};
  // SPH settings of both SPH bodies (the block's `sph`, thesis defaults
  // otherwise); an explicit `erosion: true` deactivates particles at the
  // damage cap (they are never deleted; the FE default of eroding failed
  // elements whenever damage is on is not carried over to SPH).
  b.sph = pi.value("sph", json::object());
  if (!b.sph.contains("deactivate_failed")) b.sph["deactivate_failed"] = pi.value("erosion", false);
  // Smoothing lengths kept at their initial value through reference updates:
  // with the body default (growth up to 2x) the quarter Al/Al model's time
  // step collapsed 1000-fold 13 ns into a 1500 m/s impact; with h fixed the
  // run finished with a verdict (and 1000 m/s settled in 1035 steps, not 3714).
  if (!b.sph.contains("max_h_growth")) b.sph["max_h_growth"] = k_sph_max_h_growth;
  return b;
}

// The impact's own duration t_impact (contact, spring-back) and the maximum
// time t_max, which also covers a held particle's settling.
struct ImpactTimes {
  double impact = 0.0;  // s
  double max = 0.0;     // s
};

ImpactTimes impact_times(const ImpactRequest& r) {
  const double v = r.velocity, R = r.radius;
  const double E_star = effective_modulus(r.particle_material, r.substrate_material);
  const double t_hertz = v > 0.0 ? hertz_time(R, particle_mass(r), E_star, v) : 0.0;
  ImpactTimes t;
  t.impact = v > 0.0 ? 3.0 * std::max(t_hertz, std::min(R / v, 10.0 * t_hertz)) : 0.0;
  const double t_settle = k_settle_transits * R / p_wave_speed(r.particle_material);
  const double t_max_default = v > 0.0 ? std::max(t.impact, t_settle) : 0.0;
  const json& end = r.block.value("end_time", json("adaptive"));
  t.max = end.is_number() ? end.get<double>() : r.block.value("max_time", t_max_default);
  if (!(t.max > 0.0)) {
    fail(k_base + "/velocity",
         "must be > 0 (m/s) unless end_time is given: the impact never happens");
  }
  return t;
}

// The scene's time block: the maximum time, and the looser balance check of
// SPH models (their impacts close the balance to 1-6 % of the initial energy,
// Al/Al, 300-3000 m/s, 6-10 spacings across: the contact's node-level
// landings and the viscosity's booking; docs/verification.md, SPH; 1 % for FE).
json time_block(const json& doc, bool sph, double t_max) {
  json time = doc.value("time", json::object());
  time["end_time"] = t_max;
  if (sph && !time.contains("energy_balance_limit")) {
    time["energy_balance_limit"] = k_sph_energy_balance_limit;
  }
  return time;
}

// The crudest level: the particle as a rigid mass, the substrate as the
// rigid mass of a hemisphere of the particle's radius, joined over the Hertz
// contact area at v (a = sqrt(R delta_max)).
json two_mass_block(const ImpactRequest& r) {
  const double R = r.radius, v = r.velocity;
  const double M = particle_mass(r), m_sub = hemisphere_mass(r);
  const double m_star = M * m_sub / (M + m_sub);
  const double E_star = effective_modulus(r.particle_material, r.substrate_material);
  const double delta = std::pow(15.0 * m_star * v * v / (16.0 * E_star * std::sqrt(R)), 0.4);
  const double a = std::min(std::sqrt(R * delta), R);
  return {{"M", M},
          {"m", m_sub},
          {"k", 0.0},
          {"V0", v},
          {"area", std::max(k_pi * a * a, 1e-30)},
          {"adhesion", r.has_adhesion ? r.adhesion : json{{"G_c", 0.0}}}};
}

// The initial state, k_default_snapshot_intervals - 1 more evenly over the
// impact's duration (at most t_max) and one at t_max.
json default_snapshot_times(const ImpactTimes& t) {
  json times = json::array();
  const double t_spread = t.impact > 0.0 ? std::min(t.impact, t.max) : t.max;
  for (int i = 0; i <= k_default_snapshot_intervals; ++i) {
    times.push_back(i == k_default_snapshot_intervals
                        ? t.max
                        : t_spread * static_cast<double>(i) / k_default_snapshot_intervals);
  }
  return times;
}

json particle_body(const ImpactRequest& r, const ImpactModelChoice& c, const BodyNumerics& num) {
  const double R = r.radius, v = r.velocity, h = c.element_size;
  const double rad = r.angle * k_pi / 180.0;
  const bool conduction = r.block.value("heat_conduction", false);
  json p = {
      {"name", "particle"},
      {"material", r.block.at("particle").at("material")},
      {"initial",
       {{"velocity", vec(v * std::sin(rad), 0.0, -v * std::cos(rad))},
        {"temperature",
         r.block.at("particle")
             .value("temperature", strength_references(r.particle_material.strength).T_ref)}}},
      {"switches", switches(r.damage, conduction)}};
  if (has_sph_particle(c.model)) {
    // Ball centre R + 0.1 spacing above the surface (particle centres lie
    // within R of it; the pinballs, radius h / 2, start just touching).
    p["geometry"] = {{"type", "sphere"}, {"radius", R}, {"centre", vec(0, 0, R + k_sph_gap * h)}};
    // Quarter ball on the cubic lattice: its points lie half a spacing off
    // the cut planes, so the mirrored ghosts continue the lattice. The HCP
    // lattice is not mirror-symmetric about y = 0 (ghosts 0.58 spacings from
    // their images): at 600 m/s the time step of the HCP quarter ball
    // collapsed 1000-fold in 24 ns while the full HCP ball finished.
    json ball_sph = num.sph;
    if (is_quarter(c.model) && !ball_sph.contains("lattice")) ball_sph["lattice"] = "cubic";
    p["discretization"] = {{"type", "sph"}, {"element_size", h}, {"sph", ball_sph}};
  } else {
    p["geometry"] = {{"type", "sphere"}, {"radius", R}, {"centre", vec(0, 0, R * (1 + k_gap))}};
    p["discretization"] = {{"type", is_axisymmetric(c.model) ? "fe-axisym" : "fe-hex"},
                           {"elements_across", c.elements_across}};
    p["hourglass"] = num.hourglass;
    p["artificial_viscosity"] = num.viscosity;
    p["erosion"] = num.erosion;
  }
  if (is_quarter(c.model)) p["discretization"]["sector"] = "quarter";
  return p;
}

// Substrate half-width (3D) or radius (axisymmetric) and depth, m: given, or
// grown with the velocity; an SPH block in whole spacings, so the cubic
// lattice keeps the spacing exactly.
double substrate_size(const ImpactRequest& r, const ImpactModelChoice& c) {
  const double R = r.radius, v = r.velocity, h = c.element_size;
  const double S_sph =
      h *
      std::ceil(std::min(R * (k_sph_size_base + v / k_sph_size_velocity), k_sph_size_cap * R) / h -
                1e-9);
  return r.substrate.value("size", has_sph_substrate(c.model)
                                       ? S_sph
                                       : std::min(R * (4.0 + v / k_size_velocity), 12.0 * R));
}

json substrate_body(const ImpactRequest& r, const ImpactModelChoice& c, const BodyNumerics& num) {
  const double h = c.element_size, S = substrate_size(r, c);
  const bool conduction = r.block.value("heat_conduction", false);
  json s = {{"name", "substrate"},
            {"material", r.substrate.value("material", r.block.at("particle").at("material"))},
            {"initial",
             {{"temperature",
               r.substrate.value("temperature",
                                 strength_references(r.substrate_material.strength).T_ref)}}},
            {"switches", switches(r.damage, conduction)}};
  if (has_sph_substrate(c.model)) {
    json block_sph = num.sph;
    if (!block_sph.contains("lattice")) block_sph["lattice"] = "cubic";
    s["discretization"] = {{"type", "sph"}, {"element_size", h}, {"sph", block_sph}};
  } else {
    const double R = r.radius, grow = r.velocity / k_uniform_velocity;
    const double u_r = std::min(S, R * (k_uniform_radius_base + grow));
    const double u_z = std::min(S, R * (k_uniform_depth_base + grow));
    s["discretization"] = {
        {"type", is_axisymmetric(c.model) ? "fe-axisym" : "fe-hex"},
        {"element_size", h},
        {"grading",
         {{"focus", vec(0, 0, 0)},
          {"ratio", k_grading_ratio},
          {"uniform_extent", vec(u_r, is_axisymmetric(c.model) ? 0.0 : u_r, u_z)}}}};
    s["hourglass"] = num.hourglass;
    s["artificial_viscosity"] = num.viscosity;
    s["erosion"] = num.erosion;
  }
  if (is_axisymmetric(c.model)) {
    s["geometry"] = {{"type", "rectangle"}, {"r_max", S}, {"z_min", -S}, {"z_max", 0.0}};
  } else if (is_quarter(c.model)) {
    s["geometry"] = {{"type", "box"}, {"min", vec(0, 0, -S)}, {"max", vec(S, S, 0)}};
  } else {
    s["geometry"] = {{"type", "box"}, {"min", vec(-S, -S, -S)}, {"max", vec(S, S, 0)}};
  }
  return s;
}

// Symmetry planes of a quarter model on both bodies, absorbing far faces of
// the substrate.
json boundary_conditions(const ImpactModelChoice& c) {
  json bcs = json::array();
  auto add = [&](const char* body, std::initializer_list<const char*> faces, const char* type) {
    for (const char* on : faces) bcs.push_back({{"body", body}, {"on", on}, {"type", type}});
  };
  const bool quarter = is_quarter(c.model);
  if (quarter) add("particle", {"x_min", "y_min"}, "symmetry");
  if (c.rigid_substrate) return bcs;
  if (is_axisymmetric(c.model)) {
    add("substrate", {"outer", "bottom"}, "absorbing");
  } else if (quarter) {
    add("substrate", {"x_max", "y_max", "z_min"}, "absorbing");
    add("substrate", {"x_min", "y_min"}, "symmetry");
  } else {
    add("substrate", {"x_min", "x_max", "y_min", "y_max", "z_min"}, "absorbing");
  }
  return bcs;
}

json contact_interaction(const ImpactRequest& r, const ImpactModelChoice& c) {
  json contact = {
      {"type", "contact"}, {"master", "substrate"}, {"slave", "particle"}, {"method", "lagrange"}};
  if (r.has_adhesion) contact["adhesion"] = r.adhesion;
  // Two passes are the contact's default between FE bodies (scene_io.cpp);
  // the block may ask for the one pass of the thesis.
  if (const auto tp = r.block.find("two_pass_contact"); tp != r.block.end()) {
    if (has_sph_particle(c.model) && tp->get<bool>()) {
      fail(k_base + "/two_pass_contact", "is for FE models only");
    }
    contact["two_pass"] = *tp;
  }
  return contact;
}

std::string joined(const std::vector<std::string>& reasons) {
  std::string out = reasons.front();
  for (std::size_t i = 1; i < reasons.size(); ++i) out += "; " + reasons[i];
  return out;
}

}  // namespace

ImpactRequest read_impact_request(const json& doc, const std::filesystem::path& base_dir) {
  ImpactRequest r;
  r.block = doc.at("particle_impact");
  const json& particle = r.block.at("particle");
  r.substrate = r.block.value("substrate", json::object());
  r.particle_material =
      scene_material(particle.at("material"), base_dir, k_base + "/particle/material");
  r.substrate_material = scene_material(r.substrate.value("material", particle.at("material")),
                                        base_dir, k_base + "/substrate/material");
  r.radius = particle.at("radius").get<double>();
  r.velocity = r.block.at("velocity").get<double>();
  r.angle = r.block.value("angle", 0.0);
  r.has_adhesion = r.block.contains("adhesion");
  r.adhesion = r.block.value("adhesion", json::object());
  // Damage is on when `erosion` or D_adh_max needs it (or `damage` says so).
  // With damage on, elements that reach the damage cap D_max are eroded
  // unless `erosion` is false: a failed element carries next to no stress
  // (G_d = (1 - D_max) G), and kept in the mesh it only tangles in the
  // jetting rim of a fast impact (800 m/s, 12 across: internal energy
  // negative, bulk-viscosity work twice the impact energy). Its mass and
  // energy are booked as eroded; the impact run limits the eroded share of
  // the particle (max_eroded_fraction).
  const bool adhesion_erosion =
      r.has_adhesion && r.adhesion.contains("D_adh_max") && !r.adhesion.at("D_adh_max").is_null();
  // The yield-drop activation detects the onset of an adiabatic shear
  // instability, which the material law produces only with its damage
  // softening (thesis 1.4.4, 2.2.2: damage is added to the law so that the
  // interface can localise): damage is on by default with that criterion too.
  const bool yield_drop = r.has_adhesion && r.adhesion.contains("activation") &&
                          r.adhesion.at("activation").value("rule", "none") == "yield-drop";
  r.damage =
      r.block.value("damage", r.block.value("erosion", false) || adhesion_erosion || yield_drop);
  r.erosion = r.damage && r.block.value("erosion", true);
  r.fidelity = r.block.value("fidelity", "auto");
  r.substrate_type = r.substrate.value("type", "auto");
  r.particle_discretization = particle.value("discretization", "auto");
  r.substrate_discretization = r.substrate.value("discretization", "auto");
  r.particle_flow_stress = impact_flow_stress(r.particle_material);
  return r;
}

ImpactModelChoice choose_model(const ImpactRequest& r) {
  ImpactModelChoice c;
  std::vector<std::string> reasons;
  c.model = chosen_fidelity(r, reasons);
  check_discretizations(r, c.model);
  choose_resolution(r, c);
  choose_substrate(r, c, reasons);
  reasons.push_back(r.has_adhesion ? "adhesion on contact pairs"
                                   : "no adhesion asked: plain contact");
  if (!r.damage) reasons.push_back("no erosion, D_adh_max or yield-drop activation: damage off");
  if (c.model == Fidelity::two_mass) {
    reasons.push_back("substrate as a rigid hemisphere of mass " +
                      std::to_string(hemisphere_mass(r)) +
                      " kg, link area from the Hertz contact radius");
  }
  if (has_sph_particle(c.model)) {
    reasons.push_back("particle spacing " + std::to_string(c.element_size * 1e6) + " um (" +
                      std::to_string(r.radius / c.element_size) + " across R)");
  }
  c.why = joined(reasons);
  return c;
}

ExpandedImpact expand_particle_impact(const json& doc, const std::filesystem::path& base_dir) {
  const ImpactRequest r = read_impact_request(doc, base_dir);
  ExpandedImpact out;
  out.choice = choose_model(r);
  const ImpactModelChoice& c = out.choice;
  const ImpactTimes t = impact_times(r);
  const bool sph = has_sph_particle(c.model);

  json scene = {{"name", doc.at("name")}, {"particle_impact", r.block}};
  if (doc.contains("description")) scene["description"] = doc.at("description");
  if (doc.contains("output")) scene["output"] = doc.at("output");
  scene["time"] = time_block(doc, sph, t.max);
  const std::string model_name(to_string(c.model));
  if (c.model == Fidelity::two_mass) {
    scene["two_mass"] = two_mass_block(r);
    scene["time"] = {{"end_time", 100.0 * std::max(t.max, 1e-12)}};
    scene["particle_impact"]["model"] = {{"name", model_name}, {"why", c.why}};
    out.scene = std::move(scene);
    return out;
  }
  json& output = scene["output"];
  if (!output.contains("snapshot_times") && !output.contains("snapshot_count")) {
    output["snapshot_times"] = default_snapshot_times(t);
  }
  if (r.block.value("heat_conduction", false) && (sph || has_sph_substrate(c.model))) {
    fail(k_base + "/heat_conduction",
         "SPH bodies conduct no heat; ask for an FE fidelity (fe-axisym, fe-3d-quarter, "
         "fe-3d-full)");
  }
  const BodyNumerics num = body_numerics(r, c.element_size);
  json bodies = json::array({particle_body(r, c, num)});
  json interactions = json::array();
  if (c.rigid_substrate) {
    interactions.push_back(
        {{"type", "rigid-wall"}, {"point", vec(0, 0, 0)}, {"normal", vec(0, 0, 1)}});
  } else {
    bodies.push_back(substrate_body(r, c, num));
    interactions.push_back(contact_interaction(r, c));
  }
  scene["bodies"] = std::move(bodies);
  scene["boundary_conditions"] = boundary_conditions(c);
  scene["interactions"] = std::move(interactions);
  scene["particle_impact"]["model"] = {
      {"name", model_name}, {"rigid_substrate", c.rigid_substrate}, {"why", c.why}};
  out.scene = std::move(scene);
  return out;
}

}  // namespace splat
