#include "solver/sph/sph_body.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "solver/common/parallel.hpp"
#include "solver/common/simd_lanes.hpp"
#include "solver/material/damage.hpp"

#ifdef _OPENMP
#include <omp.h>
#define SPLAT_OMP(directive) _Pragma(#directive)
#else
#define SPLAT_OMP(directive)
#endif

// The pair loops are also compiled for AVX2 and AVX-512, chosen at run time (never
// -march=native: the build must run on machines without it). The AVX-512 clone
// is x86-64-v4 (AVX-512 F, VL, BW, DQ, CD), not bare avx512f: the loops work on
// 256-bit vectors, which only VL lets use all 32 vector registers (with
// avx512f alone they had 16 and spilled; 6 % of the impact step).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SPLAT_TARGET_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define SPLAT_TARGET_CLONES
#endif

namespace splat {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Particles per reduction block: partial sums over fixed blocks combined in
// block order do not depend on the thread count. Blocks are handed out by a
// guided schedule (which thread computes a block changes no bit): each thread
// starts on a long run of neighbouring blocks, so most of the neighbours it
// gathers stay in its own cache, and the shrinking runs at the end balance
// particles with few pairs (surfaces) or a thread the OS pauses. (Blocks
// handed out one at a time, as before, interleave the threads over the whole
// body: the pair loops ran 1.6x faster on 2 threads than on 1, against 1.95x
// now; bench_sph_impact.)
constexpr std::size_t block_size = 64;
// Particles per block of the energy and power sums (a few flops per particle).
constexpr std::size_t sum_block_size = 1024;
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

// Runs body(first, last, sums) for every block [first, last), in parallel.
template <class Body>
void for_block_ranges(std::size_t n, std::vector<BlockSums>& blocks, Body&& body) {
  const long long nb = static_cast<long long>(num_blocks(n));
  blocks.assign(static_cast<std::size_t>(nb), BlockSums{});
  SPLAT_OMP(omp parallel for schedule(guided) if (static_cast<long long>(n) >= min_parallel_particles))
  for (long long bk = 0; bk < nb; ++bk) {
    const std::size_t k = static_cast<std::size_t>(bk);
    body(k * block_size, std::min(n, (k + 1) * block_size), blocks[k]);
  }
}

// Runs body(i, sums) for every particle, in fixed blocks, in parallel.
template <class Body>
void for_blocks(std::size_t n, std::vector<BlockSums>& blocks, Body&& body) {
  for_block_ranges(n, blocks, [&body](std::size_t first, std::size_t last, BlockSums& s) {
    for (std::size_t i = first; i < last; ++i) body(i, s);
  });
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

// The pair loops take four pairs of one particle per step in GCC vector
// extensions (one AVX2 register of doubles; the AVX-512 clone uses its wider
// register file, the default clone two SSE2 halves). The arithmetic is
// element-wise IEEE without FMA contraction, so every clone gives the same
// bits; the lane sums are combined in lane order at the end, so a particle's
// result does not depend on the thread that computes it. Lanes past the end
// of a particle's list hold the particle itself with zero pair weights: all
// their contributions are exact zeros.
// GCC 12 reports vectors assigned before any use as (maybe-)uninitialized
// in the non-AVX clone (split into SSE2 halves); the warnings are off for the
// vector code only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
constexpr int lanes = 4;
using vd = double __attribute__((vector_size(lanes * sizeof(double))));
using vmask = long __attribute__((vector_size(lanes * sizeof(double))));
static_assert(sizeof(long) == sizeof(double));

// The helpers return through references: a vector returned by value would
// change the ABI of the non-AVX clone (-Wpsabi).
inline void broadcast(vd& out, double s) {
  out = vd{s, s, s, s};
}

// out[l] = p[stride j[l] + offset].
inline void gather(vd& out, const double* __restrict p, const std::size_t* j, std::size_t stride,
                   std::size_t offset) {
  static_assert(lanes == 4);
  out = vd{p[stride * j[0] + offset], p[stride * j[1] + offset], p[stride * j[2] + offset],
           p[stride * j[3] + offset]};
}

// out0[l] = p[stride j[l] + offset] and out1[l] = p[stride j[l] + offset + 1]:
// two neighbouring fields of each lane's record in one 16-byte load per lane
// and two in-lane shuffles (a 4x2 transpose), against four scalar loads and
// three shuffles for each field through gather(). The values are the same.
inline void gather2(vd& out0, vd& out1, const double* __restrict p, const std::size_t* j,
                    std::size_t stride, std::size_t offset) {
  using v2d = double __attribute__((vector_size(2 * sizeof(double))));
  static_assert(lanes == 4);
  v2d a0, a1, a2, a3;
  std::memcpy(&a0, p + stride * j[0] + offset, sizeof(v2d));
  std::memcpy(&a1, p + stride * j[1] + offset, sizeof(v2d));
  std::memcpy(&a2, p + stride * j[2] + offset, sizeof(v2d));
  std::memcpy(&a3, p + stride * j[3] + offset, sizeof(v2d));
  // Written out element by element (not as arrays and loops), which GCC 12
  // compiles to two inserts and two unpacks instead of a trip through memory.
  const vd t0 = __builtin_shufflevector(a0, a2, 0, 1, 2, 3);  // lanes 0 and 2
  const vd t1 = __builtin_shufflevector(a1, a3, 0, 1, 2, 3);  // lanes 1 and 3
  out0 = __builtin_shufflevector(t0, t1, 0, 4, 2, 6);
  out1 = __builtin_shufflevector(t0, t1, 1, 5, 3, 7);
}

// out[a][l] = p[3 j[l] + a]: the lanes of an array of 3-vectors.
inline void gather_vec3(vd out[3], const double* __restrict p, const std::size_t* j) {
  gather2(out[0], out[1], p, j, 3, 0);
  gather(out[2], p, j, 3, 2);
}

// The vector of the lanes of an array (an initialiser: assigning through a
// reference draws false -Wmaybe-uninitialized warnings from GCC 12).
#define SPLAT_LANES(a)             \
  vd {                             \
    (a)[0], (a)[1], (a)[2], (a)[3] \
  }
static_assert(lanes == 4);

// out = sqrt(x) per lane, correctly rounded (IEEE) in every clone. SSE2 is
// part of x86-64, so its packed root serves all clones, without the errno
// branch std::sqrt carries.
inline void sqrt_lanes(vd& out, const vd& x) {
#if defined(__GNUC__) && defined(__SSE2__)
  using v2d = double __attribute__((vector_size(2 * sizeof(double))));
  const v2d lo = __builtin_ia32_sqrtpd(v2d{x[0], x[1]});
  const v2d hi = __builtin_ia32_sqrtpd(v2d{x[2], x[3]});
  out = vd{lo[0], lo[1], hi[0], hi[1]};
#else
  double r[lanes];
  for (int l = 0; l < lanes; ++l) r[l] = std::sqrt(x[l]);
  out = SPLAT_LANES(r);
#endif
}

// out = {sum a, sum b, sum c, sum d}, each lane sum as (l0 + l1) + (l2 + l3).
inline void lane_sums4(vd& out, const vd& a, const vd& b, const vd& c, const vd& d) {
  using vindex = long __attribute__((vector_size(lanes * sizeof(long))));
  const vindex even = {0, 4, 2, 6}, odd = {1, 5, 3, 7}, low = {0, 1, 4, 5}, high = {2, 3, 6, 7};
  // ab = {a0 + a1, b0 + b1, a2 + a3, b2 + b3}, cd likewise.
  const vd ab = __builtin_shuffle(a, b, even) + __builtin_shuffle(a, b, odd);
  const vd cd = __builtin_shuffle(c, d, even) + __builtin_shuffle(c, d, odd);
  out = __builtin_shuffle(ab, cd, low) + __builtin_shuffle(ab, cd, high);
}

// The pairs k0 .. k0 + lanes - 1 of particle i (list end `end`): neighbour
// indices, mirror ops and the per-pair constants, padded past the end.
struct PairLanes {
  std::size_t j[lanes];
  int op[lanes];
  double t[lanes];   // t_ij = V_j s_ij, 1/m^2 (0 when padded)
  double w[lanes];   // V_j W_ij / r0^2, 1/m^2 (0 when padded)
  double dw[lanes];  // m_j W'(r0), kg/m^4 (0 when padded)
};

template <bool with_mirrors, bool with_stabilisers>
inline void load_lanes(const SphBody& b, std::size_t i, int k0, int end, PairLanes& p) {
  if (k0 + lanes <= end) {  // a full chunk (all but the last of a list): no padding
    const std::size_t k = static_cast<std::size_t>(k0);
    for (int l = 0; l < lanes; ++l) {
      const std::size_t kl = k + static_cast<std::size_t>(l);
      p.j[l] = static_cast<std::size_t>(b.pairs.j[kl]);
      p.op[l] = with_mirrors ? b.pairs.op[kl] : 0;
      p.t[l] = b.pair_t[kl];
      p.w[l] = with_stabilisers ? static_cast<double>(b.pair_hg[kl]) : 0.0;
      p.dw[l] = with_stabilisers ? static_cast<double>(b.pair_visc[kl]) : 0.0;
    }
    return;
  }
  for (int l = 0; l < lanes; ++l) {
    const int k = k0 + l;
    const bool live = k < end;
    const std::size_t kk = static_cast<std::size_t>(live ? k : 0);
    p.j[l] = live ? static_cast<std::size_t>(b.pairs.j[kk]) : i;
    p.op[l] = with_mirrors && live ? b.pairs.op[kk] : 0;
    p.t[l] = live ? b.pair_t[kk] : 0.0;
    p.w[l] = with_stabilisers && live ? static_cast<double>(b.pair_hg[kk]) : 0.0;
    p.dw[l] = with_stabilisers && live ? static_cast<double>(b.pair_visc[kk]) : 0.0;
  }
}

// F and Fdot of particle i from the current positions and velocities:
// F_i = N_i + A_i B_i^T, Fdot_i = Adot_i B_i^T with
// A_i = sum_j (op(x_j) - x_i) (x) V_j g_ij, Adot_i = sum_j (S v_j - v_i) (x) V_j g_ij
// (V_j gc_ij = B_i V_j g_ij, so the correction leaves the pair loop).
template <bool with_mirrors>
SPLAT_TARGET_CLONES void deformation(const SphBody& b, const NodeSet& nodes, const Mirrors& m,
                                     std::size_t i, Mat3& F, Mat3& Fdot) {
  const std::size_t base = b.node_begin;
  const double* __restrict X = b.X.data()->data();
  const double* __restrict x = nodes.x[base].data();
  const double* __restrict v = nodes.v[base].data();
  vd Xi[3], xi[3], vi[3];
  for (int a = 0; a < 3; ++a) {
    broadcast(Xi[a], X[3 * i + a]);
    broadcast(xi[a], x[3 * i + a]);
    broadcast(vi[a], v[3 * i + a]);
  }
  // The first chunk (padding only if the list is empty) sets the sums: no
  // zeroed accumulators in memory.
  vd A[3][3], Adot[3][3];
  const int begin = b.pairs.offsets[i], end = b.pairs.offsets[i + 1];
  for (int k0 = begin; k0 == begin || k0 < end; k0 += lanes) {
    PairLanes p;
    load_lanes<with_mirrors, false>(b, i, k0, end, p);
    const vd t = SPLAT_LANES(p.t);
    vd g[3], dx[3], dv[3];
    vd Xg[3], xg[3], vg[3];
    gather_vec3(Xg, X, p.j);
    gather_vec3(xg, x, p.j);
    gather_vec3(vg, v, p.j);
    for (int a = 0; a < 3; ++a) {
      vd Xj = Xg[a], xj = xg[a], vj = vg[a];
      if constexpr (with_mirrors) {
        double sg_l[lanes], sh_l[lanes];
        for (int l = 0; l < lanes; ++l) {
          sg_l[l] = m.sign[p.op[l]][a], sh_l[l] = m.shift[p.op[l]][a];
        }
        const vd sg = SPLAT_LANES(sg_l), sh = SPLAT_LANES(sh_l);
        Xj = sg * Xj + sh;
        xj = sg * xj + sh;
        vj = sg * vj;
      }
      g[a] = t * (Xj - Xi[a]);  // V_j g_ij
      dx[a] = xj - xi[a];
      dv[a] = vj - vi[a];
    }
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        if (k0 == begin) {
          A[r][c] = dx[r] * g[c];
          Adot[r][c] = dv[r] * g[c];
        } else {
          A[r][c] += dx[r] * g[c];
          Adot[r][c] += dv[r] * g[c];
        }
      }
    }
  }
  // Lane sums four at a time: A(r, c) = sums[(3 r + c) / 4][(3 r + c) % 4].
  const vd zero = {};
  vd sums[5];
  lane_sums4(sums[0], A[0][0], A[0][1], A[0][2], A[1][0]);
  lane_sums4(sums[1], A[1][1], A[1][2], A[2][0], A[2][1]);
  lane_sums4(sums[2], A[2][2], Adot[0][0], Adot[0][1], Adot[0][2]);
  lane_sums4(sums[3], Adot[1][0], Adot[1][1], Adot[1][2], Adot[2][0]);
  lane_sums4(sums[4], Adot[2][1], Adot[2][2], zero, zero);
  Mat3 As, Adots;
  for (int e = 0; e < 9; ++e) {
    As(e / 3, e % 3) = sums[e / 4][e % 4];
    Adots(e / 3, e % 3) = sums[(e + 9) / 4][(e + 9) % 4];
  }
  F = b.null_projector[i];
  F.noalias() += As * b.B[i].transpose();
  Fdot.noalias() = Adots * b.B[i].transpose();
}

