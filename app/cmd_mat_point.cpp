// splat mat-point: drives one material point through a constant-rate
// deformation and prints CSV (time, strain, stress, plastic_strain,
// temperature, damage, yield_stress, ... in SI units) to stdout or --out.
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "app/commands.hpp"
#include "solver/input/material_io.hpp"
#include "solver/material/material_point_driver.hpp"

namespace splat::app {

namespace {

struct MatPointOptions {
  std::string material;
  std::string mode;
  double strain_rate = 0.0;
  double max_strain = 0.0;
  int steps = 1000;
  std::optional<double> temperature;
  bool isothermal = false;
  bool no_damage = false;
  bool no_thermal_softening = false;
  bool no_rate_hardening = false;
  double length = 1e-3;
  double initial_damage = 0.0;
  std::string out;
};

int run_mat_point(const MatPointOptions& o) {
  MaterialPointRequest req;
  req.material = load_material(o.material);
  req.mode = parse_loading_mode(o.mode);
  req.strain_rate = o.strain_rate;
  req.max_strain = o.max_strain;
  req.steps = o.steps;
  req.temperature = o.temperature.value_or(strength_references(req.material.strength).T_ref);
  req.switches.adiabatic_heating = !o.isothermal;
  req.switches.damage = !o.no_damage;
  req.switches.thermal_softening = !o.no_thermal_softening;
  req.switches.rate_hardening = !o.no_rate_hardening;
  req.length = o.length;
  req.initial_damage = o.initial_damage;

  const MaterialPointResult result = run_material_point(req);
  const std::string csv = material_point_csv(result);
  if (o.out.empty()) {
    std::fputs(csv.c_str(), stdout);
  } else {
    std::ofstream f(o.out);
    f << csv;
    if (!f) {
      std::fprintf(stderr, "splat mat-point: error: cannot write '%s'\n", o.out.c_str());
      return 2;
    }
  }
  if (!result.converged) {
    std::fprintf(stderr, "splat mat-point: stopped: %s\n", result.message.c_str());
    return 3;
  }
  return 0;
}

}  // namespace

void register_mat_point(CLI::App& app, CommandTable& commands) {
  auto opts = std::make_shared<MatPointOptions>();
  CLI::App* sub = app.add_subcommand(
      "mat-point", "Drive one material point through a constant-rate deformation; print CSV");
  sub->add_option("--material", opts->material, "Library material name or JSON file")->required();
  sub->add_option("--mode", opts->mode, "uniaxial-stress | uniaxial-strain | simple-shear")
      ->required();
  sub->add_option("--strain-rate", opts->strain_rate, "Strain rate magnitude, 1/s (> 0)")
      ->required();
  sub->add_option("--max-strain", opts->max_strain,
                  "Final true strain (shear strain in simple shear); negative = compression")
      ->required();
  sub->add_option("--steps", opts->steps, "Number of equal time steps")->capture_default_str();
  sub->add_option("--temperature", opts->temperature,
                  "Initial temperature, K (default: the material's T_ref)");
  sub->add_flag("--isothermal", opts->isothermal, "No adiabatic heating");
  sub->add_flag("--no-damage", opts->no_damage, "Switch damage off");
  sub->add_flag("--no-thermal-softening", opts->no_thermal_softening,
                "Switch the temperature dependence of the flow stress off (at T_ref)");
  sub->add_flag("--no-rate-hardening", opts->no_rate_hardening,
                "Switch the rate dependence of the flow stress off (at eps_dot_0)");
  sub->add_option("--length", opts->length,
                  "Characteristic length for the fracture-energy damage law, m")
      ->capture_default_str();
  sub->add_option("--initial-damage", opts->initial_damage, "Initial damage, -")
      ->capture_default_str();
  sub->add_option("--out", opts->out, "Write the CSV to this file instead of stdout");
  commands.emplace_back(sub, [opts] { return run_mat_point(*opts); });
}

}  // namespace splat::app
