#include "solver/sph/sph_particles.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "solver/mesh/mesh.hpp"

namespace splat {

namespace {

// splitmix64: a reproducible stream of 64-bit values from a seed.
std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Uniform in [-1, 1).
double uniform_pm1(std::uint64_t& state) {
  return 2.0 * static_cast<double>(splitmix64(state) >> 11) * 0x1.0p-53 - 1.0;
}

void require_positive(double value, const std::string& what) {
  if (!(value > 0.0)) {
    throw std::invalid_argument("particle generation: " + what + " must be > 0, got " +
                                std::to_string(value));
  }
}

double sector_fraction(ParticleSector s) {
  switch (s) {
    case ParticleSector::half:
      return 0.5;
    case ParticleSector::quarter:
      return 0.25;
    default:
      return 1.0;
  }
}

// Keeps the point if it lies in the sector about the axis point `c`.
bool in_sector(const Vec3& p, const Vec3& c, ParticleSector s) {
  if (s == ParticleSector::full) return true;
  if (p.y() < c.y()) return false;
  return s == ParticleSector::half || p.x() >= c.x();
}

// Lattice points (positions only) in the axis-aligned box [bmin, bmax] about
// `origin`, on the chosen lattice at spacing d.
template <class Visit>
void for_lattice_points(Lattice lattice, double d, const Vec3& origin, const Vec3& bmin,
                        const Vec3& bmax, Visit&& visit) {
  if (lattice == Lattice::cubic) {
    const auto range = [&](int axis, long& a, long& b) {
      a = static_cast<long>(std::floor((bmin[axis] - origin[axis]) / d - 0.5)) - 1;
      b = static_cast<long>(std::ceil((bmax[axis] - origin[axis]) / d - 0.5)) + 1;
    };
    long i0, i1, j0, j1, k0, k1;
    range(0, i0, i1);
    range(1, j0, j1);
    range(2, k0, k1);
    for (long k = k0; k <= k1; ++k)
      for (long j = j0; j <= j1; ++j)
        for (long i = i0; i <= i1; ++i)
          visit(origin + d * Vec3(static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5,
                                  static_cast<double>(k) + 0.5));
    return;
  }
  const double dy = 0.5 * std::sqrt(3.0) * d;
  const double dz = std::sqrt(2.0 / 3.0) * d;
  const long k0 = static_cast<long>(std::floor((bmin.z() - origin.z()) / dz)) - 1;
  const long k1 = static_cast<long>(std::ceil((bmax.z() - origin.z()) / dz)) + 1;
  const long j0 = static_cast<long>(std::floor((bmin.y() - origin.y()) / dy)) - 2;
  const long j1 = static_cast<long>(std::ceil((bmax.y() - origin.y()) / dy)) + 2;
  const long i0 = static_cast<long>(std::floor((bmin.x() - origin.x()) / d)) - 2;
  const long i1 = static_cast<long>(std::ceil((bmax.x() - origin.x()) / d)) + 2;
  for (long k = k0; k <= k1; ++k) {
    const bool b_layer = (k & 1) != 0;
    const double sx = b_layer ? 0.5 * d : 0.0;
    const double sy = b_layer ? d / (2.0 * std::sqrt(3.0)) : 0.0;
    for (long j = j0; j <= j1; ++j) {
      const double row = (j & 1) != 0 ? 0.5 * d : 0.0;
      for (long i = i0; i <= i1; ++i) {
        // Offsets of d/4 keep every point off the planes x = 0 and y = 0.
        visit(origin + Vec3((static_cast<double>(i) + 0.25) * d + row + sx,
                            (static_cast<double>(j) + 0.25) * dy + sy,
                            (static_cast<double>(k) + 0.5) * dz));
      }
    }
  }
}

// Fills a cloud with the lattice points of one shape: the spec, the
// boundary layer thickness t and the lattice cell volume.
class CloudBuilder {
 public:
  CloudBuilder(const ParticleSpec& spec, ParticleCloud& cloud)
      : spec_(spec),
        cloud_(cloud),
        d_(spec.spacing),
        t_(cloud.layer_thickness),
        cell_(spec.lattice == Lattice::cubic ? d_ * d_ * d_ : d_ * d_ * d_ / std::sqrt(2.0)) {}

  void sphere() {
    require_positive(spec_.radius, "radius");
    const double R = spec_.radius;
    const Vec3 c = spec_.centre;
    cloud_.exact_volume = 4.0 / 3.0 * std::numbers::pi * R * R * R * sector_fraction(spec_.sector);
    const Vec3 ext = Vec3::Constant(R);
    for_lattice_points(spec_.lattice, d_, c, c - ext, c + ext, [&](const Vec3& p) {
      const double r = (p - c).norm();
      if (r > R || !in_sector(p, c, spec_.sector)) return;
      std::uint32_t bits = sector_bits(p, c);
      Vec3 n = Vec3::Zero();
      if (R - r < t_) {
        bits |= boundary_curved;
        if (r > 0.0) n = (p - c) / r;
      }
      add(p, cell_, bits, n);
    });
  }