struct PairConstants {
  double alpha_c;  // Monaghan alpha times the wave speed, m/s
  double beta;     // Monaghan beta, -
  double c_hg;     // hourglass coefficient, -
};

struct PairSums {
  Vec3 f_stress, f_visc, f_hg;  // N
  double k_hg;                  // hourglass stiffness sum_j c_hg E_ij V_i V_j W_ij / r0^2, N/m
  double max_mu;                // largest approach mu_ij, m/s
};

// Stress, viscosity and hourglass forces on particle i (the formulas of the
// header), without branches in the pair loop: inactive neighbours and
// coincident pairs are masked (inv_r = 0), the viscosity of receding pairs by
// mu = 0.
template <bool with_mirrors>
SPLAT_TARGET_CLONES PairSums pair_forces(const SphBody& b, const NodeSet& nodes, const Mirrors& m,
                                         const PairConstants& pc, std::size_t i) {
  const std::size_t base = b.node_begin;
  const double* __restrict X = b.X.data()->data();
  const double* __restrict x = nodes.x[base].data();
  const double* __restrict v = nodes.v[base].data();
  // The neighbours' records: field f of neighbour j at R[stride j + f].
  const double* __restrict R = b.record.data()->PB;
  constexpr std::size_t stride = sizeof(SphPairRecord) / sizeof(double);
  const SphPairRecord& rec_i = b.record[i];
  const double* Fi = rec_i.F;
  vd Xi[3], xi[3], vi[3];
  for (int a = 0; a < 3; ++a) {
    broadcast(Xi[a], X[3 * i + a]);
    broadcast(xi[a], x[3 * i + a]);
    broadcast(vi[a], v[3 * i + a]);
  }
  const double Vi = b.volume_ref[i];
  vd h_i, rho_i, E_i, zero = {};
  broadcast(h_i, rec_i.h);
  broadcast(rho_i, rec_i.rho);
  broadcast(E_i, rec_i.E_hg);
  const double mi = nodes.mass[base + i];
  // a = sum_j V_j g_ij, fp = sum_j S P_j B_j S V_j g_ij, then
  // f_stress = V_i (P_i B_i a + fp).
  vd a_sum[3] = {}, fp[3] = {}, fv[3] = {}, fh[3] = {};
  vd k_sum = {}, max_mu = {};
  const double hg_scale = pc.c_hg * Vi;
  const int begin = b.pairs.offsets[i], end = b.pairs.offsets[i + 1];
  for (int k0 = begin; k0 < end; k0 += lanes) {
    PairLanes p;
    load_lanes<with_mirrors, true>(b, i, k0, end, p);
    const vd t = SPLAT_LANES(p.t), w = SPLAT_LANES(p.w), dw = SPLAT_LANES(p.dw);
    double sg_l[3][lanes], sh_l[3][lanes];
    for (int a = 0; a < 3; ++a) {
      for (int l = 0; l < lanes; ++l) {
        sg_l[a][l] = m.sign[p.op[l]][a], sh_l[a][l] = m.shift[p.op[l]][a];
      }
    }
    const vd sg[3] = {SPLAT_LANES(sg_l[0]), SPLAT_LANES(sg_l[1]), SPLAT_LANES(sg_l[2])};
    vd dX[3], g[3], Sg[3], Sd[3], xij[3], vij[3];
    vd Xg[3], xg[3], vg[3];
    gather_vec3(Xg, X, p.j);
    gather_vec3(xg, x, p.j);
    gather_vec3(vg, v, p.j);
    for (int a = 0; a < 3; ++a) {
      // op(X_j) - X_i, recomputed (storing it cost 24 B per pair).
      vd Xj = Xg[a], xj = xg[a], vj = vg[a];
      if constexpr (with_mirrors) {
        const vd sh = SPLAT_LANES(sh_l[a]);
        Xj = sg[a] * Xj + sh;
        xj = sg[a] * xj + sh;
        vj = sg[a] * vj;
      }
      dX[a] = Xj - Xi[a];
      g[a] = t * dX[a];  // V_j g_ij
      if constexpr (with_mirrors) {
        Sg[a] = sg[a] * g[a];
        Sd[a] = sg[a] * dX[a];
      } else {
        Sg[a] = g[a];
        Sd[a] = dX[a];
      }
      xij[a] = xj - xi[a];
      vij[a] = vj - vi[a];
    }
    // The neighbours' records, two fields at a time: PB_j (0-8) and F_j
    // (9-17), column-major (element (r, c) at 3 c + r), h, rho, E_hg and
    // activity (18-21).
    vd rec[22];
    for (std::size_t f = 0; f < 22; f += 2) gather2(rec[f], rec[f + 1], R, p.j, stride, f);
    const vd* PBj = rec;
    const vd* Fj = rec + 9;
    vd pg[3], Fd[3], Fid[3];
    for (int r = 0; r < 3; ++r) {
      pg[r] = PBj[r] * Sg[0] + PBj[3 + r] * Sg[1] + PBj[6 + r] * Sg[2];
      Fd[r] = Fj[r] * Sd[0] + Fj[3 + r] * Sd[1] + Fj[6 + r] * Sd[2];  // S F_j S dX = S (F_j (S dX))
      Fid[r] = Fi[r] * dX[0] + Fi[3 + r] * dX[1] + Fi[6 + r] * dX[2];
    }
    for (int a = 0; a < 3; ++a) {
      a_sum[a] += g[a];
      if constexpr (with_mirrors) {
        fp[a] += sg[a] * pg[a];
      } else {
        fp[a] += pg[a];
      }
    }

    const vd r_sq = xij[0] * xij[0] + xij[1] * xij[1] + xij[2] * xij[2];
    static_assert(lanes == 4);
    const vmask valid = (rec[21] != zero) & (r_sq > zero);  // active, not coincident
    vd r;
    sqrt_lanes(r, r_sq);
    const vd inv_r = valid ? 1.0 / r : zero;

    // Monaghan viscosity between approaching particles (vx < 0), with one
    // division: q = 1 / (d1 d2), mu = h vx / d1, Pi = (...) / d2.
    const vd vx_any = vij[0] * xij[0] + vij[1] * xij[1] + vij[2] * xij[2];
    const vd vx = zero < vx_any ? zero : vx_any;
    const vd h_j = rec[18], rho_j = rec[19], E_j = rec[20];
    const vd hij = 0.5 * (h_i + h_j);
    const vd d1 = r_sq + 0.01 * hij * hij;
    const vd d2 = 0.5 * (rho_i + rho_j);
    const vd q = 1.0 / (d1 * d2);
    const vd mu = hij * vx * d2 * q;
    const vd Pi = (-pc.alpha_c * mu + pc.beta * mu * mu) * d1 * q;
    const vd approach = valid ? -mu : zero;
    max_mu = max_mu < approach ? approach : max_mu;
    const vd central = mi * dw * Pi * inv_r;

    // Ganzenmueller hourglass control: eps = (F_i dX + S F_j S dX) / 2 - x_ij.
    vd delta = {};
    for (int a = 0; a < 3; ++a) {
      vd Fj_dX = Fd[a];
      if constexpr (with_mirrors) Fj_dX = sg[a] * Fd[a];
      delta += (0.5 * (Fid[a] + Fj_dX) - xij[a]) * xij[a];
    }
    const vd E_ij = 0.5 * (E_i + E_j);
    const vd hg = hg_scale * E_ij * w * delta * inv_r * inv_r;
    const vd k_pair = E_ij * w;  // the pair's hourglass stiffness over hg_scale
    k_sum += valid ? k_pair : zero;
    for (int a = 0; a < 3; ++a) {
      fv[a] += central * xij[a];
      fh[a] -= hg * xij[a];
    }
  }
  vd sums[3];
  lane_sums4(sums[0], a_sum[0], a_sum[1], a_sum[2], fp[0]);
  lane_sums4(sums[1], fp[1], fp[2], fv[0], fv[1]);
  lane_sums4(sums[2], fv[2], fh[0], fh[1], fh[2]);
  PairSums out;
  const Vec3 a_i(sums[0][0], sums[0][1], sums[0][2]);
  const Vec3 fp_i(sums[0][3], sums[1][0], sums[1][1]);
  out.f_stress = Vi * (b.PB(i) * a_i + fp_i);
  out.f_visc = Vec3(sums[1][2], sums[1][3], sums[2][0]);
  out.f_hg = Vec3(sums[2][1], sums[2][2], sums[2][3]);
  double k = k_sum[0], mu_max = max_mu[0];
  for (int l = 1; l < lanes; ++l) {
    k += k_sum[l];
    mu_max = std::max(mu_max, max_mu[l]);
  }
  out.k_hg = hg_scale * k;
  out.max_mu = mu_max;
  return out;
}

