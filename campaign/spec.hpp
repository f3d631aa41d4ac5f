// A campaign spec (schemas/campaign.schema.json) and its expansion into jobs.
//
// Expansion is the Cartesian product of the parameter axes (G_c, sigma_c,
// yield_drop_percent, D_adh_max, then `fields` in order) with the velocity
// axis. A job is the base scene with the axis values written at their JSON
// pointers and then fully resolved (every default written out, materials
// inlined). Its identity is the SHA-256 of the canonical text of the resolved
// scene and the solver version, so identical jobs run once and stored
// results are found again from any campaign.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "campaign/windows.hpp"
#include "solver/common/enum_names.hpp"

namespace splat::campaign {

// One parameter axis: a name (the spec key, or the pointer for `fields`), the
// scene pointer it writes and its values.
struct ParameterAxis {
  std::string name;
  std::string pointer;
  std::string unit;
  std::vector<nlohmann::json> values;
  bool is_field = false;  // from `fields` (named by its pointer)
};

struct RefinementOptions {
  double tolerance = 0.0;  // m/s; bracket width at which an edge counts as found
  int max_extra_jobs = 100;
  double guard_band = 0.0;      // m/s; band around each edge sampled to the tolerance (islands)
  bool coarse_to_fine = false;  // finer resolution levels run near the coarser level's edges only
  int points_per_round = 1;     // new velocities per window and round (1 = bisection)
  RefinementRule rule() const { return {tolerance, guard_band, points_per_round}; }
};

struct JobOptions {
  double time_limit = 3600.0;  // s, per attempt
  int retries = 1;             // extra attempts after a transient failure
  int threads = 1;
};

enum class ExecutorKind { local, slurm };

inline constexpr NameTable<ExecutorKind, 2> k_executor_names{{
    {ExecutorKind::local, "local"},
    {ExecutorKind::slurm, "slurm"},
}};
static_assert(names_in_order(k_executor_names));

constexpr const auto& names_of(ExecutorKind) {
  return k_executor_names;
}

struct CampaignSpec {
  std::string name;
  std::string description;
  std::vector<std::string> tags;
  nlohmann::json base_scene;       // the scene document (read from the file when given as a path)
  std::filesystem::path base_dir;  // folder that relative paths in the scene resolve against
  std::string velocity_pointer;
  double velocity_scale = 1.0;     // value written at the pointer = scale * velocity
  std::vector<double> velocities;  // m/s, in the order given
  std::vector<ParameterAxis> axes;
  std::optional<RefinementOptions> refinement;
  JobOptions job;
  int priority = 0;
  ExecutorKind executor = ExecutorKind::local;
  nlohmann::json document;  // the spec as given (base scene inlined), for the store
};

// Validates `doc` (schema "campaign") and reads it. `base_dir` is the campaign
// file's folder (base scene paths are relative to it). Throws InputError with
// every violation, each naming its field (e.g. "/velocity/pointer: required
// unless the base scene has a two_mass block").
CampaignSpec read_campaign(const nlohmann::json& doc, const std::filesystem::path& base_dir = {});
CampaignSpec load_campaign(const std::filesystem::path& file);

// Turns a scene document with axis values applied into the fully resolved
// scene that runs. The default is splat's own resolution (read_scene);
// tests of the executor plug in others.
using SceneResolver = std::function<nlohmann::json(const nlohmann::json& scene,
                                                   const std::filesystem::path& base_dir)>;
SceneResolver splat_scene_resolver();
// splat's resolution that never reads a file: a scene naming a material that
// is not in the library (a path) throws InputError at that material. For
// scenes that come over the network.
SceneResolver library_scene_resolver();

// The version string that goes into every job identity: "VERSION+COMMIT".
std::string solver_version_string();

struct ExpandedJob {
  std::string hash;        // sha256 of canonical scene text + "\n" + solver version
  nlohmann::json scene;    // fully resolved
  nlohmann::json params;   // {axis name: value} of the parameter axes (not velocity)
  std::string params_key;  // canonical text of params: the parameter set's identity
  double velocity = 0.0;   // m/s
};

// The job for one parameter set at one velocity.
ExpandedJob make_job(const CampaignSpec& spec, const nlohmann::json& params, double velocity,
                     const SceneResolver& resolve, const std::string& solver_version);

// The axis of the spec that is a resolution ladder (a `fields` axis on a
// resolution pointer, campaign/ladders.hpp, with two or more numeric
// values), or none.
const ParameterAxis* ladder_axis(const CampaignSpec& spec);

// Every parameter set of the spec (product of the parameter axes), in order.
std::vector<nlohmann::json> parameter_sets(const CampaignSpec& spec);

// The full grid: parameter sets x velocities, one entry per distinct
// (parameter set, velocity) point; with refinement coarse_to_fine, only the
// coarsest level of the ladder axis (the finer ones are refinement's). Two points may share a hash
// (the same resolved scene); the store runs such a job once and links both points to it.
std::vector<ExpandedJob> expand(const CampaignSpec& spec, const SceneResolver& resolve,
                                const std::string& solver_version);

// Canonical text of a JSON document (sorted keys, no spaces): what hashes see.
std::string canonical_text(const nlohmann::json& doc);

// The hash of the spec document, used to find a campaign again on resume.
std::string spec_hash(const CampaignSpec& spec);

}  // namespace splat::campaign
