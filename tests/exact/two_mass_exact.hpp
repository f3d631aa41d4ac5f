// Reference solutions of the two-mass adhesion problem (thesis 3.5.1.1),
// written from the equations of motion independently of the solver (no
// solver header is included here).
//
// Set-up: M moves at V0 along +x and touches m at t = 0 (gap g = x_m - x_M =
// 0); m rests on a spring k at x = 0. The collision is elastic. The link then
// carries a tension F in [0, F_cap] while the pair would open (a rigid-plastic
// cohesive link: F = F_cap while g_dot > 0, any F <= F_cap that keeps
// g_dot = 0, none while the pair closes); the work F dg done while opening is
// charged to the budget B = G_c A, and the link lets go when it is spent.
// Without a cap (F_cap = infinity) the link absorbs velocity jumps
// instantly, up to the remaining budget.
//
// k = 0, closed form from momentum and energy. After the elastic impact the
// centre of mass moves at u = M V0 / (M + m) and the pair opens at V0 with
// relative kinetic energy mu V0^2 / 2, mu = M m / (M + m). Whatever F_cap,
// the link takes exactly B out of that energy (or all of it: stick), so
//   g_final = sqrt(V0^2 - 2 B / mu),
//   V_M = u - m / (M + m) g_final,   v_m = u + M / (M + m) g_final,
// and, with a cap, the relative rate falls at F_cap / mu, so the link lets
// go at t_c = mu (V0 - g_final) / F_cap. (The thesis's eq. 3.5-3.6 are a
// garbled form of this; Table 3.5 prints 0.0898 for M = 1, m = 2, V0 = 1,
// B = 0.2, where this gives 0.08830.)
//
// k > 0: event-driven solution. Between events every motion is analytic
// (M: constant force; m: harmonic oscillator about -F/k; joined: oscillator
// of mass M + m); events (gap closes, opening stops or starts, the needed
// tension reaches F_cap or zero, the budget is spent) are located by
// scanning at 1/400 of the shortest time scale and bisecting to rounding.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>

