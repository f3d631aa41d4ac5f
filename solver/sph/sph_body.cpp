#include "solver/sph/sph_body.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "solver/material/damage.hpp"

#ifdef _OPENMP
#include <omp.h>
#define SPLAT_OMP(directive) _Pragma(#directive)
#else
#define SPLAT_OMP(directive)
#endif

// The pair loops are also compiled for AVX2, chosen at run time (never
// -march=native: the build must run on machines without it).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SPLAT_TARGET_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SPLAT_TARGET_CLONES
#endif

namespace splat {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Particles per reduction block: partial sums over fixed blocks combined in
// block order do not depend on the thread count.
constexpr std::size_t block_size = 64;
constexpr long long min_parallel_particles = 256;

struct BlockSums {
  double dt_min = infinity;
  double hourglass_power = 0.0;
  double viscosity_power = 0.0;
  double max_deformation = 0.0;
  int max_iterations = 0;
  bool failed = false;
  long long inverted = 0;
};

std::size_t num_blocks(std::size_t n) {
  return (n + block_size - 1) / block_size;
}

// Runs body(i, sums) for every particle, in fixed blocks, in parallel.
template <class Body>
void for_blocks(std::size_t n, std::vector<BlockSums>& blocks, Body&& body) {
  const long long nb = static_cast<long long>(num_blocks(n));
  blocks.assign(static_cast<std::size_t>(nb), BlockSums{});
  SPLAT_OMP(omp parallel for schedule(static) if (static_cast<long long>(n) >= min_parallel_particles))
  for (long long bk = 0; bk < nb; ++bk) {
    const std::size_t k = static_cast<std::size_t>(bk);
    const std::size_t end = std::min(n, (k + 1) * block_size);
    for (std::size_t i = k * block_size; i < end; ++i) body(i, blocks[k]);
  }
}

void check_settings(const SphSettings& s) {
  const auto bad = [](const char* what) {
    throw std::invalid_argument(std::string("SPH settings: ") + what);
  };
  if (!(s.h_over_spacing > 0.0)) bad("h_over_spacing must be > 0");
  if (s.visc_linear < 0.0 || s.visc_quadratic < 0.0) bad("viscosity coefficients must be >= 0");
  if (s.hourglass_coefficient < 0.0) bad("hourglass_coefficient must be >= 0");
  if (s.update_threshold < 0.0) bad("update_threshold must be >= 0");
  if (s.min_correction_eigenvalue < 0.0 || s.min_correction_eigenvalue >= 1.0) {
    bad("min_correction_eigenvalue must be in [0, 1)");
  }
  if (!(s.max_h_growth >= 1.0)) bad("max_h_growth must be >= 1");
}

// F and Fdot of particle i from the current positions and velocities:
// F_i = N_i + A_i B_i^T, Fdot_i = Adot_i B_i^T with
// A_i = sum_j (op(x_j) - x_i) (x) V_j g_ij, Adot_i = sum_j (S v_j - v_i) (x) V_j g_ij
// (V_j gc_ij = B_i V_j g_ij, so the correction leaves the pair loop).
inline void deformation(const SphBody& b, const NodeSet& nodes, bool mirrors, std::size_t i,
                        Mat3& F, Mat3& Fdot) {
  const std::size_t base = b.node_begin;
  const Vec3 xi = nodes.x[base + i];
  const Vec3 vi = nodes.v[base + i];
  const Vec3 Xi = b.X[i];
  Mat3 A = Mat3::Zero(), Adot = Mat3::Zero();
  const int end = b.pairs.offsets[i + 1];
  for (int k = b.pairs.offsets[i]; k < end; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    const std::size_t j = static_cast<std::size_t>(b.pairs.j[kk]);
    const std::uint8_t op = mirrors ? b.pairs.op[kk] : 0;
    Vec3 xj = nodes.x[base + j], vj = nodes.v[base + j], Xj = b.X[j];
    if (op != 0) {
      xj = mirror_point(b.planes, op, xj);
      vj = mirror_vector(b.planes, op, vj);
      Xj = mirror_point(b.planes, op, Xj);
    }
    const Vec3 g = b.pair_t[kk] * (Xj - Xi);  // V_j g_ij
    A.noalias() += (xj - xi) * g.transpose();
    Adot.noalias() += (vj - vi) * g.transpose();
  }
  F = b.null_projector[i];
  F.noalias() += A * b.B[i].transpose();
  Fdot.noalias() = Adot * b.B[i].transpose();
}

// The reflections of the symmetry-plane sets op = 0 .. 7 as op(p) = sign p +
// shift (componentwise; the same arithmetic as mirror_point).
struct Mirrors {
  double sign[8][3];
  double shift[8][3];
  explicit Mirrors(const SymmetryPlanes& planes) {
    for (int op = 0; op < 8; ++op) {
      for (int a = 0; a < 3; ++a) sign[op][a] = 1.0, shift[op][a] = 0.0;
      for (std::size_t k = 0; k < planes.size(); ++k) {
        if (op & (1 << k)) {
          sign[op][planes[k].axis] = -1.0;
          shift[op][planes[k].axis] = 2.0 * planes[k].position;
        }
      }
    }
  }
};

struct PairConstants {
  double alpha_c;  // Monaghan alpha times the wave speed, m/s
  double beta;     // Monaghan beta, -
  double c_hg;     // hourglass coefficient, -
};

struct PairSums {
  Vec3 f_stress, f_visc, f_hg;  // N
  double r_min;                 // current distance to the nearest active neighbour, m
  double max_mu;                // largest approach mu_ij, m/s
};

// y = M x for a column-major 3x3 matrix M.
inline void mat_vec(const double* __restrict M, const double x[3], double y[3]) {
  for (int r = 0; r < 3; ++r) y[r] = M[r] * x[0] + M[3 + r] * x[1] + M[6 + r] * x[2];
}

// Stress, viscosity and hourglass forces on particle i (the formulas of the
// header), in plain scalar arithmetic without branches in the pair loop:
// inactive neighbours and coincident pairs are masked (inv_r = 0), the
// viscosity of receding pairs by mu = 0.
template <bool with_mirrors>
SPLAT_TARGET_CLONES PairSums pair_forces(const SphBody& b, const NodeSet& nodes, const Mirrors& m,
                                         const PairConstants& pc, std::size_t i) {
  const std::size_t base = b.node_begin;
  const double* __restrict X = b.X.data()->data();
  const double* __restrict x = nodes.x[base].data();
  const double* __restrict v = nodes.v[base].data();
  const double* __restrict mass = nodes.mass.data() + base;
  const double* __restrict PB = b.PB.data()->data();
  const double* __restrict Fm = b.F.data()->data();
  const double* __restrict h = b.h.data();
  const double* __restrict rho = b.rho.data();
  const double* __restrict E_hg = b.E_hg.data();
  const std::uint8_t* __restrict active = b.active.data();
  const int* __restrict pj = b.pairs.j.data();
  const std::uint8_t* __restrict pop = b.pairs.op.data();
  const double* __restrict pt = b.pair_t.data();
  const float* __restrict pw = b.pair_w.data();
  const float* __restrict pdw = b.pair_dw.data();
  const double* Fi = Fm + 9 * i;
  double xi[3], vi[3], Xi[3];
  for (int a = 0; a < 3; ++a) {
    xi[a] = x[3 * i + a], vi[a] = v[3 * i + a], Xi[a] = X[3 * i + a];
  }
  const double mi = mass[i], Vi = b.volume_ref[i], rho_i = rho[i], E_i = E_hg[i], h_i = h[i];
  // a = sum_j V_j g_ij, fp = sum_j S P_j B_j S V_j g_ij, then
  // f_stress = V_i (P_i B_i a + fp).
  double a0 = 0, a1 = 0, a2 = 0, fp0 = 0, fp1 = 0, fp2 = 0;
  double fv0 = 0, fv1 = 0, fv2 = 0, fh0 = 0, fh1 = 0, fh2 = 0;
  double r_sq_min = infinity, max_mu = 0.0;
  const int begin = b.pairs.offsets[i], end = b.pairs.offsets[i + 1];
  for (int k = begin; k < end; ++k) {
    const std::size_t j = static_cast<std::size_t>(pj[k]);
    const int op = with_mirrors ? pop[k] : 0;
    const double* sg = m.sign[op];
    const double* sh = m.shift[op];
    double dX[3], g[3], Sg[3], Sd[3], xij[3], vij[3];
    for (int a = 0; a < 3; ++a) {
      // op(X_j) - X_i, recomputed (storing it cost 24 B per pair).
      dX[a] = (with_mirrors ? sg[a] * X[3 * j + a] + sh[a] : X[3 * j + a]) - Xi[a];
      g[a] = pt[k] * dX[a];  // V_j g_ij
      Sg[a] = with_mirrors ? sg[a] * g[a] : g[a];
      Sd[a] = with_mirrors ? sg[a] * dX[a] : dX[a];
      xij[a] = (with_mirrors ? sg[a] * x[3 * j + a] + sh[a] : x[3 * j + a]) - xi[a];
      vij[a] = (with_mirrors ? sg[a] * v[3 * j + a] : v[3 * j + a]) - vi[a];
    }
    double pg[3], Fd[3], Fid[3];
    mat_vec(PB + 9 * j, Sg, pg);
    mat_vec(Fm + 9 * j, Sd, Fd);  // S F_j S dX = S (F_j (S dX))
    mat_vec(Fi, dX, Fid);
    a0 += g[0], a1 += g[1], a2 += g[2];
    if constexpr (with_mirrors) {
      fp0 += sg[0] * pg[0], fp1 += sg[1] * pg[1], fp2 += sg[2] * pg[2];
    } else {
      fp0 += pg[0], fp1 += pg[1], fp2 += pg[2];
    }

    const double r_sq = xij[0] * xij[0] + xij[1] * xij[1] + xij[2] * xij[2];
    const bool valid = (active[j] != 0) & (r_sq > 0.0);
    const double inv_r_any = 1.0 / std::sqrt(r_sq);  // computed always: no branch
    const double inv_r = valid ? inv_r_any : 0.0;
    r_sq_min = std::min(r_sq_min, valid ? r_sq : infinity);

    // Monaghan viscosity between approaching particles (vx < 0), with one
    // division: q = 1 / (d1 d2), mu = h vx / d1, Pi = (...) / d2.
    const double vx = std::min(vij[0] * xij[0] + vij[1] * xij[1] + vij[2] * xij[2], 0.0);
    const double hij = 0.5 * (h_i + h[j]);
    const double d1 = r_sq + 0.01 * hij * hij;
    const double d2 = 0.5 * (rho_i + rho[j]);
    const double q = 1.0 / (d1 * d2);
    const double mu = hij * vx * d2 * q;
    const double Pi = (-pc.alpha_c * mu + pc.beta * mu * mu) * d1 * q;
    max_mu = std::max(max_mu, valid ? -mu : 0.0);
    const double central = mi * mass[j] * Pi * static_cast<double>(pdw[k]) * inv_r;

    // Ganzenmueller hourglass control: eps = (F_i dX + S F_j S dX) / 2 - x_ij.
    double delta = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double Fj_dX = with_mirrors ? sg[a] * Fd[a] : Fd[a];
      delta += (0.5 * (Fid[a] + Fj_dX) - xij[a]) * xij[a];
    }
    delta *= inv_r;
    const double E_ij = 0.5 * (E_i + E_hg[j]);
    const double dX_sq = dX[0] * dX[0] + dX[1] * dX[1] + dX[2] * dX[2];
    const double hg = pc.c_hg * E_ij * Vi * static_cast<double>(pw[k]) * delta / dX_sq * inv_r;
    fv0 += central * xij[0], fv1 += central * xij[1], fv2 += central * xij[2];
    fh0 -= hg * xij[0], fh1 -= hg * xij[1], fh2 -= hg * xij[2];
  }
  PairSums out;
  out.f_stress = Vi * (b.PB[i] * Vec3(a0, a1, a2) + Vec3(fp0, fp1, fp2));
  out.f_visc = Vec3(fv0, fv1, fv2);
  out.f_hg = Vec3(fh0, fh1, fh2);
  out.r_min = std::sqrt(r_sq_min);
  out.max_mu = max_mu;
  return out;
}
}  // namespace

