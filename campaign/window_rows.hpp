// Stored windows as response rows: the JSON rows of `splat windows --format
// json` and of the API, and their CSV text. Pure functions of WindowRecords.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "campaign/store.hpp"

namespace splat::campaign {

// One JSON row per parameter set: the window document (windows.hpp to_json:
// `params`, `critical_velocity`, `maximum_velocity`, brackets, `intervals`,
// `unclassified`, ...) with its `campaign_id`.
nlohmann::json window_rows(const std::vector<WindowRecord>& windows);

// The same rows as CSV with a header line; velocities in m/s, empty fields
// where an edge lies outside the swept range; `params` is quoted JSON.
std::string window_rows_csv(const std::vector<WindowRecord>& windows);

}  // namespace splat::campaign