// Lanes of four 3x3 matrices: out[e][l] = p[l][e] for the 9 entries
// (column-major: (r, c) at 3 c + r) of lane l's matrix at p[l], two entries
// per 16-byte load as in gather2. (gather2 written on top of a per-lane
// pointer version of this transpose made the pair loop 1.5 % slower: the
// transpose is spelled out in both.)
inline void gather_mat3(vd out[9], const double* const p[lanes]) {
  using v2d = double __attribute__((vector_size(2 * sizeof(double))));
  static_assert(lanes == 4);
  for (std::size_t e = 0; e < 8; e += 2) {
    v2d a0, a1, a2, a3;
    std::memcpy(&a0, p[0] + e, sizeof(v2d));
    std::memcpy(&a1, p[1] + e, sizeof(v2d));
    std::memcpy(&a2, p[2] + e, sizeof(v2d));
    std::memcpy(&a3, p[3] + e, sizeof(v2d));
    const vd t0 = __builtin_shufflevector(a0, a2, 0, 1, 2, 3);
    const vd t1 = __builtin_shufflevector(a1, a3, 0, 1, 2, 3);
    out[e] = __builtin_shufflevector(t0, t1, 0, 4, 2, 6);
    out[e + 1] = __builtin_shufflevector(t0, t1, 1, 5, 3, 7);
  }
  out[8] = vd{p[0][8], p[1][8], p[2][8], p[3][8]};
}

