// Total-Lagrangian SPH body: particles whose neighbours, kernel gradients and
// kernel correction are fixed in a reference configuration, with stresses
// from the same material kernel as the finite elements.
//
// Particles live in the shared NodeSet (solver/fe/fe_body.hpp) as the nodes of
// FE bodies do: a body owns the contiguous range [node_begin, node_end), and
// positions, velocities, forces and masses are nodes.x, v, f and mass. So the
// time loop of solver/core treats SPH particles exactly like nodes: it calls
// sph_internal_forces where it calls fe_internal_forces.
//
// Formulation (Ganzenmueller 2015, CMAME 286; Vignjevic et al. 2006; Bonet &
// Lok 1999 for the correction). With reference positions X, reference volumes
// V, h_ij = (h_i + h_j)/2, pairs (i, j, op) from sph_neighbours.hpp (op: the
// mirror across symmetry planes, S its reflection matrix, S = I for op = 0),
// dX_ij = op(X_j) - X_i, r0 = |dX_ij|:
//   g_ij  = -W'(r0, h_ij) dX_ij / r0                 (grad_i W_ij)
//   C_i   = sum_j V_j dX_ij (x) g_ij                 (symmetric, positive)
//   gc_ij = C_i^-1 g_ij                              (corrected gradient; weak
//           directions of C_i, eigenvalue < min_correction_eigenvalue, are
//           bounded and blended to a rigid map: see sph_build_reference)
//   F_i   = sum_j V_j (op(x_j) - x_i) (x) gc_ij      (exact for linear fields,
//                                                    free surfaces included)
//   Fdot_i = sum_j V_j (S v_j - v_i) (x) gc_ij
// Since g_ij = s_ij dX_ij with the scalar s_ij = -W'(r0, h_ij) / r0, each pair
// stores only t_ij = V_j s_ij; B_i = C_i^-1 is applied per particle, after the
// pair sums (F_i = sum_j (op(x_j) - x_i) (x) (t_ij dX_ij) B_i^T).
//   L_i   = Fdot_i F_mid^-1, F_mid = F_i - dt/2 Fdot_i (mid-step, as the FE bodies)
// Stress: Jaumann (Hughes-Winget) rotation of the deviator and update_point
// with d_eps = sym(L) dt and J = J_ref det F (the volume ratio to the initial
// volume), then P_i = det(F_i) sigma_i F_i^-T (first Piola-Kirchhoff).
// Forces, the gradient of sum_i V_i W(F_i) (so they conserve linear and angular
// momentum, sigma being symmetric):
//   f_i = sum_j V_i V_j (P_i gc_ij - S P_j gc_ji)    (gc_ji: of the reverse pair (j, i, op))
//       = V_i (P_i B_i sum_j t_ij dX_ij + sum_j S P_j B_j S t_ij dX_ij)
// (g_ji = -S g_ij: the reverse pair needs no storage of its own).
// Monaghan artificial viscosity (Monaghan 1992), between approaching pairs
// (v_ij . x_ij < 0, x_ij = op(x_j) - x_i, v_ij = S v_j - v_i, r = |x_ij|):
//   mu_ij = h_ij v_ij . x_ij / (r^2 + 0.01 h_ij^2),  m/s
//   Pi_ij = (-alpha c mu_ij + beta mu_ij^2) / rho_ij,  rho_ij = (rho_i + rho_j)/2
//   f_i  += m_i m_j Pi_ij W'(r0) x_ij / r            (repulsive, dissipative)
// with c the P-wave speed; thesis defaults alpha = 0.8, beta = 4 (2.1.3).
// Hourglass control (Ganzenmueller 2015, the form of LAMMPS MACHDYN): the
// error of pair ij against the mean linear map, eps_ij = Fbar dX_ij - x_ij,
// Fbar = (F_i + S F_j S)/2, projected on the pair, delta_ij = eps_ij . x_ij / r:
//   f_i  += -c_hg E_ij V_i V_j W_ij delta_ij / r0^2 x_ij / r
// E_ij the mean over i, j of (1 - D) E, or of the flow stress sigma_y once a
// particle's plastic strain exceeds 1e-3 (so the control does not stiffen
// plastic flow). Units: Pa m^3 m^3 m^-3 m m^-2 = N.
// Time step bound (stated, not the thesis's garbled eq. 2.2): per particle
//   dt_i = min(L_i s_i / (c + 1.2 (alpha c + beta max_j mu_ij)), sqrt(2 m_i / K_i))
// (sph_particle_time_step). The first is the signal-speed bound of Monaghan
// (1992) over the current spacing of the particle's neighbourhood, taken from
// the kernel and the deformation rather than from the distance to its
// nearest neighbour: L_i = min(h_i / h_over_spacing, d) is the spacing the
// reference kernel is built on (d, the initial spacing, at most: h grows at
// reference updates to reach neighbours along the most stretched direction,
// not because the particles moved apart along all of them), and s_i, the
// smallest principal stretch of F_i (smallest_stretch), shortens it as the
// neighbourhood is compressed since the reference. The stress forces see the
// neighbours only through the reference kernel gradients and F_i, so one
// close pair does not stiffen them: a particle drifting onto a symmetry plane
// nears its own mirror image (at twice its distance to the plane) while its
// neighbourhood keeps its volume, and a bound on that distance would follow
// it down to the time-step floor (tests SphTimeStep, sph_time_step); mu_ij is
// bounded by 5 |v_ij| at any distance. The second term bounds the hourglass
// springs, the only term stiffer for pairs close in the reference: K_i =
// sum_j c_hg E_ij V_i V_j W_ij / r0^2 (N/m), and by Gershgorin omega_i^2 <=
// 2 K_i / m_i, stable for dt <= 2 / omega_i (on the initial lattice about 4x
// the signal bound). The caller multiplies by its stability coefficient.
// Checks: a free elastic ball without viscosity (the bound is then d / c)
// runs stably at 1.1 (HCP) and 1.0 (cubic), unstable at 1.2, so the
// Simulation's default 0.9 is safe; the power iteration on its stiffness
// gives 2 / omega_max = 1.13 d / c for 743 HCP particles, 1.10 d / c with a
// jet of three particles of 10, 2 and 1 neighbours (kernel correction at
// min_correction_eigenvalue) on it: particles with few neighbours need no
// shorter step. Without s_i the Al/Al SPH impact without criteria blows up
// at 1500 m/s (5 across) where the jet's particles are compressed.
// Reference update: when max_i ||F_i - I||_F (Frobenius) exceeds
// update_threshold, the whole body is re-referenced at the start of
// sph_internal_forces: X = x, V_i *= det F_i, J_ref *= det F_i, F_ref = F F_ref
// (the deformation from the initial configuration), h_i = h_0 times the
// largest principal stretch of F_ref (so the kernel still reaches neighbours
// along the most stretched direction; J_ref^(1/3) would starve it), capped at
// max_h_growth h_0 (h_0 = h_over_spacing d), neighbours re-found by the
// cell search and corrections rebuilt; F is then computed afresh from the new
// reference (F = I, Fdot the current velocity gradient). Stresses, plastic
// strain, damage, temperature and energy are kept (they are Cauchy/spatial).
// Damage: as in the material kernel. Particles are never deleted; with
// deactivate_failed a particle at D_max stops carrying stress and is dropped
// from all neighbour lists at the next reference update (forced at the next
// call); it then flies freely and its energy leaves the internal energy (it is
// reported in SphStepResult::deactivated_energy).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/common/types.hpp"
#include "solver/fe/fe_body.hpp"
#include "solver/material/material.hpp"
#include "solver/material/point_update.hpp"
#include "solver/sph/sph_kernel.hpp"
#include "solver/sph/sph_neighbours.hpp"
#include "solver/sph/sph_particles.hpp"

