// The stress update of one material point over one time step: elasticity,
// equation of state, plasticity with the material's strength law
// (strength_model.hpp) and adiabatic heating, damage.
// A pure function of its inputs; the loops over elements or particles that
// call it live in the bodies, the time loop above them.
#pragma once

#include <cstddef>

#include "solver/common/types.hpp"
#include "solver/material/johnson_cook.hpp"
#include "solver/material/material.hpp"

namespace splat {

// Constants derived once per material.
struct MaterialConstants {
  double G = 0.0;     // shear modulus, Pa
  double K = 0.0;     // bulk modulus, Pa
  double rho0 = 0.0;  // reference density, kg/m^3
  double c_p = 0.0;   // specific heat, J/(kg K)
  double chi = 0.0;   // inelastic heat fraction, -
  // Temperature rise per unit plastic work per unit reference volume,
  // chi / (rho0 c_p), K m^3/J (0 with no heat capacity given).
  double heating = 0.0;
  // Longitudinal (P-wave) speed sqrt((K + 4G/3) / rho0) of the undamaged
  // material, m/s; with a Mie-Grueneisen EOS the bulk part uses max(K, rho0 c0^2).
  double wave_speed = 0.0;
  JcSeries jc_series;  // coefficients of the Johnson-Cook series shortcuts
};

MaterialConstants derive_constants(const Material& m);

// State of one point; every field changes every step. Make it with
// initial_point_state and change it only through update_point: the fields
// derived from eps_p, T and D (sigma_y_static, hardening, strength_scale) are
// kept with them there.
struct PointState {
  Mat3 s = Mat3::Zero();        // deviatoric Cauchy stress, Pa
  double p = 0.0;               // pressure, positive in compression, Pa
  double J = 1.0;               // volume ratio V / V0, -
  double e = 0.0;               // internal energy per unit reference volume, J/m^3
  double eps_p = 0.0;           // equivalent plastic strain, -
  double eps_dot_p = 0.0;       // plastic strain rate of the last step, 1/s
  double T = 300.0;             // temperature, K
  double D = 0.0;               // damage, -
  double omega = 0.0;           // damage initiation indicator (initiated at 1), -
  double eps_p_init = -1.0;     // plastic strain at initiation, -1 before, -
  double sigma_y = 0.0;         // current (damaged) yield stress at the last plastic rate, Pa
  double sigma_y_static = 0.0;  // yield stress at zero plastic rate, (1 - D) sigma_y(eps_p,
                                // 0, T, p, J); eps_p, T and D change only in plastic steps,
                                // so an elastic step needs no evaluation of the strength law
                                // unless it depends on p and J (steinberg_guinan.hpp), Pa
  double hardening = 0.0;       // Johnson-Cook: A + B eps_p^n; other laws: the undamaged
                                // sigma_y(eps_p, 0, T, p, J), Pa; with strength_scale, a cache kept
                                // by update_point (eps_p, T, D change only there) so that a
                                // plastic step starts without evaluating pow
  double strength_scale = 1.0;  // Johnson-Cook: (1 - D)(1 - T*^m); other laws: 1 - D, -;
                                // sigma_y_static = strength_scale * hardening
  double sigma_y_peak = 0.0;    // largest sigma_y seen (rate-dependent), Pa
  double plastic_work = 0.0;    // plastic work per unit reference volume, J/m^3

  // Largest sigma_y_static seen, Pa: the rate-free reference of the adhesion
  // activation test (solver/adhesion/cohesive_law.hpp).
  double sigma_y_static_peak = 0.0;

  Mat3 cauchy() const { return s - p * Mat3::Identity(); }
};

// Volume ratio at the end of a step from the strain increment's trace
// tr = tr(D) dt (mid-step D), the point's own kinematics:
//   J_new = J_old (2 + tr) / (2 - tr),
// so that J_mid tr = J_new - J_old exactly and the trapezoidal pressure work
// of update_point, -J_mid (p_old + p_new) tr / 2, is the EOS's -p dJ. A
// point's volume changes only with its motion: a position-only contact
// correction (contact_interface.hpp, correct_positions) that moves element
// nodes does no work on the material and raises no pressure.
template <class T>
T volume_ratio_after(const T& J_old, const T& tr) {
  return J_old * (2.0 + tr) / (2.0 - tr);
}

// Initial state at temperature T0 with initial damage D0 (sets sigma_y).
PointState initial_point_state(const Material& m, const ModelSwitches& sw, double T0, double D0);

struct PointUpdateResult {
  int iterations = 0;     // return-mapping iterations (0 for an elastic step)
  bool converged = true;  // false only if the return mapping failed to converge
};

// Advances `st` by one step. The caller has already rotated st.s to the end
// of the step (jaumann_rotate) and supplies:
//   d_eps  rate of deformation times dt (symmetric strain increment), -
//   J_new  volume ratio at the end of the step, -
//   dt     time step, s
//   length characteristic element length for the fracture-energy law, m
PointUpdateResult update_point(const Material& m, const MaterialConstants& mc,
                               const ModelSwitches& sw, PointState& st, const Mat3& d_eps,
                               double J_new, double dt, double length);

// update_point for a point that point_update_fast (point_update_fast.hpp)
// does not cover, without testing that again: for callers that ran the fast
// path on the same inputs (in lanes) and got "not done". update_point is
// this after that test.
PointUpdateResult update_point_general(const Material& m, const MaterialConstants& mc,
                                       const ModelSwitches& sw, PointState& st, const Mat3& d_eps,
                                       double J_new, double dt, double length);

// Heat q (J per m^3 of reference volume, either sign) brought to the point
// from outside its own update (conduction from its neighbours): the internal
// energy e and the temperature (by q / (rho0 c_p)) rise, and the strength
// caches follow the new temperature, the rate factor of the last plastic
// step kept. A point that has no heat capacity is left unchanged.
void add_heat(const Material& m, const MaterialConstants& mc, const ModelSwitches& sw,
              PointState& st, double q);

// The material update of a block of n points, as the element and particle
// loops call it (one call per block): states[index[k]] advances as
// update_point(m, mc, sw, states[index[k]], d_eps[k], J_new[k], dt, length[k])
// and out[k] is its result, to the bit. The index entries are distinct.
// Groups of 8 points run point_update_fast (point_update_fast.hpp) in SIMD
// lanes; the points it does not cover run update_point.
void update_points(const Material& m, const MaterialConstants& mc, const ModelSwitches& sw,
                   PointState* states, const int* index, std::size_t n, const Mat3* d_eps,
                   const double* J_new, double dt, const double* length, PointUpdateResult* out);

}  // namespace splat
