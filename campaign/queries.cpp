#include "campaign/queries.hpp"

namespace splat::campaign {

std::vector<CampaignJobRow> campaign_jobs(Store& store, std::int64_t campaign_id,
                                          std::optional<JobState> state, std::int64_t offset,
                                          std::int64_t limit) {
  Statement s = store.reader().prepare(
      "SELECT p.params_key, p.params, p.velocity, p.job_hash, p.origin, j.state, j.attempts, "
      "j.started_at, j.finished_at, j.wall_seconds, j.exit_reason, r.outcome, "
      "CASE WHEN json_type(j.scene, '$.two_mass') IS NOT NULL THEN 'two-mass' "
      "ELSE json_extract(j.scene, '$.particle_impact.model.name') END, "
      "(SELECT json_extract(e.value, '$.discretization.elements_across') "
      " FROM json_each(j.scene, '$.bodies') e WHERE json_extract(e.value, '$.name') = 'particle'), "
      "(SELECT json_extract(e.value, '$.discretization.element_size') "
      " FROM json_each(j.scene, '$.bodies') e WHERE json_extract(e.value, '$.name') = 'particle' "
      " AND json_extract(e.value, '$.discretization.type') = 'sph') "
      "FROM campaign_points p JOIN jobs j ON j.hash = p.job_hash "
      "LEFT JOIN results r ON r.job_hash = p.job_hash "
      "WHERE p.campaign_id = ?1 AND (?2 IS NULL OR j.state = ?2) "
      "ORDER BY p.params_key, p.velocity LIMIT ?3 OFFSET ?4");
  s.bind(1, campaign_id);
  if (state) {
    s.bind(2, to_string(*state));
  } else {
    s.bind_null(2);
  }
  s.bind(3, limit).bind(4, offset);
  std::vector<CampaignJobRow> out;
  while (s.step()) {
    CampaignJobRow r;
    r.point = {s.text(0), s.text(1), s.real(2), s.text(3), s.text(4)};
    r.state = job_state_from_string(s.text(5));
    r.attempts = static_cast<int>(s.int64(6));
    r.started_at = s.opt_real(7);
    r.finished_at = s.opt_real(8);
    r.wall_seconds = s.opt_real(9);
    r.exit_reason = s.opt_text(10).value_or("");
    r.outcome = s.opt_text(11);
    r.model = s.opt_text(12);
    r.elements_across = s.opt_int64(13);
    r.spacing = s.opt_real(14);
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<JobUse> job_uses(Store& store, const std::string& job_hash) {
  Statement s = store.reader().prepare(
      "SELECT campaign_id, params_key, params, velocity, job_hash, origin FROM campaign_points "
      "WHERE job_hash = ? ORDER BY campaign_id, params_key, velocity");
  s.bind(1, job_hash);
  std::vector<JobUse> out;
  while (s.step()) {
    out.push_back({s.int64(0), {s.text(1), s.text(2), s.real(3), s.text(4), s.text(5)}});
  }
  return out;
}

CampaignTiming campaign_timing(Store& store, std::int64_t campaign_id) {
  Statement s = store.reader().prepare(
      "SELECT COUNT(*), TOTAL(wall_seconds) FROM jobs WHERE wall_seconds IS NOT NULL "
      "AND state IN ('succeeded', 'failed', 'timed-out') AND hash IN "
      "(SELECT job_hash FROM campaign_points WHERE campaign_id = ?)");
  s.bind(1, campaign_id);
  CampaignTiming t;
  if (s.step()) {
    t.timed_jobs = static_cast<int>(s.int64(0));
    t.wall_seconds = s.real(1);
  }
  return t;
}

std::map<std::string, LevelCost> cost_by_parameter_set(Store& store, std::int64_t campaign_id) {
  Statement s = store.reader().prepare(
      "SELECT p.params_key, COUNT(*), TOTAL(j.wall_seconds) FROM campaign_points p "
      "JOIN jobs j ON j.hash = p.job_hash WHERE p.campaign_id = ? GROUP BY p.params_key");
  s.bind(1, campaign_id);
  std::map<std::string, LevelCost> out;
  while (s.step()) out[s.text(0)] = {static_cast<int>(s.int64(1)), s.real(2)};
  return out;
}

JobCounts all_job_counts(Store& store) {
  Statement s = store.reader().prepare("SELECT state, COUNT(*) FROM jobs GROUP BY state");
  return read_job_counts(s);
}

std::vector<double> all_wall_seconds(Store& store) {
  Statement s = store.reader().prepare(
      "SELECT wall_seconds FROM jobs WHERE wall_seconds IS NOT NULL AND state <> 'running'");
  std::vector<double> out;
  while (s.step()) out.push_back(s.real(0));
  return out;
}

std::vector<CampaignRecord> campaigns_page(Store& store, std::int64_t before_id,
                                           std::int64_t limit) {
  std::vector<std::int64_t> ids;
  {
    Statement s = store.reader().prepare(
        "SELECT id FROM campaigns WHERE (?1 <= 0 OR id < ?1) ORDER BY id DESC LIMIT ?2");
    s.bind(1, before_id).bind(2, limit);
    while (s.step()) ids.push_back(s.int64(0));
  }
  std::vector<CampaignRecord> out;
  for (std::int64_t id : ids) {
    if (auto c = store.campaign(id)) out.push_back(std::move(*c));
  }
  return out;
}

}  // namespace splat::campaign