// The lanes of a[idx[0..3]] (gather_mat3 of their data).
inline void gather_mat3(vd out[9], const std::vector<Mat3>& a, const std::size_t idx[lanes]) {
  const double* p[lanes] = {a[idx[0]].data(), a[idx[1]].data(), a[idx[2]].data(), a[idx[3]].data()};
  gather_mat3(out, p);
}

// C = cof(M) = det(M) M^-T in lanes, column-major: its columns are the cross
// products of M's columns 1 x 2, 2 x 0 and 0 x 1.
inline void cofactor_lanes(const vd M[9], vd C[9]) {
  C[0] = M[4] * M[8] - M[5] * M[7];
  C[1] = M[5] * M[6] - M[3] * M[8];
  C[2] = M[3] * M[7] - M[4] * M[6];
  C[3] = M[7] * M[2] - M[8] * M[1];
  C[4] = M[8] * M[0] - M[6] * M[2];
  C[5] = M[6] * M[1] - M[7] * M[0];
  C[6] = M[1] * M[5] - M[2] * M[4];
  C[7] = M[2] * M[3] - M[0] * M[5];
  C[8] = M[0] * M[4] - M[1] * M[3];
}

// The lanes of particles k0 .. k0 + 3 of a block ending at `last` (the last
// particle repeated past it) and which of them to store.
inline void block_lanes(std::size_t k0, std::size_t last, std::size_t idx[lanes],
                        bool real[lanes]) {
  for (int l = 0; l < lanes; ++l) {
    const std::size_t k = k0 + static_cast<std::size_t>(l);
    real[l] = k < last;
    idx[l] = real[l] ? k : last - 1;
  }
}

