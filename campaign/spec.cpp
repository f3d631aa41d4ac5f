#include "campaign/spec.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "campaign/ladders.hpp"
#include "campaign/sha256.hpp"
#include "solver/build_info.hpp"
#include "solver/input/material_io.hpp"
#include "solver/input/scene_io.hpp"
#include "solver/input/schema.hpp"

namespace splat::campaign {

using nlohmann::json;

namespace {

struct NamedAxis {
  const char* key;
  const char* two_mass_pointer;  // default when the base scene is a two-mass scene
  const char* impact_pointer;    // default when the base scene is a particle_impact scene
  const char* unit;
};

// The parameter axes the spec names, in expansion order.
constexpr NamedAxis k_named_axes[] = {
    {"G_c", "/two_mass/adhesion/G_c", "/particle_impact/adhesion/G_c", "J/m^2"},
    {"sigma_c", "/two_mass/adhesion/sigma_c", "/particle_impact/adhesion/sigma_c", "Pa"},
    {"yield_drop_percent", "/two_mass/adhesion/activation/drop_percent",
     "/particle_impact/adhesion/activation/drop_percent", "%"},
    {"D_adh_max", "/two_mass/adhesion/D_adh_max", "/particle_impact/adhesion/D_adh_max", "-"},
};

// Speeds a velocity range may list: far more than any campaign runs, and few
// enough to list without exhausting memory.
constexpr double k_max_range_speeds = 1e6;

// The speeds of the velocity axis; nullopt when a range lists more than
// k_max_range_speeds (a step too small for the span, or for `from` itself).
std::optional<std::vector<double>> velocity_values(const json& v) {
  std::vector<double> out;
  if (v.contains("values")) {
    for (const json& x : v.at("values")) out.push_back(x.get<double>());
    return out;
  }
  const json& r = v.at("range");
  const double from = r.at("from").get<double>();
  const double to = r.at("to").get<double>();
  const double step = r.at("step").get<double>();
  // from + i*step (not repeated addition, which drifts); `to` is included
  // when it is on the grid up to rounding. Counted first: a step below the
  // spacing of doubles at `from` never moves.
  const double count = std::floor((to - from) / step + 1e-9) + 1;
  if (!(count <= k_max_range_speeds) || from + step == from) return std::nullopt;
  for (long i = 0; i < static_cast<long>(std::max(count, 0.0)); ++i) {
    out.push_back(from + static_cast<double>(i) * step);
  }
  return out;
}

// The campaign field that wrote the job scene's pointer `at` (a velocity or
// an axis value, with the rest of the pointer below it; the axis's pointer
// itself when the scene has no such field), or nullopt when the base scene
// holds it.
std::optional<std::string> campaign_pointer_of(const CampaignSpec& spec, const json& params,
                                               double velocity, const SchemaViolation& v) {
  const std::string& at = v.pointer;
  const bool unknown_field = v.message.rfind("unknown field", 0) == 0;
  const auto below = [&](const std::string& p) -> std::optional<std::string> {
    if (p.empty()) return std::nullopt;
    if (at == p) return std::string();
    if (at.rfind(p + "/", 0) == 0) return at.substr(p.size());
    return std::nullopt;
  };
  if (const auto rest = below(spec.velocity_pointer)) {
    if (unknown_field && rest->empty()) return "/velocity/pointer";
    const json& axis = spec.document.is_object() ? spec.document.value("velocity", json()) : json();
    const auto it = std::find(spec.velocities.begin(), spec.velocities.end(), velocity);
    if (axis.is_object() && axis.contains("range")) return "/velocity/range";
    if (axis.is_object() && axis.contains("values") && it != spec.velocities.end()) {
      return "/velocity/values/" + std::to_string(it - spec.velocities.begin());
    }
    return "/velocity";
  }
  std::size_t field = 0;
  for (const ParameterAxis& a : spec.axes) {
    const std::string where = a.is_field ? "/fields/" + std::to_string(field++) : "/" + a.name;
    const auto rest = below(a.pointer);
    if (!rest || !params.contains(a.name)) continue;
    if (unknown_field && rest->empty()) return where + "/pointer";
    const auto it = std::find(a.values.begin(), a.values.end(), params.at(a.name));
    if (it == a.values.end()) return where;
    return where + "/values/" + std::to_string(it - a.values.begin()) + *rest;
  }
  return std::nullopt;
}

}  // namespace

std::string canonical_text(const json& doc) {
  return doc.dump();
}

std::string solver_version_string() {
  return std::string(splat::version()) + "+" + std::string(splat::git_commit());
}

SceneResolver splat_scene_resolver() {
  return [](const json& scene, const std::filesystem::path& base_dir) {
    return splat::resolved_scene_json(scene, base_dir);
  };
}

SceneResolver library_scene_resolver() {
  return [](const json& scene, const std::filesystem::path&) {
    std::vector<SchemaViolation> files;
    for (const splat::MaterialReference& m : splat::non_library_materials(scene)) {
      files.push_back({m.pointer, "'" + m.name +
                                      "' is no library material (files are not read for this "
                                      "scene: name a library material or give the document)"});
    }
    if (!files.empty()) throw InputError(std::move(files));
    return splat::resolved_scene_json(scene, {});
  };
}

namespace {

// The base scene: inline, or a file relative to the campaign's folder (its
// own folder then resolves the scene's relative paths).
void read_base_scene(const json& base, const std::filesystem::path& base_dir, CampaignSpec& s,
                     std::vector<SchemaViolation>& problems) {
  s.base_dir = base_dir;
  if (!base.is_string()) {
    s.base_scene = base;
    return;
  }
  std::filesystem::path p = base.get<std::string>();
  if (p.is_relative()) p = base_dir / p;
  try {
    s.base_scene = read_json_file(p);
    s.base_dir = p.parent_path();
  } catch (const InputError& e) {
    for (const SchemaViolation& v : e.violations()) problems.push_back({"/base_scene", v.message});
  }
}

// Each pointer must name a field the base scene can hold: its parent exists.
void check_pointer_parents(const CampaignSpec& s, std::vector<SchemaViolation>& problems) {
  if (!s.base_scene.is_object()) return;
  auto check_parent = [&](const std::string& pointer, const std::string& where) {
    if (pointer.empty()) return;
    const json::json_pointer p(pointer);
    if (!s.base_scene.contains(p.parent_pointer())) {
      problems.push_back({where + "/pointer", "the base scene has no '" +
                                                  p.parent_pointer().to_string() + "' to hold '" +
                                                  pointer + "'"});
    }
  };
  check_parent(s.velocity_pointer, "/velocity");
  std::size_t field = 0;
  for (const ParameterAxis& a : s.axes) {
    const std::string where = a.is_field ? "/fields/" + std::to_string(field++) : "/" + a.name;
    check_parent(a.pointer, where);
  }
}

void read_refinement(const json& doc, CampaignSpec& s, std::vector<SchemaViolation>& problems) {
  if (!doc.contains("refinement")) return;
  const json& r = doc.at("refinement");
  s.refinement = RefinementOptions{r.at("tolerance").get<double>(), r.value("max_extra_jobs", 100),
                                   r.value("guard_band", 0.0), r.value("coarse_to_fine", false),
                                   r.value("points_per_round", 1)};
  if (s.refinement->coarse_to_fine && !ladder_axis(s)) {
    problems.push_back({"/refinement/coarse_to_fine", "needs a `fields` axis on " +
                                                          k_resolution_pointers.front() +
                                                          " with two or more numeric values"});
  }
}

void read_job_options(const json& doc, CampaignSpec& s) {
  if (!doc.contains("job")) return;
  const json& j = doc.at("job");
  s.job.time_limit = j.value("time_limit", 3600.0);
  s.job.retries = j.value("retries", 1);
  s.job.threads = j.value("threads", 1);
}

}  // namespace

CampaignSpec read_campaign(const json& doc, const std::filesystem::path& base_dir) {
  validate_or_throw("campaign", doc);
  CampaignSpec s;
  s.name = doc.at("name").get<std::string>();
  s.description = doc.value("description", "");
  if (doc.contains("tags")) s.tags = doc.at("tags").get<std::vector<std::string>>();

  std::vector<SchemaViolation> problems;
  read_base_scene(doc.at("base_scene"), base_dir, s, problems);
  const bool two_mass = s.base_scene.is_object() && s.base_scene.contains("two_mass");
  // A particle_impact scene (not yet expanded: no bodies) ends stick or
  // rebound like a two-mass one, so the windows classify it the same way.
  const bool impact = s.base_scene.is_object() && s.base_scene.contains("particle_impact") &&
                      !s.base_scene.contains("bodies");

  auto pointer_of = [&](const json& axis, const std::string& where, const char* two_mass_default,
                        const char* impact_default) -> std::string {
    if (axis.contains("pointer")) return axis.at("pointer").get<std::string>();
    if (two_mass && two_mass_default) return two_mass_default;
    if (impact && impact_default) return impact_default;
    problems.push_back({where + "/pointer",
                        "required unless the base scene has a two_mass or particle_impact block"});
    return {};
  };

  const json& v = doc.at("velocity");
  s.velocity_pointer = pointer_of(v, "/velocity", "/two_mass/V0", "/particle_impact/velocity");
  const auto speeds = velocity_values(v);
  if (speeds) s.velocities = *speeds;
  s.velocity_scale = v.value("scale", 1.0);
  if (!speeds) {
    problems.push_back({"/velocity/range",
                        "lists more than 1e6 speeds (or a step too small to "
                        "move from `from` in double precision)"});
  } else if (s.velocities.empty()) {
    problems.push_back({"/velocity/range", "must contain at least one speed (from <= to)"});
  }

  std::set<std::string> pointers{s.velocity_pointer};
  auto check_unique = [&](const std::string& pointer, const std::string& where) {
    if (!pointer.empty() && !pointers.insert(pointer).second) {
      problems.push_back({where + "/pointer", "pointer '" + pointer + "' is set by another axis"});
    }
  };
  for (const NamedAxis& n : k_named_axes) {
    if (!doc.contains(n.key)) continue;
    const json& a = doc.at(n.key);
    const std::string where = std::string("/") + n.key;
    ParameterAxis axis{n.key, pointer_of(a, where, n.two_mass_pointer, n.impact_pointer), n.unit,
                       a.at("values").get<std::vector<json>>(), false};
    check_unique(axis.pointer, where);
    s.axes.push_back(std::move(axis));
  }
  if (doc.contains("fields")) {
    const json& fields = doc.at("fields");
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const json& f = fields[i];
      const std::string where = "/fields/" + std::to_string(i);
      ParameterAxis axis{f.at("pointer").get<std::string>(), f.at("pointer").get<std::string>(),
                         f.at("unit").get<std::string>(), f.at("values").get<std::vector<json>>(),
                         true};
      check_unique(axis.pointer, where);
      s.axes.push_back(std::move(axis));
    }
  }
  check_pointer_parents(s, problems);
  read_refinement(doc, s, problems);
  read_job_options(doc, s);
  s.priority = doc.value("priority", 0);
  s.executor =
      splat::parse<ExecutorKind>(doc.value("executor", "local")).value_or(ExecutorKind::local);
  if (!problems.empty()) throw InputError(std::move(problems));
  s.document = doc;
  s.document["base_scene"] = s.base_scene;
  return s;
}