namespace splat {

struct SphSettings {
  SphKernel kernel = SphKernel::cubic_spline;
  double h_over_spacing = 1.0;         // smoothing length / particle spacing, -
  double visc_linear = 0.8;            // Monaghan alpha, -
  double visc_quadratic = 4.0;         // Monaghan beta, -
  double hourglass_coefficient = 1.0;  // Ganzenmueller c_hg, -
  double update_threshold = 1.0;       // ||F - I||_F that triggers a reference update; 0 = never
  double min_correction_eigenvalue = 0.05;  // lambda_min of the kernel correction, -
  double max_h_growth = 2.0;                // cap on h / h_0 at reference updates, -
  bool deactivate_failed = false;           // particles at D_max stop carrying stress
};

// What the pair loop reads of each neighbour, in one record of three cache
// lines written by the material update every step: the pair loop finds all of
// it from one address per neighbour and loads it two fields at a time
// (separate arrays cost one address per array and neighbour, more than the
// registers hold).
struct alignas(64) SphPairRecord {
  double PB[9];     // first Piola-Kirchhoff stress times B_i, column-major, Pa
  double F[9];      // deformation gradient (copy of SphBody::F), column-major, -
  double h;         // smoothing length, m
  double rho;       // current density, kg/m^3
  double E_hg;      // hourglass modulus, Pa
  double active;    // 1 active, 0 deactivated
  double spare[2];  // padding to 192 bytes
};
static_assert(sizeof(SphPairRecord) == 192);

struct SphBody {
  std::string name;
  Material material;
  MaterialConstants constants;
  ModelSwitches switches;
  SphSettings settings;
  SymmetryPlanes planes;                     // mirrored-ghost symmetry planes (set once)
  std::size_t node_begin = 0, node_end = 0;  // this body's range in the NodeSet
  double spacing = 0.0;                      // initial particle spacing d, m

