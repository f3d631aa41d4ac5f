// Bracketed scalar root finding (Illinois variant of regula falsi with
// bracket expansion), for the few nested scalar solves outside the material
// kernels, such as the zero-lateral-stress condition of the material-point
// driver.
#pragma once

#include <cmath>
#include <stdexcept>

namespace splat {

struct RootResult {
  double x = 0.0;
  int evaluations = 0;
  bool converged = false;
};

// Finds x with |f(x)| <= f_tol for an increasing f, starting from two guesses
// x0 != x1; expands the bracket by doubling until f changes sign.
template <class F>
RootResult find_root_increasing(F&& f, double x0, double x1, double f_tol,
                                int max_evaluations = 200) {
  RootResult r;
  double a = std::min(x0, x1), b = std::max(x0, x1);
  double fa = f(a), fb = f(b);
  r.evaluations = 2;
  while (fa > 0.0 && r.evaluations < max_evaluations) {  // root is left of a
    const double w = b - a;
    b = a, fb = fa;
    a -= 2.0 * w;
    fa = f(a);
    ++r.evaluations;
  }
  while (fb < 0.0 && r.evaluations < max_evaluations) {  // root is right of b
    const double w = b - a;
    a = b, fa = fb;
    b += 2.0 * w;
    fb = f(b);
    ++r.evaluations;
  }
  if (std::abs(fa) <= f_tol) return {a, r.evaluations, true};
  if (std::abs(fb) <= f_tol) return {b, r.evaluations, true};
  if (fa > 0.0 || fb < 0.0) return r;  // no sign change found
  int side = 0;
  while (r.evaluations < max_evaluations) {
    const double x = (a * fb - b * fa) / (fb - fa);
    const double fx = f(x);
    ++r.evaluations;
    if (std::abs(fx) <= f_tol || b - a <= 1e-15 * (std::abs(a) + std::abs(b))) {
      return {x, r.evaluations, true};
    }
    if (fx < 0.0) {
      a = x, fa = fx;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = x, fb = fx;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  return r;
}

}  // namespace splat
