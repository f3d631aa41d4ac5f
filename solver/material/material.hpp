// Material description: every parameter a point needs, with its unit. Filled
// from a material JSON document (schemas/material.schema.json) by
// solver/input/material_io.hpp; the kernels read it and never change it.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "solver/material/model_switches.hpp"
#include "solver/material/strength_model.hpp"

namespace splat {

// Isotropic linear elasticity. Shear modulus G = E / (2 (1 + nu)),
// bulk modulus K = E / (3 (1 - 2 nu)).
struct ElasticParams {
  double E = 0.0;   // Young's modulus, Pa
  double nu = 0.0;  // Poisson's ratio, -

  double shear_modulus() const { return E / (2.0 * (1.0 + nu)); }
  double bulk_modulus() const { return E / (3.0 * (1.0 - 2.0 * nu)); }
};

struct ThermalParams {
  double c_p = 0.0;            // specific heat, J/(kg K)
  double heat_fraction = 0.9;  // inelastic heat fraction (Taylor-Quinney), -
  double conductivity = 0.0;   // thermal conductivity k, W/(m K); 0 = not given
};

enum class EosModel { linear, mie_gruneisen };

// Mie-Grueneisen with a linear Us-up Hugoniot (shock velocity
// Us = c0 + s up) and Grueneisen parameter Gamma0 (rho Gamma = rho0 Gamma0).
struct MieGruneisenParams {
  double c0 = 0.0;      // bulk sound speed, m/s
  double s = 0.0;       // slope of the Us-up line, -
  double gamma0 = 0.0;  // Grueneisen parameter at reference density, -
};

struct EosParams {
  EosModel model = EosModel::linear;
  std::optional<MieGruneisenParams> mie_gruneisen;  // needed when model is mie_gruneisen
};

enum class DamageInitiation { none, johnson_cook, shear };
enum class DamageEvolution { instant, plastic_strain, fracture_energy };

// Johnson-Cook ductile failure strain, thesis eq. 2.6 in the sign convention
// of Johnson & Cook (1985): eps_f = (D1 + D2 exp(D3 eta)) (1 + D4 ln eps_dot*)
// (1 + D5 T*), with eta = sigma_mean / sigma_eq (D3 < 0 for metals).
struct JohnsonCookFailureParams {
  double D1 = 0.0, D2 = 0.0, D3 = 0.0, D4 = 0.0, D5 = 0.0;  // -
};

// Shear failure, thesis eq. 2.3-2.5: theta = (k_s p + q) / tau_max clamped to
// [theta_min, theta_max]; a cubic in theta gives the failure strain at the
// lower and upper strain rates; linear in rate between them, clamped outside.
struct ShearFailureParams {
  double k_s = 0.0;                         // pressure coefficient, -
  double theta_min = 0.0, theta_max = 0.0;  // bounds of the shear stress ratio, -
  double rate_low = 0.0, rate_high = 0.0;   // strain rates of the two curves, 1/s
  double low[4] = {0, 0, 0, 0};             // cubic coefficients (A, B, C, D) at rate_low, -
  double high[4] = {0, 0, 0, 0};            // cubic coefficients (A, B, C, D) at rate_high, -
};

struct DamageParams {
  DamageInitiation initiation = DamageInitiation::none;
  JohnsonCookFailureParams jc;
  ShearFailureParams shear;
  DamageEvolution evolution = DamageEvolution::plastic_strain;
  double eps_p_max = 2.0;           // plastic strain at full damage (eq. 2.7), -
  double G_f = 0.0;                 // fracture energy (eq. 2.8), J/m^2
  double D_max = 0.9;               // cap on damage, -
  double initial_random_max = 0.0;  // upper bound of the random initial damage, -
};

struct Material {
  std::string name;
  std::string source;    // where the numbers come from
  double density = 0.0;  // reference mass density rho0, kg/m^3
  ElasticParams elastic;
  StrengthModel strength;  // the flow-stress law and its parameters
  ThermalParams thermal;
  EosParams eos;
  DamageParams damage;
};

// Longitudinal (P-wave) speed of the undamaged elastic material,
// sqrt(E (1 - nu) / ((1 + nu) (1 - 2 nu) rho0)), m/s (the equation of state
// aside: MaterialConstants::wave_speed is the time-step speed).
inline double p_wave_speed(const Material& m) {
  const double E = m.elastic.E, nu = m.elastic.nu;
  return std::sqrt(E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu) * m.density));
}

}  // namespace splat
