#include "solver/material/material_point_driver.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "solver/common/root_find.hpp"
#include "solver/material/elasticity.hpp"
#include "solver/material/point_update.hpp"

namespace splat {

LoadingMode parse_loading_mode(const std::string& text) {
  if (text == "uniaxial-stress") return LoadingMode::uniaxial_stress;
  if (text == "uniaxial-strain") return LoadingMode::uniaxial_strain;
  if (text == "simple-shear") return LoadingMode::simple_shear;
  throw std::invalid_argument(
      "--mode: must be one of uniaxial-stress, uniaxial-strain, "
      "simple-shear (got '" +
      text + "')");
}

namespace {

void check_request(const MaterialPointRequest& r) {
  auto fail = [](const std::string& msg) { throw std::invalid_argument(msg); };
  if (!(r.strain_rate > 0.0) || !std::isfinite(r.strain_rate))
    fail("--strain-rate: must be a finite number > 0 (1/s)");
  if (!(r.max_strain != 0.0) || !std::isfinite(r.max_strain) || std::abs(r.max_strain) > 10.0)
    fail("--max-strain: must be non-zero with |value| <= 10 (-)");
  if (r.steps < 1 || r.steps > 100'000'000) fail("--steps: must be in [1, 1e8]");
  if (!(r.temperature > 0.0) || !std::isfinite(r.temperature))
    fail("--temperature: must be a finite number > 0 (K)");
  if (!(r.length > 0.0) || !std::isfinite(r.length)) fail("--length: must be > 0 (m)");
  if (!(r.initial_damage >= 0.0) || r.initial_damage >= 1.0)
    fail("--initial-damage: must be in [0, 1) (-)");
}

MaterialPointRow make_row(double t, double strain, const PointState& st, LoadingMode mode,
                          int iterations) {
  MaterialPointRow row;
  row.time = t;
  row.strain = strain;
  row.stress = mode == LoadingMode::simple_shear ? st.s(0, 1) : st.s(0, 0) - st.p;
  row.plastic_strain = st.eps_p;
  row.temperature = st.T;
  row.damage = st.D;
  row.yield_stress = st.sigma_y;
  row.pressure = st.p;
  const double q = von_mises(st.s);
  row.triaxiality = q > 0.0 ? -st.p / q : 0.0;
  row.damage_indicator = st.omega;
  row.iterations = iterations;
  return row;
}

}  // namespace

MaterialPointResult run_material_point(const MaterialPointRequest& r) {
  check_request(r);
  const Material& m = r.material;
  const MaterialConstants mc = derive_constants(m);
  const double total_time = std::abs(r.max_strain) / r.strain_rate;
  const double dt = total_time / r.steps;
  const double d_axial = std::copysign(r.strain_rate * dt, r.max_strain);

  MaterialPointResult result;
  result.rows.reserve(static_cast<std::size_t>(r.steps) + 1);
  PointState st = initial_point_state(m, r.switches, r.temperature, r.initial_damage);
  result.rows.push_back(make_row(0.0, 0.0, st, r.mode, 0));

  // Scale for the zero-lateral-stress tolerance.
  const double stress_scale = std::max(initial_yield_stress(m.strength), 1e-3 * m.elastic.E) + 1.0;

  for (int step = 1; step <= r.steps; ++step) {
    PointUpdateResult upd;
    switch (r.mode) {
      case LoadingMode::uniaxial_strain: {
        Mat3 d = Mat3::Zero();
        d(0, 0) = d_axial;
        upd = update_point(m, mc, r.switches, st, d, st.J * std::exp(d_axial), dt, r.length);
        break;
      }
      case LoadingMode::simple_shear: {
        Mat3 L = Mat3::Zero();
        L(0, 1) = d_axial / dt;
        const Mat3 W = 0.5 * (L - L.transpose());
        st.s = jaumann_rotate(st.s, W, dt);
        upd =
            update_point(m, mc, r.switches, st, 0.5 * (L + L.transpose()) * dt, st.J, dt, r.length);
        break;
      }
      case LoadingMode::uniaxial_stress: {
        // Lateral strain increment that leaves sigma_yy = sigma_zz = 0.
        auto trial = [&](double d_lat, PointState& out) {
          out = st;
          const Mat3 d = Eigen::Vector3d(d_axial, d_lat, d_lat).asDiagonal();
          return update_point(m, mc, r.switches, out, d, st.J * std::exp(d.trace()), dt, r.length);
        };
        PointState tmp;
        auto lateral_stress = [&](double d_lat) {
          trial(d_lat, tmp);
          return tmp.s(1, 1) - tmp.p;
        };
        const RootResult root =
            find_root_increasing(lateral_stress, -0.5 * d_axial,
                                 -m.elastic.nu * d_axial - 1e-3 * d_axial, 1e-10 * stress_scale);
        if (!root.converged) {
          result.converged = false;
          result.message =
              "lateral stress iteration did not converge at step " + std::to_string(step);
          return result;
        }
        upd = trial(root.x, tmp);
        st = tmp;
        break;
      }
    }
    if (!upd.converged) {
      result.converged = false;
      result.message = "return mapping did not converge at step " + std::to_string(step);
    }
    const double strain = d_axial * step;
    result.rows.push_back(make_row(dt * step, strain, st, r.mode, upd.iterations));
  }
  return result;
}

std::string material_point_csv(const MaterialPointResult& result) {
  std::ostringstream out;
  out << "time,strain,stress,plastic_strain,temperature,damage,yield_stress,pressure,"
         "triaxiality,damage_indicator,iterations\n";
  char line[512];
  for (const MaterialPointRow& r : result.rows) {
    std::snprintf(line, sizeof line, "%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e,%d\n",
                  r.time, r.strain, r.stress, r.plastic_strain, r.temperature, r.damage,
                  r.yield_stress, r.pressure, r.triaxiality, r.damage_indicator, r.iterations);
    out << line;
  }
  return out.str();
}

}  // namespace splat
