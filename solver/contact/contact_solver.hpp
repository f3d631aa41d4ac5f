// Lagrange-multiplier contact impulses for one step (thesis 1.3.3.3).
//
// Unknowns: the normal impulse p_i = lambda_i dt of each pair (N s; per radian
// in 2D) and, with friction, its tangential impulses. The velocity correction
// is dv = M^-1 C^T p (eq. 1.22 times dt), with M^-1 zero on prescribed
// velocity components. The predicted gap g_i (at x_{n+1} = x_n + dt v_{n+1/2})
// changes by dt C_i dv, so the no-penetration condition g_i + dt C_i dv >= 0 is
//   (H p)_i >= b_i,   H = C M^-1 C^T (eq. 1.24),   b_i = -g_i / dt,
// the thesis's H lambda = w (eq. 1.23-1.25) written for impulses on the
// predicted positions. Rows are complementary: p_i >= lo_i, (H p - b)_i >= 0
// and (p_i - lo_i) (H p - b)_i = 0. lo_i = 0 for plain contact (no tension:
// a pair that would separate gets no force, the thesis's rebound check).
//
// A bonded adhesive pair (lo_i < 0: tension allowed down to lo_i, -infinity
// without a stress cap) must also not open further: its hold target
// b_hold_i >= b_i is the C dv that keeps its gap at its value at the start of
// the step (b_hold_i = b_i + max(g_n, 0) / dt). Its row is then
//   p_i > 0          (H p)_i = b_i        (compression: closes the gap)
//   p_i = 0          b_i <= (H p)_i <= b_hold_i
//   lo_i < p_i < 0   (H p)_i = b_hold_i   (tension: holds the opening)
//   p_i = lo_i       (H p)_i >= b_hold_i  (cap reached: opens)
// (PGS only; the active-set solver takes unbonded rows.)
//
// Coulomb friction (PGS only): after each normal update the tangential
// impulse that stops the relative tangential velocity is added and the total
// is clipped to the disc |p_t| <= mu max(p_n, 0).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/common/types.hpp"
#include "solver/contact/contact_types.hpp"

namespace splat {

// The pair rows of one step (SoA). Node slots: slave first, then the master
// face's nodes; unused slots have node -1. Nodes are local indices into
// ContactProblem::inv_mass / velocity.
struct ContactProblem {
  std::vector<std::array<int, 5>> node;
  std::vector<std::array<double, 5>> coef;  // +1 slave, -w_k master
  std::vector<Vec3> normal, tangent1, tangent2;
  std::vector<double> b;       // required C dv, m/s
  std::vector<double> lo;      // lower bound of the normal impulse, N s (0, or < 0 bonded)
  std::vector<double> b_hold;  // bonded rows: C dv that stops the opening, m/s
  std::vector<double> mu;      // friction coefficient per pair, -
  // PGS starting impulse per pair (warm start, N s), clipped to [lo, inf);
  // empty: start from p = 0. The solution does not depend on it where it is
  // unique; it only saves sweeps.
  std::vector<double> p_start;
  // Per local node.
  std::vector<Vec3> inv_mass;  // 1/m per component, 0 where prescribed, 1/kg
  std::vector<Vec3> velocity;  // v_{n+1/2} before the correction, m/s (friction)

  std::size_t pairs() const { return node.size(); }
  void clear_pairs() {
    node.clear();
    coef.clear();
    normal.clear();
    tangent1.clear();
    tangent2.clear();
    b.clear();
    lo.clear();
    b_hold.clear();
    mu.clear();
    p_start.clear();
  }
};

struct ContactSolution {
  std::vector<double> p_n;  // normal impulse per pair, N s
  std::vector<Vec3> p_t;    // tangential impulse per pair (in the tangent basis), N s
  std::vector<Vec3> dv;     // velocity correction per local node, m/s
  int iterations = 0;
  double residual = 0.0;  // largest constraint violation left, m/s
  bool converged = true;
};

struct ContactSolverSettings {
  ContactSolverKind kind = ContactSolverKind::pgs;
  // PGS stops when a sweep changes no constraint velocity C_i dv by more
  // than tolerance x max_i |b_i| (measured: bench_contact_solver).
  double tolerance = 1e-10;
  int max_iterations = 2000;
  // Projected SOR: after plain_sweeps Gauss-Seidel sweeps the contact
  // (compressive) updates are over-relaxed, p <- max(0, p - w (H p - b)_i /
  // H_ii); it converges for 0 < w < 2 (symmetric positive semidefinite H).
  // Well-conditioned systems (one pass: 6-14 sweeps) end before it starts;
  // the nearly dependent rows of two-pass contact take 2-3x fewer sweeps
  // with w = 1.5 (measured: Al/Al 600 m/s at 16 elements across, 1945 -> 707
  // sweeps at most; w = 1.7: 381).
  int plain_sweeps = 20;
  double over_relaxation = 1.5;  // w, -
};

ContactSolution solve_contact(const ContactProblem& problem, const ContactSolverSettings& settings);

// C_i dv along pair i's normal, m/s.
double normal_rate(const ContactProblem& problem, std::size_t i, const std::vector<Vec3>& dv);
// H_ii = C_i M^-1 C_i^T along pair i's normal, 1/kg.
double normal_inverse_mass(const ContactProblem& problem, std::size_t i);

// Rows i >= first that nearly repeat a row j < first: their correlation in
// the M^-1 metric, H_ij / sqrt(H_ii H_jj), is at least max_correlation
// (1: the same constraint). Returns a flag per row (0 for rows < first).
std::vector<std::uint8_t> repeated_rows(const ContactProblem& problem, std::size_t first,
                                        double max_correlation);
// The same with a threshold per row j < first (max_correlation[j]).
std::vector<std::uint8_t> repeated_rows(const ContactProblem& problem, std::size_t first,
                                        const std::vector<double>& max_correlation);

// Largest violation of the complementarity conditions of a solution: the
// most negative (H p - b)_i over all pairs, and the largest |H p - b|_i over
// pairs strictly above their lower bound, m/s.
double contact_violation(const ContactProblem& problem, const ContactSolution& solution);

}  // namespace splat