void sph_build_reference(SphBody& b) {
  const std::size_t n = b.size();
  b.pairs = find_neighbours(b.X, b.h, b.planes, b.active);
  const std::size_t np = b.pairs.num_pairs();
  b.pair_t.assign(np, 0.0);
  b.pair_w.assign(np, 0.0f);
  b.pair_dw.assign(np, 0.0f);
  b.null_projector.assign(n, Mat3::Zero());
  b.B.assign(n, Mat3::Zero());

  const long long count = static_cast<long long>(n);
  SPLAT_OMP(omp parallel for schedule(static) if (count >= min_parallel_particles))
  for (long long ii = 0; ii < count; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    const int begin = b.pairs.offsets[i], end = b.pairs.offsets[i + 1];
    Mat3 C = Mat3::Zero();
    for (int k = begin; k < end; ++k) {
      const std::size_t kk = static_cast<std::size_t>(k);
      const std::size_t j = static_cast<std::size_t>(b.pairs.j[kk]);
      const std::uint8_t op = b.pairs.op[kk];
      const Vec3 dX = mirror_point(b.planes, op, b.X[j]) - b.X[i];
      const double r0 = dX.norm();
      const KernelValue kv = kernel(b.settings.kernel, r0, 0.5 * (b.h[i] + b.h[j]));
      b.pair_w[kk] = static_cast<float>(b.volume_ref[j] * kv.w);
      b.pair_dw[kk] = static_cast<float>(kv.dw_dr);
      const double s = -kv.dw_dr / r0;  // g_ij = s dX (uncorrected)
      b.pair_t[kk] = b.volume_ref[j] * s;
      C.noalias() += b.volume_ref[j] * dX * (s * dX).transpose();
    }
    // C is symmetric positive semi-definite and close to I for a full
    // neighbourhood (about 1/2 across a flat free surface, less at edges and
    // corners). Along an eigenvector u with eigenvalue lambda >= lambda_min, B
    // inverts C; a weaker direction (a particle that kept few neighbours, or
    // neighbours only in a plane or a line) is inverted with lambda_min and
    // blended towards a rigid map through null_projector with weight
    // 1 - lambda / lambda_min, so the corrected gradients stay bounded by
    // |g| / lambda_min there (exactness is kept wherever lambda >= lambda_min).
    const double lambda_min = b.settings.min_correction_eigenvalue;
    Eigen::SelfAdjointEigenSolver<Mat3> eig;
    eig.compute(C);
    Mat3 B = Mat3::Zero();
    if (eig.eigenvalues().minCoeff() >= lambda_min && eig.eigenvalues().minCoeff() > 0.0) {
      B = C.inverse();  // the usual case; the inverse is exact to round-off
    } else {
      Mat3 null = Mat3::Zero();
      for (int a = 0; a < 3; ++a) {
        const double lambda = std::max(eig.eigenvalues()[a], 0.0);
        const Vec3 u = eig.eigenvectors().col(a);
        if (lambda >= lambda_min && lambda > 0.0) {
          B += (1.0 / lambda) * u * u.transpose();
        } else {
          if (lambda_min > 0.0) B += (1.0 / lambda_min) * u * u.transpose();
          null += (lambda_min > 0.0 ? 1.0 - lambda / lambda_min : 1.0) * u * u.transpose();
        }
      }
      b.null_projector[i] = null;
    }
    b.B[i] = B;
  }
  b.F.assign(n, Mat3::Identity());
  b.Fdot.assign(n, Mat3::Zero());
}