  void cylinder() {
    require_positive(spec_.radius, "radius");
    require_positive(spec_.z_max - spec_.z_min, "z_max - z_min");
    const double R = spec_.radius, z0 = spec_.z_min, z1 = spec_.z_max;
    const Vec3 c(0.0, 0.0, z0);
    cloud_.exact_volume = std::numbers::pi * R * R * (z1 - z0) * sector_fraction(spec_.sector);
    for_lattice_points(spec_.lattice, d_, c, Vec3(-R, -R, z0), Vec3(R, R, z1), [&](const Vec3& p) {
      const double r = std::hypot(p.x(), p.y());
      if (r > R || p.z() < z0 || p.z() > z1 || !in_sector(p, c, spec_.sector)) return;
      std::uint32_t bits = sector_bits(p, c);
      Vec3 n = Vec3::Zero();
      if (R - r < t_) {
        bits |= boundary_curved;
        if (r > 0.0) n = Vec3(p.x() / r, p.y() / r, 0.0);
      }
      if (p.z() - z0 < t_) bits |= boundary_z_min;
      if (z1 - p.z() < t_) bits |= boundary_z_max;
      add(p, cell_, bits, n);
    });
  }

  void box() {
    const Vec3 L = spec_.hi - spec_.lo;
    for (int a = 0; a < 3; ++a)
      require_positive(L[a], "box extent along axis " + std::to_string(a));
    if (spec_.sector != ParticleSector::full) {
      throw std::invalid_argument("particle generation: boxes have no sectors; set the extent");
    }
    cloud_.exact_volume = L.prod();
    if (spec_.lattice != Lattice::cubic) {
      for_lattice_points(spec_.lattice, d_, spec_.lo, spec_.lo, spec_.hi, [&](const Vec3& p) {
        for (int a = 0; a < 3; ++a) {
          if (p[a] < spec_.lo[a] || p[a] > spec_.hi[a]) return;
        }
        add(p, cell_, box_bits(p), Vec3::Zero());
      });
      return;
    }
    // Cubic: whole cells along each axis, the spacing stretched to fit.
    int n[3];
    Vec3 s;
    for (int a = 0; a < 3; ++a) {
      n[a] = std::max(1, static_cast<int>(std::lround(L[a] / d_)));
      s[a] = L[a] / n[a];
    }
    cloud_.spacing = s.mean();
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const Vec3 p = spec_.lo + Vec3((i + 0.5) * s.x(), (j + 0.5) * s.y(), (k + 0.5) * s.z());
          add(p, s.prod(), box_bits(p), Vec3::Zero());
        }
  }

 private:
  void add(const Vec3& p, double volume, std::uint32_t bits, const Vec3& normal) {
    cloud_.x.push_back(p);
    cloud_.volume.push_back(volume);
    cloud_.boundary.push_back(bits);
    cloud_.outward_normal.push_back(normal);
  }

  // Bits of the sector planes x = c.x (quarter) and y = c.y (half, quarter).
  std::uint32_t sector_bits(const Vec3& p, const Vec3& c) const {
    std::uint32_t bits = boundary_none;
    if (spec_.sector != ParticleSector::full && p.y() - c.y() < t_) bits |= boundary_y_min;
    if (spec_.sector == ParticleSector::quarter && p.x() - c.x() < t_) bits |= boundary_x_min;
    return bits;
  }

  std::uint32_t box_bits(const Vec3& p) const {
    std::uint32_t bits = boundary_none;
    const std::uint32_t lo_bit[3] = {boundary_x_min, boundary_y_min, boundary_z_min};
    const std::uint32_t hi_bit[3] = {boundary_x_max, boundary_y_max, boundary_z_max};
    for (int a = 0; a < 3; ++a) {
      if (p[a] - spec_.lo[a] < t_) bits |= lo_bit[a];
      if (spec_.hi[a] - p[a] < t_) bits |= hi_bit[a];
    }
    return bits;
  }

  const ParticleSpec& spec_;
  ParticleCloud& cloud_;
  const double d_;     // lattice spacing, m
  const double t_;     // boundary layer thickness, m
  const double cell_;  // volume per lattice point, m^3
};

}  // namespace

ParticleCloud generate_particles(const ParticleSpec& spec) {
  require_positive(spec.spacing, "spacing");
  if (spec.boundary_layers < 0) {
    throw std::invalid_argument("particle generation: boundary_layers must be >= 0");
  }
  if (spec.jitter < 0.0 || spec.jitter >= 0.5) {
    throw std::invalid_argument("particle generation: jitter must be in [0, 0.5)");
  }
  ParticleCloud cloud;
  cloud.spacing = spec.spacing;
  cloud.layer_thickness = spec.boundary_layers * spec.spacing;
  CloudBuilder build(spec, cloud);
  switch (spec.shape) {
    case ParticleShape::sphere:
      build.sphere();
      break;
    case ParticleShape::cylinder:
      build.cylinder();
      break;
    case ParticleShape::box:
      build.box();
      break;
  }
  if (spec.jitter > 0.0) {
    std::uint64_t state = spec.jitter_seed;
    const double a = spec.jitter * spec.spacing;
    for (Vec3& p : cloud.x) {
      for (int c = 0; c < 3; ++c) p[c] += a * uniform_pm1(state);
    }
  }
  double total = 0.0;
  for (double v : cloud.volume) total += v;
  cloud.volume_error = cloud.exact_volume > 0.0 ? total / cloud.exact_volume - 1.0 : 0.0;
  return cloud;
}

}  // namespace splat