// Kinematics of particles first .. last - 1, four at a time: det F of each,
// and for active particles with det F > 0 (when dt > 0) the strain increment
// dt D and the Hughes-Winget rotation of the deviatoric stress, from
// L = Fdot F_mid^-1 with F_mid = F - dt/2 Fdot (cofactors: F_mid^-1 =
// cof(F_mid)^T / det F_mid). Indexed from `first`: det[i - first],
// d_eps[i - first].
SPLAT_TARGET_CLONES void block_kinematics(SphBody& b, std::size_t first, std::size_t last,
                                          double dt, double* det, Mat3* d_eps) {
  for (std::size_t k0 = first; k0 < last; k0 += lanes) {
    std::size_t idx[lanes];
    bool real[lanes];
    block_lanes(k0, last, idx, real);
    vd F[9], CF[9];
    gather_mat3(F, b.F, idx);
    cofactor_lanes(F, CF);
    const vd detF = F[0] * CF[0] + F[1] * CF[1] + F[2] * CF[2];
    bool store[lanes];
    for (int l = 0; l < lanes; ++l) {
      if (real[l]) det[k0 + static_cast<std::size_t>(l) - first] = detF[l];
      store[l] = real[l] && b.active[idx[l]] && detF[l] > 0.0;
    }
    if (!(dt > 0.0) || !(store[0] || store[1] || store[2] || store[3])) continue;
    vd Fd[9], M[9], CM[9];
    gather_mat3(Fd, b.Fdot, idx);
    for (int e = 0; e < 9; ++e) M[e] = F[e] - (0.5 * dt) * Fd[e];
    cofactor_lanes(M, CM);
    const vd inv_det = 1.0 / (M[0] * CM[0] + M[1] * CM[1] + M[2] * CM[2]);
    // L(i, j) = sum_k Fdot(i, k) cof(j, k) / det F_mid, at 3 j + i.
    vd L[9];
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        L[3 * j + i] = (Fd[i] * CM[j] + Fd[3 + i] * CM[3 + j] + Fd[6 + i] * CM[6 + j]) * inv_det;
      }
    }
    // Hughes-Winget rotation of the deviator, W = (L - L^T) / 2, with the
    // FE element loop's lane kernels (simd_lanes.hpp); S[r][c] = s(r, c).
    vd Q[3][3], S[3][3];
    hughes_winget_rotation_cm<vd>(0.5 * (L[5] - L[7]), 0.5 * (L[6] - L[2]), 0.5 * (L[1] - L[3]), dt,
                                  Q);
    const double* Sp[lanes] = {b.state[idx[0]].s.data(), b.state[idx[1]].s.data(),
                               b.state[idx[2]].s.data(), b.state[idx[3]].s.data()};
    vd s_cm[9];
    gather_mat3(s_cm, Sp);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) S[r][c] = s_cm[3 * c + r];
    rotate_symmetric_cm<vd>(Q, S);
    for (int l = 0; l < lanes; ++l) {
      if (!store[l]) continue;
      Mat3& st_s = b.state[idx[l]].s;
      Mat3& de = d_eps[idx[l] - first];
      for (int i = 0; i < 3; ++i) {
        for (int j = i; j < 3; ++j) {
          st_s(i, j) = st_s(j, i) = S[i][j][l];
          de(i, j) = de(j, i) = dt * (0.5 * (L[3 * j + i][l] + L[3 * i + j][l]));
        }
      }
    }
  }
}