  // Set once.
  std::vector<double> volume0;        // initial volume m / rho0, m^3
  std::vector<double> surface_area0;  // initial share of the body's surface (sph_surface_area), m^2
  std::vector<Vec3> outward_normal;   // of `curved` boundary particles, else zero

  // Set at the start and at each reference update.
  std::vector<Vec3> X;                 // reference positions, m
  std::vector<double> volume_ref;      // reference volumes, m^3
  std::vector<double> J_ref;           // volume_ref / volume0, -
  std::vector<Mat3> F_ref;             // deformation of the reference from the initial state, -
  std::vector<double> h;               // smoothing lengths, m
  NeighbourList pairs;                 // reference neighbours (local indices)
  std::vector<double> pair_t;          // t_ij = V_j s_ij = -V_j W'(r0, h_ij) / r0, 1/m^2
  std::vector<float> pair_hg;          // V_j W(r0, h_ij) / r0^2, 1/m^2 (float: read by
  std::vector<float> pair_visc;        //   the stabilising terms only), m_j W'(r0, h_ij), kg/m^4
  std::vector<Mat3> null_projector;    // I - C^+ C (zero unless C_i is singular)
  std::vector<Mat3> B;                 // kernel correction C_i^-1 (bounded), -
  std::vector<Vec3> surface_gradient;  // sum_j V_j g_ij where its size marks a surface
                                       //   (sph_surface_normal), else zero, 1/m
  std::vector<double> surface_stretch_ref;  // sph_surface_stretch at the reference, -
  long long reference_updates = 0;          // count of updates so far
  bool update_pending = false;              // forces an update at the next call

  // Every step.
  std::vector<PointState> state;      // material state
  std::vector<Mat3> F;                // deformation gradient from the reference, -
  std::vector<Mat3> Fdot;             // its rate, 1/s
  std::vector<SphPairRecord> record;  // P B, F, h, rho, hourglass modulus, activity
  std::vector<double> dt_bound;       // per-particle time-step bound, s
  std::vector<std::uint8_t> active;   // 0 once deactivated
  std::vector<Vec3> f_visc;           // artificial-viscosity force of the last call, N
  std::vector<Vec3> f_hg;             // hourglass force of the last call, N