namespace splat::exact {

struct TwoMassCase {
  double M = 1.0, m = 2.0;                                 // kg
  double k = 0.0;                                          // N/m
  double V0 = 1.0;                                         // m/s
  double budget = 0.2;                                     // G_c A, J
  double F_cap = std::numeric_limits<double>::infinity();  // sigma_c A, N
};

struct TwoMassOutcome {
  bool rebound = false;                                            // the link let go
  double release_time = std::numeric_limits<double>::quiet_NaN();  // s
  double V_release = std::numeric_limits<double>::quiet_NaN();     // V_M when it let go, m/s
  double V_final = 0.0, v_final = 0.0;                             // m/s, at the end
  int events = 0;
};

inline TwoMassOutcome two_mass_closed_form_k0(const TwoMassCase& c) {
  TwoMassOutcome o;
  const double mu = c.M * c.m / (c.M + c.m);
  const double u = c.M * c.V0 / (c.M + c.m);
  const double disc = c.V0 * c.V0 - 2.0 * c.budget / mu;
  if (disc <= 0.0) {
    o.V_final = o.v_final = u;
    return o;
  }
  const double g = std::sqrt(disc);
  o.rebound = true;
  o.V_release = o.V_final = u - c.m / (c.M + c.m) * g;
  o.v_final = u + c.M / (c.M + c.m) * g;
  o.release_time = std::isfinite(c.F_cap) ? mu * (c.V0 - g) / c.F_cap : 0.0;
  return o;
}

namespace detail {

struct State {
  double t = 0.0, X = 0.0, V = 0.0, x = 0.0, v = 0.0;
};

// Separate motion over tau with link tension F (pulls M to +x, m to -x).
inline State advance(const TwoMassCase& c, const State& s, double F, double tau) {
  State r;
  r.t = s.t + tau;
  r.X = s.X + s.V * tau + 0.5 * F / c.M * tau * tau;
  r.V = s.V + F / c.M * tau;
  // x'' = -w^2 x - F/m, written without F/k so that k -> 0 stays accurate:
  // x = x0 cos(th) + v0 tau sinc(th) - (F/m) tau^2 (1 - cos th) / th^2, th = w tau.
  const double w = std::sqrt(c.k / c.m);
  const double th = w * tau;
  const double sinc = th > 1e-8 ? std::sin(th) / th : 1.0 - th * th / 6.0;
  const double half = 0.5 * th;
  const double sh = std::sin(half) / th;
  const double versine = th > 1e-8 ? 2.0 * sh * sh : 0.5;  // (1 - cos th) / th^2
  const double a_F = F / c.m;
  r.x = s.x * std::cos(th) + s.v * tau * sinc - a_F * tau * tau * versine;
  r.v = -s.x * w * std::sin(th) + s.v * std::cos(th) - a_F * tau * sinc;
  return r;
}

// Joined motion (common velocity, fixed gap) over tau.
inline State advance_joint(const TwoMassCase& c, const State& s, double tau) {
  const double gap = s.x - s.X;
  const double u = (c.M * s.V + c.m * s.v) / (c.M + c.m);
  State r;
  r.t = s.t + tau;
  const double W = std::sqrt(c.k / (c.M + c.m));
  const double th = W * tau;
  const double sinc = th > 1e-8 ? std::sin(th) / th : 1.0 - th * th / 6.0;
  r.x = s.x * std::cos(th) + u * tau * sinc;
  r.v = -s.x * W * std::sin(th) + u * std::cos(th);
  r.V = r.v;
  r.X = r.x - gap;
  return r;
}

// First tau in (0, tau_max] where f crosses zero in direction dir (+1 up,
// -1 down), scanning at `step` and bisecting; nullopt if none.
inline std::optional<double> crossing(const std::function<double(double)>& f, double tau_max,
                                      double step, int dir) {
  const auto before = [dir](double y) { return dir > 0 ? y < 0.0 : y > 0.0; };
  double a = 0.0, fa = f(0.0);
  while (a < tau_max) {
    const double b = std::min(a + step, tau_max);
    const double fb = f(b);
    if (before(fa) && !before(fb)) {
      double lo = a, hi = b;
      for (int i = 0; i < 200 && hi - lo > 1e-16 * (1.0 + hi); ++i) {
        const double mid = 0.5 * (lo + hi);
        (before(f(mid)) ? lo : hi) = mid;
      }
      return hi;
    }
    a = b;
    fa = fb;
  }
  return std::nullopt;
}

}  // namespace detail

inline TwoMassOutcome two_mass_event_driven(const TwoMassCase& c, double t_end) {
  using detail::State;
  TwoMassOutcome o;
  const double mu = c.M * c.m / (c.M + c.m);
  // Scan step: 1/400 of the shortest of the spring period, the time the cap
  // needs to stop the opening (mu V0 / F_cap) and the end time.
  double scale = t_end;
  if (c.k > 0.0) scale = std::min(scale, 2.0 * std::numbers::pi * std::sqrt(c.m / c.k));
  if (std::isfinite(c.F_cap)) scale = std::min(scale, mu * std::max(c.V0, 1e-300) / c.F_cap);
  const double step = scale / 400.0;
  const double tol = 1e-12 * (1.0 + c.V0 * t_end);
  const bool capped = std::isfinite(c.F_cap);
  const auto gap = [](const State& s) { return s.x - s.X; };
  const auto gdot = [](const State& s) { return s.v - s.V; };
  const auto needed = [&](const State& s) { return -c.M * c.k * s.x / (c.M + c.m); };

  enum class Mode { open, slack, held, free_ };
  State s;
  s.V = c.V0;
  double W = 0.0;
  bool linked = true;
  Mode mode = Mode::open;

  const auto release = [&] {
    linked = false;
    o.rebound = true;
    o.release_time = s.t;
    o.V_release = s.V;
  };
  // Elastic impact at g = 0, then the link meets the opening jump.
  const auto impact = [&] {
    const double gd = gdot(s);
    if (gd < 0.0) {
      const double P = -2.0 * mu * gd;
      s.V -= P / c.M;
      s.v += P / c.m;
    }
    if (!linked) return Mode::free_;
    if (capped) return Mode::open;
    const double g1 = gdot(s);
    const double K = 0.5 * mu * g1 * g1;
    const double u = (c.M * s.V + c.m * s.v) / (c.M + c.m);
    if (K < c.budget - W) {
      W += K;
      s.V = s.v = u;
      return Mode::held;
    }
    const double g2 = std::sqrt(std::max(g1 * g1 - 2.0 * (c.budget - W) / mu, 0.0));
    W = c.budget;
    s.V = u - c.m / (c.M + c.m) * g2;
    s.v = u + c.M / (c.M + c.m) * g2;
    release();
    return Mode::free_;
  };
  // The opening has just stopped (g_dot = 0) with the link active.
  const auto stopped = [&] {
    if (needed(s) >= 0.0 || gap(s) <= tol) {
      s.V = s.v = (c.M * s.V + c.m * s.v) / (c.M + c.m);
      return Mode::held;
    }
    return Mode::slack;
  };

  mode = impact();
  for (; o.events < 100000 && s.t < t_end; ++o.events) {
    const double tau_max = t_end - s.t;
    if (mode == Mode::open) {
      const State s0 = s;
      const double F = c.F_cap;
      const double W0 = W;
      const auto at = [&](double tau) { return detail::advance(c, s0, F, tau); };
      const auto ta =
          detail::crossing([&](double tau) { return gdot(at(tau)); }, tau_max, step, -1);
      const auto tb =
          detail::crossing([&](double tau) { return W0 + F * (gap(at(tau)) - gap(s0)) - c.budget; },
                           tau_max, step, +1);
      if (tb && (!ta || *tb <= *ta)) {
        s = at(*tb);
        W = c.budget;
        release();
        mode = Mode::free_;
      } else if (ta) {
        s = at(*ta);
        W = W0 + F * (gap(s) - gap(s0));
        mode = stopped();
      } else {
        s = at(tau_max);
        W = W0 + F * (gap(s) - gap(s0));
      }
    } else if (mode == Mode::slack) {
      const State s0 = s;
      const auto at = [&](double tau) { return detail::advance(c, s0, 0.0, tau); };
      const auto tc = detail::crossing([&](double tau) { return gap(at(tau)); }, tau_max, step, -1);
      const auto td =
          detail::crossing([&](double tau) { return gdot(at(tau)); }, tau_max, step, +1);
      if (tc && (!td || *tc <= *td)) {
        s = at(*tc);
        mode = impact();
      } else if (td) {
        s = at(*td);
        mode = needed(s) <= c.F_cap ? Mode::held : Mode::open;
        if (mode == Mode::held) s.V = s.v = (c.M * s.V + c.m * s.v) / (c.M + c.m);
      } else {
        s = at(tau_max);
      }
    } else if (mode == Mode::held) {
      const State s0 = s;
      const double u = s.v;
      if (c.k == 0.0) break;  // nothing acts: stuck for good
      const double A = std::sqrt(s.x * s.x + u * u * (c.M + c.m) / c.k);
      if (c.M * c.k * A / (c.M + c.m) <= c.F_cap && gap(s) <= tol) break;  // settled
      const auto at = [&](double tau) { return detail::advance_joint(c, s0, tau); };
      std::optional<double> te, tf;
      if (capped) {
        te = detail::crossing([&](double tau) { return needed(at(tau)) - c.F_cap; }, tau_max, step,
                              +1);
      }
      if (gap(s0) > tol) {
        tf = detail::crossing([&](double tau) { return needed(at(tau)); }, tau_max, step, -1);
      }
      if (te && (!tf || *te <= *tf)) {
        s = at(*te);
        mode = Mode::open;
      } else if (tf) {
        s = at(*tf);
        mode = Mode::slack;
      } else {
        s = at(tau_max);
      }
    } else {  // free: the link has let go; only contact remains
      if (c.k == 0.0) {
        if (gdot(s) >= 0.0) break;
      } else {
        const double w = std::sqrt(c.k / c.m);
        const double reach = std::sqrt(s.x * s.x + s.v * s.v / (w * w));
        if (s.V <= 0.0 && s.X < -reach) break;
      }
      const State s0 = s;
      const auto at = [&](double tau) { return detail::advance(c, s0, 0.0, tau); };
      const auto tc = detail::crossing([&](double tau) { return gap(at(tau)); }, tau_max, step, -1);
      if (tc) {
        s = at(*tc);
        mode = impact();
      } else {
        s = at(tau_max);
      }
    }
  }
  o.V_final = s.V;
  o.v_final = s.v;
  return o;
}

}  // namespace splat::exact