// P B = sigma cof(F) B of particles first .. last - 1 into their records,
// four at a time: zero for inactive particles and det F <= 0 (det[i - first]).
SPLAT_TARGET_CLONES void block_stress(SphBody& b, std::size_t first, std::size_t last,
                                      const double* det) {
  for (std::size_t k0 = first; k0 < last; k0 += lanes) {
    std::size_t idx[lanes];
    bool real[lanes];
    block_lanes(k0, last, idx, real);
    const double* Sp[lanes] = {b.state[idx[0]].s.data(), b.state[idx[1]].s.data(),
                               b.state[idx[2]].s.data(), b.state[idx[3]].s.data()};
    vd F[9], CF[9], Bm[9], sig[9];
    gather_mat3(F, b.F, idx);
    gather_mat3(Bm, b.B, idx);
    gather_mat3(sig, Sp);
    cofactor_lanes(F, CF);
    const vd p = {b.state[idx[0]].p, b.state[idx[1]].p, b.state[idx[2]].p, b.state[idx[3]].p};
    sig[0] -= p, sig[4] -= p, sig[8] -= p;  // sigma = s - p I
    // C = cof(F) B, then P B = sigma C; (i, j) at 3 j + i.
    vd C[9], PB[9];
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        C[3 * j + i] = CF[i] * Bm[3 * j] + CF[3 + i] * Bm[3 * j + 1] + CF[6 + i] * Bm[3 * j + 2];
      }
    }
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        PB[3 * j + i] = sig[i] * C[3 * j] + sig[3 + i] * C[3 * j + 1] + sig[6 + i] * C[3 * j + 2];
      }
    }
    for (int l = 0; l < lanes; ++l) {
      if (!real[l]) continue;
      const std::size_t i = idx[l];
      const bool stressed = b.active[i] && det[i - first] > 0.0;
      double* out = b.record[i].PB;
      for (int e = 0; e < 9; ++e) out[e] = stressed ? PB[e][l] : 0.0;
    }
  }
}
#pragma GCC diagnostic pop
}  // namespace

double sph_particle_time_step(const SphStepBoundInputs& in) {
  const double v_sig = in.c + 1.2 * (in.alpha * in.c + in.beta * in.max_mu);
  const double dt_signal = in.spacing * std::min(in.stretch, 1.0) / v_sig;
  const double dt_hourglass = in.k_hg > 0.0 ? std::sqrt(2.0 * in.mass / in.k_hg) : infinity;
  return std::min(dt_signal, dt_hourglass);
}

double smallest_stretch(const Mat3& F) {
  if (!(F.determinant() > 0.0)) return 1.0;  // inverted: carries no stress
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.computeDirect(F.transpose() * F, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(eig.eigenvalues()(0), 0.0));
}