SphBody make_sph_body(const std::string& name, const ParticleCloud& cloud, const Material& material,
                      const ModelSwitches& switches, const SphSettings& settings,
                      const SymmetryPlanes& planes, const Vec3& velocity, double temperature,
                      unsigned long long seed, NodeSet& nodes) {
  check_settings(settings);
  SphBody b;
  b.name = name;
  b.material = material;
  b.constants = derive_constants(material);
  b.switches = switches;
  b.settings = settings;
  b.planes = planes;
  b.spacing = cloud.spacing;
  b.node_begin = nodes.size();
  b.node_end = b.node_begin + cloud.size();
  const std::size_t n = cloud.size();
  const std::size_t total = b.node_end;
  nodes.x0.resize(total, Vec3::Zero());
  nodes.x.resize(total, Vec3::Zero());
  nodes.v.resize(total, Vec3::Zero());
  nodes.f.resize(total, Vec3::Zero());
  nodes.mass.resize(total, 0.0);
  nodes.boundary.resize(total, boundary_none);
  const double h0 = settings.h_over_spacing * cloud.spacing;
  b.volume0 = cloud.volume;
  b.outward_normal = cloud.outward_normal;
  b.X = cloud.x;
  b.volume_ref = cloud.volume;
  b.J_ref.assign(n, 1.0);
  b.F_ref.assign(n, Mat3::Identity());
  b.h.assign(n, h0);
  b.state.resize(n);
  b.PB.assign(n, Mat3::Zero());
  b.dt_bound.assign(n, infinity);
  b.active.assign(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t g = b.node_begin + i;
    nodes.x0[g] = nodes.x[g] = cloud.x[i];
    nodes.v[g] = velocity;
    nodes.mass[g] = material.density * cloud.volume[i];
    nodes.boundary[g] = cloud.boundary[i];
    const double D0 = switches.damage && material.damage.initial_random_max > 0.0
                          ? initial_random_damage(seed, i, material.damage.initial_random_max)
                          : 0.0;
    b.state[i] = initial_point_state(material, switches, temperature, D0);
  }
  sph_build_reference(b);
  return b;
}

