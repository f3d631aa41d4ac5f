#include "solver/contact/contact_solver.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

namespace splat {

namespace {

// C_i dv along direction d (the pair's normal or a tangent).
double row_dot(const ContactProblem& P, std::size_t i, const Vec3& d, const std::vector<Vec3>& dv) {
  double s = 0.0;
  for (int k = 0; k < 5; ++k) {
    const int n = P.node[i][k];
    if (n >= 0) s += P.coef[i][k] * d.dot(dv[n]);
  }
  return s;
}

// dv += M^-1 C_i^T (impulse along d).
void row_apply(const ContactProblem& P, std::size_t i, const Vec3& d, double impulse,
               std::vector<Vec3>& dv) {
  for (int k = 0; k < 5; ++k) {
    const int n = P.node[i][k];
    if (n >= 0) dv[n] += (P.coef[i][k] * impulse) * P.inv_mass[n].cwiseProduct(d);
  }
}

// Diagonal entry of C M^-1 C^T along directions d of pair i.
double row_diag(const ContactProblem& P, std::size_t i, const Vec3& d) {
  double h = 0.0;
  for (int k = 0; k < 5; ++k) {
    const int n = P.node[i][k];
    if (n >= 0) h += P.coef[i][k] * P.coef[i][k] * d.cwiseProduct(d).dot(P.inv_mass[n]);
  }
  return h;
}

double b_scale(const ContactProblem& P) {
  double s = 0.0;
  for (double b : P.b) s = std::max(s, std::abs(b));
  return s;
}

ContactSolution solve_pgs(const ContactProblem& P, const ContactSolverSettings& st) {
  const std::size_t np = P.pairs();
  ContactSolution sol;
  sol.p_n.assign(np, 0.0);
  sol.p_t.assign(np, Vec3::Zero());
  sol.dv.assign(P.inv_mass.size(), Vec3::Zero());
  std::vector<double> hn(np), ht1(np), ht2(np);
  for (std::size_t i = 0; i < np; ++i) {
    hn[i] = row_diag(P, i, P.normal[i]);
    ht1[i] = row_diag(P, i, P.tangent1[i]);
    ht2[i] = row_diag(P, i, P.tangent2[i]);
  }
  if (P.p_start.size() == np) {
    for (std::size_t i = 0; i < np; ++i) {
      const double p0 = std::max(P.lo[i], P.p_start[i]);
      if (p0 == 0.0 || !(hn[i] > 0.0)) continue;
      sol.p_n[i] = p0;
      row_apply(P, i, P.normal[i], p0, sol.dv);
    }
  }
  const double tol = st.tolerance * std::max(b_scale(P), 1e-300);
  // Relative tangential velocity of pair i along d, with the corrections so far.
  auto slip = [&](std::size_t i, const Vec3& d) {
    double s = 0.0;
    for (int k = 0; k < 5; ++k) {
      const int n = P.node[i][k];
      if (n >= 0) s += P.coef[i][k] * d.dot(P.velocity[n] + sol.dv[n]);
    }
    return s;
  };
  for (int it = 1; it <= st.max_iterations; ++it) {
    const double w = it > st.plain_sweeps ? st.over_relaxation : 1.0;
    double change = 0.0;
    for (std::size_t i = 0; i < np; ++i) {
      if (!(hn[i] > 0.0)) continue;  // every node of the pair is prescribed
      const double y = row_dot(P, i, P.normal[i], sol.dv);
      const double p_contact = sol.p_n[i] - w * (y - P.b[i]) / hn[i];
      double p_new = std::max(0.0, p_contact);
      if (P.lo[i] < 0.0 && p_contact <= 0.0) {
        // Bonded: hold the opening if that takes tension, within the cap.
        const double p_hold = sol.p_n[i] - (y - P.b_hold[i]) / hn[i];
        p_new = std::max(P.lo[i], std::min(p_hold, 0.0));
      }
      const double dp = p_new - sol.p_n[i];
      if (dp != 0.0) {
        row_apply(P, i, P.normal[i], dp, sol.dv);
        sol.p_n[i] = p_new;
        change = std::max(change, std::abs(dp) * hn[i]);
      }
      if (P.mu[i] > 0.0) {
        const double limit = P.mu[i] * std::max(sol.p_n[i], 0.0);
        Vec3 pt = sol.p_t[i];
        if (ht1[i] > 0.0) pt.x() -= slip(i, P.tangent1[i]) / ht1[i];
        if (ht2[i] > 0.0) pt.y() -= slip(i, P.tangent2[i]) / ht2[i];
        const double mag = pt.head<2>().norm();
        if (mag > limit) pt *= limit / mag;
        const Vec3 d = pt - sol.p_t[i];
        if (d.x() != 0.0) row_apply(P, i, P.tangent1[i], d.x(), sol.dv);
        if (d.y() != 0.0) row_apply(P, i, P.tangent2[i], d.y(), sol.dv);
        change = std::max(change, std::max(std::abs(d.x()) * ht1[i], std::abs(d.y()) * ht2[i]));
        sol.p_t[i] = pt;
      }
    }
    sol.iterations = it;
    if (change <= tol) break;
    if (it == st.max_iterations) sol.converged = false;
  }
  return sol;
}

// Primal active-set method with sparse LDL^T solves of the enforced rows
// (frictionless): rows are enforced (H p = b) or at their bound (p = lo);
// enforced rows that fall below their bound leave, bound rows that are
// violated enter, until nothing changes.
ContactSolution solve_active_set(const ContactProblem& P, const ContactSolverSettings& st) {
  const std::size_t np = P.pairs();
  ContactSolution sol;
  sol.p_n.assign(np, 0.0);
  sol.p_t.assign(np, Vec3::Zero());
  sol.dv.assign(P.inv_mass.size(), Vec3::Zero());
  if (np == 0) return sol;
  // H = C M^-1 C^T through the pairs sharing each node.
  std::vector<std::vector<std::pair<int, int>>> at_node(P.inv_mass.size());
  for (std::size_t i = 0; i < np; ++i) {
    for (int k = 0; k < 5; ++k) {
      if (P.node[i][k] >= 0) at_node[P.node[i][k]].push_back({static_cast<int>(i), k});
    }
  }
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t n = 0; n < at_node.size(); ++n) {
    for (const auto& [i, ki] : at_node[n]) {
      for (const auto& [j, kj] : at_node[n]) {
        const double h = P.coef[i][ki] * P.coef[j][kj] *
                         P.normal[i].cwiseProduct(P.normal[j]).dot(P.inv_mass[n]);
        trip.emplace_back(i, j, h);
      }
    }
  }
  Eigen::SparseMatrix<double> H(static_cast<Eigen::Index>(np), static_cast<Eigen::Index>(np));
  H.setFromTriplets(trip.begin(), trip.end());
  const double tol = st.tolerance * std::max(b_scale(P), 1e-300);
  std::vector<std::uint8_t> enforced(np);
  for (std::size_t i = 0; i < np; ++i) enforced[i] = P.b[i] > 0.0 || P.lo[i] < 0.0;
  Eigen::VectorXd p = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(np));
  for (int it = 1; it <= st.max_iterations; ++it) {
    sol.iterations = it;
    std::vector<int> idx(np, -1), rows;
    for (std::size_t i = 0; i < np; ++i) {
      if (enforced[i]) {
        idx[i] = static_cast<int>(rows.size());
        rows.push_back(static_cast<int>(i));
      } else {
        p[static_cast<Eigen::Index>(i)] = P.lo[i];
      }
    }
    if (!rows.empty()) {
      const Eigen::Index m = static_cast<Eigen::Index>(rows.size());
      std::vector<Eigen::Triplet<double>> sub;
      Eigen::VectorXd rhs(m);
      for (Eigen::Index r = 0; r < m; ++r) rhs[r] = P.b[rows[r]];
      for (int k = 0; k < H.outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator e(H, k); e; ++e) {
          const int i = static_cast<int>(e.row()), j = static_cast<int>(e.col());
          if (idx[i] < 0) continue;
          if (idx[j] >= 0) {
            sub.emplace_back(idx[i], idx[j], e.value());
          } else {
            rhs[idx[i]] -= e.value() * P.lo[j];
          }
        }
      }
      Eigen::SparseMatrix<double> Hs(m, m);
      Hs.setFromTriplets(sub.begin(), sub.end());
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(Hs);
      if (ldlt.info() != Eigen::Success) {
        sol.converged = false;
        break;
      }
      const Eigen::VectorXd x = ldlt.solve(rhs);
      for (Eigen::Index r = 0; r < m; ++r) p[rows[r]] = x[r];
    }
    const Eigen::VectorXd w = H * p;
    bool changed = false;
    for (std::size_t i = 0; i < np; ++i) {
      const auto ii = static_cast<Eigen::Index>(i);
      if (enforced[i] && p[ii] < P.lo[i]) {
        enforced[i] = 0;
        changed = true;
      } else if (!enforced[i] && w[ii] - P.b[i] < -tol) {
        enforced[i] = 1;
        changed = true;
      }
    }
    if (!changed) break;
    if (it == st.max_iterations) sol.converged = false;
  }
  for (std::size_t i = 0; i < np; ++i) {
    sol.p_n[i] = p[static_cast<Eigen::Index>(i)];
    row_apply(P, i, P.normal[i], sol.p_n[i], sol.dv);
  }
  return sol;
}

}  // namespace