CampaignSpec load_campaign(const std::filesystem::path& file) {
  return read_campaign(read_json_file(file), file.parent_path());
}

const ParameterAxis* ladder_axis(const CampaignSpec& spec) {
  for (const ParameterAxis& a : spec.axes) {
    const bool resolution = std::find(k_resolution_pointers.begin(), k_resolution_pointers.end(),
                                      a.pointer) != k_resolution_pointers.end();
    const bool numeric =
        std::all_of(a.values.begin(), a.values.end(), [](const json& v) { return v.is_number(); });
    if (a.is_field && resolution && numeric && a.values.size() >= 2) return &a;
  }
  return nullptr;
}

std::vector<json> parameter_sets(const CampaignSpec& spec) {
  std::vector<json> sets{json::object()};
  for (const ParameterAxis& a : spec.axes) {
    std::vector<json> next;
    for (const json& partial : sets) {
      for (const json& value : a.values) {
        json p = partial;
        p[a.name] = value;
        next.push_back(std::move(p));
      }
    }
    sets = std::move(next);
  }
  return sets;
}

ExpandedJob make_job(const CampaignSpec& spec, const json& params, double velocity,
                     const SceneResolver& resolve, const std::string& solver_version) {
  json scene = spec.base_scene;
  // A job writes histories but no field snapshots (an impact scene's default
  // ones) unless the base scene asks for them.
  const json* output = scene.contains("output") ? &scene["output"] : nullptr;
  if (output == nullptr || !output->is_object() ||
      (!output->contains("snapshot_times") && !output->contains("snapshot_count"))) {
    scene["output"]["snapshot_count"] = 0;
  }
  scene[json::json_pointer(spec.velocity_pointer)] = spec.velocity_scale * velocity;
  for (const ParameterAxis& a : spec.axes) {
    scene[json::json_pointer(a.pointer)] = params.at(a.name);
  }
  ExpandedJob job;
  try {
    job.scene = resolve(scene, spec.base_dir);
  } catch (const InputError& e) {
    // The scene pointers are inside the job's scene: named at the campaign
    // field that wrote the value (a velocity, an axis value) or else in the
    // base scene, saying which job.
    const std::string which =
        "job at " + std::to_string(velocity) + " m/s, parameters " + canonical_text(params);
    std::vector<SchemaViolation> v;
    for (const SchemaViolation& x : e.violations()) {
      if (const auto at = campaign_pointer_of(spec, params, velocity, x)) {
        v.push_back({*at, x.message + " (written at " + x.pointer + " of the " + which + ")"});
      } else {
        v.push_back({"/base_scene" + x.pointer, x.message + " (" + which + ")"});
      }
    }
    throw InputError(std::move(v));
  }
  job.params = params;
  job.params_key = canonical_text(params);
  job.velocity = velocity;
  job.hash = sha256_hex(canonical_text(job.scene) + "\n" + solver_version);
  return job;
}

std::vector<ExpandedJob> expand(const CampaignSpec& spec, const SceneResolver& resolve,
                                const std::string& solver_version) {
  std::vector<ExpandedJob> jobs;
  std::set<std::pair<std::string, double>> seen;
  const ParameterAxis* ladder =
      spec.refinement && spec.refinement->coarse_to_fine ? ladder_axis(spec) : nullptr;
  double coarsest = 0.0;
  if (ladder) {
    coarsest = std::min_element(ladder->values.begin(), ladder->values.end())->get<double>();
  }
  for (const json& params : parameter_sets(spec)) {
    if (ladder && params.at(ladder->name).get<double>() != coarsest) continue;
    const std::string key = canonical_text(params);
    for (double v : spec.velocities) {
      if (!seen.insert({key, v}).second) continue;
      jobs.push_back(make_job(spec, params, v, resolve, solver_version));
    }
  }
  return jobs;
}

std::string spec_hash(const CampaignSpec& spec) {
  return sha256_hex(canonical_text(spec.document));
}

}  // namespace splat::campaign