void sph_update_reference(SphBody& b, const NodeSet& nodes) {
  const std::size_t n = b.size();
  const double h0 = b.settings.h_over_spacing * b.spacing;
  for (std::size_t i = 0; i < n; ++i) {
    b.X[i] = nodes.x[b.node_begin + i];
    const double J = b.F[i].determinant();
    if (b.active[i] && J > 0.0) {
      b.volume_ref[i] *= J;
      b.J_ref[i] *= J;
      b.F_ref[i] = b.F[i] * b.F_ref[i];
    }
    // h follows the largest stretch (the widest current spacing), capped.
    Eigen::SelfAdjointEigenSolver<Mat3> eig(b.F_ref[i].transpose() * b.F_ref[i],
                                            Eigen::EigenvaluesOnly);
    const double stretch = std::sqrt(std::max(eig.eigenvalues().maxCoeff(), 0.0));
    b.h[i] = h0 * std::clamp(stretch, std::cbrt(b.J_ref[i]), b.settings.max_h_growth);
  }
  sph_build_reference(b);
  ++b.reference_updates;
  b.update_pending = false;
}

SphStepResult sph_internal_forces(SphBody& b, NodeSet& nodes, double dt) {
  SphStepResult result;
  const std::size_t n = b.size();
  std::vector<BlockSums> blocks;

  // Deformation from the reference; update the reference if due.
  const bool mirrors = !b.planes.empty();
  const auto compute_F = [&]() {
    for_blocks(n, blocks, [&](std::size_t i, BlockSums& s) {
      if (!b.active[i]) return;
      deformation(b, nodes, mirrors, i, b.F[i], b.Fdot[i]);
      s.max_deformation = std::max(s.max_deformation, (b.F[i] - Mat3::Identity()).norm());
    });
    double m = 0.0;
    for (const BlockSums& s : blocks) m = std::max(m, s.max_deformation);
    return m;
  };
  result.max_deformation = compute_F();
  const double threshold = b.settings.update_threshold;
  // A non-finite deformation (a blown-up state) is left to the caller's stop
  // checks: re-referencing it would only spread the NaNs.
  const bool finite = std::isfinite(result.max_deformation);
  if (finite && (b.update_pending || (threshold > 0.0 && result.max_deformation > threshold))) {
    sph_update_reference(b, nodes);
    result.reference_updated = true;
    result.max_deformation = compute_F();
  }

  // Material update and first Piola-Kirchhoff stress.
  const Material& mat = b.material;
  const DamageParams& dm = mat.damage;
  const bool can_fail =
      b.settings.deactivate_failed && b.switches.damage && dm.initiation != DamageInitiation::none;
  std::vector<std::uint8_t> failed(n, 0);
  for_blocks(n, blocks, [&](std::size_t i, BlockSums& s) {
    if (!b.active[i]) {
      b.PB[i].setZero();
      return;
    }
    const Mat3& F = b.F[i];
    const double detF = F.determinant();
    if (!(detF > 0.0)) {
      ++s.inverted;
      b.PB[i].setZero();
      return;
    }
    PointState& st = b.state[i];
    if (dt > 0.0) {
      const Mat3 F_mid = F - 0.5 * dt * b.Fdot[i];
      const Mat3 L = b.Fdot[i] * F_mid.inverse();
      const Mat3 D = 0.5 * (L + L.transpose());
      const Mat3 W = 0.5 * (L - L.transpose());
      st.s = rotate_symmetric(hughes_winget_rotation(W, dt), st.s);
      const double J = b.J_ref[i] * detF;
      const double length = b.spacing * std::cbrt(J);
      const PointUpdateResult r =
          update_point(mat, b.constants, b.switches, st, dt * D, J, dt, length);
      s.max_iterations = std::max(s.max_iterations, r.iterations);
      s.failed = s.failed || !r.converged;
      if (can_fail && st.D >= dm.D_max - 1e-12) failed[i] = 1;
    }
    b.PB[i].noalias() = (detF * st.cauchy()) * (F.inverse().transpose() * b.B[i]);
  });
  for (const BlockSums& s : blocks) {
    result.max_return_iterations = std::max(result.max_return_iterations, s.max_iterations);
    result.return_failed = result.return_failed || s.failed;
    result.inverted += s.inverted;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (failed[i]) {
      b.active[i] = 0;
      b.PB[i].setZero();
      result.deactivated.push_back(static_cast<int>(i));
      result.deactivated_energy += b.volume0[i] * b.state[i].e;
      b.update_pending = true;
    }
  }

  // Pair forces, gathered per particle.
  const double c = b.constants.wave_speed;
  const double alpha = b.settings.visc_linear, beta = b.settings.visc_quadratic;
  const double c_hg = b.settings.hourglass_coefficient;
  const double E = mat.elastic.E;
  // Per-particle quantities the pairs read: current density and the
  // hourglass modulus ((1 - D) E, or the flow stress once plastic).
  b.rho.resize(n);
  b.E_hg.resize(n);
  b.f_visc.assign(n, Vec3::Zero());
  b.f_hg.assign(n, Vec3::Zero());
  for_blocks(n, blocks, [&](std::size_t i, BlockSums&) {
    const PointState& st = b.state[i];
    b.rho[i] = mat.density / (b.J_ref[i] * std::max(b.F[i].determinant(), 1e-12));
    b.E_hg[i] = st.eps_p > 1e-3 ? st.sigma_y : (1.0 - st.D) * E;
  });
  const PairConstants pc{alpha * c, beta, c_hg};
  const Mirrors mirror_table(b.planes);
  for_blocks(n, blocks, [&](std::size_t i, BlockSums& s) {
    if (!b.active[i]) {
      b.dt_bound[i] = infinity;
      return;
    }
    const std::size_t gi = b.node_begin + i;
    const PairSums p = mirrors ? pair_forces<true>(b, nodes, mirror_table, pc, i)
                               : pair_forces<false>(b, nodes, mirror_table, pc, i);
    nodes.f[gi] += p.f_stress + p.f_visc + p.f_hg;
    b.f_visc[i] = p.f_visc;
    b.f_hg[i] = p.f_hg;
    const Vec3 vi = nodes.v[gi];
    s.viscosity_power -= p.f_visc.dot(vi);
    s.hourglass_power -= p.f_hg.dot(vi);
    // A particle without active neighbours keeps the bound of its spacing.
    const double L_i = p.r_min < infinity ? p.r_min : b.h[i] / b.settings.h_over_spacing;
    const double v_sig = c + 1.2 * (alpha * c + beta * p.max_mu);
    b.dt_bound[i] = L_i / v_sig;
    s.dt_min = std::min(s.dt_min, b.dt_bound[i]);
  });
  result.dt_stable = infinity;
  for (const BlockSums& s : blocks) {
    result.dt_stable = std::min(result.dt_stable, s.dt_min);
    result.hourglass_power += s.hourglass_power;
    result.viscosity_power += s.viscosity_power;
  }
  return result;
}

Vec3 sph_pair_gradient(const SphBody& b, std::size_t k) {
  const auto next =
      std::upper_bound(b.pairs.offsets.begin(), b.pairs.offsets.end(), static_cast<int>(k));
  const std::size_t i = static_cast<std::size_t>(next - b.pairs.offsets.begin()) - 1;
  const std::size_t j = static_cast<std::size_t>(b.pairs.j[k]);
  const Vec3 dX = mirror_point(b.planes, b.pairs.op[k], b.X[j]) - b.X[i];
  return b.B[i] * (b.pair_t[k] * dX);
}

double sph_internal_energy(const SphBody& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.active[i]) sum += b.volume0[i] * b.state[i].e;
  }
  return sum;
}

}  // namespace splat