  std::size_t size() const { return node_end - node_begin; }
  // P_i B_i of the last call, Pa.
  Eigen::Map<const Mat3> PB(std::size_t i) const { return Eigen::Map<const Mat3>(record[i].PB); }
};

struct SphStepResult {
  double dt_stable = 0.0;        // min over active particles of dt_i, s
  double hourglass_power = 0.0;  // -sum f_hg . v, W (the stiffness form can return energy)
  double viscosity_power = 0.0;  // -sum f_visc . v >= 0, W
  int max_return_iterations = 0;
  bool return_failed = false;
  long long inverted = 0;           // active particles with det F <= 0 (carry no stress)
  double max_deformation = 0.0;     // max ||F - I||_F after any update, -
  bool reference_updated = false;   // the body was re-referenced in this call
  std::vector<int> deactivated;     // particles (local) deactivated in this call
  double deactivated_energy = 0.0;  // V0 e of those particles, leaving the internal energy, J
};

// What the time-step bound of one particle reads (see the header comment).
struct SphStepBoundInputs {
  double spacing = 0.0;  // L_i = min(h_i / h_over_spacing, d), m
  double stretch = 1.0;  // smallest principal stretch of F_i (1 when det F_i <= 0), -
  double c = 0.0;        // P-wave speed, m/s
  double alpha = 0.0;    // Monaghan alpha, -
  double beta = 0.0;     // Monaghan beta, -
  double max_mu = 0.0;   // largest approach mu_ij, m/s
  double mass = 0.0;     // m_i, kg
  double k_hg = 0.0;     // hourglass stiffness K_i, N/m
};

// dt_i of the header comment, s (the hourglass term is absent for K_i = 0).
double sph_particle_time_step(const SphStepBoundInputs& in);

// The smallest principal stretch of F, sqrt of the smallest eigenvalue of
// F^T F, -; 1 for det F <= 0 (an inverted particle carries no stress).
double smallest_stretch(const Mat3& F);

// Builds a body from a particle cloud and appends its particles to `nodes`:
// positions, the initial velocity, boundary bits, masses rho0 V, the initial
// material state at `temperature` (K) with, when damage is on, the
// reproducible random initial damage, and the reference configuration.
// Throws std::invalid_argument for bad settings (non-positive h_over_spacing,
// negative coefficients) or planes sph_neighbours rejects.
SphBody make_sph_body(const std::string& name, const ParticleCloud& cloud, const Material& material,
                      const ModelSwitches& switches, const SphSettings& settings,
                      const SymmetryPlanes& planes, const Vec3& velocity, double temperature,
                      unsigned long long seed, NodeSet& nodes);

// Internal forces of one body, called once per step after the particles moved
// to x_{n+1} with velocity v_{n+1/2} (same contract as fe_internal_forces):
// reference update if due, F and Fdot, material update (skipped for dt = 0,
// the force evaluation before the first step), P, then stress, viscosity and
// hourglass forces ADDED to nodes.f. Each particle gathers its own pairs, so
// the result does not depend on the number of OpenMP threads.
SphStepResult sph_internal_forces(SphBody& body, NodeSet& nodes, double dt);

// The corrected kernel gradient of pair k times the neighbour's volume, V_j
// gc_ij = V_j B_i g_ij, 1/m (for checks: the force loops never form it).
Vec3 sph_pair_gradient(const SphBody& body, std::size_t k);

// The outward unit normal of particle i if it lies on the body's surface,
// else zero: -F_i^-T a_i normalised (Nanson's rule), with a_i = sum_j V_j
// grad_i W_ij, the uncorrected gradient of the reference neighbourhood's
// volume fraction (mirrored ghosts included; kept as surface_gradient by
// sph_build_reference), zero inside the body; i is on the surface when
// |a_i| h_i > k_surface_gradient. Zero for inactive particles and
// det F_i <= 0.
inline constexpr double k_surface_gradient = 0.25;  // -
Vec3 sph_surface_normal(const SphBody& body, std::size_t i);

// Particle i's share of the body's surface, m^2: its initial share times
// sph_surface_stretch. The initial shares follow the colour gradient, A_i =
// V_i |a_i| / kappa, and add up to the body's surface area: since a_i
// approximates -kappa n times the surface's delta function, the divergence
// theorem (the integral of x . n over a closed surface is 3 V) gives kappa =
// -sum_i V_i (x_i - o) . a_i / (3 sum_i V_i), with o on every symmetry plane
// (mirror faces, which carry no gradient, add nothing). Measured on spheres
// of 4 to 10 spacings across R, the shares add up to 1.16 to 1.06 times
// 4 pi R^2 (cubic) and 1.13 to 1.06 (hcp), where pi (d / 2)^2 per surface
// particle gives 0.56-0.61 and 0.82-0.93. A particle off the initial surface
// (reached later, by erosion or a reference update) starts from V_i^(2/3).
double sph_surface_area(const SphBody& body, std::size_t i);

// The ratio of particle i's share of the surface now to its initial share,
// -: Nanson's rule da / dA = J |F^-T N| from the reference to now, N the unit
// reference normal (the direction of -a_i), times the ratio reached at the
// reference (surface_stretch_ref, set at each reference update). Off the
// surface J^(2/3), the ratio of an isotropic stretch. The reference's ratio
// alone for an inactive particle or det F <= 0.
double sph_surface_stretch(const SphBody& body, std::size_t i);

// Re-references the body at the current positions (see the header comment).
void sph_update_reference(SphBody& body, const NodeSet& nodes);

// Sum over active particles of V0 e, J.
double sph_internal_energy(const SphBody& body);

// Energy sums of one body, J (or powers, W), computed in parallel over fixed
// blocks of particles: the same bits for any thread count.
struct SphEnergySums {
  double internal = 0.0;   // sum over active particles of V0 e, J
  double plastic = 0.0;    // sum over active particles of V0 w_p, J
  double viscosity = 0.0;  // -sum f_visc . v over all particles, W
  double hourglass = 0.0;  // -sum f_hg . v over all particles, W
};
// internal and plastic.
SphEnergySums sph_energy_sums(const SphBody& body);
// viscosity and hourglass: the power of the last call's stabilising forces at
// the current velocities (zero before the first call).
SphEnergySums sph_stabiliser_power(const SphBody& body, const NodeSet& nodes);

// Recomputes the reference neighbourhood and kernel correction from body.X,
// body.h, body.volume_ref (used by make_sph_body and sph_update_reference).
void sph_build_reference(SphBody& body);

}  // namespace splat
