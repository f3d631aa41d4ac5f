#include "solver/material/johnson_cook.hpp"

#include <limits>

namespace splat {

namespace {

// binom(a, k), k = 0..K-1 (K <= 14), by the recurrence
// binom(a, k) = binom(a, k - 1) (a - k + 1) / k (reciprocals from a table:
// no divisions on the chain).
template <int K>
void binomial_coefficients(double a, double (&c)[K]) {
  static_assert(K <= 14);
  static constexpr double inv[14] = {0.0,        1.0,        1.0 / 2.0,  1.0 / 3.0, 1.0 / 4.0,
                                     1.0 / 5.0,  1.0 / 6.0,  1.0 / 7.0,  1.0 / 8.0, 1.0 / 9.0,
                                     1.0 / 10.0, 1.0 / 11.0, 1.0 / 12.0, 1.0 / 13.0};
  c[0] = 1.0;
  for (int k = 1; k < K; ++k) c[k] = c[k - 1] * (a - (k - 1)) * inv[k];
}

}  // namespace

JcSeries jc_series(const JohnsonCookParams& jc) {
  JcSeries s;
  binomial_coefficients(jc.n, s.hardening);
  binomial_coefficients(jc.m, s.thermal);
  return s;
}

double jc_thermal_factor_after_heating(const JohnsonCookParams& jc, const JcSeries& series,
                                       double theta_old, double T_old, double T_new) {
  bool ok = false;
  const double theta = jc_thermal_series(jc, series, theta_old, T_old, T_new, ok);
  return ok ? theta : jc_thermal_factor(jc, true, T_new);
}

FlowStress johnson_cook_flow_stress(const JohnsonCookParams& jc, const ModelSwitches& sw,
                                    double eps_p, double eps_dot_p, double T) {
  const double theta = jc_thermal_factor(jc, sw.thermal_softening, T);
  const double rate = jc_rate_factor(jc, sw.rate_hardening, eps_dot_p);
  double hard = jc.A;
  double d_hard = 0.0;
  if (eps_p > 0.0) {
    const double pw = std::pow(eps_p, jc.n);
    hard += jc.B * pw;
    d_hard = jc.B * jc.n * pw / eps_p;
  } else if (jc.n < 1.0 && jc.B > 0.0) {
    d_hard = std::numeric_limits<double>::infinity();  // eps_p^n has a vertical tangent at 0
  } else if (jc.n == 1.0) {
    d_hard = jc.B;
  }
  double d_rate = 0.0;
  if (sw.rate_hardening && eps_dot_p > jc.eps_dot_0) d_rate = jc.C / eps_dot_p;
  return {hard * rate * theta, d_hard * rate * theta, hard * d_rate * theta};
}

ReturnMapResult johnson_cook_return(const JohnsonCookParams& jc, bool rate_hardening,
                                    double q_trial, double G_d, double eps_p, double dt,
                                    double scale, double hard0, double dp_guess, double rate_guess,
                                    const JcSeries* series) {
  constexpr int max_iterations = 200;
  const double three_g = 3.0 * G_d;
  ReturnMapResult r;
  const bool rate_on = rate_hardening && jc.C > 0.0;
  const double inv_ref = 1.0 / (jc.eps_dot_0 * dt);  // dp -> eps_dot / eps_dot_0
  // hard and rate at dp, for a dp the iteration did not end on.
  auto set_terms = [&](double dp) {
    r.hard = jc_hardening(jc, eps_p + dp);
    const double x = dp * inv_ref;
    r.rate = rate_on && x > 1.0 ? 1.0 + jc.C * std::log(x) : 1.0;
  };
  if (scale <= 0.0) {  // molten or fully damaged: no strength, return to the axis
    r.delta_eps_p = q_trial / three_g;
    r.iterations = 0;
    set_terms(r.delta_eps_p);
    return r;
  }
  double lo = 0.0;
  double hi = q_trial / three_g;
  // Converged when the residual is a tiny fraction of the trial stress or the
  // bracket has shrunk to rounding relative to its own size (the root can be
  // many decades below q_trial / 3G when n < 1 makes sigma_y steep near 0).
  const double tol_g = 1e-11 * q_trial;

  // Initial guess: hardening linearised at eps_p, no rate term (the rate
  // term's slope is unbounded at dp = 0).
  double dp = dp_guess;
  if (!(dp_guess > 0.0 && dp_guess < hi)) {
    double h0 = 0.0;
    if (eps_p > 0.0) {
      h0 = jc.n * (hard0 - jc.A) / eps_p;
    } else if (jc.n == 1.0) {
      h0 = jc.B;
    }
    dp = std::min(hi, (q_trial - scale * hard0) / (three_g + scale * h0));
  }
  // At the guess of a step that continues plastic flow the terms need no
  // exp or log: B ep^n from the cached hard0 by a binomial series, and the
  // rate factor is rate_guess.
  const bool at_guess = series && dp == dp_guess;
  r.converged = false;
  for (int it = 1; it <= max_iterations; ++it) {
    r.iterations = it;
    const double ep = eps_p + dp;
    const bool first = it == 1 && at_guess;
    double hard = jc.A, d_hard = 0.0, dd_hard = 0.0, inv_ep = 0.0, inv_dp = 0.0;
    if (ep > 0.0) {
      inv_ep = 1.0 / ep;
      // B ep^n; exp and log cost less than pow.
      bool series_ok = false;
      double b_pw = first && eps_p > 0.0
                        ? jc_hardening_series(jc, *series, hard0 - jc.A, dp / eps_p, series_ok)
                        : 0.0;
      if (!series_ok) b_pw = jc.B * std::exp(jc.n * std::log(ep));
      hard += b_pw;
      d_hard = jc.n * b_pw * inv_ep;
      dd_hard = (jc.n - 1.0) * d_hard * inv_ep;
    }
    double rate = 1.0, d_rate = 0.0, dd_rate = 0.0;
    const double x = dp * inv_ref;
    if (rate_on && x > 1.0) {
      rate += first && rate_guess > 1.0 ? rate_guess - 1.0 : jc.C * std::log(x);
      inv_dp = 1.0 / dp;
      d_rate = jc.C * inv_dp;
      dd_rate = -d_rate * inv_dp;
    }
    const ReturnEvaluation<double> e = jc_return_evaluation(
        jc, q_trial, three_g, scale, tol_g, inv_ref, rate_on, x > 1.0, rate_on && x > 1.0, dp, lo,
        hi, hard, d_hard, dd_hard, inv_ep, rate, d_rate, dd_rate, inv_dp);
    r.hard = hard;
    r.rate = rate;
    r.hard_rate = e.hard_rate;
    lo = e.lo;
    hi = e.hi;
    if (e.at_dp) {
      r.converged = true;
      break;
    }
    // Bisect when the Halley step (Newton's where the curvature term is not
    // small) leaves the bracket, stalls, or meets an unbounded slope.
    if (!(e.next > lo && e.next < hi) || e.next == dp) {
      dp = 0.5 * (lo + hi);
      continue;
    }
    // A step tiny relative to eps_p + dp (and to dp, with the rate term on,
    // which stays on the same side of the reference rate) lands where the
    // third-order Taylor expansions of A + B eps^n and 1 + C ln(x) are exact
    // to rounding: their truncation errors relative to hard rate are below
    //   trunc = (n + 3)^4 |step / ep|^4 + |C| |step / dp|^4
    // (fourth derivatives B |n (n-1) (n-2) (n-3)| ep^(n-4) <= hard (n + 3)^4 /
    // ep^4 and 6 |C| / dp^4, rate >= 1; generous by a factor of 4 and more,
    // which covers the derivatives' change over the step). Where that
    // is below 1e-14 and the expanded residual plus it is within the
    // tolerance, the step ends the iteration with the expanded terms: no
    // further exp and log, and the terms handed back (and cached by
    // update_point) are those of the law at the returned dp to 1e-14.
    dp = e.next;
    if (e.taylor) {
      r.hard = e.hard_n;
      r.rate = e.rate_n;
      r.hard_rate = e.hard_rate_n;
      r.converged = true;
      break;
    }
  }
  r.delta_eps_p = dp;
  if (!r.converged) {  // the last Newton or bisection point was not evaluated
    set_terms(dp);
    r.hard_rate = r.hard * r.rate;
  }
  return r;
}

}  // namespace splat