ContactSolution solve_contact(const ContactProblem& problem,
                              const ContactSolverSettings& settings) {
  ContactSolution sol = settings.kind == ContactSolverKind::pgs
                            ? solve_pgs(problem, settings)
                            : solve_active_set(problem, settings);
  sol.residual = contact_violation(problem, sol);
  return sol;
}

double normal_rate(const ContactProblem& P, std::size_t i, const std::vector<Vec3>& dv) {
  return row_dot(P, i, P.normal[i], dv);
}

double normal_inverse_mass(const ContactProblem& P, std::size_t i) {
  return row_diag(P, i, P.normal[i]);
}

std::vector<std::uint8_t> repeated_rows(const ContactProblem& P, std::size_t first,
                                        double max_correlation) {
  return repeated_rows(P, first, std::vector<double>(first, max_correlation));
}

std::vector<std::uint8_t> repeated_rows(const ContactProblem& P, std::size_t first,
                                        const std::vector<double>& max_correlation) {
  const std::size_t np = P.pairs();
  std::vector<std::uint8_t> out(np, 0);
  if (first >= np) return out;
  // The rows < first through each node (CSR).
  std::vector<int> offsets(P.inv_mass.size() + 1, 0), entries;
  for (std::size_t j = 0; j < first; ++j) {
    for (int k = 0; k < 5; ++k) {
      if (P.node[j][k] >= 0) ++offsets[P.node[j][k] + 1];
    }
  }
  for (std::size_t n = 0; n < P.inv_mass.size(); ++n) offsets[n + 1] += offsets[n];
  entries.resize(offsets.back());
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (std::size_t j = 0; j < first; ++j) {
    for (int k = 0; k < 5; ++k) {
      if (P.node[j][k] >= 0) entries[fill[P.node[j][k]]++] = static_cast<int>(j);
    }
  }
  // H_ij over the nodes rows i and j share.
  auto coupling = [&](std::size_t i, std::size_t j) {
    double h = 0.0;
    for (int a = 0; a < 5; ++a) {
      const int n = P.node[i][a];
      if (n < 0) continue;
      for (int b = 0; b < 5; ++b) {
        if (P.node[j][b] != n) continue;
        h += P.coef[i][a] * P.coef[j][b] * P.normal[i].cwiseProduct(P.normal[j]).dot(P.inv_mass[n]);
      }
    }
    return h;
  };
  for (std::size_t i = first; i < np; ++i) {
    const double hi = row_diag(P, i, P.normal[i]);
    if (!(hi > 0.0)) continue;
    for (int a = 0; a < 5 && !out[i]; ++a) {
      const int n = P.node[i][a];
      if (n < 0) continue;
      for (int e = offsets[n]; e < offsets[n + 1]; ++e) {
        const std::size_t j = static_cast<std::size_t>(entries[e]);
        const double hj = row_diag(P, j, P.normal[j]);
        if (hj > 0.0 && coupling(i, j) >= max_correlation[j] * std::sqrt(hi * hj)) {
          out[i] = 1;
          break;
        }
      }
    }
  }
  return out;
}

double contact_violation(const ContactProblem& P, const ContactSolution& s) {
  double worst = 0.0;
  for (std::size_t i = 0; i < P.pairs(); ++i) {
    const double y = row_dot(P, i, P.normal[i], s.dv);
    const double r = y - P.b[i];
    worst = std::max(worst, -r);  // penetration left
    if (s.p_n[i] > 0.0) worst = std::max(worst, std::abs(r));
    if (P.lo[i] < 0.0 && s.p_n[i] < 0.0) {
      const double rh = y - P.b_hold[i];
      if (s.p_n[i] > P.lo[i]) worst = std::max(worst, std::abs(rh));  // hold not met
    }
  }
  return worst;
}

}  // namespace splat