void sph_build_reference(SphBody& b) {
  const std::size_t n = b.size();
  b.pairs = find_neighbours(b.X, b.h, b.planes, b.active);
  const std::size_t np = b.pairs.num_pairs();
  b.pair_t.assign(np, 0.0);
  b.pair_hg.assign(np, 0.0f);
  b.pair_visc.assign(np, 0.0f);
  b.null_projector.assign(n, Mat3::Zero());
  b.B.assign(n, Mat3::Zero());
  b.surface_gradient.assign(n, Vec3::Zero());

  const long long count = static_cast<long long>(n);
  SPLAT_OMP(omp parallel for schedule(static) if (count >= min_parallel_particles))
  for (long long ii = 0; ii < count; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    const int begin = b.pairs.offsets[i], end = b.pairs.offsets[i + 1];
    Mat3 C = Mat3::Zero();
    Vec3 colour_gradient = Vec3::Zero();
    for (int k = begin; k < end; ++k) {
      const std::size_t kk = static_cast<std::size_t>(k);
      const std::size_t j = static_cast<std::size_t>(b.pairs.j[kk]);
      const std::uint8_t op = b.pairs.op[kk];
      const Vec3 dX = mirror_point(b.planes, op, b.X[j]) - b.X[i];
      const double r0 = dX.norm();
      const KernelValue kv = kernel(b.settings.kernel, r0, 0.5 * (b.h[i] + b.h[j]));
      // Folded per-pair constants of the stabilising terms (fixed until the
      // next reference update; particle masses never change).
      b.pair_hg[kk] = static_cast<float>(r0 > 0.0 ? b.volume_ref[j] * kv.w / (r0 * r0) : 0.0);
      b.pair_visc[kk] = static_cast<float>(b.material.density * b.volume0[j] * kv.dw_dr);
      const double s = -kv.dw_dr / r0;  // g_ij = s dX (uncorrected)
      b.pair_t[kk] = b.volume_ref[j] * s;
      colour_gradient += b.pair_t[kk] * dX;
      C.noalias() += b.volume_ref[j] * dX * (s * dX).transpose();
    }
    if (colour_gradient.norm() * b.h[i] > k_surface_gradient) {
      b.surface_gradient[i] = colour_gradient;
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

namespace {

// The initial shares of the surface (sph_surface_area): V_i |a_i| / kappa on
// the surface, V_i^(2/3) off it (kept for particles that reach it later).
std::vector<double> initial_surface_shares(const SphBody& b) {
  const std::size_t n = b.size();
  Vec3 o = Vec3::Zero();
  double volume = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    o += b.volume0[i] * b.X[i];
    volume += b.volume0[i];
  }
  o /= volume;
  for (const SymmetryPlane& p : b.planes) o[p.axis] = p.position;
  double moment = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    moment -= b.volume0[i] * (b.X[i] - o).dot(b.surface_gradient[i]);
  const double kappa = moment / (3.0 * volume);
  std::vector<double> area(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = b.surface_gradient[i].norm();
    area[i] =
        a > 0.0 && kappa > 0.0 ? b.volume0[i] * a / kappa : std::cbrt(b.volume0[i] * b.volume0[i]);
  }
  return area;
}

}  // namespace

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
  b.surface_stretch_ref.assign(n, 1.0);
  b.h.assign(n, h0);
  b.state.resize(n);
  b.record.assign(n, SphPairRecord{});
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
  b.surface_area0 = initial_surface_shares(b);
  return b;
}

void sph_update_reference(SphBody& b, const NodeSet& nodes) {
  const std::size_t n = b.size();
  const double h0 = b.settings.h_over_spacing * b.spacing;
  const long long count = static_cast<long long>(n);
  SPLAT_OMP(omp parallel for schedule(static) if (count >= min_parallel_particles))
  for (long long ii = 0; ii < count; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    b.X[i] = nodes.x[b.node_begin + i];
    b.surface_stretch_ref[i] = sph_surface_stretch(b, i);
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

namespace {

// Stage 1: the deformation gradient from the reference configuration; the
// reference is updated when due (a pending deactivation, or the largest
// deformation past the threshold).
void sph_deformation_stage(SphBody& b, const NodeSet& nodes, const Mirrors& mirror_table,
                           std::vector<BlockSums>& blocks, SphStepResult& result) {
  const std::size_t n = b.size();
  const bool mirrors = !b.planes.empty();
  const auto compute_F = [&]() {
    for_blocks(n, blocks, [&](std::size_t i, BlockSums& s) {
      if (!b.active[i]) return;
      if (mirrors) {
        deformation<true>(b, nodes, mirror_table, i, b.F[i], b.Fdot[i]);
      } else {
        deformation<false>(b, nodes, mirror_table, i, b.F[i], b.Fdot[i]);
      }
      // Squared here, the root of the largest at the end (the same value).
      s.max_deformation = std::max(s.max_deformation, (b.F[i] - Mat3::Identity()).squaredNorm());
    });
    double m = 0.0;
    for (const BlockSums& s : blocks) m = std::max(m, s.max_deformation);
    return std::sqrt(m);
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
}

// Stage 2: the batched material update and first Piola-Kirchhoff stress per
// block, then the deactivation of failed particles.
void sph_material_stage(SphBody& b, double dt, std::vector<BlockSums>& blocks,
                        SphStepResult& result) {
  const std::size_t n = b.size();
  const Material& mat = b.material;
  const DamageParams& dm = mat.damage;
  const bool can_fail =
      b.settings.deactivate_failed && b.switches.damage && dm.initiation != DamageInitiation::none;
  std::vector<std::uint8_t> failed(n, 0);
  // Per block: kinematics of each stressed particle, ONE batched material
  // update of the block's particles, then P B and the per-particle quantities
  // the pairs read: current density and the hourglass modulus ((1 - D) E, or
  // the flow stress once plastic).
  const double E = mat.elastic.E;
  const bool energy_law = b.switches.damage && dm.evolution == DamageEvolution::fracture_energy;
  for_block_ranges(n, blocks, [&](std::size_t first, std::size_t last, BlockSums& s) {
    int index[block_size];
    Mat3 d_eps[block_size];
    double J_new[block_size], length[block_size], det[block_size];
    PointUpdateResult out[block_size];
    std::size_t count = 0;
    // In lanes: det F, the rotated deviator and dt D (block_kinematics).
    Mat3 d_eps_block[block_size];
    block_kinematics(b, first, last, dt, det, d_eps_block);
    for (std::size_t i = first; i < last; ++i) {
      const double detF = det[i - first];
      if (!b.active[i]) continue;
      if (!(detF > 0.0)) {
        ++s.inverted;
        continue;
      }
      if (dt > 0.0) {
        index[count] = static_cast<int>(i);
        d_eps[count] = d_eps_block[i - first];
        J_new[count] = b.J_ref[i] * detF;
        // Only the fracture-energy damage law reads the length; other
        // scenes skip its cube root (about 1 % of the step).
        length[count] = energy_law ? b.spacing * std::cbrt(J_new[count]) : b.spacing;
        ++count;
      }
    }
    if (count > 0) {
      update_points(mat, b.constants, b.switches, b.state.data(), index, count, d_eps, J_new, dt,
                    length, out);
    }
    for (std::size_t k = 0; k < count; ++k) {
      s.max_iterations = std::max(s.max_iterations, out[k].iterations);
      s.failed = s.failed || !out[k].converged;
      const std::size_t i = static_cast<std::size_t>(index[k]);
      if (can_fail && b.state[i].D >= dm.D_max - 1e-12) failed[i] = 1;
    }
    block_stress(b, first, last, det);  // P B = sigma det(F) F^-T B, in lanes
    for (std::size_t i = first; i < last; ++i) {
      const double detF = det[i - first];
      const PointState& st = b.state[i];
      SphPairRecord& rec = b.record[i];
      rec.h = b.h[i];
      rec.rho = mat.density / (b.J_ref[i] * std::max(detF, 1e-12));
      rec.E_hg = st.eps_p > 1e-3 ? st.sigma_y : (1.0 - st.D) * E;
      rec.active = b.active[i] ? 1.0 : 0.0;
      Eigen::Map<Mat3>(rec.F) = b.F[i];
    }
  });
  for (const BlockSums& s : blocks) {
    result.max_return_iterations = std::max(result.max_return_iterations, s.max_iterations);
    result.return_failed = result.return_failed || s.failed;
    result.inverted += s.inverted;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (failed[i]) {
      b.active[i] = 0;
      b.record[i].active = 0.0;
      Eigen::Map<Mat3>(b.record[i].PB).setZero();
      result.deactivated.push_back(static_cast<int>(i));
      result.deactivated_energy += b.volume0[i] * b.state[i].e;
      b.update_pending = true;
    }
  }
}

// Stage 3: pair forces gathered per particle, the stabilisers' power and
// each particle's stable step.
void sph_pair_force_stage(SphBody& b, NodeSet& nodes, const Mirrors& mirror_table,
                          std::vector<BlockSums>& blocks, SphStepResult& result) {
  const std::size_t n = b.size();
  const bool mirrors = !b.planes.empty();
  const double c = b.constants.wave_speed;
  const double alpha = b.settings.visc_linear, beta = b.settings.visc_quadratic;
  const double c_hg = b.settings.hourglass_coefficient;
  b.f_visc.resize(n);
  b.f_hg.resize(n);
  const PairConstants pc{alpha * c, beta, c_hg};
  for_blocks(n, blocks, [&](std::size_t i, BlockSums& s) {
    if (!b.active[i]) {
      b.dt_bound[i] = infinity;
      b.f_visc[i].setZero();
      b.f_hg[i].setZero();
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
    const double spacing = std::min(b.h[i] / b.settings.h_over_spacing, b.spacing);
    b.dt_bound[i] = sph_particle_time_step(
        {spacing, smallest_stretch(b.F[i]), c, alpha, beta, p.max_mu, nodes.mass[gi], p.k_hg});
    s.dt_min = std::min(s.dt_min, b.dt_bound[i]);
  });
  result.dt_stable = infinity;
  for (const BlockSums& s : blocks) {
    result.dt_stable = std::min(result.dt_stable, s.dt_min);
    result.hourglass_power += s.hourglass_power;
    result.viscosity_power += s.viscosity_power;
  }
}

}  // namespace

SphStepResult sph_internal_forces(SphBody& b, NodeSet& nodes, double dt) {
  SphStepResult result;
  std::vector<BlockSums> blocks;
  const Mirrors mirror_table(b.planes);
  sph_deformation_stage(b, nodes, mirror_table, blocks, result);
  sph_material_stage(b, dt, blocks, result);
  sph_pair_force_stage(b, nodes, mirror_table, blocks, result);
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

Vec3 sph_surface_normal(const SphBody& b, std::size_t i) {
  const Vec3& a = b.surface_gradient[i];
  const Mat3& F = b.F[i];
  if (!b.active[i] || a.squaredNorm() == 0.0 || !(F.determinant() > 0.0)) return Vec3::Zero();
  const Vec3 n = -(F.inverse().transpose() * a);
  return n.allFinite() ? Vec3(n.normalized()) : Vec3::Zero();
}

double sph_surface_area(const SphBody& b, std::size_t i) {
  return b.surface_area0[i] * sph_surface_stretch(b, i);
}

double sph_surface_stretch(const SphBody& b, std::size_t i) {
  const double at_reference = b.surface_stretch_ref[i];
  const Mat3& F = b.F[i];
  const double J = F.determinant();
  if (!b.active[i] || !(J > 0.0)) return at_reference;
  const Vec3& a = b.surface_gradient[i];
  if (a.squaredNorm() == 0.0) return at_reference * std::cbrt(J * J);
  const double ratio = J * (F.inverse().transpose() * a.normalized()).norm();
  return std::isfinite(ratio) ? at_reference * ratio : at_reference;
}

namespace {

// Sums over the particles of term(i) (a Vec2), in fixed blocks combined in
// block order: the same bits for any thread count.
template <class Term>
Vec2 particle_sum(std::size_t n, Term&& term) {
  return block_sum(n, sum_block_size, static_cast<std::size_t>(min_parallel_particles),
                   Vec2(Vec2::Zero()), [&](std::size_t first, std::size_t last) {
                     Vec2 sum = Vec2::Zero();
                     for (std::size_t i = first; i < last; ++i) sum += term(i);
                     return sum;
                   });
}

}  // namespace

double sph_internal_energy(const SphBody& b) {
  return sph_energy_sums(b).internal;
}

SphEnergySums sph_energy_sums(const SphBody& b) {
  const Vec2 sum = particle_sum(b.size(), [&](std::size_t i) {
    return b.active[i] ? Vec2(b.volume0[i] * b.state[i].e, b.volume0[i] * b.state[i].plastic_work)
                       : Vec2::Zero();
  });
  return {sum.x(), sum.y()};
}

SphEnergySums sph_stabiliser_power(const SphBody& b, const NodeSet& nodes) {
  SphEnergySums out;
  if (b.f_hg.size() != b.size()) return out;  // before the first force evaluation
  const Vec2 sum = particle_sum(b.size(), [&](std::size_t i) {
    const Vec3& v = nodes.v[b.node_begin + i];
    return Vec2(-b.f_visc[i].dot(v), -b.f_hg[i].dot(v));
  });
  out.viscosity = sum.x();
  out.hourglass = sum.y();
  return out;
}

}  // namespace splat
