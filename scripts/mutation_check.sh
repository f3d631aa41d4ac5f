#!/usr/bin/env bash
# Breaks the physics on purpose, one mutation at a time, and checks that the
# named verification tests then FAIL (and pass again once restored). This is
# how we know each verification test can fail. Not part of CI (it rebuilds
# once per mutation); run it after changing a kernel or a test:
#   scripts/mutation_check.sh
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$here/build-mutation"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSPLAT_BUILD_BENCHMARKS=OFF >/dev/null

# file | literal text | replacement | gtest filter that must fail
mutations=(
  "solver/material/johnson_cook.cpp|rate += jc.C * std::log(x);|rate += 0.5 * jc.C * std::log(x);|uniaxial_johnson_cook.*"
  "solver/material/johnson_cook.hpp|std::exp(jc.m * std::log(t_star))|std::exp(1.1 * jc.m * std::log(t_star))|uniaxial_johnson_cook.*"
  "solver/material/johnson_cook.cpp|std::exp(jc.n * std::log(ep))|std::exp(1.02 * jc.n * std::log(ep))|uniaxial_johnson_cook.*:simple_shear.*"
  "solver/material/zerilli_armstrong.cpp|std::exp(-za.C3 * temp|std::exp(za.C3 * temp|uniaxial_zerilli_armstrong.*"
  "solver/material/zerilli_armstrong.cpp|za.C4 * temp * ln_rate|0.9 * za.C4 * temp * ln_rate|uniaxial_zerilli_armstrong.isothermal*"
  "solver/material/zerilli_armstrong.cpp|const double hard = za.C2 * root * thermal;|const double hard = za.C2 * root * root * thermal;|uniaxial_zerilli_armstrong.*"
  "solver/material/preston_tonks_wallace.cpp|std::erf(w.kappa * T_hat|std::erf(1.1 * w.kappa * T_hat|uniaxial_preston_tonks_wallace.*"
  "solver/material/preston_tonks_wallace.cpp|return {tau_s + a / w.p * std::log(inner)|return {tau_s - a / w.p * std::log(inner)|uniaxial_preston_tonks_wallace.*"
  "solver/material/steinberg_guinan.hpp|1.0 - sg.B * (temp - sg.T_ref)|1.0 - 1.1 * sg.B * (temp - sg.T_ref)|material_library_sources.flow_stress_follows_the_source_closed_form"
  "solver/material/steinberg_guinan.hpp|return {sg.Y_max * shear, 0.0, 0.0};|return {1.01 * sg.Y_max * shear, 0.0, 0.0};|material_library_sources.steinberg_guinan_saturates_at_the_table_y_max"
  "solver/material/strength_model.hpp|const double g = q_trial - three_g * dp - r.sigma_y;|const double g = q_trial - 1.02 * three_g * dp - r.sigma_y;|uniaxial_zerilli_armstrong.*"
  "solver/material/point_update.cpp|s *= std::max(q_trial - 3.0 * G_d * dp|s *= std::max(q_trial - 2.9 * G_d * dp|uniaxial_johnson_cook.*"
  "solver/material/point_update.cpp|st.T += mc.chi * w * J_new|st.T += w * J_new|adiabatic_heating.*"
  "solver/material/point_update.cpp|eos_split(m.eos, mc.K,|eos_split(m.eos, 1.01 * mc.K,|elastic_uniaxial_strain.*"
  "solver/material/point_update.cpp|Mat3 s = st.s + 2.0 * G_d|Mat3 s = st.s + 2.02 * G_d|elastic_uniaxial_strain.*:uniaxial_johnson_cook.elastic*"
  "solver/material/point_update.cpp|D = span > 0.0 ? D + dp_after_init / span|D = span > 0.0 ? D + 1.1 * dp_after_init / span|jc_ductile_damage.*"
  "solver/material/damage.hpp|d.D2 * std::exp(d.D3 * triaxiality)|d.D2 * std::exp(-d.D3 * triaxiality)|jc_ductile_damage.*"
  "solver/material/damage.hpp|return std::max(lo + (hi - lo) * w|return std::max(hi + (lo - hi) * w|shear_failure_damage.*"
  "solver/material/damage.hpp|(k_s * p + q) / tau_max|(k_s * p + q) / (1.05 * tau_max)|shear_failure_damage.*"
  "solver/material/elasticity.hpp|(Mat3::Identity() - half).inverse() * (Mat3::Identity() + half)|(Mat3::Identity() + half).inverse() * (Mat3::Identity() - half)|objective_rate.*"
  "solver/material/elasticity.hpp|const Mat3 half = 0.5 * dt * W;|const Mat3 half = 0.45 * dt * W;|objective_rate.*:simple_shear.*"
  "solver/fe/fe_body.cpp|nodes.mass[body.conn[e][a]] += body.element_mass[e] / npe;|nodes.mass[body.conn[e][a]] += 1.05 * body.element_mass[e] / npe;|elastic_bar_wave_speed.*"
  "solver/material/point_update.cpp|      0.5 * J_mid * ((sigma_old.array()|      0.45 * J_mid * ((sigma_old.array()|freely_vibrating_elastic_body.*"
  "solver/adhesion/cohesive_law.cpp|double dW = I * (g_free - 0.5 * h * I);|double dW = I * (g_free - h * I);|two_mass_adhesion.free_mass*"
  "solver/adhesion/cohesive_law.cpp|2.0 * W_rem / (g_free + std::sqrt(disc))|W_rem / g_free + 0.0 * disc|two_mass_adhesion.free_mass*"
  "solver/adhesion/cohesive_law.cpp|const double I_cap = max_tension(p, area) * dt;|const double I_cap = 1.05 * max_tension(p, area) * dt;|two_mass_adhesion.spring*"
  "solver/two_mass/two_mass_model.cpp|constexpr double k_restitution = 1.0;|constexpr double k_restitution = 0.95;|two_mass_adhesion.free_mass*"
  "solver/two_mass/two_mass_model.cpp|double v_new = v - dt * s.k * x / s.m;|double v_new = v - dt * 1.02 * s.k * x / s.m;|two_mass_adhesion.spring*"
  "solver/sph/sph_body.cpp|    b.B[i] = B;|    b.B[i] = Mat3::Identity();|SphWaves.ElasticWaveSpeedInAColumn"
  "solver/sph/sph_body.cpp|mat_vec(PB + 9 * j, Sg, pg);|mat_vec(PB + 9 * i, Sg, pg);|SphConservation.*"
  "solver/sph/sph_body.cpp|(detF * st.cauchy()) * (F.inverse().transpose() * b.B[i]);|(detF * st.cauchy()) * b.B[i];|SphConservation.*"
  "solver/sph/sph_body.cpp|fp0 += sg[0] * pg[0], fp1 += sg[1] * pg[1], fp2 += sg[2] * pg[2];|fp0 += pg[0], fp1 += pg[1], fp2 += pg[2];|SphBoundaries.QuarterBall*"
  "solver/sph/sph_boundary.cpp|a.area.push_back(body.volume0[i] / layer_thickness);|a.area.push_back(body.volume0[i] / body.spacing);|SphBoundaries.AbsorbingEnd*"
  "solver/sph/sph_body.cpp|nodes.mass[g] = material.density * cloud.volume[i];|nodes.mass[g] = 1.1 * material.density * cloud.volume[i];|SphWaves.*"
)

status=0
for entry in "${mutations[@]}"; do
  IFS='|' read -r file from to filter <<<"$entry"
  path="$here/$file"
  cp "$path" "$path.orig"
  python3 - "$path" "$from" "$to" <<'PY'
import sys
p, a, b = sys.argv[1:4]
s = open(p).read()
if a not in s:
    sys.exit(f"mutation text not found in {p}: {a}")
open(p, "w").write(s.replace(a, b, 1))
PY
  if [ $? -ne 0 ]; then mv "$path.orig" "$path"; status=1; continue; fi
  if cmake --build "$build" --target splat_verification_tests -j "$(nproc)" >/dev/null 2>&1 &&
     ! "$build/tests/splat_verification_tests" --gtest_filter="$filter" >/dev/null 2>&1; then
    echo "caught   : $file: '$from' -> '$to' ($filter fails)"
  else
    echo "MISSED   : $file: '$from' -> '$to' ($filter still passes or did not build)"
    status=1
  fi
  mv "$path.orig" "$path"
  touch "$path"
done
cmake --build "$build" --target splat_verification_tests -j "$(nproc)" >/dev/null 2>&1
"$build/tests/splat_verification_tests" >/dev/null 2>&1 || { echo "restored tree FAILS"; status=1; }
exit $status
